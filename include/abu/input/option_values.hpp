// The values of command options that are not a scene's keys, read as every front end reads
// them (the CLI's options; the Python module's arguments of the same meaning): lists of
// reals and cell grids. Bad text is InputError naming the option (exit 2).
//
//   std::vector<double> balls = abu::parse_real_list("2, 4.5", "--balls");
//   auto [cells1, cells2] = abu::parse_cell_grid("40x30", "--grid");
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace abu {

/// A comma-separated list of finite reals ("2, 4.5,1e-3"; spaces around items allowed), as
/// --balls, --from-state, --fixed and --at-balls take it; otherwise InputError naming
/// `option`.
std::vector<double> parse_real_list(const std::string& text, const std::string& option);

/// "N" or "N1xN2": cells per axis, integers in 2..1000 (a basin's grid of start angles);
/// otherwise InputError naming `option`.
std::pair<int, int> parse_cell_grid(const std::string& text, const std::string& option);

}  // namespace abu
