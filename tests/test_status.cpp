// Results carry a status (core/status.hpp): converged, not converged or a numerical issue,
// with the reason, and the library reports it instead of aborting or throwing.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <type_traits>

#include "abu/continuation/bordered.hpp"
#include "abu/core/params.hpp"
#include "abu/core/status.hpp"
#include "abu/equilibria/equilibria.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/scan.hpp"

namespace {

abu::Params default_params() {  // data/scenes/default.toml
  abu::Params p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = abu::FrictionLaw::coulomb;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 0.0, 0.0, 0.0, 0.0};
  return p;
}

}  // namespace

TEST_CASE("status: one outcome type for the library and the continuation engine", "[status]") {
  STATIC_REQUIRE(std::is_same_v<abu::arclength::Status, abu::Outcome>);
  CHECK(abu::to_string(abu::Outcome::numerical_issue) == "numerical issue");
  CHECK(abu::arclength::to_string(abu::arclength::Status::not_converged) == "not converged");
  // merge keeps the worst outcome and the first reason for it.
  abu::Status s;
  CHECK(s.ok());
  s.merge(abu::Outcome::not_converged, "first");
  s.merge(abu::Outcome::not_converged, "second");
  CHECK(s.reason == "first");
  s.merge(abu::Outcome::numerical_issue, "worse");
  s.merge(abu::Outcome::converged, "");
  CHECK(s.outcome == abu::Outcome::numerical_issue);
  CHECK(s.reason == "worse");
}

TEST_CASE("status: the default scene's equilibria and spectra converge", "[status]") {
  const abu::Params p = default_params();
  const abu::Analysis a = abu::analyze(p);
  const auto points = a.equilibria.points();
  REQUIRE(points.size() == 6);
  for (std::size_t i = 0; i < points.size(); ++i) {
    CHECK(points[i].status.ok());
    CHECK(points[i].status.reason.empty());
    CHECK(points[i].converged == points[i].status.ok());
    CHECK(a.spectra[i].status.ok());
    CHECK(a.spectra[i].converged);
  }
}

TEST_CASE("status: a polish from a non-finite guess is a numerical issue, not an abort", "[status]") {
  const abu::Params p = default_params();
  const abu::EquilibriumSet set = abu::find_equilibria(p);
  abu::Equilibrium guess = set.points()[0];
  guess.position(0) = std::numeric_limits<long double>::quiet_NaN();
  const abu::Equilibrium e = abu::polish_equilibrium(p, guess);
  CHECK_FALSE(e.converged);
  CHECK(e.status.outcome == abu::Outcome::numerical_issue);
  CHECK_FALSE(e.status.reason.empty());
}

TEST_CASE("status: the spectrum of a non-finite linearization is a numerical issue", "[status]") {
  // J is not finite: the QR (and GSL's balancing) cannot run; the spectrum says so
  // instead of aborting or returning values that look computed.
  const abu::Params p = default_params();
  const abu::EquilibriumSet set = abu::find_equilibria(p);
  const abu::Equilibrium e = set.points()[0];
  auto lin = abu::linearize(p.cast<long double>(), e.state());
  lin.stiffness(0, 0) = std::numeric_limits<long double>::infinity();
  const abu::Spectrum sp = abu::compute_spectrum(lin);
  CHECK(sp.status.outcome == abu::Outcome::numerical_issue);
  CHECK(sp.status.reason.view().find("QR") != std::string_view::npos);
}

TEST_CASE("status: QR-only spectra say they are not refined", "[status]") {
  const abu::Params p = default_params();
  const abu::EquilibriumSet set = abu::find_equilibria(p);
  const abu::Equilibrium e = set.points()[0];
  const auto lin = abu::linearize(p.cast<long double>(), e.state());
  const abu::Spectrum sp = abu::compute_spectrum(lin, abu::SpectrumMethod::dense_qr);
  CHECK(sp.status.outcome == abu::Outcome::not_converged);
  CHECK_FALSE(sp.converged);
  CHECK(abu::compute_spectrum(lin).status.ok());
}

TEST_CASE("status: n-ball equilibria (aligned and balanced samples) carry a status", "[status]") {
  abu::ParamsN p;
  const abu::Params two = default_params();
  p.rotor = two.rotor;
  p.omega = two.omega;
  p.law = two.law;
  p.kappa = two.kappa;
  p.balls.resize(3);
  for (auto& b : p.balls) b = two.balls[0];
  const abu::AnalysisN a = abu::analyze(p);
  const auto points = a.equilibria.points();
  REQUIRE(points.size() > 8);
  for (std::size_t i = 0; i < points.size(); ++i) {
    CHECK(points[i].converged == points[i].status.ok());
    CHECK(a.spectra[i].converged == a.spectra[i].status.ok());
  }
}
