// The prescribed spin speed omega(t) of a simulation (model.md §9): constant, a linear
// ramp, or a piecewise-linear profile read from a file. Between breakpoints the angular
// acceleration omega' is constant, so the integrator restarts at each breakpoint (where
// omega' jumps) and the vector field is smooth in between; after the last breakpoint the
// speed is held.
//
//   auto ramp = abu::SpeedProfile::ramp(100.0, 400.0, 200.0);   // 100 -> 400 rad/s at 200 rad/s^2
//   double w = ramp.omega(0.5), wd = ramp.omega_dot(0.5);       // 200 rad/s, 200 rad/s^2
//   double theta = ramp.angle(0.5);                              // spin angle, fixed frame
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace abu {

class SpeedProfile {
 public:
  struct Point {
    double t;      ///< [s]
    double omega;  ///< [rad/s]
  };

  /// omega(t) = omega for all t. Throws InputError(origin, 0, key, rule) unless omega > 0.
  static SpeedProfile constant(double omega, const std::string& origin = "--set", const std::string& key = "omega");
  /// From omega0 at t = 0 to omega1 at |omega1 - omega0| / alpha, then held. alpha > 0
  /// is the magnitude of the angular acceleration [rad/s^2] (a run-down if omega1 <
  /// omega0). omega0 = 0 is a run-up from rest. Throws InputError unless omega0 >= 0,
  /// omega1 > 0 and alpha > 0 (finite).
  static SpeedProfile ramp(double omega0, double omega1, double alpha, const std::string& origin = "--ramp");
  /// Parses "OMEGA0:OMEGA1:ALPHA" (the --ramp option), each value times `to_rad_per_s` (the
  /// speeds typed in rpm or Hz, the acceleration in the same unit per second). Throws InputError.
  static SpeedProfile parse_ramp(std::string_view text, const std::string& origin = "--ramp", double to_rad_per_s = 1.0);
  /// Points (t, omega), t strictly increasing from t = 0, every omega > 0; linear in
  /// between, held after the last. Throws InputError naming `origin` and the point.
  static SpeedProfile piecewise_linear(std::vector<Point> points, const std::string& origin);
  /// Reads a profile file: one `t, omega` pair a line (comma or blank separated), `#`
  /// comments and one optional header line `t,omega`. Throws InputError(file, line, ...).
  static SpeedProfile load(const std::string& path);

  const std::vector<Point>& points() const { return points_; }
  bool is_constant() const;
  /// omega(t) [rad/s]; t < 0 gives omega(0).
  double omega(double t) const;
  /// omega'(t) [rad/s^2], right-continuous: the slope of the segment that starts at or
  /// before t (0 after the last point).
  double omega_dot(double t) const;
  /// The spin angle theta(t) = integral_0^t omega [rad] (x_fixed = R(theta) q, model.md §2.3).
  double angle(double t) const;
  double max_omega() const;
  double min_omega() const;
  /// The end of the last varying segment [s] (0 for a constant speed).
  double end_of_change() const;
  /// Breakpoints strictly inside (t0, t1): where omega' jumps.
  std::vector<double> breakpoints(double t0, double t1) const;
  /// Times in [0, t_end] at which omega(t) = value (each crossing once, in order).
  std::vector<double> crossings(double value, double t_end) const;
  /// "constant 900 rad/s", "ramp 100 -> 400 rad/s at 200 rad/s^2", "profile FILE (K points)".
  std::string describe() const;

 private:
  std::vector<Point> points_;
  std::string description_;
  std::size_t segment(double t) const;  // index i with points_[i].t <= t < points_[i+1].t (last if beyond)
};

}  // namespace abu
