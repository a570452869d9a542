// `equilibria` on an unround race (report_unround.hpp, model.md §11).
#include "abu/output/report_unround.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "abu/output/format.hpp"
#include "abu/output/provenance.hpp"

namespace abu {

namespace {
std::string num(double v, std::string_view what) { return format_number(v, what); }

double dynamic_stiffness(const ParamsN& p) {
  return std::hypot(p.rotor.stiffness - p.omega * p.omega * p.total_mass(), p.rotor.damping * p.omega);
}

// The bare rotor's whirl omega^2 U / |K + iC| with the balls' mass (§5's "opposite"
// reference q0): what the residual whirl is compared with.
double bare_whirl(const ParamsN& p) { return p.omega * p.omega * p.rotor.unbalance / dynamic_stiffness(p); }

std::string search_line(const UnroundResult& r) {
  return fmt::format("search (model.md §11.4): {} boxes tested, {} leaves (Newton starts), {} unresolved, index sum {}{}",
                     r.search.boxes_tested, r.search.leaves, r.search.unresolved, r.search.index_sum,
                     r.doubt.empty() ? std::string(": complete")
                                     : std::string(": INCOMPLETE, equilibria may be missing or degenerate"));
}

std::string design_line(const UnroundResult& r, const ParamsN& p) {
  if (!r.best_stable) return "design figure: no stable equilibrium: the balls do not settle at this speed";
  const auto& e = r.list[*r.best_stable];
  return fmt::format("design figure: residual whirl |q| = {:.6g} m (best stable state, #{}; a circular whirl of that "
                     "radius in the fixed frame) against {:.6g} m for the bare rotor (ratio {:.4g})",
                     e.amplitude, *r.best_stable + 1, bare_whirl(p), e.amplitude / bare_whirl(p));
}
}  // namespace


std::string unround_table(const UnroundResult& r, const ParamsN& p, const RaceShape& race, std::string_view scene) {
  const int n = p.n_balls();
  std::string out = fmt::format("{}: unround race (model.md §11), omega = {} rad/s, {} balls, law {}\n", scene,
                                p.omega, n, to_string(p.law));
  out += describe_race(race, "");
  const double lambda = unround_lambda(p, race);
  out += fmt::format("Lambda = max k^2 eps_k |K + iC| / (m omega^2) = {:.4g} (§11.6): {}\n", lambda,
                     lambda <= kFirstOrderLambda ? "first-order regime (Lambda <= 0.1)"
                                                 : "beyond the first-order regime");
  out += fmt::format("{}\n\n", search_line(r));
  out += fmt::format("{:>3} {:>13} {:>13} {:>13}", "#", "|q| [m]", "q1 [m]", "q2 [m]");
  for (int i = 0; i < n; ++i) out += fmt::format(" {:>9}", fmt::format("beta{}", i + 1));
  out += fmt::format(" {:>5} {:>9} {:>13} {:>9}\n", "index", "residual", "abscissa", "stability");
  for (std::size_t k = 0; k < r.list.size(); ++k) {
    const auto& e = r.list[k];
    out += fmt::format("{:>3} {:>13.6e} {:>13.5e} {:>13.5e}", k + 1, e.amplitude, double(e.position(0)),
                       double(e.position(1)));
    for (int i = 0; i < n; ++i) out += fmt::format(" {:>9.5f}", double(e.position(2 + i)));
    out += fmt::format(" {:>+5d} {:>9.1e} {:>13.5e} {:>9}\n", e.index, e.residual, e.spectrum.abscissa,
                       to_string(e.spectrum.stability));
  }
  out += "\n(abscissa: largest real part of the rotating-frame eigenvalues [1/s]; index: sign det of the ball "
         "conditions' Jacobian)\n";
  out += fmt::format("{}\n", design_line(r, p));
  return out;
}

std::string unround_csv(const UnroundResult& r, const ParamsN& p, const RaceShape& race, const std::string& header) {
  const int n = p.n_balls();
  std::string out = header;
  out += describe_race(race, "# ");
  out += fmt::format("# Lambda = {} (first order for Lambda <= 0.1: {})\n", num(unround_lambda(p, race), "Lambda"),
                     unround_lambda(p, race) <= kFirstOrderLambda);
  out += fmt::format("# {}\n# {}\n", search_line(r), design_line(r, p));
  out += "# columns: q [m] rotating frame (|q| = fixed-frame whirl radius), beta [rad], residual dimensionless, "
         "index = sign det(dg/dbeta) (model.md §11.4), eigenvalues [1/s] rotating frame, sorted by real part\n";
  out += "equilibrium,q1,q2,q_abs";
  for (int i = 0; i < n; ++i) out += fmt::format(",beta{}", i + 1);
  out += ",residual,index,spectral_abscissa,stable,best";
  for (int k = 0; k < 2 * n + 4; ++k) out += fmt::format(",re{},im{}", k + 1, k + 1);
  out += "\n";
  for (std::size_t k = 0; k < r.list.size(); ++k) {
    const auto& e = r.list[k];
    out += fmt::format("{},{},{},{}", k + 1, num(double(e.position(0)), "q1"), num(double(e.position(1)), "q2"),
                       num(e.amplitude, "|q|"));
    for (int i = 0; i < n; ++i) out += fmt::format(",{}", num(double(e.position(2 + i)), "beta"));
    out += fmt::format(",{},{},{},{},{}", num(e.residual, "residual"), e.index, num(e.spectrum.abscissa, "abscissa"),
                       e.spectrum.stability == Stability::stable ? 1 : 0, r.best_stable == k ? 1 : 0);
    for (int j = 0; j < e.spectrum.count; ++j) {
      const auto l = e.spectrum.eigenvalues[std::size_t(j)];
      out += fmt::format(",{},{}", num(l.real(), "eigenvalue"), num(l.imag(), "eigenvalue"));
    }
    out += "\n";
  }
  return out;
}

std::string unround_json(const UnroundResult& r, const ParamsN& p, const RaceShape& race, std::string_view command_line,
                         std::string_view scene) {
  const int n = p.n_balls();
  std::string out = "{\n";
  out += fmt::format("  \"program\": {},\n  \"command\": {},\n  \"scene\": {},\n", json_string("stability-scan"),
                     json_string(command_line), json_string(scene));
  out += fmt::format("  \"parameters\": {},\n  \"balls\": {},\n  \"frame\": \"rotating\",\n",
                     json_string(describe_parameters(p)), n);
  out += "  \"race\": [";
  for (std::size_t i = 0; i < race.balls.size(); ++i) {
    out += i ? ", [" : "[";
    for (std::size_t k = 0; k < race.balls[i].size(); ++k) {
      const auto& h = race.balls[i][k];
      out += fmt::format("{}{{\"order\": {}, \"amplitude\": {}, \"phase\": {}}}", k ? ", " : "", h.order,
                         num(h.amplitude, "amplitude"), num(h.phase, "phase"));
    }
    out += "]";
  }
  out += "],\n";
  const double lambda = unround_lambda(p, race);
  out += fmt::format("  \"lambda\": {}, \"first_order_regime\": {},\n", num(lambda, "Lambda"),
                     lambda <= kFirstOrderLambda);
  out += fmt::format(
      "  \"search\": {{\"boxes_tested\": {}, \"leaves\": {}, \"unresolved\": {}, \"index_sum\": {}, \"complete\": {}, "
      "\"doubt\": {}}},\n",
      r.search.boxes_tested, r.search.leaves, r.search.unresolved, r.search.index_sum, r.doubt.empty(),
      json_string(r.doubt));
  out += fmt::format("  \"q_bare\": {{\"value\": {}, \"unit\": \"m\"}},\n", num(bare_whirl(p), "q0"));
  if (r.best_stable)
    out += fmt::format("  \"best_stable\": {{\"equilibrium\": {}, \"q_abs\": {{\"value\": {}, \"unit\": \"m\"}}}},\n",
                       *r.best_stable + 1, num(r.list[*r.best_stable].amplitude, "|q|"));
  else
    out += "  \"best_stable\": null,\n";
  out += "  \"equilibria\": [";
  for (std::size_t k = 0; k < r.list.size(); ++k) {
    const auto& e = r.list[k];
    out += fmt::format("{}\n    {{\"equilibrium\": {}, \"q1\": {}, \"q2\": {}, \"q_abs\": {}, \"beta\": [", k ? "," : "",
                       k + 1, num(double(e.position(0)), "q1"), num(double(e.position(1)), "q2"),
                       num(e.amplitude, "|q|"));
    for (int i = 0; i < n; ++i) out += fmt::format("{}{}", i ? ", " : "", num(double(e.position(2 + i)), "beta"));
    out += fmt::format("], \"residual\": {}, \"index\": {}, \"stability\": \"{}\", \"spectral_abscissa\": {}, "
                       "\"eigenvalues\": [",
                       num(e.residual, "residual"), e.index, to_string(e.spectrum.stability),
                       num(e.spectrum.abscissa, "abscissa"));
    for (int j = 0; j < e.spectrum.count; ++j) {
      const auto l = e.spectrum.eigenvalues[std::size_t(j)];
      out += fmt::format("{}[{}, {}]", j ? ", " : "", num(l.real(), "eigenvalue"), num(l.imag(), "eigenvalue"));
    }
    out += "]}";
  }
  out += "\n  ]\n}\n";
  return out;
}

namespace {
std::string angle_columns(int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += fmt::format(",beta{}", i + 1);
  return out;
}
std::string angle_values(const UnroundEquilibrium& e) {
  std::string out;
  for (Eigen::Index i = 2; i < e.position.size(); ++i) out += fmt::format(",{}", num(double(e.position(i)), "beta"));
  return out;
}
int balls_of(const UnroundEquilibrium& e) { return int(e.position.size()) - 2; }
}  // namespace

std::string unround_sweep_csv(const UnroundSweep& s, const std::string& header) {
  int n = 0;
  for (const auto& r : s.points)
    if (!r.list.empty()) n = balls_of(r.list.front());
  std::string out = header;
  out += fmt::format("# unround race (model.md §11.10): every equilibrium of the complete search (§11.4) per value of "
                     "{} [{}]; q [m] rotating frame (|q| = fixed-frame whirl radius), beta [rad], abscissa [1/s] "
                     "(rotating frame); first_order = Lambda <= {} (§11.6)\n",
                     s.name, s.unit, kFirstOrderLambda);
  out += fmt::format("{},equilibrium,q1,q2,q_abs{},index,spectral_abscissa,stable,best,lambda,first_order\n", s.name,
                     angle_columns(n));
  for (std::size_t v = 0; v < s.values.size(); ++v) {
    const auto& r = s.points[v];
    for (std::size_t k = 0; k < r.list.size(); ++k) {
      const auto& e = r.list[k];
      out += fmt::format("{},{},{},{},{}{},{},{},{},{},{},{}\n", num(s.values[v], s.name), k + 1,
                         num(double(e.position(0)), "q1"), num(double(e.position(1)), "q2"), num(e.amplitude, "|q|"),
                         angle_values(e), e.index, num(e.spectrum.abscissa, "abscissa"),
                         e.spectrum.stability == Stability::stable ? 1 : 0, r.best_stable == k ? 1 : 0,
                         num(s.lambdas[v], "Lambda"), s.lambdas[v] <= kFirstOrderLambda ? 1 : 0);
    }
  }
  return out;
}

std::string unround_sweep_summary_csv(const UnroundSweep& s, const std::string& header) {
  std::string out = header;
  out += fmt::format("# unround race (model.md §11.10), per value of {} [{}]: best_q_abs = |q| of the best stable "
                     "state [m] (empty: none stable), q_bare = the bare rotor's whirl [m], complete = the search of "
                     "§11.4 found every equilibrium (no unresolved leaf, index sum 0)\n",
                     s.name, s.unit);
  out += fmt::format("{},equilibria,stable,best_q_abs,q_bare,lambda,first_order,complete\n", s.name);
  for (std::size_t v = 0; v < s.values.size(); ++v) {
    const auto& r = s.points[v];
    long stable = 0;
    for (const auto& e : r.list) stable += e.spectrum.stability == Stability::stable ? 1 : 0;
    out += fmt::format("{},{},{},{},{},{},{},{}\n", num(s.values[v], s.name), r.list.size(), stable,
                       r.best_stable ? num(r.list[*r.best_stable].amplitude, "|q|") : std::string(),
                       num(s.bare_whirls[v], "q0"), num(s.lambdas[v], "Lambda"),
                       s.lambdas[v] <= kFirstOrderLambda ? 1 : 0, r.doubt.empty() ? 1 : 0);
  }
  return out;
}

namespace {
std::string branch_row(std::size_t branch, const UnroundBranchPoint& pt) {
  const auto& e = pt.state;
  return fmt::format("{},{},{},{},{}{},{},{},{}", branch + 1, num(pt.factor, "unroundness"),
                     num(double(e.position(0)), "q1"), num(double(e.position(1)), "q2"), num(e.amplitude, "|q|"),
                     angle_values(e), e.index, num(e.spectrum.abscissa, "abscissa"),
                     e.spectrum.stability == Stability::stable ? 1 : 0);
}
int balls_of(const UnroundBranches& b) {
  for (const auto& br : b.branches)
    if (!br.points.empty()) return balls_of(br.points.front().state);
  return 0;
}
const char* kBranchNote =
    "# unround race: equilibrium branches in the unroundness factor e (every race amplitude times e; model.md "
    "§11.10), pseudo-arclength; q [m] rotating frame (|q| = fixed-frame whirl radius), beta [rad] wrapped to "
    "[0, 2 pi), index = sign det(dg/dbeta) (changes at a fold LP), abscissa [1/s] rotating frame\n";
}  // namespace

std::string unround_branch_csv(const UnroundBranches& b, const std::string& header) {
  std::string out = fmt::format("{}{}", header, kBranchNote);
  if (!b.doubt.empty()) out += fmt::format("# doubt: {}\n", b.doubt);
  out += fmt::format("branch,unroundness,q1,q2,q_abs{},index,spectral_abscissa,stable\n", angle_columns(balls_of(b)));
  for (std::size_t k = 0; k < b.branches.size(); ++k)
    for (const auto& pt : b.branches[k].points) out += fmt::format("{}\n", branch_row(k, pt));
  return out;
}

std::string unround_special_csv(const UnroundBranches& b, const std::string& header) {
  std::string out = fmt::format("{}{}", header, kBranchNote);
  out += fmt::format("label,branch,unroundness,q1,q2,q_abs{},index,spectral_abscissa,stable\n",
                     angle_columns(balls_of(b)));
  for (std::size_t k = 0; k < b.branches.size(); ++k)
    for (const auto& s : b.branches[k].specials) out += fmt::format("{},{}\n", s.kind, branch_row(k, s.point));
  return out;
}

}  // namespace abu
