#include "abu/core/gsl_errors.hpp"

#include <gsl/gsl_errno.h>

#include <mutex>

namespace abu {

void quiet_gsl_errors() {
  static std::once_flag once;
  std::call_once(once, [] { gsl_set_error_handler_off(); });
}

}  // namespace abu
