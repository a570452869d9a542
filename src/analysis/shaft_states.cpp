// The states of a flexible shaft with their rightmost eigenvalues (shaft_states.hpp).
#include "abu/analysis/shaft_states.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "abu/core/cancel.hpp"
#include "abu/core/errors.hpp"
#include "abu/input/shaft_scene.hpp"
#include "abu/equilibria/shaft_race_equilibria.hpp"
#include "abu/model/shaft_race.hpp"
#include "abu/scan/shaft_map.hpp"

namespace abu {

using cplx = std::complex<double>;

double shaft_band(const ShaftSpectrumOptions& o, double omega) { return o.band > 0 ? o.band : 10.0 * omega; }

ShaftSystem shaft_system_of(const Scene& scene) {
  const ParamsN p = params_of<any_balls>(scene);
  try {
    return make_shaft_system(shaft_spec_of(scene), p);
  } catch (const std::invalid_argument& e) {
    // The scene reader checks the model's rules with file and line (shaft_scene.hpp); one it
    // missed is still bad input, named here.
    throw InputError(scene.file, 0, "shaft", e.what());
  }
}

ShaftState analyze_shaft_state(const ShaftSystem& sys, const ShaftEquilibrium& e, const ShaftSpectrumOptions& o,
                               bool vectors, const RaceShape* race) {
  ShaftState pt;
  pt.eq = e;
  const Eigen::VectorXd& s = e.position;
  const int b = sys.balancer_dof();
  pt.q_abs = std::hypot(s[b], s[b + 1]);
  for (int k = 0; k < sys.nodes(); ++k) {
    const double d = std::hypot(s[4 * k], s[4 * k + 1]);
    if (d > pt.max_deflection) pt.max_deflection = d, pt.max_node = k;
  }
  pt.spectrum = race ? pencil_rightmost(shaft_pencil(linearize_shaft_on_race(sys, *race, s)), sys.balancer.omega,
                                        o.eigenvalues, o.band, vectors, &pt.merged)  // model.md (18.18.2)
                     : shaft_rightmost(sys, e.state(), o.eigenvalues, o.band, vectors, &pt.merged);
  // The verdict's rule and the structural zeros set aside: scan/shaft_map.hpp (shared with `map`).
  ShaftVerdict v = shaft_verdict(pt.spectrum, e.structural_zeros);
  pt.structural = std::move(v.structural);
  pt.rightmost = v.abscissa;
  const SpectrumCoverage& c = pt.spectrum.coverage;
  const std::string cover =
      c.empty() ? std::string("nothing covered")
                : fmt::format("covered: every eigenvalue with {:.6g} <= Re <= {:.6g} and |Im| <= {:.6g} 1/s is listed "
                              "({})",
                              c.real_min, c.real_max, c.imag_max, c.how);
  pt.verdict = v.verdict;
  if (v.verdict == "unstable") {
    pt.verdict_text = fmt::format("unstable: an eigenvalue with Re = {:.6g} 1/s > 0 was found", pt.rightmost);
  } else if (v.verdict == "stable") {
    pt.verdict_text = fmt::format(
        "stable as far as covered: every listed eigenvalue has Re < 0 (rightmost {:.6g} 1/s){}; {}. Eigenvalues with "
        "|Im| above the band or Re above {:.6g} 1/s are not excluded",
        pt.rightmost,
        e.structural_zeros
            ? fmt::format(", {} structural zero(s) set aside{}", e.structural_zeros,
                          v.zero_copies ? fmt::format(" and {} value(s) indistinguishable from 0 beside them (relative "
                                                      "residual >= 1: copies of the zero, model.md §19.7)",
                                                      v.zero_copies)
                                        : std::string())
            : "",
        cover, c.real_max);
  } else {
    pt.verdict_text = fmt::format(
        "undetermined: {}; {}",
        !v.doubt.empty()        ? std::string_view(v.doubt)
        : pt.spectrum.status.ok() ? std::string_view("the covered region does not reach Re >= 0")
                                  : pt.spectrum.status.reason.view(),
        cover);
  }
  return pt;
}

ShaftStates analyze_shaft_states(const ShaftSystem& sys, const BalancedSampling& sampling,
                                 const ShaftSpectrumOptions& o) {
  ShaftStates out{sys, o, {}, {}, {}, {}};
  const ShaftEquilibriumSet set = find_shaft_equilibria(sys, sampling);
  for (const auto& e : set.list) {
    throw_if_stopped("equilibria (shaft)");
    if (!e.status.ok())
      out.warnings += fmt::format("warning: omega={}: a {} equilibrium's polish: {} (residual {:.3g})\n",
                                  sys.balancer.omega, to_string(e.family), e.status.reason, e.residual);
    out.states.push_back(analyze_shaft_state(sys, e, o, false));
    const ShaftState& pt = out.states.back();
    if (!pt.spectrum.status.ok())
      out.warnings += fmt::format("warning: omega={}: {} equilibrium: ARPACK: {} ({} eigenvalue(s) found)\n",
                                  sys.balancer.omega, to_string(e.family), pt.spectrum.status.reason,
                                  pt.spectrum.eigenpairs.size());
  }
  if (!set.status.ok())
    out.warnings += fmt::format("warning: omega={}: shaft equilibria: {}\n", sys.balancer.omega, set.status.reason);
  for (const auto& pt : out.states)
    if (pt.spectrum.eigenpairs.empty())
      throw NumericalError(fmt::format("omega={}: ARPACK found no eigenvalue of a {} equilibrium: {}",
                                       sys.balancer.omega, to_string(pt.eq.family), pt.spectrum.status.reason));
  return out;
}

ShaftStates analyze_shaft_race_states(const ShaftSystem& sys, const RaceShape& race, const ShaftSpectrumOptions& o) {
  ShaftStates out{sys, o, {}, {}, {}, race};
  const ShaftRaceEquilibria set = find_shaft_race_equilibria(sys, race);
  out.race_complete = set.doubt.empty();
  if (!set.doubt.empty()) out.warnings += fmt::format("warning: omega={}: {}\n", sys.balancer.omega, set.doubt);
  for (const auto& e : set.list) {
    throw_if_stopped("equilibria (shaft, unround race)");
    if (!e.status.ok())
      out.warnings += fmt::format("warning: omega={}: race equilibrium {}'s polish: {} (residual {:.3g})\n",
                                  sys.balancer.omega, e.member, e.status.reason, e.residual);
    out.states.push_back(analyze_shaft_state(sys, e, o, false, &race));
    const ShaftState& pt = out.states.back();
    if (!pt.spectrum.status.ok())
      out.warnings += fmt::format("warning: omega={}: race equilibrium {}: ARPACK: {} ({} eigenvalue(s) found)\n",
                                  sys.balancer.omega, e.member, pt.spectrum.status.reason, pt.spectrum.eigenpairs.size());
    if (pt.spectrum.eigenpairs.empty())
      throw NumericalError(fmt::format("omega={}: ARPACK found no eigenvalue of race equilibrium {}: {}",
                                       sys.balancer.omega, e.member, pt.spectrum.status.reason));
  }
  if (!set.status.ok())
    out.warnings += fmt::format("warning: omega={}: shaft equilibria: {}\n", sys.balancer.omega, set.status.reason);
  return out;
}

double shaft_forward_share(const ShaftSystem& sys, const Eigen::SparseMatrix<double>& mass, const Eigen::VectorXd& s,
                           const Eigen::VectorXcd& v) {
  double fwd = 0.0, all = 0.0;
  auto add = [&](double m, cplx a1, cplx a2) {
    const cplx wp = (a1 + cplx(0, 1) * a2) / 2.0;
    const cplx wm = (std::conj(a1) + cplx(0, 1) * std::conj(a2)) / 2.0;
    fwd += m * std::norm(wp);
    all += m * (std::norm(wp) + std::norm(wm));
  };
  // Translations and tilts of every node: both pairs turn with the frame (model.md §18.5), and
  // the diagonal of A weighs them by their kinetic energy (kg for u, kg m^2 for psi).
  for (int k = 0; k < sys.nodes(); ++k) {
    add(mass.coeff(4 * k, 4 * k), v[4 * k], v[4 * k + 1]);
    add(mass.coeff(4 * k + 2, 4 * k + 2), v[4 * k + 2], v[4 * k + 3]);
  }
  const int b = sys.balancer_dof();
  for (int i = 0; i < sys.n_balls(); ++i) {
    const auto& ball = sys.balancer.balls[std::size_t(i)];
    const double beta = s[sys.ball_dof(i)];
    const cplx db = v[sys.ball_dof(i)];
    add(ball.mass, v[b] - ball.race_radius * std::sin(beta) * db, v[b + 1] + ball.race_radius * std::cos(beta) * db);
  }
  return all > 0 ? fwd / all : 0.5;
}

}  // namespace abu
