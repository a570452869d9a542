// Stability changes of a flexible rotor's balanced state along omega (shaft_crossings.hpp,
// model.md §18.14).
#include "abu/scan/shaft_crossings.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "abu/core/bracketed_root.hpp"
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
  std::string failure;  // the tracking's failure that ended the search, if one did
  const auto re_lambda = [&](double w) -> std::optional<double> {
    const Tracked t = track(w, false);
    if (!t.ok) {
      failure = fmt::format(": at omega = {}: {}", w, t.why);
      return std::nullopt;
    }
    return t.pair.value.real();
  };
  // 1e-12 relative: the reported 1e-10 with room for the eigenvalue's rounding.
  RootSearch search;
  search.relative_width = 1e-12;
  const BracketedRoot found = bracketed_root(re_lambda, std::min(w_a, w_b), std::max(w_a, w_b), search);
  const double root = found.root, lo = found.lower, hi = found.upper;
  const bool converged = found.converged();
  const Tracked at = track(root, true);
  if (!at.ok || !converged) {
    c.status = {Outcome::not_converged, fmt::format("Brent on Re lambda(omega) = 0 in [{}, {}] did not converge{}", lo,
                                                    hi, !failure.empty() ? failure
                                                        : at.ok          ? std::string()
                                                                         : ": " + at.why)};
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
