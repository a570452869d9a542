// The zero of a function of one variable inside a bracket where it changes sign, by Brent's
// method (GSL's gsl_root_fsolver_brent): the one locator of every special point located
// along a parameter or a branch's chord — folds, branch points and Hopf points of equilibrium
// branches (continuation/), fold, flip and Neimark–Sacker points of cycle branches
// (dynamics/), a shaft mode's crossing of the imaginary axis (scan/).
//
//   abu::RootSearch search;
//   search.relative_width = 1e-12;
//   abu::BracketedRoot r = abu::bracketed_root([&](double x) -> std::optional<double> { ... }, lo, hi, search);
//   if (r.end == abu::BracketedRoot::End::converged) use(r.root);
//
// The tolerance policy: a bracket [lower, upper] is narrow enough when
// |upper - lower| < absolute_width + relative_width * min(|lower|, |upper|)
// (gsl_root_test_interval), or when the caller's `stop` says so (a test function whose own
// noise keeps the bracket from shrinking). Each caller states its widths where it calls,
// with why.
#pragma once

#include <functional>
#include <optional>

namespace abu {

struct RootSearch {
  double absolute_width = 0.0;  ///< default 0
  double relative_width = 0.0;  ///< default 0 (one of the two must be > 0)
  int max_iterations = 200;     ///< default 200 (Brent reaches 1e-15 of a bracket in < 60)
  /// Called after each iteration with the new root estimate, the previous one and the
  /// iteration (0 first): true ends the search as converged. Default: none.
  std::function<bool(double root, double previous, int iteration)> stop;
};

struct BracketedRoot {
  enum class End {
    converged,          ///< the bracket below the widths, or `stop` said so
    evaluation_failed,  ///< the function returned no value (lower/upper: the bracket before it)
    no_sign_change,     ///< the ends have the same sign (or GSL refused the bracket)
    solver_error,       ///< GSL's iteration failed (a non-finite value)
    max_iterations,     ///< the bracket still wider than asked
  };
  End end = End::no_sign_change;
  double root = 0.0;   ///< the last estimate (the bracket's middle before the first)
  double lower = 0.0;  ///< the final bracket
  double upper = 0.0;
  int iterations = 0;
  bool converged() const { return end == End::converged; }
};

/// `f` returns the function's value, or nothing where it cannot be evaluated (a corrector
/// that did not converge): the search then ends at once. `lower < upper`.
BracketedRoot bracketed_root(const std::function<std::optional<double>(double)>& f, double lower, double upper,
                             const RootSearch& search);

}  // namespace abu
