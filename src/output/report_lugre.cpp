#include "abu/output/report_lugre.hpp"

#include <cmath>

#include <fmt/format.h>

#include "abu/core/errors.hpp"
#include "abu/output/format.hpp"
#include "abu/output/provenance.hpp"

namespace abu {

namespace {

// The routes of §12.5 agree to rounding (~1e-12 relative on these spectra); a deviation
// above this is reported as a warning (the reported values are route (a)'s).
constexpr double kRouteTolerance = 1e-7;

std::string num(double v, std::string_view what) { return format_number(v, what); }

void append_field(std::string& out, const std::string& value) {
  out += ',';
  out += value;
}

std::vector<const LugreSideSpectrum*> sides_of(const LugreRest& r) {
  if (r.zero_bristle) return {&r.forward};
  return {&r.forward, &r.backward};
}

std::string side_name(const LugreRest& r, const LugreSideSpectrum& s) {
  return std::string(r.zero_bristle ? std::string_view("both") : to_string(s.side));
}

}  // namespace

namespace {

// The comment lines and the column names of the LuGre equilibria CSV, after `lead`.
std::string lugre_csv_head(int n, std::string_view lead) {
  std::string out;
  out += "# lugre (model.md §12): every configuration is an equilibrium; rows: the z = 0 ones (§5, §13) and the stuck "
         "states asked for; side: one-sided Jacobian (12.9), 'both' where z = 0\n";
  out += "# eigenvalues [1/s, rotating frame]: the 2n + 4 normal ones (12.10) by real part, then the n zeros along the "
         "family as 0,0; z [rad]; load = tau/mu_s (|load| <= 1 reachable from z = 0)\n";
  out += lead;
  out += "family,pattern,member,side,q1,q2";
  for (int i = 1; i <= n; ++i) out += fmt::format(",beta{}", i);
  for (int i = 1; i <= n; ++i) out += fmt::format(",z{}", i);
  for (int i = 1; i <= n; ++i) out += fmt::format(",load{}", i);
  out += ",reachable,rotor_residual,spectral_abscissa,side_stable,stable,non_smooth,verdict,n_zero,route_deviation";
  for (int k = 1; k <= 3 * n + 4; ++k) out += fmt::format(",re{},im{}", k, k);
  out += '\n';
  return out;
}

// One line per state and side, each starting with `lead`.
void append_lugre_rows(std::string& out, const std::vector<LugreRow>& rows, int n, std::string_view lead) {
  for (const auto& row : rows) {
    const LugreRest& r = row.rest;
    for (const LugreSideSpectrum* s : sides_of(r)) {
      out += lead;
      out += fmt::format("{},{},{},{}", row.family, row.pattern, row.member, side_name(r, *s));
      for (int k = 0; k < n + 2; ++k) append_field(out, num(r.position(k), "position"));
      for (int i = 0; i < n; ++i) append_field(out, num(r.bristle[std::size_t(i)], "z"));
      for (int i = 0; i < n; ++i) append_field(out, num(r.load_ratio[std::size_t(i)], "load"));
      out += fmt::format(",{},{},{},{},{},{},{},{},{}", r.reachable ? 1 : 0, num(r.rotor_residual, "residual"),
                         num(s->normal.abscissa, "abscissa"), s->normal.stability == Stability::stable ? 1 : 0,
                         r.stable ? 1 : 0, r.non_smooth ? 1 : 0, r.verdict(), s->zeros,
                         num(s->route_deviation, "route deviation"));
      for (int k = 0; k < s->normal.count; ++k) {
        append_field(out, num(s->normal.eigenvalues[std::size_t(k)].real(), "eigenvalue"));
        append_field(out, num(s->normal.eigenvalues[std::size_t(k)].imag(), "eigenvalue"));
      }
      for (int k = 0; k < s->zeros; ++k) out += ",0,0";
      out += '\n';
    }
  }
}

}  // namespace

std::string lugre_equilibria_csv(const std::vector<LugreRow>& rows, const ParamsN& p, const std::string& header) {
  const int n = p.n_balls();
  std::string out = header + lugre_csv_head(n, "");
  append_lugre_rows(out, rows, n, "");
  return out;
}

std::string lugre_sweep_csv(std::string_view param, const std::vector<double>& values,
                            const std::vector<std::vector<LugreRow>>& rows, const ParamsN& p, const std::string& header) {
  const int n = p.n_balls();
  std::string out = header;
  out += fmt::format("# sweep of {} (model.md §12.8): per value the z = 0 equilibria with both one-sided spectra; "
                     "stable = both sides stable, non_smooth = the sides disagree\n",
                     param);
  out += lugre_csv_head(n, fmt::format("{},", param));
  for (std::size_t k = 0; k < values.size(); ++k) append_lugre_rows(out, rows[k], n, num(values[k], param) + ",");
  return out;
}

std::string lugre_equilibria_json(const std::vector<LugreRow>& rows, const ParamsN& p, std::string_view command_line,
                                  std::string_view scene_file) {
  const int n = p.n_balls();
  std::string out = "{\n";
  out += fmt::format("  \"program\": \"stability-scan {}\",\n", ABU_VERSION);
  out += fmt::format("  \"command\": {},\n  \"scene\": {},\n", json_string(command_line), json_string(scene_file));
  out += fmt::format("  \"parameters\": {},\n", json_string(describe_parameters(p)));
  out += fmt::format("  \"balls\": {},\n  \"law\": \"lugre\",\n  \"state_dimension\": {},\n", n, 3 * n + 4);
  out += "  \"units\": \"q [m], beta [rad], z [rad], load = tau/mu_s [-], eigenvalues [1/s]\",\n";
  out += "  \"frame\": \"rotating\",\n  \"equilibria\": [";
  for (std::size_t e = 0; e < rows.size(); ++e) {
    const auto& row = rows[e];
    const LugreRest& r = row.rest;
    out += e ? ",\n    {" : "\n    {";
    out += fmt::format("\"family\": {}, \"pattern\": {}, \"member\": {}, \"q\": [{}, {}], \"beta\": [",
                       json_string(row.family), json_string(row.pattern), row.member, num(r.position(0), "q"),
                       num(r.position(1), "q"));
    for (int i = 0; i < n; ++i) out += fmt::format("{}{}", i ? ", " : "", num(r.position(2 + i), "beta"));
    out += "], \"z\": [";
    for (int i = 0; i < n; ++i) out += fmt::format("{}{}", i ? ", " : "", num(r.bristle[std::size_t(i)], "z"));
    out += "], \"load\": [";
    for (int i = 0; i < n; ++i) out += fmt::format("{}{}", i ? ", " : "", num(r.load_ratio[std::size_t(i)], "load"));
    out += fmt::format("], \"reachable\": {}, \"rotor_residual\": {}, \"stable\": {}, \"non_smooth\": {}, "
                       "\"verdict\": {}, \"sides\": [",
                       r.reachable, num(r.rotor_residual, "residual"), r.stable, r.non_smooth, json_string(r.verdict()));
    const auto sides = sides_of(r);
    for (std::size_t k = 0; k < sides.size(); ++k) {
      const LugreSideSpectrum& s = *sides[k];
      out += fmt::format("{}{{\"side\": {}, \"stability\": {}, \"spectral_abscissa\": {}, \"n_zero\": {}, "
                         "\"route_deviation\": {}, \"eigenvalues\": [",
                         k ? ", " : "", json_string(side_name(r, s)), json_string(to_string(s.normal.stability)),
                         num(s.normal.abscissa, "abscissa"), s.zeros, num(s.route_deviation, "route deviation"));
      for (int j = 0; j < s.normal.count; ++j)
        out += fmt::format("{}[{}, {}]", j ? ", " : "", num(s.normal.eigenvalues[std::size_t(j)].real(), "eigenvalue"),
                           num(s.normal.eigenvalues[std::size_t(j)].imag(), "eigenvalue"));
      out += "]}";
    }
    out += "]}";
  }
  out += "\n  ]\n}\n";
  return out;
}

std::string lugre_equilibria_table(const std::vector<LugreRow>& rows, const ParamsN& p) {
  const int n = p.n_balls();
  std::string out = fmt::format(
      "{} balls; omega = {} rad/s, friction lugre (model.md §12): state 3n + 4 = {}; every configuration is an "
      "equilibrium (z = -tau / sigma0)\neigenvalues in the rotating frame [1/s]: the normal spectrum of each one-sided "
      "Jacobian (12.10); the n = {} zeros along the family are not listed\n",
      n, p.omega, 3 * n + 4, n);
  for (const auto& row : rows) {
    const LugreRest& r = row.rest;
    out += fmt::format("\n{}{}{} {}  q = ({:.6g}, {:.6g}) m, |q| = {:.6g} m, beta = (", row.family,
                       row.pattern.empty() ? "" : " ", row.pattern, row.member, r.position(0), r.position(1),
                       std::hypot(r.position(0), r.position(1)));
    for (int i = 0; i < n; ++i) out += fmt::format("{}{:.12g}", i ? ", " : "", r.position(2 + i));
    out += ") rad\n    z = (";
    for (int i = 0; i < n; ++i) out += fmt::format("{}{:.6g}", i ? ", " : "", r.bristle[std::size_t(i)]);
    out += ") rad, tau/mu_s = (";
    for (int i = 0; i < n; ++i) out += fmt::format("{}{:.4g}", i ? ", " : "", r.load_ratio[std::size_t(i)]);
    out += fmt::format(") {}; {}\n", r.reachable ? "reachable" : "NOT reachable from z = 0 (|tau| > mu_s)",
                       r.verdict());
    for (const LugreSideSpectrum* s : sides_of(r)) {
      out += fmt::format("    side {}: {}, spectral abscissa {:.9g} 1/s; routes (12.10) / deflated J agree to {:.1e}\n",
                         side_name(r, *s), to_string(s->normal.stability), s->normal.abscissa, s->route_deviation);
      out += fmt::format("    {:>28} {:>24}\n", "Re lambda [1/s]", "Im lambda [1/s]");
      for (int k = 0; k < s->normal.count; ++k)
        out += fmt::format("    {:>28.15g} {:>24.15g}\n", s->normal.eigenvalues[std::size_t(k)].real(),
                           s->normal.eigenvalues[std::size_t(k)].imag());
    }
  }
  return out;
}

std::string lugre_warnings(const std::vector<LugreRow>& rows) {
  std::string out;
  for (const auto& row : rows) {
    const LugreRest& r = row.rest;
    const std::string name = fmt::format("{}{}{} {}", row.family, row.pattern.empty() ? "" : " ", row.pattern, row.member);
    for (const LugreSideSpectrum* s : sides_of(r)) {
      if (!(s->route_deviation <= kRouteTolerance))
        out += fmt::format("stability-scan: warning: {}: the two routes to the normal spectrum (model.md §12.5) "
                           "differ by {:.2g} relative (side {})\n",
                           name, s->route_deviation, side_name(r, *s));
      if (!s->normal.converged)
        out += fmt::format("stability-scan: warning: {}: an eigenvalue refinement did not converge (side {})\n", name,
                           side_name(r, *s));
    }
    if (!r.reachable)
      out += fmt::format("stability-scan: warning: {}: |tau_i| > mu_s for some ball: not reachable from z(0) = 0 "
                         "(model.md §12.3)\n",
                         name);
    if (r.non_smooth)
      out += fmt::format("stability-scan: warning: {}: the one-sided spectra disagree (forward {}, backward {}): "
                         "non-smooth, simulation decides (model.md §12.5)\n",
                         name, to_string(r.forward.normal.stability), to_string(r.backward.normal.stability));
  }
  return out;
}

}  // namespace abu
