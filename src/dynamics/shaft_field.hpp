// Internal to simulate_shaft (shaft_simulation.cpp): the first-order field of the flexible
// rotor with its balls in the rotating frame, at constant speed (model.md §18.6) and during a
// run-up (the omega' terms of §18.16), and its Jacobian for the implicit steppers; the balls on a
// round race or on an unround race's paths (their share of the composed rigid machine at the
// balancer node, model.md §18.20).
//
// The field solves A(beta) s'' = b by the structure of A (model.md (18.16.3)): M_tot is
// constant, so M_tot^-1 is formed once (dense, 4 N_nodes squared); the balls couple to the
// shaft only at the balancer node, so per evaluation there is one dense product with M_tot^-1,
// a few sparse products with K, C, G and an n x n Cholesky of the balls' Schur complement.
// Nothing is allocated per field evaluation; a Jacobian evaluation allocates the sparse
// matrices of linearize_shaft (O(nnz K + nnz M) entries).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "abu/model/model.hpp"
#include "abu/model/shaft_bearings.hpp"
#include "abu/model/shaft_system.hpp"
#include "abu/model/unround_race.hpp"

namespace abu::shaft_detail {

/// The stiffness probe's figures [1/s]: the fastest decay max |Re lambda| (what an implicit
/// stepper can step over) and the fastest underdamped oscillation max |Im lambda| over
/// |Im| > |Re| (what every stepper must follow: the shaft's bending and tilt modes).
struct StiffnessProbe {
  double decay = 0, oscillation = 0;
};

class ShaftOde {
 public:
  /// `race` null or round(): the balls on circles (18.6.2); otherwise on the race's paths
  /// (model.md §18.20; copied).
  explicit ShaftOde(const ShaftSystem& sys, const RaceShape* race = nullptr);

  int dim() const { return 2 * d_; }
  int configuration_size() const { return d_; }
  /// omega(t) and omega' of the current segment of the speed profile.
  void set_speed(double omega, double omega_dot) {
    omega_ = omega;
    omega_dot_ = omega_dot;
  }
  double omega() const { return omega_; }
  double omega_dot() const { return omega_dot_; }
  /// The spin angle theta(t) [rad] that turns the anisotropic bearings' deviatoric part (model.md
  /// §18.19): their fixed axes n1, n2 are a1, a2 at theta = 0. Unused without them.
  void set_angle(double theta) { theta_ = theta; }
  bool anisotropic() const { return !bearings_.empty(); }
  bool unround() const { return unround_; }

  /// f = (s', s'') at the state y (size dim()). Returns false if a value is not finite or the
  /// balls' Schur complement is not positive definite (it is whenever A is, §18.6).
  bool field(const double* y, double* f);

  /// J = df/dx (row-major dim x dim) and df/dt = omega' df/domega + omega df/dtheta at y. False
  /// if not finite.
  bool jacobian(const double* y, double* dfdy, double* dfdt);

  /// The eigenvalues of J at y (dense) in two figures (model.md §18.16).
  StiffnessProbe probe(const double* y);

  unsigned long rhs_count = 0, jacobian_count = 0;

 private:
  void add_deviator(const double* u, const double* ud);  // the anisotropic bearings' share of w (18.19.5)
  // The balls' terms at the balancer node: coupling rows Bq (2 x n), inertia diag(D), the node's
  // force (f1, f2) and the ball rows b_beta; round (18.6.2), (9.2)-(9.4) or on the race (18.20.1).
  struct BallTerms;
  void round_ball_terms(const double* y, BallTerms& t) const;
  void race_ball_terms(const double* y, BallTerms& t);
  // A, C, K at y into mass_ and kc_: round (18.7.1)-(18.7.2) with (18.16.4), or on the race
  // (18.20.3); false if the field is not finite.
  bool round_matrices(const double* y);
  bool race_matrices(const double* y);
  void add_runup_shaft_stiffness();  // K_shaft += omega' (M_tot Jr + G / 2) (18.16.4)
  void rigid_view(const double* y, State<double, any_balls>& x) const;  // (q, beta, q', beta')
  ShaftSystem sys_;  // sys_.balancer.omega follows set_speed for linearize_shaft
  int ns_, n_, d_, b_;
  Eigen::SparseMatrix<double> k_, c_, g_;
  Eigen::MatrixXd minv_;  // M_tot^-1, ns x ns
  Eigen::Matrix2d h_;     // its balancer-node block
  double omega_ = 0, omega_dot_ = 0, theta_ = 0;
  // The anisotropic bearings (model.md §18.19): the node's u1 index and K_f, C_f; the field adds
  // their deviatoric force unless `deviator_on_` is off (the Jacobian's reference field).
  struct Bearing {
    int dof;
    AnisotropicSupport support;
  };
  std::vector<Bearing> bearings_;
  bool deviator_on_ = true;
  // An unround race (model.md §18.20): its paths and the rigid-layout work storage (bounded).
  RaceShape race_;
  bool unround_ = false;
  State<double, any_balls> rigid_x_;
  DofMatrix<double, any_balls> share_mass_;
  Coordinates<double, any_balls> share_force_;
  Eigen::VectorXd theta_rhs_;  // Jacobian work: -dw/dtheta, then df/dtheta's lower half (size d)
  // Per ball: a_i = m_i l_i, j_i m_i l_i^2, l_i, the run-up moment m_i l_i (l_i - (j_i - 1) r_i) (9.4).
  std::vector<double> a_, inertia_, l_, euler_;
  Eigen::VectorXd v_, w_, acc_;  // work vectors, ns
  // Jacobian work (allocated at the first evaluation, reused).
  Eigen::MatrixXd mass_, kc_, sol_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  std::vector<double> f_plus_, f_minus_, f_still_;
};

}  // namespace abu::shaft_detail
