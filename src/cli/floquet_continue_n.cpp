// `continue` on an anisotropic scene with n >= 3 balls (docs/model.md §10.16): the branches
// of the mean system's balanced samples, judged by Floquet at every point.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "abu/continuation/branches_n.hpp"
#include "abu/core/errors.hpp"
#include "abu/equilibria/balanced_closure.hpp"
#include "floquet_commands.hpp"

namespace abu::cli {

int continue_anisotropic_n(const Scene& scene, const SceneOptions& scene_options, ParamRef param, double to,
                           const ContinuationOptions& numerics, const BalancedSampling& sampling, bool chart,
                           const std::string& output_dir) {
  // The balanced set solves q = 0, sum m_i l_i e^{i beta_i} = -U whatever the support (§10.3):
  // the mean system's balanced samples, each traced with its free angles held (§13.7), are the
  // real system's balanced states; only their stability changes (Floquet, n - 2 unit
  // multipliers deflated, §10.4).
  const ParamsN base = params_of<any_balls>(scene);
  const ContinuationRunN run = continue_branches(base, param, to, floquet_branch_numerics(numerics), sampling);
  const FloquetSweepOptions options;
  FloquetSweep all;
  all.param = param;
  int branches = 0;
  for (const BranchN& b : run.branches) {
    if (b.family != Family::balanced) continue;
    ++branches;
    FloquetSweep branch;
    branch.param = param;
    for (const BranchPointN& point : b.points) {
      EquilibriumN e;
      e.member = b.member;
      e.on_balanced_set = true;
      e.position = point.position;
      append_balanced_floquet(branch, base, scene, param, double(point.parameter), e, options, "sample");
    }
    // At a bisection point the sample is the branch's: its free angles held, balls 1 and 2
    // closing the balance by Newton from the branch point nearest in the parameter.
    const auto at = [&](double value, int member, const FloquetOptions& o) -> std::optional<BalancedFloquet> {
      const auto nearest = std::min_element(b.points.begin(), b.points.end(), [&](const auto& x, const auto& y) {
        return std::abs(double(x.parameter) - value) < std::abs(double(y.parameter) - value);
      });
      ParamsN p = base;
      set(p, param, value);
      const std::optional<EquilibriumN> e = balanced_sample_at(p, nearest->position, member);
      if (!e) return std::nullopt;
      return balanced_floquet(p, *scene.support, *e, o);
    };
    locate_floquet_crossings(branch, at, options);
    all.values.insert(all.values.end(), branch.values.begin(), branch.values.end());
    all.points.insert(all.points.end(), branch.points.begin(), branch.points.end());
    all.crossings.insert(all.crossings.end(), branch.crossings.begin(), branch.crossings.end());
  }
  fmt::print(stderr,
             "{} balanced sample branch(es) of {} balls, {} points (continuation of the mean system's balanced "
             "samples, free angles held; n - 2 = {} unit multipliers deflated)\n",
             branches, scene.balls.size(), all.values.size(), scene.balls.size() - 2);
  return write_floquet_outputs(scene, scene_options, all, base, false, chart, output_dir, "floquet_branch",
                               fmt::format("balanced samples of {} balls in {}", scene.balls.size(), to_string(param)));
}

}  // namespace abu::cli
