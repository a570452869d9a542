// Periodic orbits by multiple shooting, continued with the arclength engine
// (periodic_orbits.hpp, docs/model.md §17).
#include "abu/dynamics/periodic_orbits.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <utility>
#include <vector>

#include "abu/core/gsl_errors.hpp"
#include "abu/linear/floquet.hpp"
#include "abu/model/model.hpp"
#include "cycle_flow.hpp"
#include "cycle_problem.hpp"  // the shooting problem of one branch

namespace abu {
namespace {

using namespace cycle_flow;  // the flow of the shooting intervals (cycle_flow.hpp)

}  // namespace

// ---------------------------------------------------------------------------------------
// The normal form at a Hopf point (model.md (17.3)).

HopfPrediction predict_from_hopf(const Params& p0, ParamRef ref, const SpecialPoint& hopf) {
  HopfPrediction out;
  Params p = p0;
  set(p, ref, double(hopf.parameter));
  Coordinates<double, 2> s = hopf.position.cast<double>();
  const State8 x = at_rest<double, 2>(s);
  const Matrix8 J = jacobian(p, x);
  const double w = hopf.frequency;
  const Eigen::MatrixXd Jd = J, Jt = J.transpose();
  Eigen::EigenSolver<Eigen::MatrixXd> er(Jd), el(Jt);
  if (er.info() != Eigen::Success || el.info() != Eigen::Success) return out;
  Eigen::Index ir = 0, il = 0;
  const std::complex<double> iw(0, w);
  const Eigen::Matrix<std::complex<double>, kDim, 1> lr = er.eigenvalues(), ll = el.eigenvalues();
  for (Eigen::Index i = 1; i < kDim; ++i) {
    if (std::abs(lr(i) - iw) < std::abs(lr(ir) - iw)) ir = i;
    if (std::abs(ll(i) + iw) < std::abs(ll(il) + iw)) il = i;
  }
  const Eigen::Matrix<std::complex<double>, kDim, kDim> vr = er.eigenvectors(), vl = el.eigenvectors();
  Eigen::VectorXcd q = vr.col(ir);
  q /= q.norm();
  Eigen::VectorXcd pl = vl.col(il);
  const std::complex<double> c = pl.dot(q);  // p^H q
  if (std::abs(c) == 0) return out;
  pl /= std::conj(c);
  // dJ/dp along the equilibrium branch: x_eq'(p) = -J^-1 f_p, central differences of J.
  const State8 fp = parameter_derivative(p, x, ref);
  const State8 dx = -J.partialPivLu().solve(fp);
  const double h = 1e-6 * std::max(std::abs(double(hopf.parameter)), 1e-12);
  Params pa = p, pb = p;
  set(pa, ref, double(hopf.parameter) + h);
  set(pb, ref, double(hopf.parameter) - h);
  const State8 xa = x + h * dx, xb = x - h * dx;
  const Eigen::MatrixXd dJ = (Eigen::MatrixXd(jacobian(pa, xa)) - Eigen::MatrixXd(jacobian(pb, xb))) / (2 * h);
  const std::complex<double> dlambda = pl.dot(dJ.cast<std::complex<double>>() * q);
  out.slope = dlambda.real();
  out.eigenvector.assign(q.data(), q.data() + q.size());
  const Eigen::Vector2cd a = q.head<2>();
  const double major = 2 * std::sqrt(0.5 * (a.squaredNorm() + std::abs(a.dot(a.conjugate()))));
  const double l1 = hopf.lyapunov;
  if (!(l1 != 0 && out.slope != 0 && w > 0)) return out;
  out.amplitude_coefficient = std::sqrt(std::abs(out.slope / (w * l1))) * major;
  out.ok = std::isfinite(out.amplitude_coefficient);
  return out;
}

namespace {

using cycle_problem::CycleProblem;
using cycle_problem::shooting_setup;

template <class Problem>
CycleBranch trace_cycles(Problem& problem, const Params& p, ParamRef ref, const SpecialPoint& hopf,
                         const HopfPrediction& pred, double from, double to, const CycleOptions& o,
                         const Eigen::Matrix<double, kDim, 1>& D, CycleBranch out);

}  // namespace

double cycle_branch_memory_estimate(const CycleOptions& o) {
  const double intervals = std::max({o.intervals, o.adapt_intervals ? o.max_intervals : 0, o.stiff_intervals});
  const double orbit = 1.5e3 + (o.keep_profiles ? 120 * intervals : 0);
  return 10e6 + 32e3 * intervals + 1e3 * double(o.stiff_intervals) * o.max_stiff_steps +
         double(o.continuation.max_steps) * orbit;
}

CycleBranch continue_cycles(const Params& p0, ParamRef ref, const SpecialPoint& hopf, double from, double to,
                            const CycleOptions& o) {
  quiet_gsl_errors();
  CycleBranch out;
  out.hopf_parameter = double(hopf.parameter);
  out.hopf_frequency = hopf.frequency;
  out.lyapunov = hopf.lyapunov;
  if (from > to) std::swap(from, to);
  const auto fail = [&](Outcome why_kind, std::string why) {
    out.status.merge(why_kind, "see reason");
    out.reason = std::move(why);
    return out;
  };
  if (hopf.label != Label::HB || !(hopf.frequency > 0))
    return fail(Outcome::numerical_issue, "not a Hopf point with a positive frequency");
  const HopfPrediction pred = predict_from_hopf(p0, ref, hopf);
  out.real_part_slope = pred.slope;
  if (!pred.ok)
    return fail(Outcome::numerical_issue, fmt::format("degenerate Hopf point at {} = {:.10g}: l1 = {:g}, dRe(lambda)/dp = {:g}",
                                                      to_string(ref), out.hopf_parameter, hopf.lyapunov, pred.slope));
  Params p = p0;
  const double w = hopf.frequency;
  set(p, ref, out.hopf_parameter);
  const auto [D, type, radau] = shooting_setup(p0, ref, hopf);
  out.stiff = radau;
  if (radau && !(o.stiff_steps >= 1 && o.stiff_intervals >= 2 && o.max_stiff_steps >= o.stiff_steps))
    return fail(Outcome::numerical_issue, "the stiff route's intervals and steps are not positive");

  if (o.chord_corrector) {
    CycleProblem<true> problem(p0, ref, from, to, 2 * std::numbers::pi / w, o, type, D, radau);
    return trace_cycles(problem, p, ref, hopf, pred, from, to, o, D, std::move(out));
  }
  CycleProblem<false> problem(p0, ref, from, to, 2 * std::numbers::pi / w, o, type, D, radau);
  return trace_cycles(problem, p, ref, hopf, pred, from, to, o, D, std::move(out));
}

CycleCorrection correct_cycle(const Params& p0, ParamRef ref, const SpecialPoint& hopf, const CycleOrbit& guess,
                              double from, double to, const CycleOptions& o) {
  quiet_gsl_errors();
  CycleCorrection out;
  if (from > to) std::swap(from, to);
  if (hopf.label != Label::HB || !(hopf.frequency > 0) || !(guess.parameter >= from && guess.parameter <= to)) {
    out.status.merge(Outcome::numerical_issue, "see reason");
    out.reason = "not a Hopf point with a positive frequency, or the guess outside [from, to]";
    return out;
  }
  const auto [D, type, radau] = shooting_setup(p0, ref, hopf);
  CycleProblem<true> problem(p0, ref, from, to, 2 * std::numbers::pi / hopf.frequency, o, type, D, radau);
  Eigen::VectorXd u;
  if (!problem.unknowns_from(guess.state0, guess.period, guess.parameter, u)) {
    out.status.merge(Outcome::numerical_issue, "see reason");
    out.reason = "the guess could not be integrated over its period";
    return out;
  }
  problem.set_phase(u);
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(u.size());
  fixed(problem.param_index()) = 1;  // the parameter held at the guess's value
  // The chord corrector from a guess farther than one continuation step (another
  // parameter value) may run out of iterations while still contracting: restarted from its
  // last iterate, with the Newton matrix there, a few times (the parameter stays fixed).
  auto c = arclength::correct(problem, u, fixed);
  for (int restart = 0; restart < 4 && !c.converged() && c.status == Outcome::not_converged && c.u.allFinite(); ++restart)
    c = arclength::correct(problem, Eigen::VectorXd(c.u), fixed);
  if (!c.converged()) {
    out.status.merge(c.status, "see reason");
    out.reason = std::string("the corrector did not converge: ") + std::string(c.reason);
    return out;
  }
  problem.evaluate(c.u, fixed, c.jacobian, arclength::Stage::start);
  Eigen::VectorXd uu = c.u, t = fixed;
  problem.commit(uu, t, arclength::Stage::start);
  out.orbit = problem.orbits_.back();
  return out;
}

namespace {

// The stiff route's discretization (model.md §17.11): the steps per interval doubled at the
// first orbit (its parameter held) until its period and resolved multipliers (those the
// factors represent: all but the frozen-spectra ones) change by at most stiff_accuracy; false
// (out's status and reason set) if the corrector fails or max_stiff_steps is reached first.
template <class Problem>
bool refine_steps(Problem& problem, Eigen::VectorXd& u, const CycleOptions& o, CycleBranch& out) {
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(u.size());
  fixed(problem.param_index()) = 1;
  const auto resolved = [&](const Eigen::VectorXd& v) {
    std::vector<std::complex<double>> m = product_eigenvalues(problem.at(v).transitions).values;
    m.resize(2);  // the two slow ones (the orbit's plane); the rest are the fast modes' R(h lambda)^N
    return m;
  };
  double previous_period = problem.period(u);
  std::vector<std::complex<double>> previous = resolved(u);
  for (;;) {
    const int steps = 2 * problem.steps_per_interval();
    if (steps > o.max_stiff_steps) {
      out.status.merge(Outcome::not_converged, "see reason");
      out.reason = fmt::format("the first orbit's period and multipliers still changed by {:.3g} (relative) at {} Radau "
                               "steps per interval, more than stiff_accuracy = {:g}",
                               out.discretization_change, steps / 2, o.stiff_accuracy);
      return false;
    }
    problem.set_steps_per_interval(steps);
    problem.set_phase(u);
    const auto c = arclength::correct(problem, u, fixed);
    if (!c.converged()) {
      out.status.merge(c.status, "see reason");
      out.reason = fmt::format("the first orbit with {} Radau steps per interval did not converge: {}", steps, c.reason);
      return false;
    }
    u = c.u;
    const std::vector<std::complex<double>> now = resolved(u);
    double change = std::abs(problem.period(u) - previous_period) / problem.period(u);
    for (std::size_t k = 0; k < now.size(); ++k)
      change = std::max(change, std::abs(now[k] - previous[k]) / std::max(std::abs(now[k]), 1e-6));
    out.discretization_change = change;
    out.steps_per_interval = steps;
    previous_period = problem.period(u);
    previous = now;
    if (change <= o.stiff_accuracy) return true;
  }
}

// The first orbit from the normal form, then the branch (continue_cycles).
template <class Problem>
CycleBranch trace_cycles(Problem& problem, const Params& p, ParamRef ref, const SpecialPoint& hopf,
                         const HopfPrediction& pred, double from, double to, const CycleOptions& o,
                         const Eigen::Matrix<double, kDim, 1>& D, CycleBranch out) {
  const auto fail = [&](Outcome why_kind, std::string why) {
    out.status.merge(why_kind, "see reason");
    out.reason = std::move(why);
    return out;
  };
  const double pH = out.hopf_parameter, w = hopf.frequency;
  const State8 xH = at_rest<double, 2>(Coordinates<double, 2>(hopf.position.cast<double>()));
  // The first orbit from the normal form: scaled size first_amplitude.
  Eigen::VectorXcd q(kDim);
  for (int i = 0; i < kDim; ++i) q(i) = pred.eigenvector[std::size_t(i)];
  const double qs = (D.cwiseInverse().cast<std::complex<double>>().asDiagonal() * q).norm();
  double z = o.first_amplitude / qs;
  double dp = -z * z * w * hopf.lyapunov / pred.slope;
  if (pH + dp < from || pH + dp > to) {
    const double room = dp > 0 ? to - pH : pH - from;
    if (!(room > 0)) return fail(Outcome::numerical_issue, "the cycles are born outside the parameter interval");
    z *= std::sqrt(0.5 * room / std::abs(dp));
    dp = -z * z * w * hopf.lyapunov / pred.slope;
  }
  const State8 dxdp = -jacobian(p, xH).partialPivLu().solve(parameter_derivative(p, xH, ref));
  const int M = problem.intervals();
  Eigen::VectorXd u(problem.size()), hopf_u(problem.size());
  for (int j = 0; j < M; ++j) {
    const double phase = 2 * std::numbers::pi * j / M;  // the first orbit's mesh is uniform
    const Eigen::VectorXcd osc = q * std::polar(1.0, phase);
    for (int i = 0; i < kDim; ++i) {
      u(kDim * j + i) = problem.weight(j) * ((xH(i) + dp * dxdp(i) + 2 * z * osc(i).real()) / D(i));
      hopf_u(kDim * j + i) = problem.weight(j) * (xH(i) / D(i));
    }
  }
  u(problem.period_index()) = hopf_u(problem.period_index()) = 1;
  u(problem.param_index()) = (pH + dp - from) / (to - from);
  hopf_u(problem.param_index()) = (pH - from) / (to - from);
  problem.set_phase(u);
  // Corrected at a fixed projection on the normal form's direction (its amplitude), the
  // parameter free: well conditioned, where a fixed parameter is not (near omega_H the
  // amplitude at fixed p is determined only through l1 |z|^2, model.md §17.3).
  const Eigen::VectorXd fix = (u - hopf_u).normalized();
  const auto first = arclength::correct(problem, u, fix);
  if (!first.converged())
    return fail(first.status, fmt::format("the first orbit near {} = {:.10g} (from the normal form) did not converge: {}",
                                          to_string(ref), pH + dp, first.reason));
  Eigen::VectorXd first_u = first.u;
  out.intervals = M;
  if (problem.radau() && !refine_steps(problem, first_u, o, out))
    return out;
  problem.set_phase(first_u);
  const arclength::Start<Problem> st =
      arclength::start(problem, first_u, Eigen::VectorXd(first_u - hopf_u), false);
  const auto r = arclength::trace(problem, st.u, st.tangent, st.jacobian, o.continuation);
  out.orbits = std::move(problem.orbits_);
  out.specials = std::move(problem.specials_);
  out.end = r.end;
  out.steps = r.stats.steps;
  out.newton_iterations = r.stats.newton_iterations;
  out.flow_evaluations = problem.flows();
  out.state_flow_evaluations = problem.state_flows();
  out.state_steps = problem.state_steps();
  out.newton_steps = problem.newton_steps();
  out.floquet_steps = problem.floquet_steps();
  out.extrapolated_matrices = problem.extrapolations();
  out.remeshes = problem.remeshes();
  out.intervals = problem.intervals();
  if (r.end != arclength::End::end_of_interval) {
    out.status.merge(r.status == Outcome::converged ? Outcome::converged : r.status, "see reason");
    const double last = out.orbits.empty() ? pH : out.orbits.back().parameter;
    out.reason = fmt::format("{} after {} = {:.10g}: {}", to_string(r.end), to_string(ref), last, r.reason);
  }
  return out;
}

}  // namespace

}  // namespace abu
