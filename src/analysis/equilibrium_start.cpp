#include "abu/analysis/equilibrium_start.hpp"

#include <fmt/format.h>

#include <charconv>
#include <vector>

#include "abu/core/errors.hpp"
#include "abu/dynamics/simulation.hpp"

namespace abu {

EquilibriumChoice parse_equilibrium_choice(const std::string& text, const std::string& option, bool unround_race,
                                           const std::string& balls_option, const std::string& state_option) {
  if (unround_race)  // its equilibria are not the analysis this start displaces (model.md §11)
    throw NotSupportedError(fmt::format("{} on an unround race (model.md §11): start from {} or from an equilibrium's "
                                        "state with {}",
                                        option, balls_option, state_option));
  return parse_equilibrium_choice(text, option);
}

EquilibriumChoice parse_equilibrium_choice(const std::string& text, const std::string& option) {
  EquilibriumChoice c;
  std::vector<std::string> parts;
  for (std::size_t s = 0;;) {
    const auto colon = text.find(':', s);
    parts.push_back(text.substr(s, colon == std::string::npos ? std::string::npos : colon - s));
    if (colon == std::string::npos) break;
    s = colon + 1;
  }
  const auto bad = [&] {
    return InputError(option, 0, "",
                      fmt::format("expected balanced[:K], together[:K], opposite[:K] or aligned:PATTERN[:K] (PATTERN "
                                  "like +-+), got '{}'",
                                  text));
  };
  c.family = parts[0];
  std::size_t next = 1;
  if (c.family == "aligned") {
    if (parts.size() < 2 || parts[1].empty() || parts[1].find_first_not_of("+-") != std::string::npos) throw bad();
    c.pattern = parts[1];
    next = 2;
  } else if (c.family != "balanced" && c.family != "together" && c.family != "opposite") {
    throw bad();
  }
  if (parts.size() > next + 1) throw bad();
  if (parts.size() == next + 1) {
    const auto& m = parts[next];
    const auto [end, ec] = std::from_chars(m.data(), m.data() + m.size(), c.member);
    if (m.empty() || ec != std::errc() || end != m.data() + m.size() || c.member < 1) throw bad();
  }
  return c;
}

namespace {

template <int N, class A>
State<double, N> start_at(const ParamsT<double, N>& p, const A& analysis, const EquilibriumChoice& c, double eps,
                          const std::string& option) {
  const auto points = analysis.equilibria.points();
  const int n = ball_count(p);
  std::string pattern = c.pattern;
  if (c.family == "together") pattern = std::string(std::size_t(n), '+');
  if (c.family == "opposite") pattern = "+-";
  std::string listed;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const bool balanced = e.family == Family::balanced;
    const std::string pat = balanced ? "" : pattern_string(e.pattern, n);
    listed += fmt::format(" {}{}:{}", balanced ? "balanced" : "aligned", balanced ? "" : ":" + pat, e.member);
    const bool match = c.family == "balanced" ? balanced : (!balanced && pat == pattern);
    if (!match || e.member != c.member) continue;
    const auto& sp = analysis.spectra[i];
    int k = 0;
    while (k < sp.count && sp.structural[std::size_t(k)]) ++k;  // the rightmost non-structural eigenvalue
    if (k >= sp.count) throw NumericalError(option + ": the equilibrium has no non-structural eigenvalue");
    ModeVector<N> mode = sp.vectors[std::size_t(k)];
    if (mode.size() != n + 2 || mode.isZero(0))
      throw NumericalError(option + ": no eigenvector for the rightmost eigenvalue");
    Coordinates<double, N> pos = e.position_si();
    return perturbed_equilibrium(p, pos, sp.eigenvalues[std::size_t(k)], mode, eps);
  }
  throw InputError(option, 0, "", fmt::format("no such equilibrium at omega = {} rad/s; there are:{}", p.omega, listed));
}

}  // namespace

State<double, 2> start_from_equilibrium(const Params& p, const Analysis& analysis, const EquilibriumChoice& choice,
                                        double eps, const std::string& option) {
  return start_at(p, analysis, choice, eps, option);
}
State<double, any_balls> start_from_equilibrium(const ParamsN& p, const AnalysisN& analysis,
                                                const EquilibriumChoice& choice, double eps, const std::string& option) {
  return start_at(p, analysis, choice, eps, option);
}

}  // namespace abu
