// Equilibria of the flexible rotor with its balls (model.md §18.8).
//
//  balanced  the whole shaft undeflected (u = 0), the balls at a balanced state of the
//            rigid model with the same U (equilibria_n.hpp: W(beta) = 0); for n >= 3
//            samples of the (n - 2)-dimensional set, as there.
//  aligned   every ball on the line of the balancer node's deflection q. The shaft
//            answers a force at the balancer node through its complex receptance h(omega):
//            q = h omega^2 W(beta), so the balls see a rigid rotor with the dynamic
//            stiffness K_eff + i C_eff = 1/h; the rigid closed forms of model.md §13.2 with
//            K, C replaced give every aligned equilibrium, the shaft's deflection follows
//            from one sparse solve, and Newton on the full sparse static equations
//            polishes it (status, residual).
//
//   abu::ShaftEquilibriumSet set = abu::find_shaft_equilibria(sys);
//   for (const auto& e : set.list) ... e.position (s = (u, beta)), e.residual, e.status ...
#pragma once

#include <complex>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "abu/core/status.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/model/shaft_system.hpp"

namespace abu {

/// One equilibrium: s = (u, beta), all speeds 0. Fields as EquilibriumT's.
struct ShaftEquilibrium {
  Family family = Family::balanced;
  unsigned pattern = 0;  ///< aligned: bit i set when ball i + 1 is opposite phi
  int member = 1;        ///< root of the pattern (1, 2), or balanced sample index
  Eigen::VectorXd position;  ///< s = (u (4 N_nodes), beta_1..beta_n), beta in [0, 2 pi)
  /// Normwise backward error of the static equations b(s, 0) = 0:
  /// max_i |b_i| / max_i (|K_s| |s| + |f|)_i (model.md §18.8); 0 for an exact zero.
  double residual = 0.0;
  int newton_iterations = 0;
  Status status{Outcome::not_converged, "not polished"};
  bool is_set = false;           ///< representative of a circle (U = 0)
  bool on_balanced_set = false;  ///< sample of the balanced set of n >= 3 balls
  int structural_zeros = 0;      ///< as EquilibriumT::structural_zeros
  /// An equilibrium of an unround race (model.md §18.18): `member` is its place in the race's
  /// list (by |q|); family and pattern are not read.
  bool on_unround_race = false;

  Eigen::VectorXd state() const;  ///< (s, 0)
};

struct ShaftEquilibriumSet {
  std::vector<ShaftEquilibrium> list;  ///< balanced samples, then aligned by pattern, member
  unsigned degeneracy = degeneracy_none;
  BalancedSetSummary balanced_set;
  /// K_eff + i C_eff = 1/h(omega) at the balancer node [N/m] (model.md §18.8); nullopt
  /// when the rotating-frame stiffness is singular (an undamped critical speed): then no
  /// aligned equilibria are listed and `status` says why.
  std::optional<std::complex<double>> dynamic_stiffness;
  Status status{};  ///< the worst of the aligned solves and polishes
};

/// Every equilibrium (balanced samples and every aligned one).
ShaftEquilibriumSet find_shaft_equilibria(const ShaftSystem& sys, const BalancedSampling& sampling = {});

/// The complex receptance H_k of every node's translation to a force at the balancer node,
/// u1_k + i u2_k = H_k (F1 + i F2) (model.md (18.17.2)); H at the balancer node is h of
/// (18.8.1). nullopt if the rotating-frame stiffness is singular (an undamped critical speed).
std::optional<Eigen::VectorXcd> node_receptances(const ShaftSystem& sys);

/// K_eff + i C_eff = 1/h(omega) at the balancer node, from the sparse rotating-frame
/// stiffness of rotating_matrices (balls' mass included); nullopt if it is singular.
std::optional<std::complex<double>> balancer_dynamic_stiffness(const ShaftSystem& sys);

/// The rigid balancer whose support has the given dynamic stiffness: the same balls, law,
/// omega and U; rotor.mass = the balancer disc's mass, stiffness and damping chosen so
/// that k - omega^2 M = Re, c omega = Im (model.md §18.8). Its equilibria are the
/// shaft's, node q = u at the balancer node.
ParamsN equivalent_rigid_params(const ShaftSystem& sys, std::complex<double> dynamic_stiffness);

/// The shaft equilibrium of a rigid one of equivalent_rigid_params: u = h omega^2 W(beta)
/// solved on the whole shaft, then Newton on the sparse static equations.
ShaftEquilibrium shaft_equilibrium_from_rigid(const ShaftSystem& sys, const EquilibriumN& rigid);

}  // namespace abu
