// "Did you mean" (core/suggest.hpp): the edit distance and which names are near enough.
#include <catch2/catch.hpp>

#include "abu/core/suggest.hpp"

TEST_CASE("edit distance counts insertions, deletions, substitutions and transpositions once", "[suggest]") {
  CHECK(abu::edit_distance("stifness", "stiffness") == 1);   // insertion
  CHECK(abu::edit_distance("omgea", "omega") == 1);          // transposition
  CHECK(abu::edit_distance("Omega", "omega") == 0);          // case does not count
  CHECK(abu::edit_distance("equilibrium", "equilibria") == 2);
  CHECK(abu::edit_distance("", "mass") == 4);
  CHECK(abu::edit_distance("kitten", "sitting") == 3);       // the textbook case
}

TEST_CASE("closest_name suggests only slips of the keyboard", "[suggest]") {
  const std::vector<std::string_view> keys{"mass", "stiffness", "damping", "unbalance"};
  CHECK(abu::closest_name("stifness", keys) == "stiffness");
  CHECK(abu::closest_name("dampnig", keys) == "damping");
  CHECK_FALSE(abu::closest_name("inertia", keys));  // 6+ edits from everything
  CHECK_FALSE(abu::closest_name("mass", keys));     // known: nothing to suggest
  // One character: only its case (one edit would reach every one-letter symbol).
  CHECK(abu::closest_name("K", {"k", "c"}) == "k");
  CHECK_FALSE(abu::closest_name("x", {"k", "c"}));
  CHECK(abu::did_you_mean("sped", {"rotor", "speed"}) == "; did you mean 'speed'?");
  CHECK(abu::did_you_mean("zzz", {"rotor", "speed"}).empty());
}

TEST_CASE("closest_param knows the model's symbols and keeps a ball index", "[suggest]") {
  CHECK(abu::closest_param("omgea") == "omega");
  CHECK(abu::closest_param("Mr") == "M_r");
  CHECK(abu::closest_param("kapa") == "kappa");
  CHECK(abu::closest_param("mu_k2") == "mu_c2");  // the first of mu_c, mu_s at one edit
  CHECK_FALSE(abu::closest_param("m3"));          // spelled right; the index is what is wrong
  CHECK_FALSE(abu::closest_param("nn"));          // n only where the ball count is a parameter
  CHECK(abu::closest_param("nn", true) == "n");
  CHECK(abu::split_names("mass, stiffness, damping") == std::vector<std::string_view>{"mass", "stiffness", "damping"});
}
