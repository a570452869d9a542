// The [simulate] table of a scene: see simulate_table.hpp.
#include "simulate_table.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "abu/core/errors.hpp"

namespace abu::scene_reading {

namespace {

constexpr std::string_view kSimulateKeys = "ramp, speed_profile, t_end, every, rtol, method, balls, from_state";
constexpr std::string_view kRampKeys = "omega0, omega1, alpha";
constexpr std::string_view kMethods = "auto, bdf, rk8pd, rk4imp, bsimp, rkf45";

std::optional<double> real(Problems& p, const std::string& key, const toml::node& node, toml::source_position pos) {
  const std::optional<double> value = number_value(p, key, node, pos);
  if (!value) return std::nullopt;
  const double x = *value;
  if (!std::isfinite(x)) {
    p.add(pos, key, "must be finite");
    return std::nullopt;
  }
  return x;
}

std::optional<std::vector<double>> reals(Problems& p, const std::string& key, const toml::node& node,
                                         toml::source_position pos) {
  const auto* a = node.as_array();
  if (!a) {
    p.add(pos, key, fmt::format("must be an array of numbers, got {}", describe(node)));
    return std::nullopt;
  }
  std::vector<double> v;
  for (const auto& e : *a) {
    auto x = real(p, key, e, pos);
    if (!x) return std::nullopt;
    v.push_back(*x);
  }
  return v;
}

}  // namespace

SimulateSettings read_simulate_table(Problems& p, const toml::table& table, const std::string& file, int n_balls) {
  SimulateSettings s;
  bool ramp_seen = false, profile_seen = false;
  toml::source_position profile_pos{}, ramp_pos{}, balls_pos{};
  for (auto&& [k, node] : table) {
    const std::string name(k.str());
    const std::string key = "simulate." + name;
    const auto pos = k.source().begin;
    if (name == "ramp") {
      ramp_seen = true;
      ramp_pos = pos;
      const auto* t = node.as_table();
      if (!t) {
        p.add(pos, key, fmt::format("must be a table {{ omega0 = W0, omega1 = W1, alpha = A }}, got {}", describe(node)));
        continue;
      }
      std::optional<double> w0, w1, alpha;
      bool bad = false;
      for (auto&& [rk, rnode] : *t) {
        const std::string rname(rk.str()), rkey = key + "." + rname;
        const auto rpos = rk.source().begin;
        auto x = real(p, rkey, rnode, rpos);
        bad = bad || !x;
        if (rname == "omega0") {
          w0 = x;
        } else if (rname == "omega1") {
          w1 = x;
        } else if (rname == "alpha") {
          alpha = x;
          if (x && !(*x > 0)) {
            p.add(rpos, rkey, fmt::format("the angular acceleration must be > 0 rad/s^2 (got {})", *x));
            bad = true;
          }
        } else {
          p.add(rpos, rkey,
                unknown_name_rule("unknown key", closest_name(rname, split_names(kRampKeys)), "allowed here", kRampKeys));
          bad = true;
        }
      }
      if (bad) continue;
      if (!w0 || !w1 || !alpha) {
        p.add(pos, key, "needs omega0 and omega1 [rad/s] and alpha [rad/s^2]");
        continue;
      }
      if (!(*w0 > 0 && *w1 > 0)) {
        p.add(pos, key, fmt::format("a ramp must stay at omega > 0 rad/s (got {} -> {})", *w0, *w1));
        continue;
      }
      s.speed = SpeedProfile::ramp(*w0, *w1, *alpha, file);
    } else if (name == "speed_profile") {
      profile_seen = true;
      profile_pos = pos;
      const auto* str = node.as_string();
      if (!str) {
        p.add(pos, key, fmt::format("must be a file name (a string), got {}", describe(node)));
        continue;
      }
      // Relative to the scene file, so that a scene and its profile travel together.
      namespace fs = std::filesystem;
      fs::path path(str->get());
      if (path.is_relative()) path = fs::path(file).parent_path() / path;
      try {
        s.speed = SpeedProfile::load(path.string());
      } catch (const InputError& e) {
        p.add(pos, key,
              e.line() > 0 ? fmt::format("{}, line {}: {}{}", e.file(), e.line(), e.key().empty() ? "" : e.key() + ": ",
                                         e.rule())
                           : fmt::format("{}: {}", e.file(), e.rule()));
      }
    } else if (name == "t_end" || name == "every") {
      if (auto x = real(p, key, node, pos)) {
        if (*x > 0)
          (name == "t_end" ? s.t_end : s.every) = *x;
        else
          p.add(pos, key, fmt::format("must be > 0 s (got {})", *x));
      }
    } else if (name == "rtol") {
      if (auto x = real(p, key, node, pos)) {
        if (*x >= 1e-14 && *x < 0.1)
          s.rtol = *x;
        else
          p.add(pos, key, fmt::format("the tolerance must lie in [1e-14, 0.1): below 1e-14 no double-precision step meets it (unit roundoff 1.1e-16) (got {})", *x));
      }
    } else if (name == "method") {
      const auto* str = node.as_string();
      const std::string m = str ? str->get() : std::string();
      const auto methods = split_names(kMethods);  // one list: its begin and end compared below
      if (str && std::find(methods.begin(), methods.end(), std::string_view(m)) != methods.end())
        s.method = m;
      else
        p.add(pos, key,
              str ? unknown_name_rule("unknown integration method", closest_name(m, split_names(kMethods)), "expected",
                                      kMethods)
                  : fmt::format("must be a string ({}), got {}", kMethods, describe(node)));
    } else if (name == "balls") {
      balls_pos = pos;
      if (auto v = reals(p, key, node, pos)) {
        if (int(v->size()) != n_balls)
          p.add(pos, key, fmt::format("one angle [rad] per ball: the scene has {} balls, got {} values", n_balls,
                                      v->size()));
        else
          s.balls = *v;
      }
    } else if (name == "from_state") {
      if (auto v = reals(p, key, node, pos)) {
        if (int(v->size()) != 2 * n_balls + 4)
          p.add(pos, key,
                fmt::format("a state of {} balls has 2n + 4 = {} values (q1,q2,beta1..,dq1,dq2,dbeta1..), got {}",
                            n_balls, 2 * n_balls + 4, v->size()));
        else
          s.from_state = *v;
      }
      if (!s.balls.empty() || balls_pos.line != 0)
        p.add(pos, key, fmt::format("balls (line {}) and from_state exclude each other: give one start", balls_pos.line));
    } else {
      p.add(pos, key,
            unknown_name_rule("unknown key", closest_name(name, split_names(kSimulateKeys)), "allowed here",
                              kSimulateKeys));
    }
  }
  if (ramp_seen && profile_seen) {
    const bool ramp_first = before(ramp_pos, profile_pos);
    p.add(ramp_first ? profile_pos : ramp_pos, ramp_first ? "simulate.speed_profile" : "simulate.ramp",
          fmt::format("ramp and speed_profile exclude each other: give one run-up (the other is at line {})",
                      ramp_first ? ramp_pos.line : profile_pos.line));
  }
  return s;
}

}  // namespace abu::scene_reading
