// The Campbell view on an anisotropic support (docs/model.md §10.15): the balanced states'
// Floquet modes as fixed-frame whirl frequencies, against the isotropic views (k_x = k_y)
// and against the bare rotor's fixed-frame eigenvalues (§10.7's "rotor alone").
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/Eigenvalues>

#include "abu/linear/floquet_modes.hpp"
#include "abu/linear/modes.hpp"
#include "abu/scan/scan.hpp"

using namespace abu;
using cd = std::complex<double>;

namespace {

// BASE of docs/model.md §10.8 (two or more viscous balls).
ParamsN base(int n = 2) {
  ParamsN p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = FrictionLaw::viscous;
  p.balls.resize(std::size_t(n));
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 1e-3, 0.001, 0.003, 0.1};
  if (n == 3) {
    // Unequal balls: equal ones have equal ball-mode rates, a degenerate eigenvalue whose
    // eigenvectors (and so the shares) are any combination; the comparison needs them distinct.
    p.balls[1].mass = 2.9e-5;
    p.balls[2].mass = 2.5e-5;
    p.rotor.unbalance = 9e-7;  // a balanced set with room (capacity 1.57e-6)
  }
  return p;
}

// The isotropic analysis' balanced equilibria with their mode views (model.md §16).
struct IsoState {
  EquilibriumN e;
  std::vector<ModeView> modes;
};
std::vector<IsoState> isotropic_balanced(const ParamsN& p) {
  const AnalysisN a = analyze(p, BalancedSampling{4});  // a few samples of the set (n >= 3)
  std::vector<IsoState> out;
  const auto points = a.equilibria.points();
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (points[k].family != Family::balanced && !points[k].on_balanced_set) continue;
    IsoState s{points[k], {}};
    for (const ModeView& m : mode_views(p, points[k].position, a.spectra[k]))
      if (m.kind != ModeKind::set_direction) s.modes.push_back(m);
    out.push_back(s);
  }
  return out;
}

}  // namespace

// k_x = k_y, c_x = c_y, no cross terms: J(t) = J0, Hill's matrix is block diagonal, and every
// Floquet mode must be an isotropic mode (16.1)-(16.3): same fixed-frame eigenvalue, shares and
// label, whichever ladder member Hill reports. Tolerance 1e-9 of omega on frequencies (Hill
// and the isotropic refinement are both ~1e-12 accurate) and 1e-7 on the shares, which
// divide eigenvector norms (each ~1e-10 relative).
TEST_CASE("floquet campbell: k_x = k_y gives the isotropic Campbell values", "[floquet_campbell]") {
  for (int n : {2, 3}) {
    for (double omega : {150.0, 260.0, 900.0}) {
      ParamsN p = base(n);
      p.omega = omega;
      const AnisotropicSupport iso{p.rotor.stiffness, p.rotor.stiffness, 0.0, p.rotor.damping, p.rotor.damping, 0.0};
      const std::vector<IsoState> states = isotropic_balanced(p);
      REQUIRE(!states.empty());
      for (const IsoState& s : states) {
        const FloquetModes f = floquet_mode_views(p, iso, s.e);
        REQUIRE(f.status.ok());
        INFO("n = " << n << ", omega = " << omega << ", member " << s.e.member);
        REQUIRE(f.modes.size() == s.modes.size());
        for (const ModeView& m : f.modes) {
          const auto it = std::min_element(s.modes.begin(), s.modes.end(), [&](const ModeView& a, const ModeView& b) {
            return std::abs(a.fixed - m.fixed) < std::abs(b.fixed - m.fixed);
          });
          INFO("Floquet mode " << m.fixed << " against isotropic " << it->fixed);
          CHECK(std::abs(it->fixed - m.fixed) <= 1e-9 * omega);
          CHECK(it->whirl_frequency == Approx(m.whirl_frequency).margin(1e-9 * omega));
          CHECK(it->damping_ratio == Approx(m.damping_ratio).margin(1e-9));
          CHECK(it->rotor_share == Approx(m.rotor_share).margin(1e-7));
          CHECK(it->forward_share == Approx(m.forward_share).margin(1e-7));
          CHECK(it->common_share == Approx(m.common_share).margin(1e-7));
          CHECK(it->kind == m.kind);
        }
      }
    }
  }
}

// The bare anisotropic rotor (balls of 1e-10 kg, U below their capacity): its fixed-frame
// equation M z'' + C_f z' + K_f z = 0 does not depend on omega (no gyroscopic terms), so the
// Campbell diagram's two rotor modes are horizontal lines at the imaginary parts of the
// eigenvalues mu of [[0, I], [-K_f/M, -C_f/M]] (§10.7), with zeta = -Re mu/|mu|. With C_f = 0
// they are the two bearing frequencies sqrt(k_x/M), sqrt(k_y/M): the split at omega -> 0 and
// at every speed. Tolerance 1e-6 relative: the balls' coupling (2 m l / U-order, 1e-10 kg
// balls) and Hill's truncation (1e-12) are far below it.
TEST_CASE("floquet campbell: the bare anisotropic rotor whirls at its bearing frequencies at every speed",
          "[floquet_campbell]") {
  for (const bool damped : {false, true}) {
    ParamsN p = base(2);
    // d scaled with the mass: the ball rates stay BASE's (~70 1/s) instead of 2e10 1/s, which
    // would only make Hill's matrix stiff (long double) without changing the rotor's lines.
    for (auto& b : p.balls) b.d *= 1e-10 / b.mass, b.mass = 1e-10;
    p.rotor.unbalance = 2e-12;  // capacity 3.6e-12: a balanced state exists
    const double kx = 8100.0, ky = 6900.0, kxy = damped ? 250.0 : 0.0;
    const double cx = damped ? 2.4 : 0.0, cy = damped ? 1.6 : 0.0, cxy = damped ? 0.15 : 0.0;
    const AnisotropicSupport s{kx, ky, kxy, cx, cy, cxy};
    p.rotor.stiffness = s.mean_stiffness();
    p.rotor.damping = s.mean_damping();
    const double M = p.total_mass();
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topRightCorner<2, 2>().setIdentity();
    A.bottomLeftCorner<2, 2>() << -kx / M, -kxy / M, -kxy / M, -ky / M;
    A.bottomRightCorner<2, 2>() << -cx / M, -cxy / M, -cxy / M, -cy / M;
    const Eigen::Vector4cd mu = A.eigenvalues();
    std::vector<cd> expected;
    for (const cd& m : mu)
      if (m.imag() > 0) expected.push_back(m);
    REQUIRE(expected.size() == 2);
    if (!damped) {
      std::sort(expected.begin(), expected.end(), [](cd a, cd b) { return a.imag() < b.imag(); });
      CHECK(expected[0].imag() == Approx(std::sqrt(ky / M)).epsilon(1e-12));
      CHECK(expected[1].imag() == Approx(std::sqrt(kx / M)).epsilon(1e-12));
    }
    const double omega_n = std::sqrt(s.mean_stiffness() / M);
    // From omega_n/4 (the harmonics' coupling |kappa|/(4 M omega^2) = 0.35 there) through the
    // split to 4 omega_n.
    for (const double ratio : {0.25, 0.97, 1.5, 4.0}) {
      p.omega = ratio * omega_n;
      const AnalysisN analysis = analyze(p);
      const auto points = analysis.equilibria.points();
      int checked = 0;
      for (const EquilibriumN& e : points) {
        if (e.family != Family::balanced) continue;
        const FloquetModes f = floquet_mode_views(p, s, e);
        REQUIRE(f.status.ok());
        std::vector<const ModeView*> rotor;
        for (const ModeView& m : f.modes)
          if (m.rotor_share >= 0.5) rotor.push_back(&m);
        INFO("damped " << damped << ", omega/omega_n = " << ratio << ", N = " << f.harmonics);
        REQUIRE(rotor.size() == 2);
        for (const cd& want : expected) {
          const auto it = std::min_element(rotor.begin(), rotor.end(), [&](const ModeView* a, const ModeView* b) {
            return std::abs(std::abs(a->whirl_frequency) - want.imag()) < std::abs(std::abs(b->whirl_frequency) - want.imag());
          });
          CHECK(std::abs((*it)->whirl_frequency) == Approx(want.imag()).epsilon(1e-6));
          CHECK((*it)->fixed.real() == Approx(want.real()).margin(1e-6 * std::abs(want)));
          CHECK((*it)->damping_ratio == Approx(-want.real() / std::abs(want)).margin(1e-6));
        }
        ++checked;
      }
      CHECK(checked >= 1);
    }
  }
}
