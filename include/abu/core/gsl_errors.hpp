// GSL reports errors through a handler that by default prints and calls abort(). The
// library never aborts (errors.hpp): every module that calls GSL checks its return codes
// and turns a failure into its result's Status, so the aborting handler must be off
// before any GSL call, also in programs that never pass through the CLI.
//
// The library switches it off once: at static initialization of every program that links
// a module calling GSL (the spectra, src/linear/spectrum_starts.cpp, which every
// analysis and continuation uses), and again, once, from those modules before their first
// GSL call (for callers running before static initialization has finished). A program that
// wants its own handler installs it in main(), after static initialization: the library
// does not switch it off again.
#pragma once

namespace abu {

/// gsl_set_error_handler_off(), the first time only (thread-safe: std::call_once).
void quiet_gsl_errors();

}  // namespace abu
