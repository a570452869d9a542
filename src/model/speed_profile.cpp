// Prescribed spin speed of a simulation (model.md §9): see speed_profile.hpp.
#include "abu/model/speed_profile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "abu/core/errors.hpp"
#include "abu/core/text_file.hpp"

namespace abu {

namespace {
bool parse_real(std::string_view text, double& value) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  if (text.empty()) return false;
  if (text.front() == '+') text.remove_prefix(1);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}
}  // namespace

SpeedProfile SpeedProfile::constant(double omega, const std::string& origin, const std::string& key) {
  if (!(std::isfinite(omega) && omega > 0)) throw InputError(origin, 0, key, "the spin speed must be > 0 rad/s");
  SpeedProfile p;
  p.points_ = {{0.0, omega}};
  p.description_ = fmt::format("constant {} rad/s", omega);
  return p;
}

SpeedProfile SpeedProfile::ramp(double omega0, double omega1, double alpha, const std::string& origin) {
  if (!(std::isfinite(omega0) && omega0 >= 0 && std::isfinite(omega1) && omega1 > 0))
    throw InputError(origin, 0, "OMEGA0:OMEGA1:ALPHA",
                     fmt::format("a ramp starts at omega >= 0 (0: from rest) and ends at omega > 0 rad/s (got {} -> {})",
                                 omega0, omega1));
  if (!(std::isfinite(alpha) && alpha > 0))
    throw InputError(origin, 0, "OMEGA0:OMEGA1:ALPHA",
                     fmt::format("the angular acceleration ALPHA must be > 0 rad/s^2 (got {})", alpha));
  SpeedProfile p;
  p.points_ = {{0.0, omega0}};
  if (omega1 != omega0) p.points_.push_back({std::abs(omega1 - omega0) / alpha, omega1});
  p.description_ = fmt::format("ramp {} -> {} rad/s at {} rad/s^2", omega0, omega1, omega1 >= omega0 ? alpha : -alpha);
  return p;
}

SpeedProfile SpeedProfile::parse_ramp(std::string_view text, const std::string& origin, double to_rad_per_s) {
  double v[3];
  std::size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t colon = k < 2 ? text.find(':', start) : text.size();
    if (colon == std::string_view::npos || !parse_real(text.substr(start, colon - start), v[k]) ||
        (k == 2 && text.find(':', start) != std::string_view::npos))
      throw InputError(origin, 0, std::string(text), "expected OMEGA0:OMEGA1:ALPHA, three finite reals (rad/s, rad/s, rad/s^2)");
    start = colon + 1;
  }
  return ramp(v[0] * to_rad_per_s, v[1] * to_rad_per_s, v[2] * to_rad_per_s, origin);
}

SpeedProfile SpeedProfile::piecewise_linear(std::vector<Point> points, const std::string& origin) {
  if (points.empty()) throw InputError(origin, 0, "", "a speed profile needs at least one point (t, omega)");
  if (points.front().t != 0.0)
    throw InputError(origin, 0, "t", fmt::format("a speed profile starts at t = 0 (got {})", points.front().t));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(points[i].omega > 0))
      throw InputError(origin, 0, "omega",
                       fmt::format("point {}: omega must be > 0 rad/s (got {})", i + 1, points[i].omega));
    if (i > 0 && !(points[i].t > points[i - 1].t))
      throw InputError(origin, 0, "t",
                       fmt::format("point {}: t must increase strictly (t = {} after {})", i + 1, points[i].t,
                                   points[i - 1].t));
  }
  SpeedProfile p;
  p.points_ = std::move(points);
  p.description_ = fmt::format("profile {} ({} points)", origin, p.points_.size());
  return p;
}

SpeedProfile SpeedProfile::load(const std::string& path) {
  std::istringstream in(read_text_file(path, profile_size_limit, "speed profile"));
  std::vector<Point> points;
  std::string line;
  int number = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::string text = line;
    std::replace(text.begin(), text.end(), ',', ' ');
    std::replace(text.begin(), text.end(), '\t', ' ');
    std::istringstream fields(text);
    std::vector<std::string> cols;
    for (std::string f; fields >> f;) cols.push_back(f);
    if (cols.empty()) continue;
    if (header_allowed && cols.size() == 2 && cols[0] == "t" && cols[1] == "omega") {
      header_allowed = false;
      continue;
    }
    header_allowed = false;
    Point pt{};
    if (cols.size() != 2 || !parse_real(cols[0], pt.t) || !parse_real(cols[1], pt.omega))
      throw InputError(path, number, "", "expected two finite reals `t, omega` [s, rad/s]");
    if (!points.empty() && !(pt.t > points.back().t))
      throw InputError(path, number, "t",
                       fmt::format("t must increase strictly (t = {} after {})", pt.t, points.back().t));
    if (!(pt.omega > 0)) throw InputError(path, number, "omega", fmt::format("omega must be > 0 rad/s (got {})", pt.omega));
    if (points.empty() && pt.t != 0.0)
      throw InputError(path, number, "t", fmt::format("a speed profile starts at t = 0 (got {})", pt.t));
    points.push_back(pt);
  }
  if (points.empty()) throw InputError(path, number, "", "the speed profile has no points");
  return piecewise_linear(std::move(points), path);
}

bool SpeedProfile::is_constant() const {
  return std::all_of(points_.begin(), points_.end(), [&](const Point& p) { return p.omega == points_.front().omega; });
}

std::size_t SpeedProfile::segment(double t) const {
  // points_ is short (a ramp has two); the last index whose t <= query.
  const auto it = std::upper_bound(points_.begin(), points_.end(), t, [](double v, const Point& p) { return v < p.t; });
  return it == points_.begin() ? 0 : std::size_t(it - points_.begin()) - 1;
}

double SpeedProfile::omega_dot(double t) const {
  const std::size_t i = segment(t);
  if (i + 1 >= points_.size() || t < 0) return 0.0;
  return (points_[i + 1].omega - points_[i].omega) / (points_[i + 1].t - points_[i].t);
}

double SpeedProfile::omega(double t) const {
  if (t <= 0) return points_.front().omega;
  const std::size_t i = segment(t);
  if (i + 1 >= points_.size()) return points_.back().omega;
  return points_[i].omega + omega_dot(t) * (t - points_[i].t);
}

double SpeedProfile::angle(double t) const {
  if (t <= 0) return points_.front().omega * t;
  double theta = 0;
  for (std::size_t i = 0; i + 1 < points_.size() && points_[i].t < t; ++i) {
    const double t1 = std::min(t, points_[i + 1].t), dt = t1 - points_[i].t;
    const double slope = (points_[i + 1].omega - points_[i].omega) / (points_[i + 1].t - points_[i].t);
    theta += points_[i].omega * dt + 0.5 * slope * dt * dt;
  }
  if (t > points_.back().t) theta += points_.back().omega * (t - points_.back().t);
  return theta;
}

double SpeedProfile::max_omega() const {
  double m = 0;
  for (const auto& p : points_) m = std::max(m, p.omega);
  return m;
}
double SpeedProfile::min_omega() const {
  double m = points_.front().omega;
  for (const auto& p : points_) m = std::min(m, p.omega);
  return m;
}
double SpeedProfile::end_of_change() const {
  for (std::size_t i = points_.size(); i-- > 1;)
    if (points_[i].omega != points_[i - 1].omega) return points_[i].t;
  return 0.0;
}

std::vector<double> SpeedProfile::breakpoints(double t0, double t1) const {
  std::vector<double> out;
  for (const auto& p : points_)
    if (p.t > t0 && p.t < t1) out.push_back(p.t);
  return out;
}

std::vector<double> SpeedProfile::crossings(double value, double t_end) const {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < points_.size() && points_[i].t <= t_end; ++i) {
    const double a = points_[i].omega - value, b = points_[i + 1].omega - value;
    if (a == 0 && (out.empty() || out.back() != points_[i].t)) out.push_back(points_[i].t);
    if ((a < 0 && b > 0) || (a > 0 && b < 0)) {
      const double t = points_[i].t + (points_[i + 1].t - points_[i].t) * a / (a - b);
      if (t <= t_end) out.push_back(t);
    }
  }
  if (points_.back().omega == value && points_.back().t <= t_end &&
      (out.empty() || out.back() != points_.back().t))
    out.push_back(points_.back().t);
  return out;
}

std::string SpeedProfile::describe() const { return description_; }

}  // namespace abu
