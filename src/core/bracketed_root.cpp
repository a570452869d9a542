// Brent's method on a bracket (bracketed_root.hpp): GSL's solver, one loop for every caller.
#include "abu/core/bracketed_root.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <memory>

#include "abu/core/gsl_errors.hpp"

namespace abu {

namespace {
struct Evaluation {
  const std::function<std::optional<double>(double)>* f;
  bool failed = false;
};

double evaluate(double x, void* raw) {
  auto& e = *static_cast<Evaluation*>(raw);
  if (e.failed) return 0.0;
  const std::optional<double> v = (*e.f)(x);
  if (!v) {
    e.failed = true;
    return 0.0;  // a zero ends GSL's iteration; the failure is reported, not the root
  }
  return *v;
}

struct SolverDeleter {
  void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
};
}  // namespace

BracketedRoot bracketed_root(const std::function<std::optional<double>(double)>& f, double lower, double upper,
                             const RootSearch& search) {
  quiet_gsl_errors();  // GSL returns its errors (core/gsl_errors.hpp)
  BracketedRoot out;
  out.lower = lower;
  out.upper = upper;
  out.root = 0.5 * (lower + upper);
  Evaluation ev{&f};
  gsl_function fn;
  fn.function = &evaluate;
  fn.params = &ev;
  const std::unique_ptr<gsl_root_fsolver, SolverDeleter> solver(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  if (!solver) return out;
  const int set = gsl_root_fsolver_set(solver.get(), &fn, lower, upper);  // evaluates both ends
  if (ev.failed) {
    out.end = BracketedRoot::End::evaluation_failed;
    return out;
  }
  if (set != GSL_SUCCESS) return out;  // no_sign_change
  out.end = BracketedRoot::End::max_iterations;
  for (int it = 0; it < search.max_iterations; ++it) {
    // Either failure leaves root and bracket as they were before this iteration.
    if (gsl_root_fsolver_iterate(solver.get()) != GSL_SUCCESS) {
      out.end = BracketedRoot::End::solver_error;
      return out;
    }
    if (ev.failed) {
      out.end = BracketedRoot::End::evaluation_failed;
      return out;
    }
    const double previous = out.root;
    out.iterations = it + 1;
    out.root = gsl_root_fsolver_root(solver.get());
    out.lower = gsl_root_fsolver_x_lower(solver.get());
    out.upper = gsl_root_fsolver_x_upper(solver.get());
    if (gsl_root_test_interval(out.lower, out.upper, search.absolute_width, search.relative_width) == GSL_SUCCESS ||
        (search.stop && search.stop(out.root, previous, it))) {
      out.end = BracketedRoot::End::converged;
      return out;
    }
  }
  return out;
}

}  // namespace abu
