// Anisotropic bearings on a flexible shaft (docs/model.md §18.19): the scene keys, the
// deviatoric bearing force in simulate's field against the fixed-frame force written out here,
// the Jacobian and df/dt against differences of the field, an isotropic bearing in the matrix
// form against the same bearing written `stiffness = k`, and the one-node shaft against the rigid
// simulate on the anisotropic support. The fixed-frame scipy reference of a four-element shaft
// is tests/reference/shaft_aniso_reference.py.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "../src/dynamics/shaft_field.hpp"  // internal to src/dynamics: the field alone
#include "abu/analysis/shaft_states.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/input/scene.hpp"
#include "abu/model/shaft_bearings.hpp"

namespace {

using abu::ShaftSystem;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

const char* const kFour = "tests/scenes/shaft/aniso_four_elements.toml";
const char* const kOneNode = "tests/scenes/shaft/one_node_aniso.toml";

ShaftSystem system_of(const std::string& relative, double omega) {
  abu::Scene scene = abu::load_scene(std::string(ABU_SOURCE_DIR) + "/" + relative);
  scene.omega = omega;
  return abu::shaft_system_of(scene);
}

// A state of natural size: translations ~ L, tilts ~ L / 0.1 m, angles in [0, 2 pi), rates
// times omega; the balls' rates ~ 5 % of omega (as tests/test_shaft_simulation.cpp).
Eigen::VectorXd random_state(const ShaftSystem& sys, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double L = abu::displacement_scale(abu::shaft_summary_params(sys)), w = sys.balancer.omega;
  const int d = sys.configuration_size(), ns = sys.shaft_dofs();
  Eigen::VectorXd x(2 * d);
  for (int i = 0; i < d; ++i) {
    const double size = i >= ns ? 3.0 : (i % 4 < 2 ? L : 10.0 * L);
    x(i) = (i >= ns ? 3.0 + size * unit(rng) : size * unit(rng));
    x(d + i) = (i >= ns ? 0.05 : 1.0) * w * size * unit(rng);
  }
  return x;
}

double natural_size(const ShaftSystem& sys, int i) {
  const double L = abu::displacement_scale(abu::shaft_summary_params(sys)), w = sys.balancer.omega;
  const int d = sys.configuration_size(), ns = sys.shaft_dofs(), c = i % d;
  const double size = c >= ns ? 3.0 : (c % 4 < 2 ? L : 10.0 * L);
  return i < d ? size : (c >= ns ? 0.05 : 1.0) * w * size;
}

Eigen::Matrix2d rotation(double theta) {
  Eigen::Matrix2d R;
  R << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  return R;
}

// The generalized force of the bearings' deviatoric part on the configuration at spin angle
// theta, from the FIXED frame: the node's translation U = R u, velocity U' = R (u' + omega J u),
// the bearing force -K_f U - C_f U', back on the rotating axes by R^T, less the mean part
// -k_bar u - c_bar (u' + omega J u) that the shaft's matrices hold (model.md (18.19.1)).
Eigen::VectorXd deviatoric_force(const ShaftSystem& sys, const Eigen::VectorXd& x, double omega, double theta) {
  const int d = sys.configuration_size();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(d);
  const Eigen::Matrix2d R = rotation(theta);
  Eigen::Matrix2d J;
  J << 0, -1, 1, 0;
  for (const auto& b : sys.spec.bearings) {
    if (!b.anisotropic) continue;
    const auto& s = *b.anisotropic;
    Eigen::Matrix2d K, C;
    K << s.k_x, s.k_xy, s.k_xy, s.k_y;
    C << s.c_x, s.c_xy, s.c_xy, s.c_y;
    const int k = 4 * b.node;
    const Eigen::Vector2d u = x.segment<2>(k), v = x.segment<2>(d + k) + omega * J * x.segment<2>(k);
    const Eigen::Vector2d fixed = -K * (R * u) - C * (R * v);
    g.segment<2>(k) += R.transpose() * fixed + s.mean_stiffness() * u + s.mean_damping() * v;
  }
  return g;
}

// max over the acceleration half of |a_i - b_i| / max_j |b_j| over the block of i.
double block_error(const ShaftSystem& sys, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const int d = sys.configuration_size(), ns = sys.shaft_dofs();
  const auto block = [&](int i) { return i >= ns ? 2 : (i % 4 < 2 ? 0 : 1); };
  double scale[3] = {0, 0, 0}, worst = 0;
  for (int i = 0; i < d; ++i) scale[block(i)] = std::max(scale[block(i)], std::abs(b(d + i)));
  for (int i = 0; i < d; ++i) worst = std::max(worst, std::abs(a(d + i) - b(d + i)) / scale[block(i)]);
  return worst;
}

}  // namespace

TEST_CASE("shaft aniso: [[bearing]] takes the fixed-frame matrices, their means go into K and C", "[shaft_aniso]") {
  const ShaftSystem sys = system_of(kFour, 600.0);
  REQUIRE(sys.spec.bearings.size() == 2);
  const abu::ShaftBearing& b = sys.spec.bearings[0];
  REQUIRE(b.anisotropic);
  CHECK(b.anisotropic->k_x == 2.2e4);
  CHECK(b.anisotropic->k_xy == 1.5e3);
  CHECK(b.anisotropic->c_y == 8.0);
  CHECK(b.stiffness == 2.0e4);  // (k_x + k_y) / 2, exact in binary here
  CHECK(b.damping == 10.0);
  CHECK(abu::has_anisotropic_bearings(sys.spec));
  CHECK(sys.fixed.stiffness.coeff(0, 1) == 0.0);  // the mean is isotropic: no cross term in K
  const std::string text = abu::describe_shaft(sys.spec, "# ");
  CHECK_THAT(text, Catch::Contains("bearing at node 0: K_f [[22000, 1500], [1500, 18000]] N/m, C_f [[12, 1], [1, 8]]"));
  abu::ShaftSpec broken = sys.spec;
  broken.bearings[0].anisotropic->k_xy = 3e4;  // det < 0
  CHECK_THAT(*abu::shaft_spec_violation(broken), Catch::Contains("bearing 1: K_f") && Catch::Contains("positive definite"));
  broken = sys.spec;
  broken.bearings[1].stiffness = 1.0;  // not the mean of its K_f
  CHECK_THAT(*abu::shaft_spec_violation(broken), Catch::Contains("bearing 2: stiffness and damping must be the means"));
}

TEST_CASE("shaft aniso: the field adds the fixed-frame bearing force turned onto the rotating axes", "[shaft_aniso]") {
  // f = the mean shaft's field (shaft_field, sparse LDL^T of A) + A^-1 (g, 0), g the deviatoric
  // force written above from the fixed frame. Two routes to A^-1 of the same right-hand side:
  // ~cond(A) eps, 1e-9 of a block's largest entry (as the isotropic check in
  // test_shaft_simulation.cpp); a wrong sign or angle of the deviator is O(1e-2) of the block.
  std::mt19937 rng(5);
  for (const char* scene : {kFour, kOneNode}) {
    CAPTURE(scene);
    const ShaftSystem sys = system_of(scene, 600.0);
    abu::shaft_detail::ShaftOde ode(sys);
    for (const double theta : {0.0, 0.7, 2.9}) {
      CAPTURE(theta);
      ode.set_speed(600.0, 0.0);
      ode.set_angle(theta);
      const Eigen::VectorXd x = random_state(sys, rng);
      Eigen::VectorXd f(x.size());
      REQUIRE(ode.field(x.data(), f.data()));
      const int d = sys.configuration_size();
      Eigen::VectorXd ref = abu::shaft_field(sys, x);
      const Eigen::MatrixXd A = Eigen::MatrixXd(abu::shaft_mass_matrix(sys, x.head(d)));
      ref.tail(d) += A.llt().solve(deviatoric_force(sys, x, 600.0, theta));
      CHECK(f.head(d) == ref.head(d));
      CHECK(block_error(sys, f, ref) <= 1e-9);
      // The deviator matters here: without it the field differs by far more than the tolerance.
      CHECK(block_error(sys, abu::shaft_field(sys, x), ref) > 1e-6);
    }
  }
}

TEST_CASE("shaft aniso: the Jacobian and df/dt are the field's derivatives", "[shaft_aniso]") {
  // The bearings' share of J, J - J(mean shaft) (the mean shaft's J is checked in
  // test_shaft_simulation.cpp), against central differences of the share of the field,
  // g = f - f(mean shaft), with steps 1e-3 of each component's natural size: g is linear in u, u'
  // and smooth in beta, truncation ~1e-7 and rounding eps |f| / h, measured ~1e-9 of the share's
  // largest entry; 1e-4 of it still catches a missing block (C_dev on u' is ~1e-3 of it). df/dt =
  // omega' df/domega + omega df/dtheta against a central difference in t along omega(t), theta(t)
  // (step 1e-7 s: truncation and rounding ~1e-9 of the largest entry, measured <= 4e-6), to 1e-4 of it.
  std::mt19937 rng(13);
  for (const char* scene : {kFour, kOneNode}) {
    for (const double omega_dot : {0.0, 2.0e4}) {
      CAPTURE(scene, omega_dot);
      const ShaftSystem sys = system_of(scene, 600.0);
      abu::ShaftSpec mean_spec = sys.spec;
      for (auto& b : mean_spec.bearings) b.anisotropic.reset();  // stiffness, damping: the means
      const ShaftSystem mean = abu::make_shaft_system(mean_spec, sys.balancer);
      abu::shaft_detail::ShaftOde ode(sys), ode_mean(mean);
      const Eigen::VectorXd x = random_state(sys, rng);
      const int dim = int(x.size());
      const double w = 600.0, theta = 1.1;
      RowMajor jac(dim, dim), jac_mean(dim, dim);
      Eigen::VectorXd dfdt(dim), dfdt_mean(dim);
      ode.set_speed(w, omega_dot);
      ode.set_angle(theta);
      ode_mean.set_speed(w, omega_dot);
      REQUIRE(ode.jacobian(x.data(), jac.data(), dfdt.data()));
      REQUIRE(ode_mean.jacobian(x.data(), jac_mean.data(), dfdt_mean.data()));
      const RowMajor share = jac - jac_mean;
      const auto f = [&](const Eigen::VectorXd& at, double t) {  // along omega(t), theta(t) from t = 0
        Eigen::VectorXd out(dim);
        ode.set_speed(w + omega_dot * t, omega_dot);
        ode.set_angle(theta + w * t + 0.5 * omega_dot * t * t);
        REQUIRE(ode.field(at.data(), out.data()));
        return out;
      };
      const auto g = [&](const Eigen::VectorXd& at) {
        Eigen::VectorXd out(dim);
        REQUIRE(ode_mean.field(at.data(), out.data()));
        return Eigen::VectorXd(f(at, 0.0) - out);
      };
      double worst = 0;
      for (int j = 0; j < dim; ++j) {
        const double h = 1e-3 * natural_size(sys, j);
        Eigen::VectorXd xp = x, xm = x;
        xp(j) += h;
        xm(j) -= h;
        const Eigen::VectorXd difference = (g(xp) - g(xm)) / (2 * h), column = share.col(j);
        worst = std::max(worst, (column - difference).cwiseAbs().maxCoeff());
      }
      CHECK(worst <= 1e-4 * share.cwiseAbs().maxCoeff());
      CHECK(share.cwiseAbs().maxCoeff() > 0.0);
      const double ht = 1e-7;
      const Eigen::VectorXd dt = (f(x, ht) - f(x, -ht)) / (2 * ht);
      CHECK((dfdt - dt).cwiseAbs().maxCoeff() <= 1e-4 * dt.cwiseAbs().maxCoeff());
      CHECK(dt.cwiseAbs().maxCoeff() > 0.0);
    }
  }
}

TEST_CASE("shaft aniso: an isotropic bearing in the matrix form runs the isotropic trajectory", "[shaft_aniso]") {
  // stiffness_x = stiffness_y = k, xy = 0 gives K_dev = R^T (k I) R - k I = 0 up to the rounding of
  // cos^2 + sin^2 (~1e-16 k), so the field differs from the isotropic one by rounding only and the
  // adaptive run by rounding carried through continuous step-size decisions: 1e-12 of the scaled
  // size (L + |q|, rad) leaves a factor ~1e3 over eps for the growth over the run, while any real
  // deviator (1 % of k) moves q by ~1e-3 of L.
  const ShaftSystem iso = system_of("tests/scenes/shaft/sim_four_elements.toml", 600.0);
  abu::ShaftSpec spec = iso.spec;
  for (auto& b : spec.bearings) b.anisotropic = abu::AnisotropicSupport{b.stiffness, b.stiffness, 0.0, b.damping, b.damping, 0.0};
  const ShaftSystem matrix = abu::make_shaft_system(spec, iso.balancer);
  const double L = abu::displacement_scale(abu::shaft_summary_params(iso));
  for (const auto& speed : {abu::SpeedProfile::constant(600.0), abu::SpeedProfile::ramp(300.0, 600.0, 3.0e4)}) {
    CAPTURE(speed.describe());
    abu::SimulationOptions o;
    o.t_end = 0.03;
    o.every = 5e-4;
    o.rtol = 1e-9;
    o.method = abu::IntegrationMethod::rk8pd;
    const auto a = abu::simulate_shaft(iso, speed, abu::shaft_start_at_rest(iso, {0.5, 2.0, 4.0}), o);
    const auto b = abu::simulate_shaft(matrix, speed, abu::shaft_start_at_rest(matrix, {0.5, 2.0, 4.0}), o);
    REQUIRE(a.run.status == abu::SimulationStatus::completed);
    REQUIRE(b.run.status == abu::SimulationStatus::completed);
    REQUIRE(a.run.samples.size() == b.run.samples.size());
    double worst_q = 0, worst_beta = 0;
    for (std::size_t k = 0; k < a.run.samples.size(); ++k) {
      const auto &p = a.run.samples[k].x, &q = b.run.samples[k].x;
      const double size = L + std::hypot(p(0), p(1));
      worst_q = std::max({worst_q, std::abs(p(0) - q(0)) / size, std::abs(p(1) - q(1)) / size});
      for (int i = 0; i < 3; ++i) worst_beta = std::max(worst_beta, std::abs(p(2 + i) - q(2 + i)));
    }
    CHECK(worst_q <= 1e-12);
    CHECK(worst_beta <= 1e-12);
  }
}

TEST_CASE("shaft aniso: a one-node shaft runs the rigid anisotropic trajectory", "[shaft_aniso]") {
  // model.md §18.9 with §18.19: one disc on one anisotropic bearing is the rigid rotor on the
  // anisotropic support of §10 (its field (20.1)) plus a decoupled tilt pair; both turn the
  // support with theta(t) = integral of omega, a1 = n1 at t = 0. Each route keeps its global error
  // within ~8 rtol of the scaled size (model.md §15.1), so they agree to 2 x 8 rtol: 20 rtol
  // (L + |q|) on q and 20 rtol rad on beta (as the isotropic reduction, test_shaft_simulation.cpp).
  const ShaftSystem sys = system_of(kOneNode, 900.0);
  const abu::AnisotropicSupport support = *sys.spec.bearings[0].anisotropic;
  abu::ParamsN rigid = sys.balancer;
  rigid.rotor.mass = sys.spec.discs[0].mass;
  rigid.rotor.stiffness = support.mean_stiffness();
  rigid.rotor.damping = support.mean_damping();
  const double L = abu::displacement_scale(rigid), rtol = 1e-9;
  for (const auto& speed : {abu::SpeedProfile::constant(900.0), abu::SpeedProfile::ramp(300.0, 900.0, 3000.0)}) {
    CAPTURE(speed.describe());
    abu::SimulationOptions o;
    o.t_end = 0.3;
    o.every = 1e-3;
    o.rtol = rtol;
    o.method = abu::IntegrationMethod::rk8pd;
    const auto s = abu::simulate_shaft(sys, speed, abu::shaft_start_at_rest(sys, {2.0, 4.0}), o);
    abu::SimulationOptions ro = o;
    ro.support = &support;
    const auto r = abu::simulate(rigid, speed, abu::start_at_rest(rigid, std::vector<double>{2.0, 4.0}), ro);
    REQUIRE(s.run.status == abu::SimulationStatus::completed);
    REQUIRE(r.status == abu::SimulationStatus::completed);
    REQUIRE(s.run.samples.size() == r.samples.size());
    double worst_q = 0, worst_beta = 0, largest_q = 0;
    for (std::size_t k = 0; k < r.samples.size(); ++k) {
      REQUIRE(s.run.samples[k].t == r.samples[k].t);
      const auto &a = s.run.samples[k].x, &b = r.samples[k].x;
      const double size = L + std::hypot(b(0), b(1));
      largest_q = std::max(largest_q, std::hypot(b(0), b(1)) / L);
      worst_q = std::max({worst_q, std::abs(a(0) - b(0)) / size, std::abs(a(1) - b(1)) / size});
      worst_beta = std::max({worst_beta, std::abs(a(2) - b(2)), std::abs(a(3) - b(3))});
    }
    CHECK(worst_q <= 20 * rtol);
    CHECK(worst_beta <= 20 * rtol);
    CHECK(largest_q > 0.1);  // the rotor moves: the comparison is not of two resting states
    CHECK(s.x_end(2) == 0.0);  // the tilts: nothing couples them to the rest
    CHECK(s.x_end(3) == 0.0);
  }
}
