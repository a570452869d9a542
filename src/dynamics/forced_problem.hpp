// The shooting problem of the pi/omega-periodic orbits of a rigid rotor on an anisotropic
// support (docs/model.md §10.14, §20.4): multiple shooting over the forcing period with the
// three-stage Radau IIA map, its unknowns continued either in the anisotropy homotopy
// parameter delta (forced_orbits.cpp) or in a physical parameter of the machine
// (forced_branch.cpp, §20.9). Internal to src/dynamics.
#pragma once

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "abu/dynamics/forced_orbits.hpp"
#include "abu/linear/floquet.hpp"
#include "abu/model/machine_field.hpp"
#include "forced_orbits_radau.hpp"
#include "shooting_flow.hpp"

namespace abu::detail {

using StateX = State<double, any_balls>;

// The scaled field y = D^-1 x of (10.14.1) with its Jacobian D^-1 J D and its derivative in
// the scaled parameter: the homotopy's u_p = delta / delta_end (D^-1 df/ddelta * delta_end),
// or with `family` a physical parameter lambda = from + span u_p (model.md §20.9): then the
// time is tau = omega t (the period pi whatever omega), the field f / omega, and its lambda
// derivative the central difference of f / omega between the machines at lambda -+ h.
struct ForcedContext {
  ParamsN p;  // the machine of the homotopy in delta (a family's are here, up, down)
  AnisotropicSupport support;
  const RaceShape* race = nullptr;  // an unround race under the support (model.md §20); null: round
  Eigen::VectorXd scale;  // D
  int dim = 0;            // 2 n + 4
  double delta = 0;       // the homotopy parameter of the current evaluation
  double span = 1;        // d delta / d (scaled parameter) = delta_end; or d lambda / d u_p
  MachineFieldValue value;  // the last evaluation (bounded storage: no allocation per step)
  // The physical parameter's family (null: the homotopy in delta).
  const MachineFamily* family = nullptr;
  double from = 0;  // lambda at u_p = 0
  double lambda = std::numeric_limits<double>::quiet_NaN();
  double h = 0;  // the difference step in lambda
  MachineAtValue here, up, down;
  MachineFieldValue side;  // f at lambda -+ h

  // The machines at lambda and lambda -+ h (built once per value, not per step). h = 1e-6 of
  // the interval: the difference's truncation ~1e-12 and rounding ~1e-10 relative only slow
  // Newton's last digit (the residual, not the Jacobian, decides the point).
  void set_value(double value_of_lambda) {
    if (value_of_lambda == lambda) return;
    lambda = value_of_lambda;
    h = 1e-6 * std::abs(span);
    here = (*family)(lambda);
    up = (*family)(lambda + h);
    down = (*family)(lambda - h);
  }
  void evaluate(double t, const Eigen::VectorXd& y, bool derivatives) {
    StateX x(dim);
    for (int i = 0; i < dim; ++i) x(i) = scale(i) * y(i);
    if (!family) {
      machine_field(p, RigidMachine{race, &support, delta}, x, p.omega * t, 0.0, value, derivatives);  // (20.1)
      return;
    }
    machine_field(here.params, RigidMachine{&here.race, &support, 1.0}, x, t, 0.0, value, derivatives);  // (20.1), t = tau
    const double w = here.params.omega;
    value.field /= w;
    if (derivatives) value.jacobian /= w;
  }
  // The Radau step's field(t, y, F, J, P); with a family P is left to parameter() (the
  // difference quotient costs two more fields: only at the converged stages).
  template <class F, class P>
  void operator()(double t, const Eigen::VectorXd& y, F&& f, Eigen::MatrixXd& J, P&& par) {
    evaluate(t, y, true);
    for (int i = 0; i < dim; ++i) {
      f(i) = value.field(i) / scale(i);
      if (!family) par(i) = value.delta_derivative(i) * span / scale(i);
      for (int j = 0; j < dim; ++j) J(i, j) = value.jacobian(i, j) * scale(j) / scale(i);
    }
  }
  bool deferred_parameter() const { return family != nullptr; }
  // d(f / omega)/dlambda at (tau, y) by the central difference between the machines at lambda -+ h.
  template <class P>
  void parameter(double t, const Eigen::VectorXd& y, P&& par) {
    StateX x(dim);
    for (int i = 0; i < dim; ++i) x(i) = scale(i) * y(i);
    machine_field(up.params, RigidMachine{&up.race, &support, 1.0}, x, t, 0.0, side, false);
    for (int i = 0; i < dim; ++i) par(i) = side.field(i) / up.params.omega;
    machine_field(down.params, RigidMachine{&down.race, &support, 1.0}, x, t, 0.0, side, false);
    for (int i = 0; i < dim; ++i) par(i) = 0.5 * (par(i) - side.field(i) / down.params.omega) / h * span / scale(i);
  }
};

using Evaluated = detail::ShootingEvaluation;

class ForcedProblem : public detail::ShootingSystem<ForcedProblem> {
 public:
  static constexpr std::size_t test_count = 1;  // d delta / ds: a fold in delta

  ForcedProblem(const ParamsN& p, const RigidMachine& machine, const Eigen::VectorXd& scale,
                const ForcedOrbitOptions& o)
      : ShootingSystem(1e-15, 1e2), o_(o), m_(o.intervals), steps_(o.steps_per_interval), dim_(int(scale.size())),
        radau_(int(scale.size())) {
    ctx_.p = p;
    ctx_.support = *machine.support;
    ctx_.race = machine.race;
    ctx_.scale = scale;
    ctx_.dim = dim_;
    ctx_.span = o.delta_end;
    period_ = std::numbers::pi / p.omega;
  }
  // The same orbits continued in a physical parameter lambda = from + span u_p of `family`
  // (model.md §20.9), the time tau = omega t: the integration's period is pi.
  ForcedProblem(const MachineFamily& family, double from, double span, const AnisotropicSupport& support,
                const Eigen::VectorXd& scale, const ForcedOrbitOptions& o)
      : ShootingSystem(1e-15, 1e2), o_(o), m_(o.intervals), steps_(o.steps_per_interval), dim_(int(scale.size())),
        radau_(int(scale.size())) {
    ctx_.family = &family;
    ctx_.from = from;
    ctx_.span = span;
    ctx_.support = support;
    ctx_.scale = scale;
    ctx_.dim = dim_;
    ctx_.delta = 1;
    ctx_.set_value(from);
    period_ = std::numbers::pi;
  }
  /// The parameter's value at u: delta (the homotopy) or lambda (a family).
  double value(const Vec& u) const { return ctx_.family ? ctx_.from + ctx_.span * u(param_index()) : delta(u); }
  /// The orbit's period in time [s]: pi / omega at u's parameter.
  double physical_period(const Vec& u) const {
    set_parameter(u);
    return ctx_.family ? std::numbers::pi / ctx_.here.params.omega : period_;
  }

  int size() const { return dim_ * m_ + 1; }
  int param_index() const { return dim_ * m_; }
  double delta(const Vec& u) const { return u(param_index()) * o_.delta_end; }
  double interval() const { return period_ / m_; }
  int steps_per_interval() const { return steps_; }
  // A finer (or coarser) discretization of the same unknowns: the cache is dropped.
  void set_steps(int steps) {
    steps_ = steps;
    cache_.u.resize(0);
  }

  // Newton on the discrete shooting equations converges quadratically to rounding (the
  // derivatives are those of the discrete map): steps down to 1e-14 of the O(1) scaled
  // unknowns; a stall above 1e-11, or a residual above 1e-13, is a failure.
  arclength::NewtonSettings newton() const {
    arclength::NewtonSettings s;
    s.max_iterations = 12;
    s.step_tolerance = 1e-14;
    s.stall_tolerance = 1e-11;
    s.residual_tolerance = 1e-13;
    return s;
  }

  // One shooting interval from (t0, y0) in `steps` Radau steps: the summed increment `acc`
  // (x(t0 + h) - x(t0), scaled, summed apart from y0: see forced_orbits_radau.hpp), and with
  // `phi` the transition matrix and `z` the parameter sensitivity. `at_step` sees each step's
  // end state.
  template <class AtStep>
  bool run(double t0, const Vec& y0, int steps, double span, Vec& acc, Eigen::MatrixXd* phi, Vec* z, AtStep&& at_step,
           std::string_view& why) const {
    const int d = dim_;
    const double h = span / steps;
    acc.setZero(d);
    if (phi) phi->setIdentity(d, d);
    if (z) z->setZero(d);
    // per-interval buffers: no allocation per step
    Vec y = y0, z_next(d);
    Eigen::MatrixXd step_phi(d, d), phi_next(d, d);
    for (int k = 0; k < steps; ++k) {
      if ((k & 63) == 0) throw_if_stopped("forced orbit");
      if (!radau_.advance(ctx_, t0 + k * h, y, h, phi != nullptr, why)) return false;
      acc += radau_.increment();
      y = y0 + acc;
      if (phi) {
        step_phi = radau_.state_derivative();
        step_phi.diagonal().array() += 1.0;
        z_next.noalias() = step_phi * *z;
        *z = z_next + radau_.parameter_derivative();
        phi_next.noalias() = step_phi * *phi;
        phi->swap(phi_next);
      }
      at_step(y);
    }
    return true;
  }

  const Evaluated& at(const Vec& u) const {
    if (cache_.u.size() == u.size() && cache_.u == u) return cache_;
    throw_if_stopped("forced orbit");
    Evaluated& e = cache_;
    e.u = u;
    e.ok = true;
    e.why = {};
    const int n = size(), d = dim_;
    e.residual = Vec::Zero(n - 1);
    e.jacobian = Jacobian::Zero(n - 1, n);
    e.transitions.assign(std::size_t(m_), Eigen::MatrixXd::Identity(d, d));
    set_parameter(u);
    Vec acc(d), z(d);
    for (int j = 0; j < m_; ++j) {
      std::string_view why;
      if (!run(j * interval(), u.segment(d * j, d), steps_, interval(), acc, &e.transitions[std::size_t(j)], &z,
               [](const Vec&) {}, why)) {
        e.ok = false;
        e.why = why;
        e.residual.setConstant(1e300);
        return e;
      }
      const int next = (j + 1) % m_;
      // (y_j - y_{j+1}) + increment: the difference of nearby values is exact, the increment
      // carries its own relative accuracy (a stuck ball's angle: see forced_orbits_radau.hpp).
      e.residual.segment(d * j, d) = (u.segment(d * j, d) - u.segment(d * next, d)) + acc;
      e.jacobian.block(d * j, d * j, d, d) = e.transitions[std::size_t(j)];
      e.jacobian.block(d * j, d * next, d, d) -= Eigen::MatrixXd::Identity(d, d);
      e.jacobian.block(d * j, param_index(), d, 1) = z;
    }
    return e;
  }

  arclength::Crossing crossing(const Vec&, const Vec& to) const {
    // Back below delta = 0: the family turned (a fold in delta) before reaching delta_end.
    if (to(param_index()) < 0)
      return arclength::Crossing::leaving("the orbit family turned back in delta (a fold) before reaching the scene's "
                                          "support: no orbit continues this equilibrium there");
    return arclength::box_crossing(to, {param_index()});
  }

  arclength::Evaluation<double, 1> evaluate(const Vec&, const Vec& t, const Jacobian&, arclength::Stage) {
    arclength::Evaluation<double, 1> out;
    out.tests = {t(param_index())};
    return out;
  }
  void locate(unsigned, const arclength::Segment<Vec>&) { folded_ = true; }
  void commit(Vec&, Vec&, arclength::Stage) {}
  bool folded() const { return folded_; }

  // The shooting states of u (delta from u) filled by one uninterrupted run from y1: y_j at t_j.
  bool chain(const Vec& y1, Vec& u) const {
    set_parameter(u);
    Vec acc(dim_), y = y1;
    std::string_view why;
    for (int j = 0; j < m_; ++j) {
      u.segment(dim_ * j, dim_) = y;
      if (!run(j * interval(), y, steps_, interval(), acc, nullptr, nullptr, [](const Vec&) {}, why)) return false;
      y += acc;
    }
    cache_.u.resize(0);
    return y.allFinite();
  }

  // The multipliers of the discrete monodromy at u with the current step count.
  ProductEigenvalues multipliers(const Vec& u) const { return product_eigenvalues(at(u).transitions); }

  // The orbit's data at a converged u; `coarse` the multipliers of the same unknowns with
  // half the steps (their difference bounds the discretization error, §10.18).
  // `fine`: the multipliers at u with the current steps when the caller has them already.
  void describe(const Vec& u, const ProductEigenvalues& coarse, ForcedOrbit& o, const ProductEigenvalues* fine = nullptr) {
    o.delta = ctx_.family ? 1.0 : delta(u);
    o.period = physical_period(u);
    o.steps_per_interval = steps_;
    ProductEigenvalues f = fine ? *fine : multipliers(u);
    if (!f.status.ok()) {
      o.status.merge(f.status);
      o.reason = fmt::format("Floquet multipliers: {}", f.status.reason);
      return;
    }
    o.state0.resize(std::size_t(dim_));
    for (int i = 0; i < dim_; ++i) o.state0[std::size_t(i)] = u(i) * ctx_.scale(i);
    std::vector<Eigen::VectorXd> states;
    if (!sample(u, o, states)) return;
    const std::size_t unresolved = stiff_multipliers(f, states);
    o.unresolved_multipliers = int(unresolved);
    o.multipliers = f.values;
    o.log_moduli = f.log_moduli;
    o.exponents.clear();
    for (std::size_t k = 0; k < f.values.size(); ++k) {
      // lambda = (omega/pi) (ln|rho| + i arg rho), Im in (-omega, omega] (model.md §10.4).
      o.exponents.emplace_back(f.log_moduli[k] / o.period, f.arguments[k] / o.period);
    }
    // The discretization error: the resolved multipliers against those with half the steps
    // (a fifth-order method: the coarse error is 32 times the fine one, so the difference
    // bounds it), relative to max(|rho|, 1e-6) as the acceptance compares them.
    o.discretization_error = 0;
    const std::size_t resolved = f.values.size() - unresolved;
    for (std::size_t k = 0; k < resolved; ++k) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < coarse.values.size(); ++i)
        best = std::min(best, std::abs(coarse.values[i] - f.values[k]));
      o.discretization_error = std::max(o.discretization_error, best / std::max(std::abs(f.values[k]), 1e-6));
    }
    o.band = o.discretization_error + 64 * std::numeric_limits<double>::epsilon() * m_ * steps_;
    const double top = f.log_moduli.empty() ? 0.0 : *std::max_element(f.log_moduli.begin(), f.log_moduli.end());
    o.verdict = top < -o.band ? Stability::stable : top > o.band ? Stability::unstable : Stability::marginal;
  }

 private:
  // The stiff multipliers (coulomb balls' rates ~1e8 1/s, e^{-1e5} over the period): the
  // Radau map damps them by its stability function, R(h lambda) ~ 1/(h lambda), not by
  // e^{h lambda}, so their discrete values say only "below 1e-300". A multiplier that the
  // discrete map shrinks by more than e^{-1/2} per step on average (resolved ones move by
  // 1e-4 per step) is replaced by exp of the period average of the matching fast eigenvalue
  // of J(x(t)) along the orbit (the frozen-coefficient rate of the slaved fast mode, to
  // O(slow/fast) ~ 1e-5 relative); returns how many were so replaced.
  std::size_t stiff_multipliers(ProductEigenvalues& f, const std::vector<Eigen::VectorXd>& states) {
    const double total_steps = double(m_ * steps_);
    std::size_t count = 0;
    for (double l : f.log_moduli) count += (l / total_steps < -0.5) ? 1 : 0;
    if (count == 0 || states.empty()) return count;
    std::vector<double> mean(count, 0.0);
    Eigen::EigenSolver<Eigen::MatrixXd> es;
    std::vector<double> re(static_cast<std::size_t>(dim_));
    for (std::size_t s = 0; s < states.size(); ++s) {
      ctx_.evaluate(period_ * double(s) / double(states.size()), states[s], true);
      es.compute(Eigen::MatrixXd(ctx_.value.jacobian), false);
      for (int i = 0; i < dim_; ++i) re[std::size_t(i)] = es.eigenvalues()(i).real();
      std::sort(re.begin(), re.end());  // most negative first
      for (std::size_t k = 0; k < count; ++k) mean[k] += re[k] / double(states.size());
    }
    // The multipliers are sorted by modulus, descending: the last `count` are the stiff ones,
    // the least negative of them first.
    const std::size_t first = f.values.size() - count;
    for (std::size_t k = 0; k < count; ++k) {
      const double l = mean[count - 1 - k] * period_;
      f.log_moduli[first + k] = l;
      f.values[first + k] = std::exp(l);
      f.arguments[first + k] = 0;
    }
    return count;
  }

  // The orbit over one period from y_1 in the same steps, without restarts: |q| at every step
  // point (M * steps uniform samples), max and mean |q|, the ball angles' extremes, and the
  // periodicity (the shooting residual of the uninterrupted run). `states` gets the samples.
  bool sample(const Vec& u, ForcedOrbit& o, std::vector<Eigen::VectorXd>& states) {
    const int n = dim_ / 2 - 2;
    std::vector<double> qabs;
    std::vector<std::vector<double>> balls(static_cast<std::size_t>(n));
    set_parameter(u);
    Vec acc(dim_);
    std::string_view why;
    const Vec y1 = u.head(dim_);
    const bool ran = run(0.0, y1, m_ * steps_, period_, acc, nullptr, nullptr, [&](const Vec& s) {
      states.push_back(s);
      qabs.push_back(std::hypot(s(0) * ctx_.scale(0), s(1) * ctx_.scale(1)));
      for (int b = 0; b < n; ++b) balls[std::size_t(b)].push_back(s(2 + b));
    }, why);
    if (!ran) {
      o.status.merge(Outcome::numerical_issue, "see reason");
      o.reason = fmt::format("sampling the orbit: {}", why);
      return false;
    }
    // the samples at t_k = k h, k = 1..N: rotate so that the list starts at t = 0 (t_N = period)
    std::rotate(states.rbegin(), states.rbegin() + 1, states.rend());
    o.periodicity = acc.cwiseAbs().maxCoeff();
    o.q_abs_max = detail::periodic_max(qabs);
    double sum = 0;
    for (double v : qabs) sum += v;  // uniform samples of a periodic function: the trapezoid rule
    o.q_abs_mean = sum / double(qabs.size());
    for (double& v : qabs) v = -v;
    o.q_abs_min = -detail::periodic_max(qabs);
    o.ball_min.clear();
    o.ball_max.clear();
    for (auto& v : balls) {
      o.ball_max.push_back(detail::periodic_max(v));
      for (double& x : v) x = -x;
      o.ball_min.push_back(-detail::periodic_max(v));
    }
    return true;
  }

  void set_parameter(const Vec& u) const {
    if (ctx_.family)
      ctx_.set_value(value(u));
    else
      ctx_.delta = delta(u);
  }

  ForcedOrbitOptions o_;
  int m_, steps_, dim_;
  double period_ = 0;
  mutable ForcedContext ctx_;
  mutable detail::RadauStep radau_;
  mutable Evaluated cache_;
  bool folded_ = false;
};

static_assert(arclength::Problem<ForcedProblem>);

// The scaling D of the shooting unknowns (model.md (10.14.3)).
inline Eigen::VectorXd forced_orbit_scale(const ParamsN& p) {
  const int n = p.n_balls(), d = 2 * n + 4;
  const double L = displacement_scale(p), w = p.omega;
  Eigen::VectorXd D = Eigen::VectorXd::Ones(d);
  D.segment(n + 2, n + 2).setConstant(w);
  D.head(2) *= L;
  D.segment(n + 2, 2) *= L;
  return D;
}

// `out` with its failure recorded: the outcome merged into its status, the reason kept.
inline ForcedOrbit failed(ForcedOrbit& out, Outcome outcome, std::string why) {
  out.status.merge(outcome, "see reason");
  out.reason = std::move(why);
  return out;
}

inline ForcedOrbit refined_forced_orbit(ForcedProblem& problem, Eigen::VectorXd u, const ForcedOrbitOptions& o, ForcedOrbit& out) {
  // The discretization's error, a posteriori (model.md §10.18): the multipliers with half the
  // steps on the same unknowns; while their difference exceeds the target, the steps double
  // and Newton (delta fixed by the border) corrects the orbit on the finer grid.
  Eigen::VectorXd fix = Eigen::VectorXd::Zero(problem.size());
  fix(problem.param_index()) = 1;
  for (;;) {
    const int steps = problem.steps_per_interval();
    problem.set_steps(std::max(1, steps / 2));
    const ProductEigenvalues coarse = problem.multipliers(u);
    problem.set_steps(steps);
    problem.describe(u, coarse, out);
    if (!out.status.ok()) return out;
    if (out.discretization_error <= o.accuracy || 2 * steps > o.max_steps_per_interval) break;
    problem.set_steps(2 * steps);
    const auto c = arclength::correct(problem, u, fix);
    out.newton_iterations += c.iterations;
    if (c.status != Outcome::converged)
      return failed(out, c.status, fmt::format("refining the orbit with {} steps per interval: {}", 2 * steps, c.reason));
    u = c.u;
  }
  // Still above the target at max_steps_per_interval (a near-double multiplier, whose members
  // move by the square root of the monodromy's error, can do that): the orbit is kept, and
  // the band, which contains the estimate, carries it into the verdict.
  return out;
}
}  // namespace abu::detail
