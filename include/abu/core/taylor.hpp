// Truncated Taylor series in one variable ("jets"): exact higher derivatives of the
// model along a direction, without finite-difference steps.
//
// A Taylor<T, K> holds c_0 .. c_K of g(t) = c_0 + c_1 t + ... + c_K t^K + O(t^(K+1)).
// Evaluating the vector field at x0 + t u with t a Taylor<long double, 3> variable gives
//   f(x0 + t u) = f(x0) + J u t + (1/2) D^2 f[u, u] t^2 + (1/6) D^3 f[u, u, u] t^3,
// every coefficient to the rounding of long double: the first Lyapunov coefficient's
// bilinear and trilinear forms (model.md (6.8)-(6.10)) then follow by polarization.
//
//   abu::Taylor<long double, 3> t = abu::Taylor<long double, 3>::variable(0.0L);
//   auto y = sin(2.0L * t);   // y.c[3] = -8/6 = d^3/dt^3 sin(2t) / 3! at 0
//
// Only the operations the model uses are defined: + - * / with scalars and series, sin,
// cos, exp, atan (the recurrences of Griewank & Walther, "Evaluating derivatives", ch. 13).
#pragma once

#include <array>
#include <cmath>
#include <type_traits>

#include <Eigen/Core>

namespace abu {

template <class T, int K>
struct Taylor {
  static_assert(K >= 1, "a Taylor series needs at least the first-order term");
  std::array<T, K + 1> c{};  ///< c[k] = g^(k)(0) / k!

  Taylor() = default;
  /// A constant (every higher coefficient zero). Implicit so that model code written for
  /// scalars (T(2) * x, p.cast<U>()) reads the same for series.
  template <class S, std::enable_if_t<std::is_arithmetic_v<S>, int> = 0>
  Taylor(S value) {  // NOLINT(google-explicit-constructor)
    c[0] = T(value);
  }
  /// The independent variable t shifted to `value`: value + t.
  static Taylor variable(T value) {
    Taylor v(value);
    v.c[1] = T(1);
    return v;
  }

  Taylor& operator+=(const Taylor& b) {
    for (int k = 0; k <= K; ++k) c[k] += b.c[k];
    return *this;
  }
  Taylor& operator-=(const Taylor& b) {
    for (int k = 0; k <= K; ++k) c[k] -= b.c[k];
    return *this;
  }
  Taylor& operator*=(const Taylor& b) { return *this = *this * b; }
  Taylor& operator/=(const Taylor& b) { return *this = *this / b; }

  friend Taylor operator-(const Taylor& a) {
    Taylor r;
    for (int k = 0; k <= K; ++k) r.c[k] = -a.c[k];
    return r;
  }
  friend Taylor operator+(Taylor a, const Taylor& b) { return a += b; }
  friend Taylor operator-(Taylor a, const Taylor& b) { return a -= b; }
  friend Taylor operator*(const Taylor& a, const Taylor& b) {
    Taylor r;
    for (int k = 0; k <= K; ++k)
      for (int i = 0; i <= k; ++i) r.c[k] += a.c[i] * b.c[k - i];
    return r;
  }
  // q = a / b: b q = a term by term, q_k = (a_k - sum_{i=1..k} b_i q_{k-i}) / b_0.
  friend Taylor operator/(const Taylor& a, const Taylor& b) {
    Taylor q;
    for (int k = 0; k <= K; ++k) {
      T s = a.c[k];
      for (int i = 1; i <= k; ++i) s -= b.c[i] * q.c[k - i];
      q.c[k] = s / b.c[0];
    }
    return q;
  }
  // Equal as series: every coefficient (the model asks `omega_dot != 0`).
  friend bool operator==(const Taylor& a, const Taylor& b) { return a.c == b.c; }
  friend bool operator!=(const Taylor& a, const Taylor& b) { return !(a == b); }

  // exp: e' = a' e, so k e_k = sum_{j=1..k} j a_j e_{k-j}.
  friend Taylor exp(const Taylor& a) {
    using std::exp;
    Taylor e;
    e.c[0] = exp(a.c[0]);
    for (int k = 1; k <= K; ++k) {
      T s = 0;
      for (int j = 1; j <= k; ++j) s += T(j) * a.c[j] * e.c[k - j];
      e.c[k] = s / T(k);
    }
    return e;
  }
  // sin and cos together: s' = a' c, c' = -a' s.
  friend void sin_cos_series(const Taylor& a, Taylor& s, Taylor& co) {
    using std::cos;
    using std::sin;
    s = Taylor();
    co = Taylor();
    s.c[0] = sin(a.c[0]);
    co.c[0] = cos(a.c[0]);
    for (int k = 1; k <= K; ++k) {
      T ss = 0, cs = 0;
      for (int j = 1; j <= k; ++j) {
        ss += T(j) * a.c[j] * co.c[k - j];
        cs += T(j) * a.c[j] * s.c[k - j];
      }
      s.c[k] = ss / T(k);
      co.c[k] = -cs / T(k);
    }
  }
  friend Taylor sin(const Taylor& a) {
    Taylor s, co;
    sin_cos_series(a, s, co);
    return s;
  }
  friend Taylor cos(const Taylor& a) {
    Taylor s, co;
    sin_cos_series(a, s, co);
    return co;
  }
  // atan: y' = a' / (1 + a^2); the quotient series r = a' / (1 + a^2) gives y_k = r_{k-1} / k.
  friend Taylor atan(const Taylor& a) {
    using std::atan;
    const Taylor u = Taylor(1) + a * a;
    std::array<T, K> r{};  // r = (sum_k k a_k t^(k-1)) / u, to order K - 1
    for (int k = 0; k < K; ++k) {
      T s = T(k + 1) * a.c[k + 1];
      for (int i = 1; i <= k; ++i) s -= u.c[i] * r[k - i];
      r[k] = s / u.c[0];
    }
    Taylor y;
    y.c[0] = atan(a.c[0]);
    for (int k = 1; k <= K; ++k) y.c[k] = r[k - 1] / T(k);
    return y;
  }
};

}  // namespace abu

// Eigen sees a Taylor series as a non-integer scalar of its own kind (matrices of them are
// only added, assigned and multiplied by the model; no decomposition is asked of them).
template <class T, int K>
struct Eigen::NumTraits<abu::Taylor<T, K>> : Eigen::GenericNumTraits<abu::Taylor<T, K>> {
  using Real = abu::Taylor<T, K>;
  using NonInteger = abu::Taylor<T, K>;
  using Nested = abu::Taylor<T, K>;
  using Literal = abu::Taylor<T, K>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = K + 1,
    AddCost = K + 1,
    MulCost = (K + 1) * (K + 2) / 2,
  };
  static inline Real epsilon() { return Real(Eigen::NumTraits<T>::epsilon()); }
  static inline Real dummy_precision() { return Real(Eigen::NumTraits<T>::dummy_precision()); }
  static inline int digits10() { return Eigen::NumTraits<T>::digits10(); }
};
