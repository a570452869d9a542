// Shaft scenes (include/abu/input/shaft_scene.hpp, docs/model.md §18.10–§18.11): what a valid
// [shaft] scene becomes, and the rules the invalid scenes 100–111 do not cover one by one.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>

#include "abu/core/errors.hpp"
#include "abu/input/scene.hpp"
#include "abu/input/shaft_scene.hpp"
#include "abu/model/shaft.hpp"

namespace {

// The shaft scene of tests/scenes/invalid/100–111 before a rule is broken.
const char* const kShaft = R"([rotor]
unbalance = 1.0e-4
[shaft]
balancer_node = 4
[[shaft.element]]
length = 0.4
outer_diameter = 0.04
youngs_modulus = 2.1e11
density = 7850.0
segments = 4
[[disc]]
node = 4
mass = 4.93
polar_inertia = 2.466e-2
transverse_inertia = 1.249e-2
[[bearing]]
node = 0
stiffness = 5.0e7
damping = 500.0
[[bearing]]
node = 3
stiffness = 5.0e7
damping = 500.0
[[ball]]
mass = 4.1e-3
race_radius = 0.08
radius = 5.0e-3
[[ball]]
mass = 4.1e-3
race_radius = 0.08
radius = 5.0e-3
[friction]
law = "coulomb"
mu = 0.002
kappa = 1.0e3
[speed]
omega = 2500.0
)";

// A rigid two-ball scene (no [shaft]), 17 lines.
constexpr const char* kRigid = R"([rotor]
mass = 0.12
stiffness = 7500.0
damping = 2.0
unbalance = 6.0e-7
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[friction]
law = "none"
[speed]
omega = 900.0
)";

// kShaft with lines replaced (1-based line -> replacement text, "" deletes the line).
std::string edited(std::initializer_list<std::pair<int, std::string>> edits) {
  std::string out, line;
  std::istringstream in(kShaft);
  for (int i = 1; std::getline(in, line); ++i) {
    bool replaced = false;
    for (const auto& [n, text] : edits)
      if (n == i) {
        if (!text.empty()) out += text + "\n";
        replaced = true;
      }
    if (!replaced) out += line + "\n";
  }
  return out;
}

abu::InputError refused(const std::string& text) {
  try {
    abu::parse_scene(text, "shaft.toml");
  } catch (const abu::InputError& e) {
    return e;
  }
  FAIL("the scene was accepted");
  return abu::InputError("", -1, "", "");
}

}  // namespace

TEST_CASE("a shaft scene becomes the ShaftSpec it describes", "[scene][shaft]") {
  const abu::Scene s = abu::parse_scene(kShaft, "shaft.toml");
  REQUIRE(s.shaft);
  const abu::ShaftSpec& spec = abu::shaft_spec_of(s);
  // segments = 4 cuts the 0.4 m section into 4 elements of 0.1 m (0.4/4 is exact in binary
  // up to one rounding: 1e-15 relative).
  REQUIRE(spec.elements.size() == 4);
  CHECK(spec.nodes() == 5);
  for (const auto& e : spec.elements) {
    CHECK(e.length == Approx(0.1).epsilon(1e-15));
    CHECK(e.outer_diameter == 0.04);
    CHECK(e.inner_diameter == 0.0);    // default: solid
    CHECK(e.shear_modulus == 0.0);     // absent: Euler–Bernoulli
    CHECK(e.density == 7850.0);
  }
  const auto x = abu::node_positions(spec);
  REQUIRE(x.size() == 5);
  for (int k = 0; k < 5; ++k) CHECK(x[std::size_t(k)] == Approx(0.1 * k).margin(1e-15));
  REQUIRE(spec.discs.size() == 1);
  CHECK(spec.discs[0].node == 4);
  CHECK(spec.discs[0].polar_inertia == 2.466e-2);
  REQUIRE(spec.bearings.size() == 2);
  CHECK(spec.bearings[1].node == 3);
  CHECK(spec.bearings[1].tilt_stiffness == 0.0);  // default
  CHECK(spec.balancer_node == 4);
  // [rotor] gives U only; M_r, k, c have no meaning here and are 0.
  CHECK(s.rotor.unbalance == 1.0e-4);
  CHECK(s.rotor.mass == 0.0);
  CHECK(s.rotor.stiffness == 0.0);
  // Mass by hand: rho pi D^2/4 L + m_disc = 7850 * pi * 0.0004 * 0.4 + 4.93 (1e-13: a sum of four terms).
  CHECK(abu::shaft_mass(spec) == Approx(7850.0 * std::numbers::pi * 0.0004 * 0.4 + 4.93).epsilon(1e-13));
}

TEST_CASE("a rigid scene has no shaft, and shaft_spec_of says so", "[scene][shaft]") {
  const abu::Scene s = abu::parse_scene(kRigid, "rigid.toml");
  CHECK_FALSE(s.shaft);
  CHECK_THROWS_AS(abu::shaft_spec_of(s), abu::NotSupportedError);
}

TEST_CASE("the bearings must hold the shaft against rigid-body motion", "[scene][shaft]") {
  // One bearing (node 0 only): the shaft pivots about it.
  const auto one = refused(edited({{20, ""}, {21, ""}, {22, ""}, {23, ""}}));
  CHECK(one.key() == "bearing");
  CHECK(one.line() == 17);  // the first bearing's node
  CHECK_THAT(one.rule(), Catch::Contains("free to tilt about that node"));
  // The same bearing with a tilt spring holds it.
  const abu::Scene held = abu::parse_scene(edited({{19, "damping = 500.0\ntilt_stiffness = 1e5"}, {20, ""}, {21, ""},
                                                   {22, ""}, {23, ""}}),
                                           "shaft.toml");
  CHECK(held.shaft->bearings.size() == 1);
  // Two bearings on one node add up but still leave the tilt free.
  const auto same_node = refused(edited({{21, "node = 0"}}));
  CHECK(same_node.key() == "bearing");
  // No stiffness at all: free translation.
  const auto soft = refused(edited({{18, "stiffness = 0.0"}, {22, "stiffness = 0.0"}}));
  CHECK_THAT(soft.rule(), Catch::Contains("free to translate"));
}

TEST_CASE("a disc's polar inertia is at most twice its transverse inertia", "[scene][shaft]") {
  // Swapped values: I_p = 1.249e-2 is fine, but I_p = 2.466e-2 with I_d = 1.0e-2 is no rigid body.
  const auto e = refused(edited({{15, "transverse_inertia = 1.0e-2"}}));
  CHECK(e.key() == "disc[1].transverse_inertia");  // the later of the two keys
  CHECK(e.line() == 15);
  CHECK_THAT(e.rule(), Catch::Contains("I_p <= 2 I_d"));
  // A thin disc has I_p = 2 I_d exactly: accepted.
  CHECK_NOTHROW(abu::parse_scene(edited({{15, "transverse_inertia = 1.233e-2"}}), "shaft.toml"));
}

TEST_CASE("element tables with no balancer node, and shaft keys of the wrong kind", "[scene][shaft]") {
  const auto no_shaft = refused(edited({{3, ""}, {4, ""}}));
  // [shaft.element] tables then define an implicit [shaft]: the balancer_node is missing.
  CHECK(no_shaft.key() == "shaft.balancer_node");
  const auto segments_real = refused(edited({{10, "segments = 4.0"}}));
  CHECK(segments_real.key() == "shaft.element[1].segments");
  CHECK_THAT(segments_real.rule(), Catch::Contains("must be an integer"));
  const auto segments_zero = refused(edited({{10, "segments = 0"}}));
  CHECK_THAT(segments_zero.rule(), Catch::Contains("must be an integer 1..100000"));
  const auto shear = refused(edited({{9, "density = 7850.0\nshear_modulus = -1.0"}}));
  CHECK(shear.key() == "shaft.element[1].shear_modulus");
  const auto node_real = refused(edited({{12, "node = 4.5"}}));
  CHECK(node_real.key() == "disc[1].node");
  const auto e_zero = refused(edited({{8, "youngs_modulus = 0.0"}}));
  CHECK(e_zero.key() == "shaft.element[1].youngs_modulus");
  CHECK_THAT(e_zero.rule(), Catch::Contains("must be > 0"));
  const auto stiff_rotor = refused(edited({{2, "unbalance = 1.0e-4\nstiffness = 1.0"}}));
  CHECK(stiff_rotor.key() == "rotor.stiffness");
  CHECK_THAT(stiff_rotor.rule(), Catch::Contains("[[bearing]]"));
}

TEST_CASE("a disc or bearing in a rigid scene is refused", "[scene][shaft]") {
  const std::string rigid = std::string(kRigid) + R"([[disc]]
node = 0
mass = 1.0
polar_inertia = 0.0
transverse_inertia = 0.0
)";
  const auto e = refused(rigid);
  CHECK(e.key() == "disc");
  CHECK(e.line() == 18);
  CHECK_THAT(e.rule(), Catch::Contains("add [shaft]"));
}

TEST_CASE("a shaft scene refuses the rigid rotor's k, c, M_r as overrides and takes omega", "[scene][shaft]") {
  abu::Scene s = abu::parse_scene(kShaft, "shaft.toml");
  for (const char* a : {"k=1e6", "c=3", "M_r=2"}) {
    try {
      abu::apply_override(s, a);
      FAIL("accepted " << a);
    } catch (const abu::InputError& e) {
      CHECK_THAT(e.rule(), Catch::Contains("[[bearing]]"));
    }
  }
  abu::apply_override(s, "omega=3000");
  CHECK(s.omega == 3000.0);
  abu::apply_override(s, "U=2e-4");
  CHECK(s.rotor.unbalance == 2e-4);
  CHECK(s.shaft->elements.size() == 4);  // the shaft is shared by copies and unchanged
}
