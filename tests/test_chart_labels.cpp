// What a chart's subtitle says (output/chart_labels.hpp): a quantity that varies is named with its
// range, never with the scene's value; the speed is always said.
#include <catch2/catch.hpp>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "abu/core/parallel.hpp"
#include "abu/input/scene.hpp"
#include "abu/output/chart_labels.hpp"
#include "scene_texts.hpp"

using namespace abu;
using abu::testing::kBase;
using abu::testing::line_replaced;

TEST_CASE("a chart subtitle names what varies and the speed", "[chart_labels]") {
  const Scene s = parse_scene(kBase, "base.toml");
  const std::string plain = chart_subtitle(s, {});
  CHECK(plain.find("speed omega = 900 rad/s") != std::string::npos);
  CHECK(plain.find("mu = 0.002") != std::string::npos);
  CHECK(plain.find("varies") == std::string::npos);

  const std::string over_mu = chart_subtitle(s, {}, {{"mu", 1e-4, 1e-2, "-"}});
  CHECK(over_mu.rfind("varies: mu = 0.0001 .. 0.01 (x axis)|", 0) == 0);
  CHECK(over_mu.find("mu = 0.002") == std::string::npos);  // the scene's value is not the chart's
  CHECK(over_mu.find("mu varies") != std::string::npos);

  const std::string over_omega = chart_subtitle(s, {}, {{"omega", 100, 1000, "rad/s"}});
  CHECK(over_omega.find("900 rad/s") == std::string::npos);
  CHECK(over_omega.find("speed omega varies") != std::string::npos);

  // the ball radius moves mu through f (mu = f / r, model.md §1.1), but not m and l given as they
  // are; a scene with mu given keeps it: nothing follows r
  const Scene rolling = parse_scene(line_replaced(kBase, 17, "f = 2.0e-6").c_str(), "rolling.toml");
  const std::string over_r = chart_subtitle(rolling, {}, {{"r", 5e-4, 2e-3, "m"}, {"m1", 1e-5, 3e-5, "kg", "y axis"}});
  CHECK(over_r.find("mu follows r") != std::string::npos);
  CHECK(over_r.find("l = 0.018 m") != std::string::npos);
  CHECK(over_r.find("m m1 varies") != std::string::npos);
  CHECK(over_r.find("(y axis)") != std::string::npos);
  const std::string given = chart_subtitle(s, {}, {{"r", 5e-4, 2e-3, "m"}});
  CHECK(given.find("follows") == std::string::npos);
  CHECK(given.find("mu = 0.002") != std::string::npos);

  // k moves omega_n, and the capacity stays
  const std::string over_k = chart_subtitle(s, {}, {{"k", 1e3, 1e4, "N/m"}});
  CHECK(over_k.find("omega_n varies") != std::string::npos);
  CHECK(over_k.find("capacity sum m l = 1.188e-06") != std::string::npos);
}

TEST_CASE("for_each_index visits every index once and rethrows the first failure", "[parallel]") {
  for (const int threads : {1, 2, 5}) {
    std::vector<std::atomic<int>> seen(97);
    for_each_index(97, threads, [&](int k) {
      ++seen[std::size_t(k)];
      return true;
    });
    for (const auto& v : seen) CHECK(v.load() == 1);
  }
  std::atomic<int> calls{0};
  CHECK_THROWS_AS(for_each_index(1000, 2,
                                 [&](int k) {
                                   ++calls;
                                   if (k == 3) throw std::runtime_error("item 3");
                                   return true;
                                 }),
                  std::runtime_error);
  CHECK(calls.load() < 1000);  // the hand-out stops at the failure
  calls = 0;
  for_each_index(50, 2, [&](int k) {
    ++calls;
    return k < 10;  // an interruption: false stops the hand-out
  });
  CHECK(calls.load() < 50);
}
