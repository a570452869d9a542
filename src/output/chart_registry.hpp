// What the output transaction and the chart runner share (internal to src/output): the
// temporaries reserved for a chart's outputs, and those whose chart failed (not committed).
#pragma once

#include <mutex>
#include <set>
#include <string>

namespace abu::detail {

std::mutex& chart_mutex();
std::set<std::string>& reserved_outputs();      ///< guarded by chart_mutex()
std::set<std::string>& failed_chart_outputs();  ///< guarded by chart_mutex()

}  // namespace abu::detail
