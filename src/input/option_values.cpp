#include "abu/input/option_values.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <string_view>

#include "abu/core/errors.hpp"

namespace abu {

std::vector<double> parse_real_list(const std::string& text, const std::string& option) {
  std::vector<double> v;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    std::string_view item(text.data() + start, comma - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    double x = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), x);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || !std::isfinite(x))
      throw InputError(option, 0, "", fmt::format("expected a comma-separated list of finite reals, got '{}'", text));
    v.push_back(x);
    start = comma + 1;
  }
  return v;
}

std::pair<int, int> parse_cell_grid(const std::string& text, const std::string& option) {
  const auto x = text.find('x');
  auto one = [&](std::string_view s) {
    int v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size() || v < 2 || v > 1000)
      throw InputError(option, 0, text, "expected N or N1xN2, cells per axis, integers in 2..1000");
    return v;
  };
  if (x == std::string::npos) {
    const int n = one(text);
    return {n, n};
  }
  return {one(std::string_view(text).substr(0, x)), one(std::string_view(text).substr(x + 1))};
}

}  // namespace abu
