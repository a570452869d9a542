// Finite-element shaft: element matrices, discs, bearings, assembly (model.md §18.1–§18.4).
#include "abu/model/shaft.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace abu {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

double area(const ShaftElement& e) {
  return std::numbers::pi / 4.0 * (e.outer_diameter * e.outer_diameter - e.inner_diameter * e.inner_diameter);
}
/// Second moment of area about a diameter, pi (D^4 - d^4) / 64 (the polar one is twice it).
double area_moment(const ShaftElement& e) {
  const double D2 = e.outer_diameter * e.outer_diameter, d2 = e.inner_diameter * e.inner_diameter;
  return std::numbers::pi / 64.0 * (D2 * D2 - d2 * d2);
}

/// Plane p (0: (u1, psi2), 1: (u2, -psi1)) of node k: the dof of the deflection w and of
/// the section rotation theta, and theta's sign (model.md (18.4.1)).
struct PlaneDofs {
  int w, theta;
  double theta_sign;
};
PlaneDofs plane_dofs(int node, int plane) {
  return plane == 0 ? PlaneDofs{4 * node + 0, 4 * node + 3, 1.0} : PlaneDofs{4 * node + 1, 4 * node + 2, -1.0};
}

/// The global dof and sign of local plane dof i (0..3: w_k, theta_k, w_k+1, theta_k+1).
std::pair<int, double> local_dof(int element, int plane, int i) {
  const PlaneDofs d = plane_dofs(element + i / 2, plane);
  return i % 2 == 0 ? std::pair{d.w, 1.0} : std::pair{d.theta, d.theta_sign};
}

/// X placed in both planes: P1 X P1^T + P2 X P2^T (model.md (18.4.2)).
void add_both_planes(Triplets& t, int element, const Eigen::Matrix4d& x) {
  for (int plane = 0; plane < 2; ++plane)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        if (x(i, j) == 0.0) continue;
        const auto [gi, si] = local_dof(element, plane, i);
        const auto [gj, sj] = local_dof(element, plane, j);
        t.emplace_back(gi, gj, si * sj * x(i, j));
      }
}

/// The gyroscopic coupling of the two planes: P1 R P2^T - P2 R P1^T with R = int I_p' N_theta^T N_theta
/// (model.md (18.4.4)): skew.
void add_gyroscopic(Triplets& t, int element, const Eigen::Matrix4d& r) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      if (r(i, j) == 0.0) continue;
      const auto [a1, s1] = local_dof(element, 0, i);
      const auto [b2, s2] = local_dof(element, 1, j);
      t.emplace_back(a1, b2, s1 * s2 * r(i, j));
      const auto [a2, t2] = local_dof(element, 1, i);
      const auto [b1, t1] = local_dof(element, 0, j);
      t.emplace_back(a2, b1, -t2 * t1 * r(i, j));
    }
}

Eigen::SparseMatrix<double> to_sparse(int n, const Triplets& t) {
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  m.prune(0.0);
  m.makeCompressed();
  return m;
}

}  // namespace

double shear_coefficient(const ShaftElement& e) {
  if (e.shear_modulus <= 0.0) return 0.0;
  // Cowper, "The shear coefficient in Timoshenko's beam theory", J. Appl. Mech. 33
  // (1966) 335, table 1, hollow circular section with m = d_inner / d_outer:
  //   kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2)
  // (solid: 6 (1 + nu) / (7 + 6 nu); thin tube m -> 1: 2 (1 + nu) / (4 + 3 nu)).
  const double nu = e.youngs_modulus / (2.0 * e.shear_modulus) - 1.0;
  const double m = e.inner_diameter / e.outer_diameter, m2 = m * m;
  const double s = (1.0 + m2) * (1.0 + m2);
  return 6.0 * (1.0 + nu) * s / ((7.0 + 6.0 * nu) * s + (20.0 + 12.0 * nu) * m2);
}

BeamElementMatrices beam_element_matrices(const ShaftElement& e) {
  // The interdependent-interpolation element (Nelson, "A finite rotating shaft element
  // using Timoshenko beam theory", J. Mech. Des. 102 (1980) 793; Friswell et al.,
  // Dynamics of Rotating Machines (2010) §5.4): the shape functions are the exact static
  // solution of the Timoshenko beam, so Phi -> 0 gives the cubic Hermite element of
  // Euler–Bernoulli with consistent mass. Derived from the shape functions by
  // tests/reference/shaft_elements.py, which compares these closed forms (model.md §18.1).
  const double L = e.length, A = area(e), I = area_moment(e);
  const double kappa = shear_coefficient(e);
  const double phi = kappa > 0.0 ? 12.0 * e.youngs_modulus * I / (kappa * e.shear_modulus * A * L * L) : 0.0;
  const double p1 = 1.0 + phi, p2 = phi * phi;
  BeamElementMatrices out;
  out.shear_parameter = phi;

  {  // translational mass rho A L / (1 + Phi)^2 [m1 m2 m3 m4; m2 m5 -m4 m6; m3 -m4 m1 -m2; m4 m6 -m2 m5]
    const double m1 = 13.0 / 35 + 7.0 / 10 * phi + p2 / 3;
    const double m2 = (11.0 / 210 + 11.0 / 120 * phi + p2 / 24) * L;
    const double m3 = 9.0 / 70 + 3.0 / 10 * phi + p2 / 6;
    const double m4 = -(13.0 / 420 + 3.0 / 40 * phi + p2 / 24) * L;
    const double m5 = (1.0 / 105 + phi / 60 + p2 / 120) * L * L;
    const double m6 = -(1.0 / 140 + phi / 60 + p2 / 120) * L * L;
    out.translational_mass << m1, m2, m3, m4,  //
        m2, m5, -m4, m6,                        //
        m3, -m4, m1, -m2,                       //
        m4, m6, -m2, m5;
    out.translational_mass *= e.density * A * L / (p1 * p1);
  }
  {  // rotary inertia rho I / (L (1 + Phi)^2) [r1 r2 -r1 r2; r2 r3 -r2 r4; -r1 -r2 r1 -r2; r2 r4 -r2 r3]
    const double r1 = 6.0 / 5;
    const double r2 = (1.0 / 10 - phi / 2) * L;
    const double r3 = (2.0 / 15 + phi / 6 + p2 / 3) * L * L;
    const double r4 = (-1.0 / 30 - phi / 6 + p2 / 6) * L * L;
    out.rotary_mass << r1, r2, -r1, r2,  //
        r2, r3, -r2, r4,                  //
        -r1, -r2, r1, -r2,                //
        r2, r4, -r2, r3;
    out.rotary_mass *= e.density * I / (L * p1 * p1);
  }
  {  // E I / (L^3 (1 + Phi)) [12 6L -12 6L; 6L (4+Phi)L^2 -6L (2-Phi)L^2; ...]
    const double L2 = L * L;
    out.stiffness << 12, 6 * L, -12, 6 * L,            //
        6 * L, (4 + phi) * L2, -6 * L, (2 - phi) * L2,  //
        -12, -6 * L, 12, -6 * L,                        //
        6 * L, (2 - phi) * L2, -6 * L, (4 + phi) * L2;
    out.stiffness *= e.youngs_modulus * I / (L2 * L * p1);
  }
  return out;
}

std::optional<std::string> shaft_spec_violation(const ShaftSpec& spec) {
  const int nodes = spec.nodes();
  auto node_ok = [&](int k) { return k >= 0 && k < nodes; };
  for (std::size_t i = 0; i < spec.elements.size(); ++i) {
    const ShaftElement& e = spec.elements[i];
    const auto bad = [&](const char* rule) { return fmt::format("shaft element {}: {}", i + 1, rule); };
    if (!(e.length > 0.0) || !std::isfinite(e.length)) return bad("length must be > 0");
    if (!(e.outer_diameter > 0.0) || !std::isfinite(e.outer_diameter)) return bad("outer diameter must be > 0");
    if (!(e.inner_diameter >= 0.0) || !(e.inner_diameter < e.outer_diameter))
      return bad("inner diameter must be >= 0 and < the outer diameter");
    if (!(e.youngs_modulus > 0.0) || !std::isfinite(e.youngs_modulus)) return bad("Young's modulus must be > 0");
    if (!(e.density >= 0.0) || !std::isfinite(e.density)) return bad("density must be >= 0");
    if (!(e.shear_modulus >= 0.0) || !std::isfinite(e.shear_modulus)) return bad("shear modulus must be >= 0");
    if (e.shear_modulus > 0.0) {
      const double nu = e.youngs_modulus / (2.0 * e.shear_modulus) - 1.0;
      if (!(nu > -1.0 && nu < 0.5)) return bad("Poisson's ratio E/(2G) - 1 must be in (-1, 0.5)");
    }
  }
  for (std::size_t i = 0; i < spec.discs.size(); ++i) {
    const ShaftDisc& d = spec.discs[i];
    if (!node_ok(d.node)) return fmt::format("disc {}: node {} is not in [0, {}]", i + 1, d.node, nodes - 1);
    if (!(d.mass >= 0.0) || !(d.polar_inertia >= 0.0) || !(d.transverse_inertia >= 0.0) || !std::isfinite(d.mass) ||
        !std::isfinite(d.polar_inertia) || !std::isfinite(d.transverse_inertia))
      return fmt::format("disc {}: mass and inertias must be finite and >= 0", i + 1);
  }
  for (std::size_t i = 0; i < spec.bearings.size(); ++i) {
    const ShaftBearing& b = spec.bearings[i];
    if (!node_ok(b.node)) return fmt::format("bearing {}: node {} is not in [0, {}]", i + 1, b.node, nodes - 1);
    for (double v : {b.stiffness, b.damping, b.tilt_stiffness, b.tilt_damping})
      if (!(v >= 0.0) || !std::isfinite(v))
        return fmt::format("bearing {}: stiffness and damping must be finite and >= 0", i + 1);
    if (const auto& a = b.anisotropic) {  // model.md §18.19: the rules of §10.1, the means in K and C
      if (auto why = stiffness_matrix_violation(a->k_x, a->k_y, a->k_xy)) return fmt::format("bearing {}: {}", i + 1, *why);
      if (auto why = damping_matrix_violation(a->c_x, a->c_y, a->c_xy)) return fmt::format("bearing {}: {}", i + 1, *why);
      if (b.stiffness != a->mean_stiffness() || b.damping != a->mean_damping())
        return fmt::format("bearing {}: stiffness and damping must be the means of K_f and C_f (model.md §18.19)", i + 1);
    }
  }
  if (!node_ok(spec.balancer_node))
    return fmt::format("balancer node {} is not in [0, {}]", spec.balancer_node, nodes - 1);
  bool disc_at_balancer = false;
  for (const ShaftDisc& d : spec.discs) disc_at_balancer = disc_at_balancer || d.node == spec.balancer_node;
  if (!disc_at_balancer) return fmt::format("balancer node {} carries no disc", spec.balancer_node);
  // Every dof needs inertia (model.md §18.9): the element mass matrices are positive
  // definite on their dofs when rho > 0 and the discs' on theirs, so M is positive
  // definite iff every diagonal entry is > 0.
  const ShaftMatrices m = assemble_shaft(spec);
  static constexpr const char* names[] = {"u1", "u2", "psi1", "psi2"};
  for (int k = 0; k < spec.dofs(); ++k)
    if (!(m.mass.coeff(k, k) > 0.0))
      return fmt::format("node {}: dof {} has no inertia (massless shaft and no disc mass or transverse inertia there); "
                         "a massless node is not condensed (model.md §18.9)",
                         k / 4, names[k % 4]);
  return std::nullopt;
}

bool has_anisotropic_bearings(const ShaftSpec& spec) {
  for (const ShaftBearing& b : spec.bearings)
    if (b.anisotropic) return true;
  return false;
}

ShaftMatrices assemble_shaft(const ShaftSpec& spec) {
  const int n = spec.dofs();
  Triplets mass, stiffness, damping, gyroscopic;
  for (int el = 0; el < int(spec.elements.size()); ++el) {
    const BeamElementMatrices m = beam_element_matrices(spec.elements[el]);
    add_both_planes(mass, el, m.translational_mass + m.rotary_mass);
    add_both_planes(stiffness, el, m.stiffness);
    // Polar inertia per length 2 rho I: the element's gyroscopic matrix is twice its rotary mass.
    add_gyroscopic(gyroscopic, el, 2.0 * m.rotary_mass);
  }
  for (const ShaftDisc& d : spec.discs) {
    const int k = 4 * d.node;
    mass.emplace_back(k, k, d.mass);
    mass.emplace_back(k + 1, k + 1, d.mass);
    mass.emplace_back(k + 2, k + 2, d.transverse_inertia);
    mass.emplace_back(k + 3, k + 3, d.transverse_inertia);
    // I_d psi1'' + Omega I_p psi2' = M1,  I_d psi2'' - Omega I_p psi1' = M2   (18.2.2)
    gyroscopic.emplace_back(k + 2, k + 3, d.polar_inertia);
    gyroscopic.emplace_back(k + 3, k + 2, -d.polar_inertia);
  }
  for (const ShaftBearing& b : spec.bearings) {
    const int k = 4 * b.node;
    for (int i = 0; i < 2; ++i) {
      stiffness.emplace_back(k + i, k + i, b.stiffness);
      damping.emplace_back(k + i, k + i, b.damping);
      stiffness.emplace_back(k + 2 + i, k + 2 + i, b.tilt_stiffness);
      damping.emplace_back(k + 2 + i, k + 2 + i, b.tilt_damping);
    }
  }
  return {to_sparse(n, mass), to_sparse(n, stiffness), to_sparse(n, damping), to_sparse(n, gyroscopic)};
}

std::string describe_shaft(const ShaftSpec& spec, std::string_view prefix) {
  std::string out = fmt::format("{}flexible shaft (model.md §18): {} nodes, balancer at node {}\n", prefix, spec.nodes(),
                                spec.balancer_node);
  for (std::size_t e = 0; e < spec.elements.size(); ++e) {
    const ShaftElement& el = spec.elements[e];
    out += fmt::format("{}element {} (nodes {}-{}): length {} m, outer {} m, inner {} m, E {} Pa, rho {} kg/m^3, G {} Pa\n",
                       prefix, e, e, e + 1, el.length, el.outer_diameter, el.inner_diameter, el.youngs_modulus,
                       el.density, el.shear_modulus);
  }
  for (const ShaftDisc& d : spec.discs)
    out += fmt::format("{}disc at node {}: mass {} kg, I_p {} kg m^2, I_d {} kg m^2\n", prefix, d.node, d.mass,
                       d.polar_inertia, d.transverse_inertia);
  for (const ShaftBearing& b : spec.bearings) {
    if (const auto& a = b.anisotropic)  // the fixed-frame matrices on (n1, n2), model.md §18.19
      out += fmt::format("{}bearing at node {}: K_f [[{}, {}], [{}, {}]] N/m, C_f [[{}, {}], [{}, {}]] N s/m, k_psi {} "
                         "N m/rad, c_psi {} N m s/rad\n",
                         prefix, b.node, a->k_x, a->k_xy, a->k_xy, a->k_y, a->c_x, a->c_xy, a->c_xy, a->c_y,
                         b.tilt_stiffness, b.tilt_damping);
    else
      out += fmt::format("{}bearing at node {}: k {} N/m, c {} N s/m, k_psi {} N m/rad, c_psi {} N m s/rad\n", prefix,
                         b.node, b.stiffness, b.damping, b.tilt_stiffness, b.tilt_damping);
  }
  return out;
}

}  // namespace abu
