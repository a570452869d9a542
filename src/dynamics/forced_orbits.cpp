// The aligned states on an anisotropic support as pi/omega-periodic orbits: multiple
// shooting over the forcing period, continued in the anisotropy homotopy parameter with
// the arclength engine (forced_orbits.hpp, docs/model.md §10.14).
#include "abu/dynamics/forced_orbits.hpp"

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "abu/core/gsl_errors.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/floquet.hpp"
#include "abu/model/anisotropic_field.hpp"
#include "shooting_flow.hpp"

namespace abu {
namespace {

using StateX = State<double, any_balls>;

// The scaled field y = D^-1 x of (10.14.1) and, with `variational`, the transition matrix
// and the delta sensitivity: Phi' = J~ Phi, z' = J~ z + D^-1 df/ddelta * delta_end.
struct ForcedContext {
  ParamsN p;
  AnisotropicSupport support;
  Eigen::VectorXd scale;  // D
  int dim = 0;            // 2 n + 4
  double delta = 0;       // the homotopy parameter of the current evaluation
  double span = 1;        // d delta / d (scaled parameter) = delta_end
  bool variational = true;
  AnisotropicFieldValue value;  // the last evaluation (bounded storage: no allocation per step)
  int augmented() const { return variational ? dim * (dim + 2) : dim; }
  void evaluate(double t, const double* y, bool derivatives) {
    StateX x(dim);
    for (int i = 0; i < dim; ++i) x(i) = scale(i) * y[i];
    anisotropic_field(p, support, x, t, delta, value, derivatives);
  }
};

int forced_rhs(double t, const double y[], double dydt[], void* params) {
  auto& c = *static_cast<ForcedContext*>(params);
  const int n = c.dim;
  c.evaluate(t, y, c.variational);
  for (int i = 0; i < n; ++i) dydt[i] = c.value.field(i) / c.scale(i);
  if (c.variational) {
    // J~ = D^-1 J D applied to every column; the last column also gets D^-1 f_delta.
    for (int k = 0; k <= n; ++k) {
      const double* col = y + n * (1 + k);
      double* out = dydt + n * (1 + k);
      for (int i = 0; i < n; ++i) {
        double sum = 0;
        for (int j = 0; j < n; ++j) sum += c.value.jacobian(i, j) * c.scale(j) * col[j];
        out[i] = sum / c.scale(i);
      }
      if (k == n)
        for (int i = 0; i < n; ++i) out[i] += c.value.delta_derivative(i) * c.span / c.scale(i);
    }
  }
  for (int i = 0; i < c.augmented(); ++i)
    if (!std::isfinite(dydt[i])) return GSL_EBADFUNC;
  return GSL_SUCCESS;
}

// For the implicit stepper: J~ on the state and on every variational column (block
// diagonal; the columns' dependence on the state is left out, as in periodic_orbits.cpp:
// it changes the stage solves, not the solution the error control accepts), and df/dt
// of the state.
int forced_jacobian(double t, const double y[], double* dfdy, double dfdt[], void* params) {
  auto& c = *static_cast<ForcedContext*>(params);
  const int n = c.dim, dim = c.augmented();
  c.evaluate(t, y, true);
  std::fill(dfdy, dfdy + std::size_t(dim) * std::size_t(dim), 0.0);
  std::fill(dfdt, dfdt + dim, 0.0);
  for (int b = 0; b < dim / n; ++b)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        dfdy[std::size_t(b * n + i) * std::size_t(dim) + std::size_t(b * n + j)] =
            c.value.jacobian(i, j) * c.scale(j) / c.scale(i);
  for (int i = 0; i < n; ++i) dfdt[i] = c.value.time_derivative(i) / c.scale(i);
  if (!c.value.jacobian.allFinite()) return GSL_EBADFUNC;
  return GSL_SUCCESS;
}

using Evaluated = detail::ShootingEvaluation;

class ForcedProblem : public detail::ShootingSystem<ForcedProblem> {
 public:
  static constexpr std::size_t test_count = 1;  // d delta / ds: a fold in delta

  ForcedProblem(const ParamsN& p, const AnisotropicSupport& s, const Eigen::VectorXd& scale,
                const ForcedOrbitOptions& o, const gsl_odeiv2_step_type* type)
      : ShootingSystem(o.rtol, 1e2), o_(o), m_(o.intervals), dim_(int(scale.size())),
        full_(type, dim_ * (dim_ + 2), o.rtol, "forced orbit: integrating an interval"),
        plain_(type, dim_, o.rtol, "forced orbit: sampling") {
    ctx_.p = p;
    ctx_.support = s;
    ctx_.scale = scale;
    ctx_.dim = dim_;
    ctx_.span = o.delta_end;
    period_ = std::numbers::pi / p.omega;
  }

  int size() const { return dim_ * m_ + 1; }
  int param_index() const { return dim_ * m_; }
  double delta(const Vec& u) const { return u(param_index()) * o_.delta_end; }
  double step() const { return period_ / m_; }

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
    ctx_.variational = true;
    ctx_.delta = delta(u);
    const double h = step();
    std::vector<double> y(std::size_t(d * (d + 2)));
    gsl_odeiv2_system sys{&forced_rhs, &forced_jacobian, std::size_t(d * (d + 2)), &ctx_};
    for (int j = 0; j < m_; ++j) {
      std::fill(y.begin(), y.end(), 0.0);
      for (int i = 0; i < d; ++i) y[std::size_t(i)] = u(d * j + i), y[std::size_t(d * (1 + i) + i)] = 1.0;
      std::string_view why;
      if (!full_.run(sys, j * h, y.data(), h, {h}, {}, why)) {
        e.ok = false;
        e.why = why;
        e.residual.setConstant(1e300);
        return e;
      }
      const int next = (j + 1) % m_;
      for (int i = 0; i < d; ++i) e.residual(d * j + i) = y[std::size_t(i)] - u(d * next + i);
      const Eigen::Map<const Eigen::MatrixXd> phi(y.data() + d, d, d);
      e.transitions[std::size_t(j)] = phi;
      e.jacobian.block(d * j, d * j, d, d) = phi;
      e.jacobian.block(d * j, d * next, d, d) -= Eigen::MatrixXd::Identity(d, d);
      for (int i = 0; i < d; ++i) e.jacobian(d * j + i, param_index()) = y[std::size_t(d * (d + 1) + i)];
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

  // The orbit's data at a converged u.
  void describe(const Vec& u, ForcedOrbit& o) {
    const Evaluated& e = at(u);
    o.delta = delta(u);
    o.period = period_;
    const ProductEigenvalues f = product_eigenvalues(e.transitions);
    o.multipliers = f.values;
    o.log_moduli = f.log_moduli;
    o.exponents.clear();
    for (std::size_t k = 0; k < f.values.size(); ++k) {
      // lambda = (omega/pi) (ln|rho| + i arg rho), Im in (-omega, omega] (model.md §10.4).
      o.exponents.emplace_back(f.log_moduli[k] / period_, f.arguments[k] / period_);
    }
    o.band = 1e3 * o_.rtol * m_;
    const double top = f.log_moduli.empty() ? 0.0 : *std::max_element(f.log_moduli.begin(), f.log_moduli.end());
    o.verdict = top < -o.band ? Stability::stable : top > o.band ? Stability::unstable : Stability::marginal;
    if (!f.status.ok()) {
      o.status.merge(f.status);
      o.reason = fmt::format("Floquet multipliers: {}", f.status.reason);
    }
    o.state0.resize(std::size_t(dim_));
    for (int i = 0; i < dim_; ++i) o.state0[std::size_t(i)] = u(i) * ctx_.scale(i);
    sample(u, o);
  }

 private:
  // Uniform samples of the orbit (samples_per_interval per interval): max and mean |q|,
  // the ball angles' extremes, and the periodicity of one run over the whole period
  // from y_1 (the multiple-shooting residual, integrated without restarts).
  void sample(const Vec& u, ForcedOrbit& o) {
    const double h = step();
    const int k = o_.samples_per_interval, n = dim_ / 2 - 2;
    std::vector<double> targets;
    for (int i = 1; i <= k * m_; ++i) targets.push_back(h * i / k);
    std::vector<double> qabs;
    std::vector<std::vector<double>> balls(static_cast<std::size_t>(n));
    ctx_.variational = false;
    ctx_.delta = delta(u);
    std::vector<double> y(static_cast<std::size_t>(dim_));
    for (int i = 0; i < dim_; ++i) y[std::size_t(i)] = u(i);
    gsl_odeiv2_system sys{&forced_rhs, &forced_jacobian, std::size_t(dim_), &ctx_};
    std::string_view why;
    const bool ran = plain_.run(sys, 0.0, y.data(), period_, targets, [&](const double* s) {
      qabs.push_back(std::hypot(s[0] * ctx_.scale(0), s[1] * ctx_.scale(1)));
      for (int b = 0; b < n; ++b) balls[std::size_t(b)].push_back(s[2 + b]);
    }, why);
    if (!ran || qabs.size() != targets.size()) {
      o.status.merge(Outcome::numerical_issue, "see reason");
      o.reason = fmt::format("sampling the orbit: {}", why);
      return;
    }
    o.periodicity = 0;
    for (int i = 0; i < dim_; ++i) o.periodicity = std::max(o.periodicity, std::abs(y[std::size_t(i)] - u(i)));
    o.q_abs_max = detail::periodic_max(qabs);
    double sum = 0;
    for (double v : qabs) sum += v;  // uniform samples of a periodic function: the trapezoid rule
    o.q_abs_mean = sum / double(qabs.size());
    o.ball_min.clear();
    o.ball_max.clear();
    for (auto& v : balls) {
      o.ball_max.push_back(detail::periodic_max(v));
      for (double& x : v) x = -x;
      o.ball_min.push_back(-detail::periodic_max(v));
    }
  }

  ForcedOrbitOptions o_;
  int m_, dim_;
  double period_ = 0;
  mutable ForcedContext ctx_;
  mutable detail::FlowIntegrator full_;
  detail::FlowIntegrator plain_;
  mutable Evaluated cache_;
  bool folded_ = false;
};

static_assert(arclength::Problem<ForcedProblem>);

std::string kind_of(const EquilibriumN& e, int n) {
  if (e.family == Family::aligned) return fmt::format("aligned {} {}", pattern_string(e.pattern, n), e.member);
  return fmt::format("{} {}", to_string(e.family), e.member);
}

}  // namespace

ForcedOrbit forced_orbit(const ParamsN& p, const AnisotropicSupport& s, const EquilibriumN& e,
                         const ForcedOrbitOptions& o) {
  quiet_gsl_errors();
  ForcedOrbit out;
  out.family = e.family;
  out.pattern = e.pattern;
  out.member = e.member;
  const int n = e.n_balls(), d = 2 * n + 4;
  out.kind = kind_of(e, n);
  out.period = std::numbers::pi / p.omega;
  const auto fail = [&](Outcome kind, std::string why) {
    out.status.merge(kind, "see reason");
    out.reason = std::move(why);
    return out;
  };
  if (e.family == Family::balanced) return fail(Outcome::numerical_issue, "a balanced state is an equilibrium, not an orbit");
  if (!e.converged) return fail(Outcome::not_converged, "its equilibrium of the mean system did not converge");
  if (e.singular()) return fail(Outcome::numerical_issue, "its equilibrium of the mean system is singular (degenerate)");
  if (!(o.intervals >= 1) || !(o.delta_end >= 0)) return fail(Outcome::numerical_issue, "bad options");
  // Scaling D (model.md (10.14.3)).
  const double L = displacement_scale(p), w = p.omega;
  Eigen::VectorXd D = Eigen::VectorXd::Ones(d);
  D.segment(n + 2, n + 2).setConstant(w);
  D.head(2) *= L;
  D.segment(n + 2, 2) *= L;
  // Stiff (ball rates far above 1/h): the implicit extrapolation stepper (§17.1's choice).
  const StateX x0 = e.position_si().size() ? at_rest<double, any_balls>(e.position_si()) : StateX();
  Eigen::EigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(jacobian(p, x0)), false);
  const double rho = es.info() == Eigen::Success ? es.eigenvalues().cwiseAbs().maxCoeff() : 0.0;
  const gsl_odeiv2_step_type* type = rho / w > 1e3 ? gsl_odeiv2_step_bsimp : gsl_odeiv2_step_rk8pd;
  ForcedProblem problem(p, s, D, o, type);
  const int M = o.intervals;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  for (int j = 0; j < M; ++j) u.segment(d * j, d) = x0.cwiseQuotient(D);
  // delta = 0: the equilibrium itself solves the shooting equations exactly.
  if (o.delta_end > 0) {
    Eigen::VectorXd inward = Eigen::VectorXd::Zero(problem.size());
    inward(problem.param_index()) = 1;
    const arclength::Start<ForcedProblem> st = arclength::start(problem, u, inward, false);
    const auto r = arclength::trace(problem, st.u, st.tangent, st.jacobian, o.continuation);
    out.steps = r.stats.steps;
    out.newton_iterations = r.stats.newton_iterations;
    if (r.end != arclength::End::end_of_interval) {
      out.delta = problem.delta(r.last);
      return fail(r.status == Outcome::converged ? Outcome::not_converged : r.status,
                  fmt::format("{} at delta = {:.6g}: {}", to_string(r.end), out.delta, r.reason));
    }
    u = r.last;
  }
  problem.describe(u, out);
  return out;
}

}  // namespace abu
