// The pseudo-arclength engine (arclength.hpp, bordered.hpp) on a problem solved by hand:
// a circle of radius r about lambda = c in the (x0, lambda) plane, lifted into n
// dimensions by x_i = x0 / (i + 1):
//     F_0 = x0^2 + (lambda - c)^2 - r^2,   F_i = x_i - x0 / (i + 1)   (i = 1 .. n-1).
// Its folds in lambda (t_lambda = 0) lie at x0 = 0, lambda = c -+ r exactly. The same
// problem runs with fixed-size Eigen types (n = 3) and bounded-dynamic ones (n = 30, the
// size of an n-ball problem), whose matrices all live on the stack.
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "abu/continuation/arclength.hpp"

namespace {

using ld = long double;
namespace al = abu::arclength;

template <int Rows, int MaxRows = Rows>
struct Types {
  static constexpr int less(int k) { return k == Eigen::Dynamic ? Eigen::Dynamic : k - 1; }
  using Vec = Eigen::Matrix<ld, Rows, 1, 0, MaxRows, 1>;
  using Residual = Eigen::Matrix<ld, less(Rows), 1, 0, MaxRows - 1, 1>;
  using Jacobian = Eigen::Matrix<ld, less(Rows), Rows, 0, MaxRows - 1, MaxRows>;
};

template <class T>
struct Circle {
  using Vec = typename T::Vec;
  using Jacobian = typename T::Jacobian;
  static constexpr std::size_t test_count = 1;  // t_lambda: folds

  int n = 3;
  ld centre = 0.5, radius = 0.25;
  ld wall = std::numeric_limits<ld>::infinity();  // F is NaN beyond lambda = wall
  bool exit_at_negative_x0 = false;
  bool always_retry = false;

  std::vector<Vec> points;
  std::vector<ld> folds;   // lambda of the located folds
  std::vector<al::Stage> stages;

  Vec at(ld x0, ld lambda) const {
    Vec u = Vec::Zero(n + 1);
    u(0) = x0;
    for (int i = 1; i < n; ++i) u(i) = x0 / (i + 1);
    u(n) = lambda;
    return u;
  }

  typename T::Residual residual(const Vec& u) const {
    typename T::Residual r(n);
    const ld lambda = u(n);
    r(0) = lambda > wall ? std::numeric_limits<ld>::quiet_NaN()
                         : u(0) * u(0) + (lambda - centre) * (lambda - centre) - radius * radius;
    for (int i = 1; i < n; ++i) r(i) = u(i) - u(0) / (i + 1);
    return r;
  }
  Jacobian jacobian(const Vec& u) const {
    Jacobian J = Jacobian::Zero(n, n + 1);
    J(0, 0) = 2 * u(0);
    J(0, n) = 2 * (u(n) - centre);
    for (int i = 1; i < n; ++i) J(i, 0) = -ld(1) / (i + 1), J(i, i) = 1;
    return J;
  }
  ld residual_size(const Vec& u) const { return residual(u).cwiseAbs().maxCoeff(); }
  static al::NewtonSettings newton() { return {}; }

  al::Crossing crossing(const Vec& /*from*/, const Vec& to) const {
    if (exit_at_negative_x0 && to(0) < 0) return al::Crossing::leaving("x0 became negative");
    return al::box_crossing(to, {n});
  }
  al::Evaluation<ld, 1> evaluate(const Vec& /*u*/, const Vec& t, const Jacobian& /*J*/, al::Stage stage) {
    stages.push_back(stage);
    al::Evaluation<ld, 1> e;
    e.retry = always_retry;
    e.reason = "asked for a shorter step";
    e.tests = {t(n)};
    return e;
  }
  // The fold by an augmented system: F = 0 with x0 = 0 (where F_x is singular), from the
  // zero of the test function's secant.
  void locate(unsigned changed, const al::Segment<Vec>& s) {
    REQUIRE(changed == 1u);
    const ld fa = s.from_tangent(n), fb = s.to_tangent(n);
    Vec guess = s.from + (fa / (fa - fb)) * (s.to - s.from);
    guess(0) = 0;
    Vec e0 = Vec::Zero(n + 1);
    e0(0) = 1;
    const auto c = al::correct(*this, guess, e0);
    REQUIRE(c.converged());
    folds.push_back(c.u(n));
  }
  void commit(Vec& u, Vec& /*t*/, al::Stage /*stage*/) { points.push_back(u); }
};

// The same, ending where it closes on itself.
template <class T>
struct Loop : Circle<T> {
  ld distance(const typename T::Vec& a, const typename T::Vec& b) const { return (a - b).cwiseAbs().maxCoeff(); }
};

using Fixed = Types<4>;
using Bounded = Types<Eigen::Dynamic, 31>;
static_assert(al::Problem<Circle<Fixed>> && al::Problem<Circle<Bounded>> && al::Problem<Loop<Bounded>>);
// Bounded-dynamic unknowns give bounded bordered matrices: no heap allocation per step.
static_assert(al::Square<Bounded::Vec>::MaxRowsAtCompileTime == 31 &&
              al::Square<Bounded::Vec>::MaxColsAtCompileTime == 31);

template <class P>
void check_on_circle(const P& p, ld tolerance) {
  for (const auto& u : p.points) {
    CHECK(std::abs(p.residual(u).cwiseAbs().maxCoeff()) <= tolerance);
  }
}

template <class T>
void full_loop(int n) {
  Loop<T> p;
  p.n = n;
  // Start on the circle's right (x0 = r, lambda = c): its tangent is along lambda.
  typename T::Vec inward = T::Vec::Zero(n + 1);
  inward(n) = 1;
  const auto s = al::start(p, p.at(p.radius, p.centre), inward, /*on_edge=*/false);
  CHECK(s.both_ways);
  CHECK(s.tangent(n) > 0.99L);
  const al::Result<Loop<T>> r = al::trace(p, s.u, s.tangent, s.jacobian, abu::ContinuationOptions{});
  CHECK(r.end == al::End::closed_loop);
  CHECK(r.status == al::Status::converged);
  REQUIRE(p.folds.size() == 2);
  CHECK(std::abs(p.folds[0] - (p.centre + p.radius)) <= 1e-15L);
  CHECK(std::abs(p.folds[1] - (p.centre - p.radius)) <= 1e-15L);
  check_on_circle(p, 1e-15L);
  CHECK(r.stats.steps + 1 == long(p.points.size()));
  CHECK(p.stages.front() == al::Stage::start);
}

}  // namespace

TEST_CASE("the engine goes round a circle, fixed-size and bounded-dynamic, folds located exactly", "[arclength]") {
  SECTION("fixed size, n = 3") { full_loop<Fixed>(3); }
  SECTION("bounded dynamic, n = 30") { full_loop<Bounded>(30); }
}

TEST_CASE("a run from the edge of the box ends on the edge exactly, one way only", "[arclength]") {
  Circle<Bounded> p;
  p.n = 5;
  p.centre = 0;
  p.radius = 0.5;  // from (0.5, 0) up over the fold at lambda = 0.5 and down to (-0.5, 0)
  Bounded::Vec inward = Bounded::Vec::Zero(6);
  inward(5) = 1;
  const auto s = al::start(p, p.at(0.5, 0), inward);
  CHECK(!s.both_ways);  // crosses lambda = 0 transversally: the other way leaves at once
  Circle<Bounded> unused = p;
  const auto both = al::trace_both_ways(p, unused, s, abu::ContinuationOptions{});
  CHECK(!both.backward_traced);
  CHECK(unused.points.empty());
  const auto& r = both.forward;
  CHECK(r.end == al::End::end_of_interval);
  CHECK(r.last(5) == 0);
  CHECK(std::abs(r.last(0) + 0.5L) <= 1e-15L);
  CHECK(p.stages.back() == al::Stage::edge);
  REQUIRE(p.folds.size() == 1);
  CHECK(std::abs(p.folds[0] - 0.5L) <= 1e-15L);
}

TEST_CASE("the problem's domain, the step limit and the minimum step end a run with a reason", "[arclength]") {
  Circle<Fixed> p;
  Fixed::Vec inward = Fixed::Vec::Zero();
  inward(3) = 1;
  SECTION("left the domain: the last point inside, the one beyond outside") {
    p.exit_at_negative_x0 = true;
    const auto s = al::start(p, p.at(p.radius, p.centre), inward, false);
    const auto r = al::trace(p, s.u, s.tangent, s.jacobian, abu::ContinuationOptions{});
    CHECK(r.end == al::End::left_domain);
    CHECK(r.reason == "x0 became negative");
    CHECK(r.last(0) >= 0);
    CHECK(r.beyond(0) < 0);
  }
  SECTION("max steps: attempts, retries included") {
    abu::ContinuationOptions o;
    o.max_steps = 3;
    const auto s = al::start(p, p.at(p.radius, p.centre), inward, false);
    const auto r = al::trace(p, s.u, s.tangent, s.jacobian, o);
    CHECK(r.end == al::End::max_steps);
    CHECK(r.status == al::Status::not_converged);
    CHECK(r.stats.steps + r.stats.rejected == 3);
  }
  SECTION("step underflow at a wall where F is not finite: where, and why") {
    p.wall = 0.6;
    abu::ContinuationOptions o;
    o.ds_min = 1e-6;
    const auto s = al::start(p, p.at(p.radius, p.centre), inward, false);
    const auto r = al::trace(p, s.u, s.tangent, s.jacobian, o);
    CHECK(r.end == al::End::step_underflow);
    CHECK(r.status == al::Status::numerical_issue);
    CHECK(r.reason.find("did not converge") != std::string::npos);
    CHECK(r.reason.find("not finite") != std::string::npos);
    CHECK(r.last(3) <= 0.6L);
    CHECK(r.last(3) > 0.6L - 1e-3L);
    CHECK(r.ds < o.ds_min * 2);
  }
  SECTION("a problem that always asks for shorter steps is granted them down to 16 ds_min, then not") {
    Loop<Fixed> q;
    q.always_retry = true;
    abu::ContinuationOptions o;
    o.ds_min = 1e-4;
    o.max_steps = 100000;
    const auto s = al::start(q, q.at(q.radius, q.centre), inward, false);
    const auto r = al::trace(q, s.u, s.tangent, s.jacobian, o);
    CHECK(r.end == al::End::closed_loop);
    CHECK(r.stats.rejected > 0);
    CHECK(q.folds.size() == 2);
  }
}

TEST_CASE("the bordered corrector says why it failed", "[arclength]") {
  Circle<Fixed> p;
  Fixed::Vec d = Fixed::Vec::Zero();
  d(3) = 1;
  SECTION("converged at a fixed lambda") {
    const auto c = al::correct(p, p.at(0.3L, 0.5L), d);
    CHECK(c.converged());
    CHECK(c.reason.empty());
    CHECK(std::abs(c.u(0) - 0.25L) <= 1e-18L);
  }
  SECTION("no solution at lambda outside the circle: a singular or diverging Newton") {
    const auto c = al::correct(p, p.at(0.3L, 0.9L), d);
    CHECK(!c.converged());
    CHECK(!c.reason.empty());
  }
  SECTION("not finite") {
    p.wall = 0;
    const auto c = al::correct(p, p.at(0.3L, 0.5L), d);
    CHECK(c.status == al::Status::numerical_issue);
  }
}
