#include "abu/core/suggest.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "abu/core/params.hpp"

namespace abu {

int edit_distance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) { return char(std::tolower(static_cast<unsigned char>(c))); };
  const std::size_t n = a.size(), m = b.size();
  // Three rows of the dynamic programme (the transposition looks two rows back).
  std::vector<int> before(m + 1), previous(m + 1), current(m + 1);
  for (std::size_t j = 0; j <= m; ++j) previous[j] = int(j);
  for (std::size_t i = 1; i <= n; ++i) {
    current[0] = int(i);
    for (std::size_t j = 1; j <= m; ++j) {
      const int cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        current[j] = std::min(current[j], before[j - 2] + 1);
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[m];
}

std::optional<std::string> closest_name(std::string_view word, const std::vector<std::string_view>& candidates) {
  const std::size_t length = word.size();
  const int allowed = length <= 1 ? 0 : length <= 5 ? 1 : int(length / 3);
  std::optional<std::string> best;
  int best_distance = allowed + 1;
  for (auto c : candidates) {
    if (c == word) continue;  // a name that is known is not misspelled
    const int d = edit_distance(word, c);
    if (d < best_distance) best_distance = d, best = std::string(c);
  }
  return best;
}

std::string did_you_mean(std::string_view word, const std::vector<std::string_view>& candidates) {
  const auto best = closest_name(word, candidates);
  return best ? fmt::format("; did you mean '{}'?", *best) : std::string();
}

std::string unknown_name_rule(std::string_view what, const std::optional<std::string>& best, std::string_view label,
                              std::string_view known) {
  return best ? fmt::format("{}; did you mean '{}'? ({}: {})", what, *best, label, known)
              : fmt::format("{}; {}: {}", what, label, known);
}

std::vector<std::string_view> split_names(std::string_view list) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < list.size()) {
    while (i < list.size() && (list[i] == ' ' || list[i] == ',')) ++i;
    std::size_t j = i;
    while (j < list.size() && list[j] != ' ' && list[j] != ',') ++j;
    if (j > i) out.push_back(list.substr(i, j - i));
    i = j;
  }
  return out;
}

std::optional<std::string> closest_param(std::string_view word, bool with_ball_count) {
  // Every symbol, by the one spelling params.cpp gives it.
  std::vector<std::string> symbols, per_ball_symbols;
  for (int q = int(Quantity::omega); q <= int(Quantity::surface_radius); ++q) {  // the last Quantity
    symbols.push_back(to_string(ParamRef{Quantity(q), -1}));
    if (is_per_ball(Quantity(q))) per_ball_symbols.push_back(symbols.back());
  }
  if (with_ball_count) symbols.push_back("n");
  const std::vector<std::string_view> names(symbols.begin(), symbols.end());
  // A per-ball symbol with an index ("m3") is spelled right; its index is what is wrong.
  std::size_t digits = word.size();
  while (digits > 0 && word[digits - 1] >= '0' && word[digits - 1] <= '9') --digits;
  const auto stem = word.substr(0, digits);
  const bool indexed = digits > 0 && digits < word.size();
  if (indexed && std::find(per_ball_symbols.begin(), per_ball_symbols.end(), stem) != per_ball_symbols.end())
    return std::nullopt;
  if (auto best = closest_name(word, names)) return best;
  // A misspelled per-ball symbol with its index: suggest for the symbol, keep the index.
  if (!indexed) return std::nullopt;
  const std::vector<std::string_view> per_ball(per_ball_symbols.begin(), per_ball_symbols.end());
  if (auto best = closest_name(stem, per_ball)) return *best + std::string(word.substr(digits));
  return std::nullopt;
}

}  // namespace abu
