// Results known by hand (model.md §5, §7; report eqs. 2.12-2.21 and Appendix A): the
// program's equilibria and spectra against closed forms written here independently,
// in long double from the exact double inputs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Cholesky>

#include "abu/equilibria/equilibria.hpp"
#include "abu/model/model.hpp"
#include "abu/core/params.hpp"
#include "abu/scan/scan.hpp"
#include "abu/linear/spectrum.hpp"

namespace {

using ld = long double;
using cld = std::complex<ld>;
using cd = std::complex<double>;
using abu::Family;
constexpr double kEps = std::numeric_limits<double>::epsilon();  // 2^-52, one ulp of 1
constexpr ld kPi = std::numbers::pi_v<ld>;

// The default scene of the brief: rolling balls (j = 7/5), coulomb friction.
abu::Params base_params() {
  abu::Params p;
  p.rotor = {0.12, 7500.0, 2.0, 6e-7};
  p.omega = 900.0;
  p.law = abu::FrictionLaw::coulomb;
  p.kappa = 1e3;
  for (auto& b : p.balls) b = {3.3e-5, 0.018, 1e-3, 1.4, 0.002, 0.0, 0.0, 0.0, 0.0};
  return p;
}

// The closed-form ingredients of model.md §5: K = k - w^2 M, C = c w, a_i = m_i l_i.
struct Scene {
  ld M, w, w2, K, C, U, a1, a2;
  explicit Scene(const abu::Params& p)
      : M(ld(p.rotor.mass) + ld(p.balls[0].mass) + ld(p.balls[1].mass)), w(p.omega), w2(w * w),
        K(ld(p.rotor.stiffness) - w2 * M), C(ld(p.rotor.damping) * w), U(p.rotor.unbalance),
        a1(ld(p.balls[0].mass) * ld(p.balls[0].race_radius)), a2(ld(p.balls[1].mass) * ld(p.balls[1].race_radius)) {}
};

// A closed-form equilibrium; `cond` is the conditioning factor of the arccos/asin
// that places its angles (|d beta / d x| * |x| for the argument x).
struct Point {
  Family family;
  cld q;
  ld b1, b2, cond;
};

ld angle_distance(ld a, ld b) { return std::abs(std::remainder(a - b, 2 * kPi)); }

// Roots of K U sin b + C U cos b + C a = 0 (eq. 2.19, Appendix A) through t = tan(b/2):
// (C a - C U) t^2 + 2 K U t + (C U + C a) = 0, discriminant 4 (U^2 (K^2 + C^2) - C^2 a^2).
// Roots returned as angles (2 atan2) so that t = infinity (b = pi) needs no special case.
std::vector<ld> line_roots(const Scene& s, ld a) {
  const ld qa = s.C * a - s.C * s.U, qb = 2 * s.K * s.U, qc = s.C * s.U + s.C * a;
  const ld disc = qb * qb - 4 * qa * qc;
  if (disc < 0) return {};
  const ld h = -(qb + std::copysign(std::sqrt(disc), qb)) / 2;
  return {2 * std::atan2(h, qa), 2 * std::atan2(qc, h)};
}

// The asin conditioning of those roots: sin(b + phi) = sigma, sigma = -C a / (U R).
ld line_cond(const Scene& s, ld a) {
  const ld sigma = std::abs(s.C * a / (s.U * std::hypot(s.K, s.C)));
  return sigma / std::sqrt(std::max(ld(1) - sigma * sigma, ld(1e-30)));
}

// All equilibria of two equal balls from the report's closed forms.
std::vector<Point> equal_ball_equilibria(const abu::Params& p) {
  const Scene s(p);
  const ld a = s.a1, R2 = s.K * s.K + s.C * s.C;
  std::vector<Point> pts;
  if (s.U < 2 * a) {  // eqs. 2.12-2.13: beta_{1,2} = pi -+ arccos(U / 2ml), q = 0
    const ld x = s.U / (2 * a), t = std::acos(x), cond = x / std::sqrt(1 - x * x);
    pts.push_back({Family::balanced, 0, kPi - t, kPi + t, cond});
    pts.push_back({Family::balanced, 0, kPi + t, kPi - t, cond});
  }
  for (const ld b : line_roots(s, 2 * a)) {  // eqs. 2.17-2.18 for q
    const ld load1 = s.U * s.w2 + 2 * a * s.w2 * std::cos(b), load2 = 2 * a * s.w2 * std::sin(b);
    const cld q((s.K * load1 + s.C * load2) / R2, (s.K * load2 - s.C * load1) / R2);
    pts.push_back({Family::together, q, b, b, line_cond(s, 2 * a)});
  }
  const cld q = s.w2 * s.U * cld(s.K, -s.C) / R2;  // eqs. 2.20-2.21: the rotor alone
  const ld b = std::atan2(q.imag(), q.real());
  pts.push_back({Family::opposite, q, b, b + kPi, 0});
  pts.push_back({Family::opposite, q, b + kPi, b + 2 * kPi, 0});
  return pts;
}

template <class Range>  // closed-form Points or the program's Equilibria
int count(const Range& pts, Family f) {
  return int(std::count_if(pts.begin(), pts.end(), [f](const auto& x) { return x.family == f; }));
}

// The program's equilibrium of the same family nearest (in angles) to a closed-form one.
const abu::Equilibrium* nearest(const abu::EquilibriumSet& set, const Point& x) {
  const abu::Equilibrium* best = nullptr;
  ld best_d = std::numeric_limits<ld>::infinity();
  for (const auto& e : set.points()) {
    if (e.family != x.family) continue;
    const ld d = std::max(angle_distance(e.position(2), x.b1), angle_distance(e.position(3), x.b2));
    if (d < best_d) best_d = d, best = &e;
  }
  return best;
}

// Static equations of model.md §5 at the double-rounded state, each over its natural size:
// rotor |(K + iC) q - w^2 (U + sum a e^{ib})| / ((|K| + C)|q| + w^2 (U + sum a)), balls
// |q1 sin b - q2 cos b| / (|q| + (U + sum a) / M).
ld static_residual(const abu::Params& p, const abu::Equilibrium& e) {
  const Scene s(p);
  const abu::Coordinates<ld, 2> x = e.position_si().cast<ld>();
  const cld q(x(0), x(1));
  const cld rotor = cld(s.K, s.C) * q - s.w2 * (s.U + s.a1 * std::polar(ld(1), x(2)) + s.a2 * std::polar(ld(1), x(3)));
  ld r = std::abs(rotor) / ((std::abs(s.K) + s.C) * std::abs(q) + s.w2 * (s.U + s.a1 + s.a2));
  for (int i = 2; i < 4; ++i)
    r = std::max(r, std::abs(x(0) * std::sin(x(i)) - x(1) * std::cos(x(i))) / (std::abs(q) + (s.U + s.a1 + s.a2) / s.M));
  return r;
}

// Pairs each formula value with the nearest unused eigenvalue; returns the largest
// relative mismatch |lambda - f| / |f|.
double worst_mismatch(const abu::Spectrum& sp, const std::vector<cd>& formula) {
  std::array<bool, 8> used{};
  double worst = 0;
  for (const cd f : formula) {
    std::size_t k = 8;
    for (std::size_t i = 0; i < 8; ++i)
      if (!used[i] && (k == 8 || std::abs(sp.eigenvalues[i] - f) < std::abs(sp.eigenvalues[k] - f))) k = i;
    used[k] = true;
    worst = std::max(worst, std::abs(sp.eigenvalues[k] - f) / std::abs(f));
  }
  return worst;
}

// Massless-ball spectrum (model.md §7) at a closed-form together/opposite point, coulomb.
std::vector<cd> massless_spectrum(const abu::Params& p, const Point& x) {
  const Scene s(p);
  const ld wn = std::sqrt(ld(p.rotor.stiffness) / s.M), zeta = ld(p.rotor.damping) / (2 * s.M * wn),
           wd = wn * std::sqrt(1 - zeta * zeta);
  std::vector<cd> f;
  for (const ld im : {wd - s.w, -(wd - s.w), wd + s.w, -(wd + s.w)}) f.emplace_back(double(-zeta * wn), double(im));
  const ld arg_q = std::arg(x.q);
  for (int i = 0; i < 2; ++i) {
    const auto& b = p.balls[std::size_t(i)];
    const ld side = std::cos((i == 0 ? x.b1 : x.b2) - arg_q) > 0 ? 1 : -1;
    const ld gamma = 2 / kPi * ld(b.mu) * ld(b.race_radius) * s.w2 * ld(p.kappa);  // -(dF/dbdot)/m
    const ld jl = ld(b.inertia_factor) * ld(b.race_radius), stiff = side * s.w2 * std::abs(x.q);
    // j l s^2 + gamma s + stiff = 0; the small root from the product of the roots (no cancellation).
    const cld fast = -(gamma + std::sqrt(cld(gamma * gamma - 4 * jl * stiff))) / (2 * jl);
    for (const cld root : {fast, stiff / (jl * fast)}) f.emplace_back(double(root.real()), double(root.imag()));
  }
  return f;
}

// Worst mismatch over the together and opposite points of a scene.
double massless_mismatch(const abu::Params& p) {
  const auto set = abu::find_equilibria(p);
  double worst = 0;
  int n = 0;
  for (const auto& x : equal_ball_equilibria(p)) {
    if (x.family == Family::balanced) continue;
    const abu::Equilibrium* e = nearest(set, x);
    REQUIRE(e != nullptr);
    worst = std::max(worst, worst_mismatch(abu::equilibrium_spectrum(p, *e), massless_spectrum(p, x)));
    ++n;
  }
  CHECK(n == 4);  // two together roots (|C 2ml| << U R) and two opposite points
  return worst;
}

// Each eigenvalue's image under `map` (negation or conjugation) is in the spectrum, within
// the two reported error estimates plus the double rounding of the printed values.
void check_closed_under(const abu::Spectrum& sp, cd (*map)(cd)) {
  for (std::size_t i = 0; i < 8; ++i) {
    const cd target = map(sp.eigenvalues[i]);
    std::size_t k = 0;
    for (std::size_t j = 1; j < 8; ++j)
      if (std::abs(sp.eigenvalues[j] - target) < std::abs(sp.eigenvalues[k] - target)) k = j;
    const double tol = 4 * (sp.error[i] + sp.error[k]) + 8 * kEps * std::abs(sp.eigenvalues[i]);
    INFO("lambda " << sp.eigenvalues[i] << " partner " << sp.eigenvalues[k] << " tol " << tol);
    CHECK(std::abs(sp.eigenvalues[k] - target) <= tol);
    // The check has teeth only if the estimates are small: a resolved spectrum.
    CHECK(sp.error[i] <= 1e-8 * std::abs(sp.eigenvalues[i]));
  }
}

}  // namespace

// Report eqs. 2.12-2.13, 2.17-2.21 for equal balls, below and above omega_n = 250 rad/s
// and with U < 2ml and U > 2ml (no balanced point): counts and states.
TEST_CASE("closed-form equilibria of equal balls", "[hand]") {
  for (const double omega : {100.0, 200.0, 240.0, 260.0, 300.0, 900.0, 3000.0}) {
    for (const double U : {1e-7, 6e-7, 1.1e-6, 2e-6}) {
      abu::Params p = base_params();
      p.omega = omega;
      p.rotor.unbalance = U;
      const auto expected = equal_ball_equilibria(p);
      const auto set = abu::find_equilibria(p);
      INFO("omega " << omega << " U " << U);
      CHECK(set.degeneracy == abu::degeneracy_none);
      for (const Family f : {Family::balanced, Family::together, Family::opposite})
        CHECK(count(set.points(), f) == count(expected, f));
      const ld L = (ld(U) + 2 * ld(3.3e-5) * ld(0.018)) / Scene(p).M;  // natural displacement
      for (const auto& x : expected) {
        const abu::Equilibrium* e = nearest(set, x);
        REQUIRE(e != nullptr);
        // Both sides are long-double evaluations of the exact inputs; asking for agreement
        // to 16 double ulps times the arccos/asin conditioning is what a double result can
        // promise, and far above the long-double noise (~1e-18 cond).
        const ld tol = 16 * kEps * (1 + x.cond);
        INFO(to_string(x.family) << " beta " << double(x.b1) << " " << double(x.b2));
        CHECK(angle_distance(e->position(2), x.b1) <= tol * 2 * kPi);
        CHECK(angle_distance(e->position(3), x.b2) <= tol * 2 * kPi);
        CHECK(std::abs(cld(e->position(0), e->position(1)) - x.q) <= tol * (std::abs(x.q) + L));
        CHECK(e->converged);
        CHECK(e->residual < 1e-14);  // rounding level of the double state (see below)
      }
    }
  }
}

// Unequal balls (m2 l2 != m1 l1): balanced closes the triangle m1l1 e^{ib1} + m2l2 e^{ib2} = -U,
// opposite solves K U sin b1 + C U cos b1 + C (m1l1 - m2l2) = 0, and every point satisfies
// the static equations; counts from the existence conditions.
TEST_CASE("unequal balls satisfy the static equations to rounding", "[hand]") {
  for (const double omega : {200.0, 900.0}) {
    for (const double U : {5e-8, 3e-7, 6e-7, 1e-6, 1.2e-6}) {
      abu::Params p = base_params();
      p.omega = omega;
      p.rotor.unbalance = U;
      p.balls[1] = {2.5e-5, 0.02, 1e-3, 1.4, 0.002, 0.0, 0.0, 0.0, 0.0};  // m2 l2 = 5e-7 vs 5.94e-7
      const Scene s(p);
      const auto set = abu::find_equilibria(p);
      INFO("omega " << omega << " U " << U);
      const bool balanced = std::abs(s.a1 - s.a2) <= s.U && s.U <= s.a1 + s.a2;
      CHECK(count(set.points(), Family::balanced) == (balanced ? 2 : 0));
      CHECK(count(set.points(), Family::together) == int(line_roots(s, s.a1 + s.a2).size()));
      CHECK(count(set.points(), Family::opposite) == int(line_roots(s, s.a1 - s.a2).size()));
      for (const auto& e : set.points()) {
        const abu::Coordinates<ld, 2> x = e.position_si().cast<ld>();
        INFO(to_string(e.family) << " beta " << double(x(2)) << " " << double(x(3)));
        // Rounding the state to double moves each equation by <= (1/2 + pi) eps of its
        // natural size (q relatively by eps/2, angles up to 2 pi by 2 pi eps/2): 16 eps.
        CHECK(static_residual(p, e) <= 16 * kEps);
        CHECK(e.residual < 1e-14);
        CHECK(e.converged);
        const ld b1 = x(2);
        if (e.family == Family::balanced) {
          const cld sum = s.a1 * std::polar(ld(1), x(2)) + s.a2 * std::polar(ld(1), x(3)) + s.U;
          CHECK(std::abs(sum) <= 16 * kEps * (s.U + s.a1 + s.a2));  // same rounding argument
          CHECK((x(0) == 0 && x(1) == 0));  // q = 0 exactly, not just small
        } else {
          const ld a = e.family == Family::together ? s.a1 + s.a2 : s.a1 - s.a2;
          const ld line = s.K * s.U * std::sin(b1) + s.C * s.U * std::cos(b1) + s.C * a;
          CHECK(std::abs(line) <= 16 * kEps * (std::abs(s.K) * s.U + s.C * s.U + s.C * std::abs(a)));
          CHECK(angle_distance(x(3), e.family == Family::together ? b1 : b1 + kPi) <= 8 * kEps);
        }
      }
    }
  }
}

// Massless-ball limit (model.md §7) at the together and opposite points: rotor eigenvalues
// -zeta wn +- i(wd -+ w), ball roots of j l s^2 + gamma s +- w^2 |q|. The neglected
// ball-rotor coupling is of relative order 2ml/U (6e-5 for m = 1e-9): tolerance 10 2ml/U.
TEST_CASE("massless-ball limit of the spectrum", "[hand]") {
  abu::Params p = base_params();
  for (auto& b : p.balls) b.mass = 1e-9;
  const double small = 2 * 1e-9 * 0.018 / p.rotor.unbalance;
  const double tiny = massless_mismatch(p);
  CHECK(tiny <= 10 * small);
  // First order in m: a ball ten times lighter must shrink the mismatch markedly (the
  // exact factor is 10; 5 leaves room for the second-order term and the rounding floor).
  for (auto& b : p.balls) b.mass = 1e-10;
  CHECK(massless_mismatch(p) * 5 <= tiny);
  // The real balls (2ml/U ~ 2) are far from the limit: the same tolerance must fail.
  for (auto& b : p.balls) b.mass = 3.3e-5;
  CHECK(massless_mismatch(p) > 10 * small);
}

// Conservative case (c = 0, no friction): Hamiltonian in the rotating frame, so spectra are
// closed under lambda -> -lambda; the balanced point above omega_n is a center (marginal).
// Every spectrum of a real J is closed under conjugation.
TEST_CASE("conservative spectra are Hamiltonian, all spectra are real", "[hand]") {
  for (const bool conservative : {true, false}) {
    for (const double omega : {150.0, 900.0}) {  // omega_n = 250 rad/s
      abu::Params p = base_params();
      p.omega = omega;
      if (conservative) p.rotor.damping = 0, p.law = abu::FrictionLaw::none;
      const auto a = abu::analyze(p);
      for (std::size_t i = 0; i < a.equilibria.points().size(); ++i) {
        INFO("conservative " << conservative << " omega " << omega << " " << to_string(a.equilibria.points()[i].family));
        check_closed_under(a.spectra[i], [](cd z) { return std::conj(z); });
        if (!conservative) continue;
        check_closed_under(a.spectra[i], [](cd z) { return -z; });
        if (omega > 250 && a.equilibria.points()[i].family == Family::balanced) {
          CHECK(a.spectra[i].stability == abu::Stability::marginal);  // a center
          CHECK(a.spectra[i].n_unstable == 0);
        }
      }
    }
  }
}

// Trace identity: sum lambda = trace J = trace(-A^-1 C) (model.md §7) at every equilibrium.
TEST_CASE("sum of eigenvalues equals the trace of the Jacobian", "[hand]") {
  std::vector<abu::Params> scenes(6, base_params());
  scenes[1].kappa = scenes[2].kappa = 1e6;  // the stiff case of model.md §8
  scenes[2].omega = scenes[3].omega = 200;  // below omega_n
  scenes[4].balls[1] = {2.5e-5, 0.02, 1e-3, 1.4, 0.002, 0.0, 0.0, 0.0, 0.0};  // unequal balls
  scenes[5].law = abu::FrictionLaw::viscous;
  for (auto& b : scenes[5].balls) b.d = 1e-3;
  for (const auto& p : scenes) {
    const auto a = abu::analyze(p);
    REQUIRE(a.equilibria.points().size() >= 4);
    for (std::size_t i = 0; i < a.equilibria.points().size(); ++i) {
      const auto& e = a.equilibria.points()[i];
      const auto J = abu::jacobian(p.cast<ld>(), e.state());
      const auto lin = abu::linearize(p.cast<ld>(), e.state());
      const ld trace_lin = -lin.mass.llt().solve(lin.damping).trace();
      cld sum = 0;
      ld sum_abs = 0;
      for (const cd z : a.spectra[i].eigenvalues) sum += cld(z.real(), z.imag()), sum_abs += std::abs(z);
      INFO("kappa " << p.kappa << " omega " << p.omega << " " << to_string(e.family) << " trace " << double(J.trace())
                    << " sum " << double(sum.real()));
      // Two long-double evaluations of one trace: they agree to long-double rounding.
      CHECK(std::abs(J.trace() - trace_lin) <= 1e-15L * std::abs(trace_lin));
      // Each eigenvalue is rounded to double (eps/2 relative) and is accurate to a few
      // eps of itself; the sum is dominated by the fast ball modes: 16 eps sum |lambda|.
      CHECK(std::abs(sum - J.trace()) <= 16 * kEps * sum_abs);
    }
  }
}

// Stribeck at an equilibrium is coulomb with mu = mu_s (same slope at 0, model.md §7):
// the same matrices up to the rounding of the slope, so the same spectrum to 1e-12.
TEST_CASE("stribeck at rest has the spectrum of coulomb with mu_s", "[hand]") {
  for (const double kappa : {1e3, 1e6}) {
    for (const double omega : {200.0, 900.0}) {
      abu::Params coulomb = base_params();
      coulomb.kappa = kappa;
      coulomb.omega = omega;
      abu::Params stribeck = coulomb;
      stribeck.law = abu::FrictionLaw::stribeck;
      for (auto& b : stribeck.balls) {
        b.mu_s = b.mu;  // the level at rest; mu itself is coulomb's and must not matter
        b.mu = 0.5;
        b.mu_c = 0.0007;
        b.v_s = 0.01;
      }
      const auto ac = abu::analyze(coulomb), as = abu::analyze(stribeck);
      REQUIRE(ac.equilibria.points().size() == as.equilibria.points().size());
      for (std::size_t i = 0; i < ac.equilibria.points().size(); ++i) {
        INFO("kappa " << kappa << " omega " << omega << " point " << i);
        for (std::size_t k = 0; k < 8; ++k) {
          const cd zc = ac.spectra[i].eigenvalues[k], zs = as.spectra[i].eigenvalues[k];
          INFO("coulomb " << zc << " stribeck " << zs);
          CHECK(std::abs(zs - zc) <= 1e-12 * std::abs(zc));
        }
        CHECK(ac.spectra[i].stability == as.spectra[i].stability);
      }
    }
  }
}

// Physics: the balanced state with dry friction is stable only above resonance: every
// Re lambda < 0 above omega_n, at least one Re lambda > 0 below it.
TEST_CASE("balanced state is stable above omega_n and unstable below", "[hand]") {
  const ld wn = std::sqrt(ld(7500.0) / Scene(base_params()).M);
  for (const double omega : {100.0, 200.0, 400.0, 900.0, 3000.0}) {
    abu::Params p = base_params();
    p.omega = omega;
    const auto a = abu::analyze(p);
    REQUIRE(count(a.equilibria.points(), Family::balanced) == 2);
    for (std::size_t i = 0; i < a.equilibria.points().size(); ++i) {
      if (a.equilibria.points()[i].family != Family::balanced) continue;
      const auto& sp = a.spectra[i];
      INFO("omega " << omega << " abscissa " << sp.abscissa);
      if (omega > wn) {
        CHECK(sp.stability == abu::Stability::stable);
        CHECK(sp.abscissa < 0);
      } else {
        CHECK(sp.stability == abu::Stability::unstable);
        CHECK(sp.n_unstable >= 1);
        CHECK(sp.abscissa > 0);
      }
    }
  }
}
