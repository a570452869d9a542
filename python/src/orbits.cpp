// abu.continue_orbits: `continue` on an unround race with an anisotropic support (docs/model.md
// §20.9), the same library call as the CLI's, its result as a dict of numpy arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "abu/analysis/composed_parameter.hpp"
#include "abu/analysis/machine_parts.hpp"
#include "abu/core/errors.hpp"
#include "abu/input/ranges.hpp"
#include "bindings.hpp"

namespace abu::python {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

py::dict orbit_branch_dict(const ComposedBranch& b) {
  const auto& pts = b.branch.points;
  const py::ssize_t k = py::ssize_t(pts.size());
  const py::ssize_t d = pts.empty() ? 0 : py::ssize_t(pts.front().orbit.state0.size());
  auto value = zeros<double>({k}), q_max = zeros<double>({k}), q_min = zeros<double>({k}), rho = zeros<double>({k}),
       band = zeros<double>({k});
  auto multipliers = zeros<std::complex<double>>({k, d});
  auto state0 = zeros<double>({k, d});
  py::list stability, orbit;
  for (py::ssize_t i = 0; i < k; ++i) {
    const ForcedOrbit& o = pts[std::size_t(i)].orbit;
    const bool usable = o.status.ok() && !o.multipliers.empty();
    value.mutable_at(i) = pts[std::size_t(i)].value;
    q_max.mutable_at(i) = usable ? o.q_abs_max : kNaN;
    q_min.mutable_at(i) = usable ? o.q_abs_min : kNaN;
    rho.mutable_at(i) = usable ? std::abs(o.multipliers.front()) : kNaN;
    band.mutable_at(i) = usable ? o.band : kNaN;
    for (py::ssize_t j = 0; j < d; ++j) {
      multipliers.mutable_at(i, j) = j < py::ssize_t(o.multipliers.size()) ? o.multipliers[std::size_t(j)] : kNaN;
      state0.mutable_at(i, j) = j < py::ssize_t(o.state0.size()) ? o.state0[std::size_t(j)] : kNaN;
    }
    stability.append(usable ? std::string(to_string(o.verdict)) : std::string());
    orbit.append(o.kind);
  }
  py::dict out;
  out["start"] = b.start_value;
  out["value"] = value;
  out["orbit"] = orbit;
  out["stability"] = stability;
  out["rho_abs_max"] = rho;
  out["q_abs_max"] = q_max;
  out["q_abs_min"] = q_min;
  out["band"] = band;
  out["multipliers"] = multipliers;
  out["state0"] = state0;
  out["end_forward"] = b.branch.end_forward;
  out["end_backward"] = b.branch.end_backward;
  out["ok"] = b.branch.status.ok();
  out["reason"] = b.branch.reason;
  return out;
}

py::dict orbit_specials_dict(const ComposedBranches& r) {
  std::vector<const ForcedSpecialPoint*> all;
  std::vector<int> branch;
  for (std::size_t i = 0; i < r.branches.size(); ++i)
    for (const ForcedSpecialPoint& s : r.branches[i].branch.specials) all.push_back(&s), branch.push_back(int(i) + 1);
  const py::ssize_t k = py::ssize_t(all.size());
  auto index = zeros<int>({k});
  auto value = zeros<double>({k}), q_max = zeros<double>({k}), lower = zeros<double>({k}), upper = zeros<double>({k});
  auto multiplier = zeros<std::complex<double>>({k});
  auto located = zeros<bool>({k});
  py::list kind;
  for (py::ssize_t i = 0; i < k; ++i) {
    const ForcedSpecialPoint& s = *all[std::size_t(i)];
    index.mutable_at(i) = branch[std::size_t(i)];
    // detected, not located: no value, the bracket of branch values it lies in
    located.mutable_at(i) = s.located;
    value.mutable_at(i) = s.located ? s.value : kNaN;
    lower.mutable_at(i) = s.located ? kNaN : s.bracket[0];
    upper.mutable_at(i) = s.located ? kNaN : s.bracket[1];
    q_max.mutable_at(i) = s.orbit.status.ok() ? s.orbit.q_abs_max : kNaN;
    multiplier.mutable_at(i) = s.multiplier;
    kind.append(s.kind);
  }
  py::dict out;
  out["branch"] = index;
  out["kind"] = kind;
  out["value"] = value;
  out["located"] = located;
  out["bracket_lower"] = lower;
  out["bracket_upper"] = upper;
  out["q_abs_max"] = q_max;
  out["multiplier"] = multiplier;
  return out;
}

py::dict continue_orbits(const Scene& scene, const std::string& param, double to, double ds, double ds_min,
                         double ds_max, int max_steps, int threads) {
  if (!unround_on_anisotropic_support(scene))
    throw NotSupportedError(fmt::format("abu.continue_orbits: {} is not an unround race on an anisotropic support "
                                        "(model.md §20.9); abu.continue_branches continues equilibria",
                                        scene.file));
  check_numerical_range(scene, "abu.continue_orbits");  // the start, as the CLI checks a scene
  const ComposedParam c = composed_param(scene, param, "param");
  ForcedBranchOptions options;
  options.continuation = {ds, ds_min, ds_max, max_steps, threads};
  if (const auto rule = options_violation(options.continuation)) throw InputError("options", 0, "", *rule);
  ComposedBranches r;
  {
    py::gil_scoped_release release;
    r = continue_composed(scene, c, to, options, "to");
  }
  py::list branches;
  for (const ComposedBranch& b : r.branches) branches.append(orbit_branch_dict(b));
  py::dict out;
  out["param"] = c.name;
  out["unit"] = c.unit_name;
  out["from_value"] = r.start;
  out["to_value"] = r.end;
  out["orbits_at_start"] = r.orbits_at_start;
  out["orbits_at_end"] = r.orbits_at_end;
  out["branches"] = branches;
  out["special_points"] = orbit_specials_dict(r);
  out["ok"] = r.status.ok();
  out["reason"] = r.reason;
  return out;
}

}  // namespace

void bind_orbits(py::module_& m) {
  m.def("continue_orbits", &continue_orbits, py::arg("scene"), py::arg("param"), py::arg("to"), py::arg("ds"),
        py::arg("ds_min"), py::arg("ds_max"), py::arg("max_steps"), py::arg("threads"),
        "Branches of periodic orbits of an unround race on an anisotropic support, as a dict (abu.continue_orbits "
        "wraps it).");
}

}  // namespace abu::python
