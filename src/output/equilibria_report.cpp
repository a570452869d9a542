// The outputs of `equilibria` (equilibria_report.hpp).
#include "abu/output/equilibria_report.hpp"

#include <fmt/format.h>

#include "abu/output/format.hpp"
#include "abu/output/gnuplot.hpp"
#include "abu/output/provenance.hpp"
#include "abu/output/report.hpp"
#include "abu/output/report_floquet.hpp"
#include "abu/output/report_forced_orbits.hpp"
#include "abu/output/report_lugre.hpp"
#include "abu/output/report_shaft.hpp"
#include "abu/output/report_stick_set.hpp"
#include "abu/output/report_unround.hpp"
#include "abu/output/report_views.hpp"

namespace abu {

namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

// A rigid rotor: the closed-form states' table, CSV or JSON; the CSV's comment lines carry the
// stated answer, the creep modes and the dry-friction verdict.
template <class States>
std::string rigid_text(const States& s, std::string_view format, const OutputContext& c) {
  const auto& a = s.analysis;
  const auto& p = s.params;
  if (format == "csv") {
    const std::string header =
        provenance_header(c.command_line, c.scene_file, p) +
        dry_first(s.dry, answer_lines(point_answer(a, p), c.unit, "# ") + creep_lines(a, s.kappa, "# "), "# ");
    if constexpr (std::is_same_v<States, RigidStates2>) {
      return equilibria_csv(a, header);
    } else {
      return equilibria_csv(a, header, p.n_balls());
    }
  }
  if (format == "json") return equilibria_json(a, c.command_line, c.scene_file, p, s.kappa, s.dry);
  return equilibria_report(a, p, c.unit, s.kappa, s.dry);  // ends with the dry-friction verdict
}

std::string anisotropic_text(const AnisotropicStates& s, std::string_view format, const OutputContext& c) {
  const ParamsN& p = s.params;
  if (format == "csv")
    return floquet_csv(s.floquet, p, provenance_header(c.command_line, c.scene_file, p)) +
           (s.orbits ? forced_orbits_csv(*s.orbits, p) : "");
  if (format == "json")
    return floquet_json(s.floquet, p, s.support, c.command_line, c.scene_file, s.orbits ? forced_orbits_json(*s.orbits) : "");
  return floquet_table(s.floquet, p, s.support) + (s.orbits ? forced_orbits_table(*s.orbits, p) : "");
}

// An unround race on an anisotropic support (model.md §20.4): the periodic orbits alone.
std::string unround_anisotropic_text(const UnroundAnisotropicStates& s, std::string_view format, const OutputContext& c) {
  const ParamsN& p = s.params;
  const AnisotropicSupport& k = s.support;
  const std::string what = fmt::format(
      "unround race on an anisotropic support (model.md §20): no state is an equilibrium; the race's {} equilibria "
      "on the mean support (k_bar = {} N/m, c_bar = {} N s/m; {}) continue to pi/omega-periodic orbits",
      s.mean.list.size(), k.mean_stiffness(), k.mean_damping(), s.mean.doubt.empty() ? "the search is complete" : s.mean.doubt);
  if (format == "csv") return provenance_header(c.command_line, c.scene_file, p) + "# " + what + "\n" + forced_orbits_csv(s.orbits, p);
  if (format == "json")
    return fmt::format("{{\n  \"command\": {},\n  \"scene\": {},\n  \"balls\": {},\n  \"omega\": {},\n  \"model\": {},\n  "
                       "\"support\": {{\"frame\": \"fixed\", \"stiffness\": [[{}, {}], [{}, {}]], \"damping\": [[{}, {}], [{}, {}]], "
                       "\"units\": \"N/m, N s/m\"}},\n  \"period\": {},\n  {}\n}}\n",
                       json_string(c.command_line), json_string(c.scene_file), p.n_balls(), p.omega, json_string(what),
                       k.k_x, k.k_xy, k.k_xy, k.k_y, k.c_x, k.c_xy, k.c_xy, k.c_y, s.orbits.orbits.empty() ? 0.0 : s.orbits.orbits[0].period,
                       forced_orbits_json(s.orbits));
  return fmt::format("{}: {} balls, omega = {} rad/s\n{}\n", c.scene_file, p.n_balls(), p.omega, what) +
         forced_orbits_table(s.orbits, p);
}

}  // namespace

double equilibria_text_bytes_per_state(std::string_view format) {
  return format == "json" ? 14e3 : format == "table" ? 3e3 : 1.5e3;
}

std::string equilibria_text(const EquilibriaReport& r, std::string_view format, const OutputContext& c) {
  const auto header = [&](const auto& p) { return provenance_header(c.command_line, c.scene_file, p); };
  return std::visit(
      Overloaded{
          [&](const RigidStates2& s) { return rigid_text(s, format, c); },
          [&](const RigidStatesN& s) { return rigid_text(s, format, c); },
          [&](const LugreStates& s) {
            if (format == "csv") return lugre_equilibria_csv(s.rows, s.params, header(s.params));
            if (format == "json") return lugre_equilibria_json(s.rows, s.params, c.command_line, c.scene_file);
            return lugre_equilibria_table(s.rows, s.params);
          },
          [&](const StickSetStates& s) {
            const ShaftStickFigures* shaft = s.shaft ? &*s.shaft : nullptr;  // on a flexible shaft (§18.17)
            if (format == "csv") return stick_set_csv(s.set, header(s.params), shaft);
            if (format == "json") return stick_set_json(s.set, c.command_line, c.scene_file, s.params, shaft);
            return stick_set_table(s.set, s.params, shaft);
          },
          [&](const UnroundStates& s) {
            if (format == "csv")
              return unround_csv(s.result, s.params, s.race, header(s.params) + dry_friction_lines(s.dry, "# "));
            if (format == "json") {
              std::string json = unround_json(s.result, s.params, s.race, c.command_line, c.scene_file);
              return json.insert(2, dry_friction_json(s.dry));  // a member after the opening "{\n"
            }
            return dry_first(s.dry, unround_table(s.result, s.params, s.race, c.scene_file), "");
          },
          [&](const AnisotropicStates& s) { return anisotropic_text(s, format, c); },
          [&](const UnroundAnisotropicStates& s) { return unround_anisotropic_text(s, format, c); },
          [&](const ShaftStates& s) {
            if (format == "csv") {  // the verdict's lines close the comment block, before the column names
              std::string csv = shaft_states_csv(s, c.command_line, c.scene_file);
              return csv.insert(csv.find("\nequilibrium,") + 1, dry_friction_lines(s.dry, "# "));
            }
            if (format == "json") {
              std::string json = shaft_states_json(s, c.command_line, c.scene_file);
              return json.insert(2, dry_friction_json(s.dry));  // a member after the opening "{\n"
            }
            return dry_first(s.dry, shaft_states_table(s, c.scene_file), "");
          },
      },
      r.states);
}

std::string equilibria_warnings(const EquilibriaReport& r) {
  return r.warnings + std::visit(Overloaded{
                                     [](const RigidStates2& s) {
                                       return analysis_warnings(s.analysis, fmt::format("omega={}", s.params.omega));
                                     },
                                     [](const RigidStatesN& s) {
                                       return analysis_warnings(s.analysis, fmt::format("omega={}", s.params.omega));
                                     },
                                     [](const LugreStates& s) { return lugre_warnings(s.rows); },
                                     [](const auto&) { return std::string(); },
                                 },
                                 r.states);
}

void stage_mode_shapes(OutputTransaction& out, const std::filesystem::path& dir, const EquilibriaReport& r,
                       const OutputContext& c, bool chart) {
  const auto stage = [&](const auto& s) {
    const auto& a = s.analysis;
    const auto& p = s.params;
    const auto csv = out.stage(dir / "modes.csv", mode_shapes_csv(a, p, provenance_header(c.command_line, c.scene_file, p)));
    const ModeChart mc = mode_chart(a, p);
    if (mc.titles.empty() || !chart) return;
    std::vector<std::pair<std::string, std::string>> vars{
        {"csv", csv.string()},
        {"png", out.reserve(dir / "modes.png").string()},
        {"equilibrium", std::to_string(mc.equilibrium + 1)},
        {"count", std::to_string(mc.titles.size())},
        {"title", fmt::format("{}: mode shapes of {} at omega = {} rad/s (rotating frame)", c.scene_file, mc.label,
                              p.omega)}};
    for (std::size_t k = 0; k < mc.titles.size(); ++k) vars.emplace_back(fmt::format("t{}", k + 1), mc.titles[k]);
    run_gnuplot(plots_dir() / "modes.gp", vars);
  };
  if (const auto* s = std::get_if<RigidStates2>(&r.states)) stage(*s);
  if (const auto* s = std::get_if<RigidStatesN>(&r.states)) stage(*s);
}

void stage_stick_set_files(OutputTransaction& out, const std::filesystem::path& d, const EquilibriaReport& r,
                           const OutputContext& c, bool chart) {
  const auto* st = std::get_if<StickSetStates>(&r.states);
  if (!st) return;
  const StickSet& s = st->set;
  const ParamsN& p = st->params;
  const std::string header = provenance_header(c.command_line, c.scene_file, p);
  out.stage(d / "stick_set.csv", stick_set_csv(s, header, st->shaft ? &*st->shaft : nullptr));
  if (s.n_balls != 2) return;
  const auto boundary = out.stage(d / "stick_boundary.csv", stick_boundary_csv(s, header));
  const auto raster = out.stage(d / "stick_raster.dat", stick_raster_dat(p, 240));
  if (!chart) return;
  std::string marks = "# smooth equilibria (tau = 0): beta1 beta2 kind (1 balanced, 2 other)\n";
  for (const auto& sd : s.seeds)
    marks += fmt::format("{},{},{}\n", sd.beta[0], sd.beta[1], sd.family == "balanced" ? 1 : 2);
  const auto seeds = out.stage(d / "stick_seeds.dat", marks);
  run_gnuplot(plots_dir() / "stick_set.gp",
              {{"csv", boundary.string()},
               {"raster", raster.string()},
               {"seeds", seeds.string()},
               {"png", out.reserve(d / "stick_set.png").string()},
               {"worst1", fmt::format("{}", s.worst_beta.empty() ? -10.0 : s.worst_beta[0])},
               {"worst2", fmt::format("{}", s.worst_beta.empty() ? -10.0 : s.worst_beta[1])},
               {"title", fmt::format("{}: stick set of coulomb-set friction at omega = {} rad/s", c.scene_file, p.omega)},
               {"subtitle", fmt::format("area {:.4g} rad^2 ({:.3g} of the torus), {} component(s), "
                                        "V = {:.4g} m (balanced comp.), V_E = {:.4g} m",
                                        s.area, s.area_fraction, s.components.size(), s.worst_q_abs,
                                        s.worst_q_abs_any)}});
}

}  // namespace abu
