// Stability changes of a flexible rotor's balanced state along omega (shaft_crossings.hpp,
// model.md §18.14).
#include "abu/scan/shaft_crossings.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cmath>
#include <map>

#include "abu/core/gsl_errors.hpp"
#include "abu/linear/sparse_spectrum.hpp"
#include "abu/scan/shaft_map.hpp"

namespace abu {

namespace {

using cplx = std::complex<double>;

struct Tracked {
  bool ok = false;
  SparseEigenpair pair;
  Eigen::VectorXd state;
  std::string why;
};

// The eigenvalue nearest `shift` of the balanced state nearest `reference` at omega.
Tracked eigenvalue_at(const std::function<ShaftSystem(double)>& system_at, const Eigen::VectorXd& reference,
                      double omega, cplx shift, bool vector) {
  Tracked t;
  const ShaftSystem sys = system_at(omega);
  const std::vector<ShaftEquilibrium> states = shaft_balanced_states(sys);
  if (states.empty()) {
    t.why = fmt::format("no balanced state at omega = {}", omega);
    return t;
  }
  const ShaftEquilibrium* best = &states.front();
  for (const auto& e : states)
    if ((e.position - reference).norm() < (best->position - reference).norm()) best = &e;
  t.state = best->state();
  const ShaftPencil pencil = shaft_pencil(linearize_shaft(sys, t.state));
  SparseSpectrumOptions o;
  o.keep_vectors = vector;
  const cplx shifts[] = {shift};
  const SparseSpectrum s = eigenvalues_near(pencil.a, pencil.b, shifts, 1, o);
  if (s.eigenpairs.empty() || !s.status.ok()) {
    t.why = fmt::format("ARPACK at omega = {}: {}", omega, s.status.ok() ? "no eigenvalue" : s.status.reason);
    return t;
  }
  t.pair = s.eigenpairs.front();
  if (t.pair.value.imag() < 0) {  // the pencil is real: keep the member with Im >= 0
    t.pair.value = std::conj(t.pair.value);
    if (vector) t.pair.vector = t.pair.vector.conjugate();
  }
  t.ok = true;
  return t;
}

}  // namespace

ShaftCrossing refine_shaft_crossing(const std::function<ShaftSystem(double)>& system_at,
                                    const Eigen::VectorXd& reference, double w_a, cplx lambda_a, double w_b, int steps) {
  ShaftCrossing c;
  // Known points of the tracked branch, omega -> lambda: each solve starts from the nearest.
  std::map<double, cplx> known{{w_a, cplx(lambda_a.real(), std::abs(lambda_a.imag()))}};
  const auto track = [&](double omega, bool vector) {
    auto it = known.lower_bound(omega);
    if (it == known.end() || (it != known.begin() && std::abs(std::prev(it)->first - omega) < std::abs(it->first - omega)))
      it = std::prev(it);
    Tracked t = eigenvalue_at(system_at, reference, omega, it->second, vector);
    ++c.evaluations;
    if (t.ok) known[omega] = t.pair.value;
    return t;
  };
  // Along the bracket in small steps (the shift stays near its eigenvalue).
  Tracked end;
  for (int i = 1; i <= steps; ++i) {
    const double w = i == steps ? w_b : w_a + (w_b - w_a) * double(i) / double(steps);
    end = track(w, false);
    if (!end.ok) {
      c.status = {Outcome::not_converged, "tracking the crossing eigenvalue: " + end.why};
      return c;
    }
  }
  const double re_a = lambda_a.real(), re_b = end.pair.value.real();
  if (!(re_a * re_b < 0)) {
    c.status = {Outcome::not_converged,
                fmt::format("the eigenvalue tracked from omega = {} (Re {:.6g}) keeps its sign up to omega = {} (Re "
                            "{:.6g}): another eigenvalue crossed",
                            w_a, re_a, w_b, re_b)};
    return c;
  }
  struct Context {
    decltype(track)* f;
    bool failed = false;
  } ctx{&track};
  gsl_function fn;
  fn.params = &ctx;
  fn.function = [](double w, void* raw) -> double {
    auto* x = static_cast<Context*>(raw);
    const Tracked t = (*x->f)(w, false);
    if (!t.ok) {
      x->failed = true;
      return 0.0;  // Brent stops at a zero; the failure is reported
    }
    return t.pair.value.real();
  };
  quiet_gsl_errors();
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  double lo = std::min(w_a, w_b), hi = std::max(w_a, w_b), root = 0.5 * (lo + hi);
  bool ok = solver && gsl_root_fsolver_set(solver, &fn, lo, hi) == GSL_SUCCESS;
  bool converged = false;
  for (int it = 0; ok && it < 200 && !ctx.failed; ++it) {
    if (gsl_root_fsolver_iterate(solver) != GSL_SUCCESS) {
      ok = false;
      break;
    }
    root = gsl_root_fsolver_root(solver);
    lo = gsl_root_fsolver_x_lower(solver);
    hi = gsl_root_fsolver_x_upper(solver);
    // 1e-12 relative: the reported 1e-10 with room for the eigenvalue's rounding.
    if (gsl_root_test_interval(lo, hi, 0, 1e-12) == GSL_SUCCESS) {
      converged = true;
      break;
    }
  }
  if (solver) gsl_root_fsolver_free(solver);
  const Tracked at = track(root, true);
  if (!ok || ctx.failed || !at.ok || !converged) {
    c.status = {Outcome::not_converged, fmt::format("Brent on Re lambda(omega) = 0 in [{}, {}] did not converge{}", lo,
                                                    hi, at.ok ? std::string() : ": " + at.why)};
    return c;
  }
  c.omega = root;
  c.value = at.pair.value;
  c.vector = at.pair.vector;
  c.state = at.state;
  c.residual = at.pair.residual;
  c.slope = (re_b - re_a) / (w_b - w_a);
  c.loses = c.slope > 0;
  c.status = {};
  return c;
}

}  // namespace abu
