// "Did you mean": the known name nearest to a misspelled one, by edit distance.
//
//   abu::did_you_mean("stifness", {"mass", "stiffness", "damping"})   // "; did you mean 'stiffness'?"
//   abu::did_you_mean("xyz", {"mass"})                                 // ""
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace abu {

/// Optimal-string-alignment distance (Levenshtein with adjacent transpositions counted
/// as one edit), case-insensitive: "omgea" -> "omega" is 1, "Omega" -> "omega" is 0.
int edit_distance(std::string_view a, std::string_view b);

/// The candidate nearest to `word`, if it is near enough to be a slip of the keyboard:
/// at most 1 edit for words of 2 to 5 characters (none but case for one character, where
/// one edit reaches every symbol), a third of the length beyond. Ties: the first listed.
std::optional<std::string> closest_name(std::string_view word, const std::vector<std::string_view>& candidates);

/// "; did you mean 'NAME'?" for closest_name's answer, or "" if there is none.
std::string did_you_mean(std::string_view word, const std::vector<std::string_view>& candidates);

/// The rule for an unknown name: "WHAT; did you mean 'BEST'? (LABEL: KNOWN)" with a
/// suggestion, "WHAT; LABEL: KNOWN" without.
std::string unknown_name_rule(std::string_view what, const std::optional<std::string>& best, std::string_view label,
                              std::string_view known);

/// Splits a help list such as "mass, stiffness, damping" or "omega U k" into its names.
std::vector<std::string_view> split_names(std::string_view list);

/// The parameter symbols of params.hpp (omega U k c M_r kappa m l r mu d mu_c mu_s v_s),
/// and for a misspelled per-ball symbol with an index ("mu_k2") the symbol with it ("mu_c2").
std::optional<std::string> closest_param(std::string_view word, bool with_ball_count = false);

}  // namespace abu
