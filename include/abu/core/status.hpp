// How a computation ended, as every result reports it (issue 7: "results carry a status
// (converged, not converged, numerical issue, with the reason)", the way Ceres' Solver::
// Summary and Spectra's CompInfo do). The result's numbers are kept in every case: a
// not-converged equilibrium is still the best point Newton found, its residual printed.
//
//   abu::Spectrum sp = abu::compute_spectrum(lin);
//   if (!sp.status.ok()) fmt::print("{}: {}\n", to_string(sp.status.outcome), sp.status.reason);
//
// `reason` points to static text (a string literal): results are copied in hot loops
// (maps, the n-ball samples) that must not allocate (tests/alloc); numbers that explain
// the failure further (a residual) are in the result's own fields and the output notes.
#pragma once

#include <string_view>

namespace abu {

/// converged: the result meets its tolerance. not_converged: the iteration ended (out of
/// iterations, stalled above the tolerance) without meeting it. numerical_issue: it could
/// not be carried out (a non-finite value, a singular system, a library routine's error).
enum class Outcome { converged, not_converged, numerical_issue };
std::string_view to_string(Outcome o);  ///< "converged", "not converged", "numerical issue"

struct Status {
  Outcome outcome = Outcome::converged;
  std::string_view reason;  ///< why not converged (static text); empty when converged

  bool ok() const { return outcome == Outcome::converged; }
  /// Keeps the first failure: a numerical issue outranks not converged, which outranks
  /// converged; among equals the earlier reason stays.
  void merge(Outcome o, std::string_view why) {
    if (int(o) > int(outcome)) outcome = o, reason = why;
  }
  void merge(const Status& other) { merge(other.outcome, other.reason); }
};

}  // namespace abu
