// The library switches GSL's aborting error handler off by itself (core/gsl_errors.hpp):
// a program that uses the library without the CLI, and never calls
// gsl_set_error_handler_off(), gets GSL's error codes back instead of abort(). A separate
// executable because the Catch2 suite's own tests (test_continuation.cpp) switch the
// handler off themselves, which would hide a library that does not.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cstdio>
#include <string>

#include "abu/equilibria/equilibria.hpp"
#include "abu/input/scene.hpp"
#include "abu/scan/scan.hpp"

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what.c_str());
  failures += ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  // 1. At main(), before any library call: the handler is already GSL's "off" handler
  //    (gsl_set_error_handler returns the one installed; nullptr is the aborting default).
  gsl_error_handler_t* installed = gsl_set_error_handler(nullptr);
  gsl_set_error_handler(installed);
  check(installed != nullptr, "GSL's aborting default handler is off before main() (static initialization)");

  // 2. A GSL error comes back as a code: Brent's method on a bracket whose ends have the
  //    same sign (what the continuation's root_on_branch can meet, branch_specials.cpp)
  //    returns GSL_EINVAL; with the default handler this line would abort the process.
  gsl_function f;
  f.function = [](double x, void*) { return x * x + 1; };
  f.params = nullptr;
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  const int code = gsl_root_fsolver_set(solver, &f, 0.0, 1.0);
  gsl_root_fsolver_free(solver);
  check(code == GSL_EINVAL, "a GSL error is returned as its code (Brent, no sign change: GSL_EINVAL)");

  // 3. The library's own GSL user still works (and is what links the initializer in):
  //    the default scene's spectra.
  const abu::Scene scene = abu::load_scene(argc > 1 ? argv[1] : "data/scenes/default.toml");
  const abu::Params p = abu::params_of<2>(scene);
  const abu::EquilibriumSet set = abu::find_equilibria(p);
  bool all = !set.points().empty();
  for (const auto& e : set.points()) {
    const abu::Spectrum sp = abu::equilibrium_spectrum(p, e);
    all = all && sp.converged && sp.count == 8;
  }
  check(all, "every spectrum of the default scene is refined");
  std::printf("%d failure(s)\n", failures);
  return failures == 0 ? 0 : 1;
}
