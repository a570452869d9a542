// Dense output of the one-step integrators of `simulate`, `basin` and the stick-slip phases
// (model.md §15.1): the quintic Hermite interpolant of one accepted step from the state y, the
// field y' = f and its time derivative y'' = J f + f_t at both ends, its error estimate, and the
// largest |q| of the interpolant inside the step (model.md §15.4).
//
//   dense::Step s;  // t0, t1 and y, y', y'' at both ends, filled by the caller
//   double x[dense::capacity];
//   s.state_at(t, x);                                       // every component at t in [t0, t1]
//   dense::QPeak pk = s.q_peak(s.t0, s.t1, s.y0, s.y1);     // largest |q| = |(y_0, y_1)| and where
//
// dense::Stepper keeps a run's bookkeeping around GSL's evolve (the current step, the estimate,
// the step limit, retaken steps, the maxima); simulation.cpp and stick_slip.cpp drive it.
// Internal to the dynamics layer. Fixed-size storage: nothing is allocated per step.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "abu/dynamics/simulation.hpp"
#include "abu/model/lugre.hpp"

namespace abu::dense {

inline constexpr int capacity = lugre_state_capacity;  // 3n + 4 for LuGre, 2n + 4 otherwise

// The quintic Hermite basis on s in [0, 1] (model.md (15.1.3)): p(s) = y0 + (y1 - y0) H3(s)
// + h [f0 H1(s) + f1 H4(s)] + h^2 [g0 H2(s) + g1 H5(s)], H0 = 1 - H3 folded into the first two
// terms so that a large angle does not cancel its own small change. Values and the first two
// derivatives in s.
struct Basis {
  double v[6], d1[6], d2[6];  // index: 1 H1, 2 H2, 3 H3, 4 H4, 5 H5 (0 unused)
  explicit Basis(double s) {
    const double s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
    v[0] = d1[0] = d2[0] = 0;
    v[1] = s - 6 * s3 + 8 * s4 - 3 * s5;
    v[2] = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5);
    v[3] = 10 * s3 - 15 * s4 + 6 * s5;
    v[4] = -4 * s3 + 7 * s4 - 3 * s5;
    v[5] = 0.5 * (s3 - 2 * s4 + s5);
    d1[1] = 1 - 18 * s2 + 32 * s3 - 15 * s4;
    d1[2] = 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4);
    d1[3] = 30 * s2 - 60 * s3 + 30 * s4;
    d1[4] = -12 * s2 + 28 * s3 - 15 * s4;
    d1[5] = 0.5 * (3 * s2 - 8 * s3 + 5 * s4);
    d2[1] = -36 * s + 96 * s2 - 60 * s3;
    d2[2] = 0.5 * (2 - 18 * s + 36 * s2 - 20 * s3);
    d2[3] = 60 * s - 180 * s2 + 120 * s3;
    d2[4] = -24 * s + 84 * s2 - 60 * s3;
    d2[5] = 0.5 * (6 * s - 24 * s2 + 20 * s3);
  }
};

/// The largest |q| found in an interval and when.
struct QPeak {
  double q_abs = 0, t = 0;
};

/// One accepted step [t0, t1] with the state, the field and its time derivative at both ends;
/// at most Cap components (the rigid routes' capacity, or a flexible shaft's state).
template <int Cap>
struct StepN {
  int dim = 0;
  double t0 = 0, t1 = 0;
  double y0[Cap] = {}, y1[Cap] = {};
  double f0[Cap] = {}, f1[Cap] = {};  // y'
  double g0[Cap] = {}, g1[Cap] = {};  // y'' (zero: the cubic Hermite interpolant)

  double h() const { return t1 - t0; }
  double value(int i, const Basis& b, double h) const {
    return y0[i] + (y1[i] - y0[i]) * b.v[3] + h * (f0[i] * b.v[1] + f1[i] * b.v[4]) +
           h * h * (g0[i] * b.v[2] + g1[i] * b.v[5]);
  }
  double rate(int i, const Basis& b, double h) const {  // dp/dt
    return (y1[i] - y0[i]) * b.d1[3] / h + f0[i] * b.d1[1] + f1[i] * b.d1[4] + h * (g0[i] * b.d1[2] + g1[i] * b.d1[5]);
  }
  double curvature(int i, const Basis& b, double h) const {  // d2p/dt2
    return (y1[i] - y0[i]) * b.d2[3] / (h * h) + (f0[i] * b.d2[1] + f1[i] * b.d2[4]) / h + g0[i] * b.d2[2] +
           g1[i] * b.d2[5];
  }

  /// Every component at t in [t0, t1]; the ends exactly.
  void state_at(double t, double* x) const {
    if (t == t1) {
      std::copy(y1, y1 + dim, x);
      return;
    }
    if (t == t0) {
      std::copy(y0, y0 + dim, x);
      return;
    }
    const double H = h();
    const Basis b((t - t0) / H);
    for (int i = 0; i < dim; ++i) x[i] = value(i, b, H);
  }

  /// The interpolant's error estimate at mid-step, per component, from the state y_prev at the
  /// start t_prev < t0 of the step before (model.md (15.1.4)): the divided difference of the
  /// sixth order through the seven conditions, times the quintic's nodal polynomial at s = 1/2.
  /// Returns max_i est_i / tol_i with tol_i = tol(i, y1_i).
  template <class Tolerance>
  double error_ratio(double t_prev, const double* y_prev, const Tolerance& tol) const {
    const double H = h(), hp = t0 - t_prev;
    const Basis b(-hp / H);
    // p(t) - y(t) = c (t - t0)^3 (t - t1)^3 + ...; c from the node t_prev, the nodal factor at mid-step.
    const double r = 0.5 * H / hp, r2 = 0.5 * H / (hp + H);
    const double mid = (r * r * r) * (r2 * r2 * r2);  // (H/2)^6 / (hp^3 (hp + H)^3)
    double worst = 0;
    for (int i = 0; i < dim; ++i) worst = std::max(worst, std::abs(value(i, b, H) - y_prev[i]) * mid / tol(i, y1[i]));
    return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
  }

  /// A cautious estimate where no step before is at hand (the first step after a start or a
  /// restart, model.md (15.1.5)): the quintic's distance at mid-step to the cubic Hermite
  /// interpolant of y and y' alone, the cubic's error (O(h^4)), which exceeds the quintic's
  /// wherever the step resolves the motion. Returns max_i distance_i / tol_i.
  template <class Tolerance>
  double cubic_ratio(const Tolerance& tol) const {
    const double H = h();
    double worst = 0;
    for (int i = 0; i < dim; ++i)
      worst = std::max(worst, std::abs(H * (f0[i] - f1[i]) / 32 + H * H * (g0[i] + g1[i]) / 64) / tol(i, y1[i]));
    return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
  }

  /// The largest |q| = hypot(y_0, y_1) of the interpolant on [ta, tb] (within [t0, t1]): the ends
  /// and every interior maximum, a root of G = q . q' where it changes sign from + to - on one
  /// of four sub-intervals, polished by safeguarded Newton on G. `xa`, `xb` hold the state at ta
  /// and tb. The interior is not searched where a bound of |p| on the step stays below `floor`
  /// (the largest |q| so far): |H3| <= 1 keeps the first two terms of (15.1.3) within the ends'
  /// largest, |H1|, |H4| <= 16/81 and |H2|, |H5| <= 0.01728 bound the others.
  QPeak q_peak(double ta, double tb, const double* xa, const double* xb, double floor = 0) const {
    QPeak best{std::hypot(xa[0], xa[1]), ta};
    const double qb = std::hypot(xb[0], xb[1]);
    if (qb > best.q_abs) best = {qb, tb};
    const double H = h();
    if (!(tb > ta) || !(H > 0)) return best;
    const auto norm = [](const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1]); };  // q: no overflow
    const double bound = std::max(norm(y0), norm(y1)) + 0.19753086419753085 * H * (norm(f0) + norm(f1)) +
                         0.01728 * H * H * (norm(g0) + norm(g1));
    if (bound * (1 + 1e-12) < std::max(floor, best.q_abs)) return best;
    const auto G = [&](double s, double* dG) {
      const Basis b(s);
      double g = 0, dg = 0;
      for (int i = 0; i < 2; ++i) {
        const double p = value(i, b, H), v = rate(i, b, H), a = curvature(i, b, H);
        g += p * v;
        dg += v * v + p * a;
      }
      if (dG) *dG = dg;
      return g;
    };
    const double sa = (ta - t0) / H, sb = (tb - t0) / H;
    constexpr int parts = 4;
    double s_lo = sa, g_lo = G(sa, nullptr);
    for (int k = 1; k <= parts; ++k) {
      const double s_hi = k == parts ? sb : sa + (sb - sa) * k / parts;
      const double g_hi = G(s_hi, nullptr);
      if (g_lo > 0 && g_hi <= 0) {
        // Bracket [lo, hi] with G(lo) > 0 >= G(hi): Newton from the secant point, bisection when
        // Newton leaves the bracket.
        double lo = s_lo, hi = s_hi, glo = g_lo, ghi = g_hi;
        double s = lo - glo * (hi - lo) / (ghi - glo);
        for (int it = 0; it < 60; ++it) {
          double dg = 0;
          const double g = G(s, &dg);
          if (g > 0) lo = s, glo = g;
          else hi = s, ghi = g;
          double next = dg < 0 ? s - g / dg : 0.5 * (lo + hi);
          if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
          if (std::abs(next - s) <= 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(s)) ||
              hi - lo <= 4 * std::numeric_limits<double>::epsilon()) {
            s = next;
            break;
          }
          s = next;
        }
        const Basis b(s);
        const double q = std::hypot(value(0, b, H), value(1, b, H));
        if (q > best.q_abs) best = {q, t0 + s * H};
      }
      s_lo = s_hi;
      g_lo = g_hi;
    }
    return best;
  }
};
using Step = StepN<capacity>;

/// The running maxima of |q| over a run (model.md §15.4): over the whole run and over the
/// parts where omega' != 0.
struct PeakTracker {
  QPeak all;
  std::optional<double> run_up;
  void add(const QPeak& p, bool speed_changing) {
    if (p.q_abs > all.q_abs) all = p;
    if (speed_changing) run_up = std::max(run_up.value_or(0.0), p.q_abs);
  }
  /// The summary's maxima (taken over the samples by summarize()) raised to the located ones.
  void merge_into(SimulationSummary& s) const {
    if (all.q_abs > s.max_q_abs) {
      s.max_q_abs = all.q_abs;
      s.t_max_q_abs = all.t;
    }
    if (run_up) s.max_q_abs_run_up = std::max(s.max_q_abs_run_up.value_or(0.0), *run_up);
  }
};

/// y'' = d/dt f(t, y(t)) by differences of the field along (1, f), for a field without a
/// Jacobian at hand (model.md §15.1), T the motion's time scale 1 / (omega_max + omega_n):
/// forward, step sqrt(eps) T, one evaluation, relative error ~ 2 sqrt(eps) = 3e-8; central, step
/// eps^(1/3) T, two evaluations, ~ eps^(2/3) = 4e-11. The error enters the interpolant (15.1.3)
/// times h^2 |H2| <= 0.0173 h^2: below 5e-10 (h nu)^2 |y| forward, so the central difference is
/// taken for rtol < 1e-9. rhs(t, y, f) returns a GSL code.
template <int Cap = capacity, class Rhs>
int second_by_difference(const Rhs& rhs, int dim, double time_scale, bool central, double t, const double* y,
                         const double* f, double* g) {
  double ahead[Cap], behind[Cap];
  const double delta = (central ? 6.055454452393343e-06 : 1.4901161193847656e-08) * time_scale;
  for (int i = 0; i < dim; ++i) ahead[i] = y[i] + delta * f[i];
  if (const int st = rhs(t + delta, ahead, g); st != 0) return st;
  if (!central) {
    for (int i = 0; i < dim; ++i) g[i] = (g[i] - f[i]) / delta;
    return 0;
  }
  double fb[Cap];
  for (int i = 0; i < dim; ++i) behind[i] = y[i] - delta * f[i];
  if (const int st = rhs(t - delta, behind, fb); st != 0) return st;
  for (int i = 0; i < dim; ++i) g[i] = (g[i] - fb[i]) / (2 * delta);
  return 0;
}

/// The sample times k * every (k = 1, 2, ...) and t_end, in order.
struct SampleClock {
  double every = 0, t_end = 0;
  unsigned long long k = 1;
  double last = 0;  // the last sample's time
  /// The next sample's time; infinity once t_end is sampled.
  double next() const {
    const double ts = std::min(double(k) * every, t_end);
    return ts > last ? ts : std::numeric_limits<double>::infinity();
  }
  void taken(double ts) {
    last = ts;
    ++k;
  }
};

/// The dense output's bookkeeping over a run (model.md §15.1): the current step's ends with y'
/// and y'', the interpolant's error estimate, the step limit it implies, the steps taken again
/// because the interpolant missed the tolerance where it was used, and the maxima of |q|.
/// Field: int rhs(t, y, f) and int second(t, y, f, g) (y'' at (t, y) given f = y'), GSL codes.
/// Cap: the largest state (a flexible shaft's Stepper is allocated on the heap).
template <class Field, int Cap = capacity>
struct Stepper {
  Field field;
  int dim;
  double rtol;
  const double* scale;   // the tolerance of component i: rtol (scale_i + |y_i| if relative_i) (15.2)
  const bool* relative;
  StepN<Cap> step;       // slot 0 is the current point
  PeakTracker peaks;
  double y_prev[Cap] = {};  // the start of the step before (its end is step.y0)
  double t_prev = 0;
  bool have_prev = false;
  double ratio = 0;      // the last step's interpolant error estimate / tolerance
  double h_limit = std::numeric_limits<double>::infinity();  // the longest step the interpolant allows
  unsigned long retaken = 0;
  int retakes_in_a_row = 0;

  Stepper(Field f, int d, double tol, const double* s, const bool* rel)
      : field(f), dim(d), rtol(tol), scale(s), relative(rel) {
    step.dim = d;
  }
  double tolerance(int i, double v) const { return rtol * (scale[i] + (relative[i] ? std::abs(v) : 0.0)); }

  /// The current point (slot 0) at t, with y' and y'' of the field as it is now (after a
  /// restart or a switch of the stick-slip modes): no step before it.
  int start(double t, const double* y) {
    step.t0 = t;
    std::copy(y, y + dim, step.y0);
    have_prev = false;
    int st = field.rhs(t, y, step.f0);
    if (st == 0) st = field.second(t, y, step.f0, step.g0);
    return st;
  }

  /// Before a step from t with the proposal h towards `target`, the next sample at t_sample: a
  /// step that would hold the sample but is longer than the interpolant allows is shortened to
  /// its reach, or ends at the sample where even that falls short of it (the sample is then the
  /// step's end, exact). Returns the step's target.
  double plan(double t, double& h, double t_sample, double target) const {
    const double H = std::min(h, target - t);
    if (t + H < t_sample || H <= h_limit) return target;
    if (t_sample - t > h_limit) return std::min(target, t_sample);
    h = h_limit;
    return target;
  }

  /// The end of an accepted step (slot 1), with f from the stepper where it is exact (else
  /// null: evaluated), and the interpolant's error estimate: (15.1.4) against the step before,
  /// after a start the cautious (15.1.5).
  int finish(double t, const double* y, const double* f_end) {
    step.t1 = t;
    std::copy(y, y + dim, step.y1);
    int st = 0;
    if (f_end)
      std::copy(f_end, f_end + dim, step.f1);
    else
      st = field.rhs(t, y, step.f1);
    if (st == 0) st = field.second(t, y, step.f1, step.g1);
    if (st != 0) return st;
    const auto tol = [&](int i, double v) { return tolerance(i, v); };
    // (15.1.4) needs a step before of comparable length (after a final, clamped step it would
    // divide rounding by a tiny nodal factor).
    const bool sixth = have_prev && step.t0 - t_prev >= 0.2 * step.h();
    ratio = sixth ? step.error_ratio(t_prev, y_prev, tol) : step.cubic_ratio(tol);
    h_limit = ratio > 0 ? 0.9 * step.h() * std::pow(ratio, sixth ? -1.0 / 6 : -0.25)
                        : std::numeric_limits<double>::infinity();
    return 0;
  }

  /// Is the step to be taken again, shorter? Where its interpolant misses the tolerance and is
  /// used: a sample strictly inside, or an interior maximum of |q| that may exceed the largest
  /// so far. At most three times in a row.
  bool retake(double t_sample, const QPeak& candidate) {
    bool used = t_sample < step.t1;
    if (!used && candidate.t > step.t0 && candidate.t < step.t1)
      used = candidate.q_abs + ratio * tolerance(0, candidate.q_abs) >= peaks.all.q_abs;
    if (!(ratio > 1) || !used || retakes_in_a_row >= 3) {
      retakes_in_a_row = 0;
      return false;
    }
    ++retakes_in_a_row;
    ++retaken;
    return true;
  }

  /// The samples in (t0, t1] of an accepted step from the interpolant (t1's exactly), each
  /// handed to record(ts, x), which returns true to end the run there; then the maxima of |q|
  /// up to where the run goes on (`candidate`: those of the whole step). Returns the time the
  /// run ends at (the stopping sample's, its state in x) or t1.
  template <class Clock, class Record>
  double emit(Clock& clock, Record&& record, const QPeak& candidate, bool speed_changing, double* x) {
    for (double ts = clock.next(); ts <= step.t1; ts = clock.next()) {
      step.state_at(ts, x);
      clock.taken(ts);
      if (record(ts, static_cast<const double*>(x))) {
        peaks.add(step.q_peak(step.t0, ts, step.y0, x, peaks.all.q_abs), speed_changing);
        return ts;
      }
    }
    peaks.add(candidate, speed_changing);
    return step.t1;
  }
  /// The largest |q| of the whole step, its interior searched only where it may exceed the
  /// largest so far.
  QPeak candidate() const { return step.q_peak(step.t0, step.t1, step.y0, step.y1, peaks.all.q_abs); }

  /// The step's end becomes the current point.
  void advance() {
    std::copy(step.y0, step.y0 + dim, y_prev);
    t_prev = step.t0;
    have_prev = true;
    step.t0 = step.t1;
    std::copy(step.y1, step.y1 + dim, step.y0);
    std::copy(step.f1, step.f1 + dim, step.f0);
    std::copy(step.g1, step.g1 + dim, step.g0);
  }
};

}  // namespace abu::dense
