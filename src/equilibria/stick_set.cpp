// The stick set of set-valued Coulomb friction and its worst residual vibration
// (model.md §14): the smooth equilibria as seeds, then the two-ball column method or the
// n-ball grid (stick_set_model.hpp lists the files). See the header for the method.
#include "abu/equilibria/stick_set.hpp"

#include <string>

#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "stick_set_model.hpp"

namespace abu {

using namespace stick_detail;

StickPoint stick_point(const ParamsN& p, const std::vector<double>& beta) {
  const StickModel m(p);
  const cplx q = m.q(beta.data());
  StickPoint out{q.real(), q.imag(), {}};
  for (int i = 0; i < m.n; ++i) out.s.push_back(m.s(q, i, beta[std::size_t(i)]));
  return out;
}

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
      seeds.push_back(sd);
    }
  }
  StickSet S = m.n == 2 ? two_ball_set(m, options, std::move(seeds)) : sampled_set(m, options, std::move(seeds));
  const double bare = std::abs(m.G) * m.U;
  S.bare_rotor_q_abs = bare;
  return S;
}

}  // namespace abu
