// A balanced sample at another parameter value (docs/model.md §10.16).
#include "abu/equilibria/balanced_closure.hpp"

#include <cmath>
#include <complex>

namespace abu {

std::optional<EquilibriumN> balanced_sample_at(const ParamsN& p, const Coordinates<long double, any_balls>& near,
                                               int member) {
  using ld = long double;
  const int n = ball_count(p);
  if (n < 3 || near.size() != 2 + n) return std::nullopt;
  auto a = [&](int i) { return ld(p.balls[std::size_t(i)].mass) * ld(p.balls[std::size_t(i)].race_radius); };
  ld scale = ld(p.rotor.unbalance);
  std::complex<ld> R = ld(p.rotor.unbalance);  // U + the held balls' part of W
  for (int i = 2; i < n; ++i) R += a(i) * std::polar(ld(1), near(2 + i)), scale += a(i);
  scale += a(0) + a(1);
  ld b1 = near(2), b2 = near(3);
  bool converged = false;
  for (int it = 0; it < 30; ++it) {
    // W(b1, b2) = R + a1 e^{i b1} + a2 e^{i b2}; dW/db_j = i a_j e^{i b_j}; 2 x 2 Newton (Cramer).
    const std::complex<ld> W = R + a(0) * std::polar(ld(1), b1) + a(1) * std::polar(ld(1), b2);
    if (std::abs(W) <= ld(1e-15) * scale) {
      converged = true;
      break;
    }
    const ld j11 = -a(0) * std::sin(b1), j12 = -a(1) * std::sin(b2);
    const ld j21 = a(0) * std::cos(b1), j22 = a(1) * std::cos(b2);
    const ld det = j11 * j22 - j12 * j21;
    if (!(std::abs(det) > ld(1e-12) * a(0) * a(1))) break;  // collinear: balls 1, 2 do not fix the set
    b1 -= (W.real() * j22 - j12 * W.imag()) / det;
    b2 -= (j11 * W.imag() - j21 * W.real()) / det;
  }
  if (!converged) return std::nullopt;
  EquilibriumN e;
  e.family = Family::balanced;
  e.member = member;
  e.on_balanced_set = true;
  e.position = near;
  e.position(0) = 0;
  e.position(1) = 0;
  e.position(2) = b1;
  e.position(3) = b2;
  e.converged = true;
  e.status = {};
  return e;
}

}  // namespace abu
