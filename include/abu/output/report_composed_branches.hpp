// The files of `continue` on an unround race with an anisotropic support (docs/model.md §20.9,
// analysis/composed_branches.hpp): one CSV row per branch point (a blank line between
// branches, so that a chart draws each as a line), one per special point, and the text for
// stderr. Formatting only.
//
//   std::string csv = abu::composed_branches_csv(b, "omega", header);
#pragma once

#include <string>

#include "abu/analysis/composed_branches.hpp"

namespace abu {

std::string composed_branches_csv(const ComposedBranches& b, const std::string& name, const std::string& header);
std::string composed_specials_csv(const ComposedBranches& b, const std::string& name, const std::string& header);
/// The special points and the doubts, one line each.
std::string composed_branches_text(const ComposedBranches& b, const std::string& name);

}  // namespace abu
