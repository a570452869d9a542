// The stick set of set-valued Coulomb friction and its worst residual vibration
// (model.md §14): the smooth equilibria as seeds, then the two-ball column method or the
// n-ball grid (stick_set_model.hpp lists the files). See the header for the method.
#include "abu/equilibria/stick_set.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "stick_set_model.hpp"

namespace abu {

using namespace stick_detail;

StickPoint stick_point(const ParamsN& p, const std::vector<double>& beta) {
  static const RaceShape round;
  return stick_point(p, round, beta);
}

StickPoint stick_point(const ParamsN& p, const RaceShape& race, const std::vector<double>& beta) {
  const StickModel m(p, &race);
  const cplx q = m.q(beta.data());
  StickPoint out{q.real(), q.imag(), {}};
  for (int i = 0; i < m.n; ++i) out.s.push_back(m.s(q, i, beta[std::size_t(i)]));
  return out;
}

namespace {
// The stick set when a bound proves it is the whole torus (model.md §14.10): |s_i| <=
// |q| / (mu_i l_i) and |q| = |G| |W(beta)| <= |G| (U + sum a_i), so if |G| (U + sum a_i) <=
// min_i mu_i l_i every arrangement sticks: E = T^n, one component holding every smooth
// equilibrium, and max |q| over it is |G| (U + sum a_i), at beta = 0 (every ball with the
// unbalance). nullopt when the bound does not decide.
std::optional<StickSet> whole_torus_by_bound(const StickModel& m, const std::vector<StickSeed>& seeds) {
  double w_max = m.U, min_bound = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m.n; ++i) {
    w_max += m.a[std::size_t(i)];
    min_bound = std::min(min_bound, m.bound[std::size_t(i)]);
  }
  // a margin of 1e-12 for the rounding of the two sides: the bound decides only clear cases
  if (!(std::abs(m.G) * w_max * (1 + 1e-12) <= min_bound)) return std::nullopt;
  StickSet S;
  S.n_balls = m.n;
  S.seeds = seeds;
  S.area = std::pow(two_pi, m.n);
  S.area_fraction = 1.0;
  S.whole_torus = true;
  StickComponent c;
  c.area = S.area;
  c.beta_at_max.assign(std::size_t(m.n), 0.0);
  c.q_abs_max = std::abs(m.q(c.beta_at_max.data()));
  c.wraps = true;
  for (std::size_t k = 0; k < S.seeds.size(); ++k) {
    S.seeds[k].component = 0;
    c.seeds.push_back(int(k));
    if (S.seeds[k].anchor) c.balanced_points.push_back(int(k));
  }
  c.spread.assign(std::size_t(m.n), 0.0);
  S.worst_q_abs_any = c.q_abs_max;
  S.worst_beta_any = c.beta_at_max;
  S.balanced_exists = !c.balanced_points.empty();
  if (S.balanced_exists) {
    S.worst_q_abs = c.q_abs_max;
    S.worst_beta = c.beta_at_max;
  } else {
    S.status = Status{Outcome::not_converged, "no balanced state in the stick set"};
  }
  S.spread.assign(std::size_t(m.n), 0.0);
  S.components.push_back(std::move(c));
  return S;
}
// Every smooth equilibrium is in E (tau = 0, model.md §14.2), and as mu -> 0 its part of E
// shrinks onto it, with a width proportional to mu: below the scan's resolution (mu = 1e-20
// on the default scene: ~1e-20 rad) no column or grid point falls inside, and E came out
// empty, "no balanced state". Such an equilibrium is kept as a component of its own, a point
// of area 0 (below the resolution), |q| its own; V and V_E then hold to O(mu).
void keep_unresolved_seeds(StickSet& S, int n) {
  int added = 0;  // (S.point_components)
  for (std::size_t k = 0; k < S.seeds.size(); ++k) {
    StickSeed& sd = S.seeds[k];
    if (sd.component >= 0) continue;
    StickComponent c;
    c.q_abs_max = sd.q_abs;
    c.beta_at_max = sd.beta;
    c.seeds = {int(k)};
    if (sd.anchor) c.balanced_points = {int(k)};
    c.spread.assign(std::size_t(n), 0.0);
    sd.component = int(S.components.size());
    S.components.push_back(std::move(c));
    ++added;
    if (sd.q_abs > S.worst_q_abs_any) S.worst_q_abs_any = sd.q_abs, S.worst_beta_any = sd.beta;
    if (!sd.anchor) continue;
    if (!S.balanced_exists || sd.q_abs > S.worst_q_abs) S.worst_q_abs = sd.q_abs, S.worst_beta = sd.beta;
    if (!S.balanced_exists) S.status = Status{};  // "no balanced state in the stick set" no longer holds
    S.balanced_exists = true;
  }
  S.point_components = added;
}

}  // namespace

StickSet stick_set(const ParamsN& p, const StickSetOptions& options) {
  const StickModel m(p);
  // the smooth equilibria: tau = 0, always in E (model.md §14.2)
  std::vector<StickSeed> seeds;
  if (m.n == 2) {
    Params p2;
    p2.rotor = p.rotor;
    p2.omega = p.omega;
    p2.law = FrictionLaw::none;
    p2.balls = {p.balls[0], p.balls[1]};
    const EquilibriumSet set = closed_form_equilibria(p2);
    for (const auto& e : set.points()) {
      StickSeed sd;
      sd.family = std::string(to_string(e.family));
      sd.beta = {double(wrap_angle(e.position[2])), double(wrap_angle(e.position[3]))};
      sd.q_abs = std::abs(m.q(sd.beta.data()));
      sd.anchor = e.family == Family::balanced;
      seeds.push_back(sd);
    }
  } else {
    ParamsN pn = p;
    pn.law = FrictionLaw::none;
    const EquilibriumSetN set = find_equilibria(pn, BalancedSampling{});
    for (const auto& e : set.points()) {
      StickSeed sd;
      sd.family = std::string(to_string(e.family));
      for (int i = 0; i < m.n; ++i) sd.beta.push_back(double(wrap_angle(e.position[2 + i])));
      sd.q_abs = std::abs(m.q(sd.beta.data()));
      sd.anchor = e.family == Family::balanced;
      seeds.push_back(sd);
    }
  }
  if (options.verdict_only)
    if (auto whole = whole_torus_by_bound(m, seeds)) {
      whole->bare_rotor_q_abs = std::abs(m.G) * m.U;
      return *whole;
    }
  StickSet S = m.n == 2 ? two_ball_set(m, options, std::move(seeds)) : sampled_set(m, options, std::move(seeds));
  keep_unresolved_seeds(S, m.n);
  const double bare = std::abs(m.G) * m.U;
  S.bare_rotor_q_abs = bare;
  return S;
}

void check_stick_set_defined(const ParamsN& p) {
  static_cast<void>(StickModel(p));  // its constructor refuses what has no stick set
}

bool whole_torus_by_bound(const ParamsN& p) {
  try {
    return whole_torus_by_bound(StickModel(p), {}).has_value();
  } catch (const NotSupportedError&) {
    return false;
  }
}

StickSet stick_set_on_race(const ParamsN& p, const RaceShape& race, std::vector<StickSeed> seeds,
                           const StickSetOptions& options) {
  const StickModel m(p, &race);
  for (StickSeed& sd : seeds) sd.q_abs = std::abs(m.q(sd.beta.data()));
  StickSet S = sampled_set(m, options, std::move(seeds));
  S.unround_race = true;
  S.anchor = "least-|q| stable equilibrium of the race";
  S.bare_rotor_q_abs = std::abs(m.G) * m.U;
  return S;
}

}  // namespace abu
