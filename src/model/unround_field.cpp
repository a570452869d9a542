// model.md §11.3 / §15.6: the unround race's field for integration, its analytic Jacobian
// and its omega derivative (see unround_field.hpp).
#include "abu/model/unround_field.hpp"

#include <cmath>

#include "abu/model/machine_field.hpp"

namespace abu {

double path_third_derivative(const RaceHarmonics& h, double l, double beta) {
  // l = E H (11.1.1): l''' = E''' H + 3 E'' H' + 3 E' H'' + E H'''. The offset circle
  // (x = beta - phi_1, S = sqrt(l^2 - d^2 sin^2 x), S' = -d^2 sin 2x / (2 S)), differentiating
  // E'' of (11.1.3) once more:
  //   E''' = d sin x + 2 d^2 sin 2x / S - 3 d^4 sin 4x / (4 S^3) - 3 d^6 sin^3 2x / (8 S^5)   (15.6.3)
  double e0 = l, e1 = 0, e2 = 0, e3 = 0;
  double h0 = 1, h1 = 0, h2 = 0, h3 = 0;
  for (const auto& harmonic : h) {
    if (harmonic.amplitude == 0.0) continue;
    if (harmonic.order == 1) {
      const double d = l * harmonic.amplitude, x = beta - harmonic.phase;
      const double sx = std::sin(x), cx = std::cos(x), s2 = std::sin(2 * x), c2 = std::cos(2 * x);
      const double S = std::sqrt(l * l - d * d * sx * sx), d2 = d * d, d4 = d2 * d2;
      e0 = d * cx + S;
      e1 = -d * sx - d2 * sx * cx / S;
      e2 = -d * cx - d2 * c2 / S - d4 * sx * sx * cx * cx / (S * S * S);
      e3 = d * sx + 2 * d2 * s2 / S - 0.75 * d4 * std::sin(4 * x) / (S * S * S) -
           0.375 * d4 * d2 * s2 * s2 * s2 / (S * S * S * S * S);
    } else {
      const double k = harmonic.order, arg = k * beta - harmonic.phase, eps = harmonic.amplitude;
      const double c = std::cos(arg), s = std::sin(arg);
      h0 += eps * c;
      h1 -= eps * k * s;
      h2 -= eps * k * k * c;
      h3 += eps * k * k * k * s;
    }
  }
  return e3 * h0 + 3 * e2 * h1 + 3 * e1 * h2 + e0 * h3;
}

// The unround race alone: the composed field of machine_field.hpp without the support's
// anisotropy (one implementation of (11.3.3)-(11.3.4), (15.6.1)-(15.6.5)).
State<double, any_balls> unround_vector_field(const ParamsN& p, const RaceShape& race, const State<double, any_balls>& x,
                                              double omega_dot) {
  MachineFieldValue v;
  machine_field(p, RigidMachine{&race, nullptr}, x, 0.0, omega_dot, v, false);
  return v.field;
}

StateMatrix<double, any_balls> unround_jacobian(const ParamsN& p, const RaceShape& race,
                                                const State<double, any_balls>& x, double omega_dot) {
  MachineFieldValue v;
  machine_field(p, RigidMachine{&race, nullptr}, x, 0.0, omega_dot, v, true);
  return v.jacobian;
}

State<double, any_balls> unround_omega_derivative(const ParamsN& p, const RaceShape& race,
                                                  const State<double, any_balls>& x) {
  MachineFieldValue v;
  machine_field(p, RigidMachine{&race, nullptr}, x, 0.0, 0.0, v, true);
  return v.omega_derivative;
}

}  // namespace abu
