// Private to the design study (design_study.cpp, design_search.cpp): one design's evaluation.
#pragma once

#include <string>
#include <vector>

#include "abu/analysis/design_study.hpp"

namespace abu {

/// A design's figures without runs: the machine's (ball mass, capacity) and the linear
/// constraints, the objective if it is a design variable; `note` says which constraint fails.
DesignPoint machine_figures(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o,
                            const std::vector<double>& values, const std::string& origin);
/// Whether the objective or a constraint needs the design's runs.
bool needs_runs(const DesignOptions& o);
/// The design's runs (the outcome study with o.outcomes' points), the run constraints and the
/// objective from them.
void run_design(const Scene& scene, const SpeedProfile& speed, const DesignOptions& o, DesignPoint& d);

}  // namespace abu
