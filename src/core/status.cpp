#include "abu/core/status.hpp"

#include <ostream>

namespace abu {

std::string_view to_string(Outcome o) {
  switch (o) {
    case Outcome::converged: return "converged";
    case Outcome::not_converged: return "not converged";
    case Outcome::numerical_issue: return "numerical issue";
  }
  return "?";
}

std::ostream& operator<<(std::ostream& out, const Reason& reason) { return out << reason.view(); }

}  // namespace abu
