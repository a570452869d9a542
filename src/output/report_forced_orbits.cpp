// Reports of the aligned states' periodic orbits on an anisotropic support
// (report_forced_orbits.hpp, docs/model.md §10.14).
#include "abu/output/report_forced_orbits.hpp"

#include <cmath>

#include <fmt/format.h>

#include "abu/output/format.hpp"

namespace abu {

namespace {

std::string_view status_text(const ForcedOrbit& o) { return o.status.ok() ? "converged" : to_string(o.status.outcome); }

// A CSV field in double quotes (RFC 4180: an embedded quote doubled).
std::string csv_quoted(std::string_view text) {
  std::string out = "\"";
  for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

// Where the orbits start, as the reports name it.
std::string_view origin_text(const ForcedOrbitAnalysis& a) {
  return a.origin == OrbitOrigin::aligned_equilibria ? "aligned equilibria of the mean system"
                                                     : "equilibria of the unround race on the mean support";
}
std::string_view origin_section(const ForcedOrbitAnalysis& a) {
  return a.origin == OrbitOrigin::aligned_equilibria ? "§10.14" : "§20.4";
}

}  // namespace

std::string forced_orbits_table(const ForcedOrbitAnalysis& a, const ParamsN& p) {
  std::string out = fmt::format(
      "\nperiodic orbits (model.md {}): {} of the {} {} continued to "
      "pi/omega-periodic orbits of this support (shooting over pi/omega, continued in the anisotropy delta = 0 -> 1). "
      "|q| over the period (rotating frame = fixed-frame whirl radius); multipliers over pi/omega, no trivial one "
      "(the system is not autonomous)\n",
      origin_section(a), a.converged, a.aligned, origin_text(a));
  for (const ForcedOrbit& o : a.orbits) {
    out += fmt::format("{}: ", o.kind);
    if (!o.status.ok()) {
      out += fmt::format("NOT FOUND ({}): {}\n", status_text(o), o.reason);
      continue;
    }
    out += fmt::format("{} (max |rho| = {:.12f}); |q| max {:.6e} m, mean {:.6e} m\n  beta range:", to_string(o.verdict),
                       o.multipliers.empty() ? 0.0 : std::abs(o.multipliers.front()), o.q_abs_max, o.q_abs_mean);
    for (std::size_t b = 0; b < o.ball_min.size(); ++b)
      out += fmt::format(" [{:.6f}, {:.6f}]", o.ball_min[b], o.ball_max[b]);
    out += fmt::format(" rad\n  {:>20}  {:>15}  {:>14}  {:>14}\n", "|rho|", "arg rho [rad]", "Re lambda", "Im lambda");
    for (std::size_t k = 0; k < o.multipliers.size(); ++k)
      out += fmt::format("  {:>20.12e}  {:>15.10f}  {:>14.6g}  {:>14.6g}\n", std::abs(o.multipliers[k]),
                         std::arg(o.multipliers[k]), o.exponents[k].real(), o.exponents[k].imag());
  }
  (void)p;
  return out;
}

std::string forced_orbits_csv(const ForcedOrbitAnalysis& a, const ParamsN& p) {
  const int n = p.n_balls(), dim = 2 * n + 4;
  std::string out = fmt::format(
      "# periodic orbits (model.md {}): {} of {} {} continued; a second block with its own "
      "header: q_abs [m] over pi/omega (rotating frame), beta ranges [rad], multipliers over pi/omega (modulus "
      "descending), mult_logmod = ln|rho|; a failed orbit has empty values and its reason\n",
      origin_section(a), a.converged, a.aligned, a.origin == OrbitOrigin::aligned_equilibria ? "aligned equilibria" : origin_text(a));
  out += "orbit,kind,status,stability,q_abs_max,q_abs_mean";
  for (int k = 1; k <= n; ++k) out += fmt::format(",beta{}_min,beta{}_max", k, k);
  for (int k = 1; k <= dim; ++k) out += fmt::format(",rho{}_re,rho{}_im,mult_logmod{}", k, k, k);
  out += ",reason\n";
  for (std::size_t i = 0; i < a.orbits.size(); ++i) {
    const ForcedOrbit& o = a.orbits[i];
    out += fmt::format("{},{},{}", i + 1, o.kind, status_text(o));
    if (o.status.ok()) {
      out += fmt::format(",{},{},{}", to_string(o.verdict), o.q_abs_max, o.q_abs_mean);
      for (std::size_t b = 0; b < o.ball_min.size(); ++b) out += fmt::format(",{},{}", o.ball_min[b], o.ball_max[b]);
      for (std::size_t k = 0; k < o.multipliers.size(); ++k)
        out += fmt::format(",{},{},{}", o.multipliers[k].real(), o.multipliers[k].imag(), o.log_moduli[k]);
      out += ",\n";
    } else {
      out += std::string(std::size_t(4 + 2 * n + 3 * dim), ',');  // the empty fields, then the reason
      out += csv_quoted(o.reason) + "\n";
    }
  }
  return out;
}

std::string forced_orbits_json(const ForcedOrbitAnalysis& a) {
  std::string out = fmt::format("\"{}\": {}, \"periodic_orbits_found\": {},\n  \"periodic_orbits\": [",
                                a.origin == OrbitOrigin::aligned_equilibria ? "aligned_equilibria" : "unround_equilibria",
                                a.aligned, a.converged);
  for (std::size_t i = 0; i < a.orbits.size(); ++i) {
    const ForcedOrbit& o = a.orbits[i];
    out += i ? ",\n    {" : "\n    {";
    out += fmt::format("\"kind\": {}, \"status\": \"{}\", \"reason\": {}, \"delta\": {}", json_string(o.kind),
                       status_text(o), json_string(o.reason), o.delta);
    if (o.status.ok()) {
      out += fmt::format(", \"stable\": {}, \"stability\": \"{}\", \"band\": {}, \"period\": {}, \"q_abs_max\": {}, "
                         "\"q_abs_mean\": {}, \"periodicity\": {},\n     \"ball_min\": [",
                         o.stable(), to_string(o.verdict), o.band, o.period, o.q_abs_max, o.q_abs_mean, o.periodicity);
      for (std::size_t b = 0; b < o.ball_min.size(); ++b) out += fmt::format("{}{}", b ? ", " : "", o.ball_min[b]);
      out += "], \"ball_max\": [";
      for (std::size_t b = 0; b < o.ball_max.size(); ++b) out += fmt::format("{}{}", b ? ", " : "", o.ball_max[b]);
      out += "], \"state0\": [";
      for (std::size_t k = 0; k < o.state0.size(); ++k) out += fmt::format("{}{}", k ? ", " : "", o.state0[k]);
      out += "],\n     \"floquet_multipliers\": [";
      for (std::size_t k = 0; k < o.multipliers.size(); ++k)
        out += fmt::format("{}[{}, {}]", k ? ", " : "", o.multipliers[k].real(), o.multipliers[k].imag());
      out += "], \"multiplier_log_moduli\": [";
      for (std::size_t k = 0; k < o.log_moduli.size(); ++k) out += fmt::format("{}{}", k ? ", " : "", o.log_moduli[k]);
      out += "],\n     \"floquet_exponents\": [";
      for (std::size_t k = 0; k < o.exponents.size(); ++k)
        out += fmt::format("{}[{}, {}]", k ? ", " : "", o.exponents[k].real(), o.exponents[k].imag());
      out += "]";
    }
    out += "}";
  }
  out += a.orbits.empty() ? "]" : "\n  ]";
  return out;
}

}  // namespace abu
