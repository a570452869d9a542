#include "abu/linear/characteristic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace abu {

namespace {

using ld = long double;
constexpr double kU = std::numeric_limits<double>::epsilon() / 2;
constexpr ld kULong = std::numeric_limits<ld>::epsilon() / 2;

// A matrix entry lambda^2 a + lambda c + k as coefficients (k, c, a).
using Quadratic = std::array<ld, 3>;
using Pencil = std::array<std::array<Quadratic, 4>, 4>;

Pencil pencil(const Linearization<ld, 2>& lin) {
  Pencil T{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) T[std::size_t(i)][std::size_t(j)] = {lin.stiffness(i, j), lin.damping(i, j), lin.mass(i, j)};
  return T;
}

bool is_zero(const Quadratic& q) { return q[0] == 0 && q[1] == 0 && q[2] == 0; }

// Determinant of the principal sub-pencil on `rows` (Leibniz: a sum over permutations of
// products of quadratics), with the magnitudes of the terms alongside.
template <std::size_t M>
PolynomialLD principal_determinant(const Pencil& T, const std::array<int, M>& rows) {
  PolynomialLD out;
  std::array<int, M> perm{};
  for (std::size_t i = 0; i < M; ++i) perm[i] = int(i);
  do {
    // Sign of the permutation by counting inversions.
    int inversions = 0;
    for (std::size_t i = 0; i < M; ++i)
      for (std::size_t j = i + 1; j < M; ++j) inversions += perm[i] > perm[j];
    std::array<ld, 9> term{}, size{};
    term[0] = 1;
    size[0] = 1;
    int degree = 0;
    bool zero = false;
    for (std::size_t i = 0; i < M && !zero; ++i) {
      const Quadratic& q = T[std::size_t(rows[i])][std::size_t(rows[std::size_t(perm[i])])];
      if (is_zero(q)) {
        zero = true;
        break;
      }
      std::array<ld, 9> next{}, next_size{};
      for (int d = 0; d <= degree; ++d)
        for (int e = 0; e < 3; ++e) {
          next[std::size_t(d + e)] += term[std::size_t(d)] * q[std::size_t(e)];
          next_size[std::size_t(d + e)] += size[std::size_t(d)] * std::abs(q[std::size_t(e)]);
        }
      term = next;
      size = next_size;
      degree += 2;
    }
    if (zero) continue;
    const ld sign = inversions % 2 ? -1 : 1;
    for (int d = 0; d <= degree; ++d) {
      out.c[std::size_t(d)] += sign * term[std::size_t(d)];
      out.magnitude[std::size_t(d)] += size[std::size_t(d)];
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return out;
}

// Horner evaluation of p and p' at z, with the running bound on p's evaluation error
// (the coefficients' own error bounds included).
struct Evaluated {
  std::complex<double> p, dp;
  double bound;
};
Evaluated evaluate(const Polynomial& poly, std::complex<double> z) {
  std::complex<double> p = poly.c[8], dp = 0;
  double bound = poly.error[8];
  double absolute = std::abs(poly.c[8]);
  const double az = std::sqrt(std::norm(z));
  for (int k = 7; k >= 0; --k) {
    dp = dp * z + p;
    p = p * z + poly.c[std::size_t(k)];
    absolute = absolute * az + std::abs(poly.c[std::size_t(k)]);
    bound = bound * az + poly.error[std::size_t(k)];
  }
  return {p, dp, bound + 4 * 8 * kU * absolute};
}

}  // namespace

PolynomialLD characteristic_polynomial(const Linearization<ld, 2>& lin) {
  return principal_determinant<4>(pencil(lin), {0, 1, 2, 3});
}

Linearization<ld, 2> friction_free(Linearization<ld, 2> lin) {
  lin.damping(2, 2) = 0;
  lin.damping(3, 3) = 0;
  return lin;
}

FrictionSplit friction_split(const Linearization<ld, 2>& free) {
  const Pencil T = pencil(free);
  FrictionSplit s;
  s.p00 = principal_determinant<4>(T, {0, 1, 2, 3});
  s.p10 = principal_determinant<3>(T, {0, 1, 3});  // ball 1's row and column removed
  s.p01 = principal_determinant<3>(T, {0, 1, 2});  // ball 2's
  s.p11 = principal_determinant<2>(T, {0, 1});     // the rotor block
  s.d00 = to_double(s.p00);
  s.d10 = to_double(s.p10);
  s.d01 = to_double(s.p01);
  s.d11 = to_double(s.p11);
  return s;
}

Polynomial combine(const FrictionSplit& split, double s1, double s2) {
  // P = P00 + s1 lambda P10 + s2 lambda P01 + s1 s2 lambda^2 P11 in double: each
  // coefficient carries the split polynomials' bounds and the rounding of its sum.
  Polynomial out;
  const double ab = s1 * s2;
  const double a = std::abs(s1), b = std::abs(s2), aab = std::abs(ab);
  for (std::size_t k = 0; k <= 8; ++k) {
    double value = split.d00.c[k], error = split.d00.error[k], size = std::abs(value);
    if (k >= 1) {
      const double t1 = s1 * split.d10.c[k - 1], t2 = s2 * split.d01.c[k - 1];
      value += t1 + t2;
      error += a * split.d10.error[k - 1] + b * split.d01.error[k - 1];
      size += std::abs(t1) + std::abs(t2);
    }
    if (k >= 2) {
      const double t3 = ab * split.d11.c[k - 2];
      value += t3;
      error += aab * split.d11.error[k - 2];
      size += std::abs(t3);
    }
    out.c[k] = value;
    out.error[k] = error + 6 * kU * size;
  }
  return out;
}

PolynomialLD combine_long(const FrictionSplit& split, ld s1, ld s2) {
  // The split's expansions times s1, s2, s1 s2 are the terms of P's: their magnitudes scale
  // alike; the products' and sums' own roundings are covered by adding |term| once more.
  PolynomialLD out;
  const ld ab = s1 * s2;
  for (std::size_t k = 0; k <= 8; ++k) {
    ld value = split.p00.c[k], size = split.p00.magnitude[k];
    if (k >= 1) {
      const ld t1 = s1 * split.p10.c[k - 1], t2 = s2 * split.p01.c[k - 1];
      value += t1 + t2;
      size += std::abs(s1) * split.p10.magnitude[k - 1] + std::abs(s2) * split.p01.magnitude[k - 1] + std::abs(t1) +
              std::abs(t2);
    }
    if (k >= 2) {
      const ld t3 = ab * split.p11.c[k - 2];
      value += t3;
      size += std::abs(ab) * split.p11.magnitude[k - 2] + std::abs(t3);
    }
    out.c[k] = value;
    out.magnitude[k] = size + std::abs(value);
  }
  return out;
}

Polynomial to_double(const PolynomialLD& p) {
  Polynomial out;
  for (std::size_t k = 0; k <= 8; ++k) {
    out.c[k] = double(p.c[k]);
    out.error[k] = double(16 * kULong * p.magnitude[k]) + kU * std::abs(out.c[k]);
  }
  return out;
}

RouthCount routh_count(const Polynomial& poly) {
  RouthCount result;
  // Normalize the leading coefficient positive and scale lambda = sigma mu by a power of
  // two near the roots' geometric mean |a0 / a8|^(1/8), so that the array stays in range;
  // positive scalings change no sign.
  double lead = poly.c[8];
  if (!(std::abs(lead) > 4 * poly.error[8])) return result;
  const double sign = lead > 0 ? 1 : -1;
  double sigma = 1;
  if (poly.c[0] != 0) {  // 2^(round(log2 |a0 / a8| / 8)) by exponent arithmetic (no pow)
    int e0 = 0, e8 = 0;
    std::frexp(poly.c[0], &e0);
    std::frexp(lead, &e8);
    const int d = e0 - e8;
    sigma = std::ldexp(1.0, (d >= 0 ? d + 4 : d - 4) / 8);
  }
  std::array<double, 9> a{}, da{};
  double power = 1;
  for (std::size_t k = 0; k <= 8; ++k) {
    a[k] = sign * poly.c[k] * power;
    da[k] = poly.error[k] * power;
    power *= sigma;
  }
  // Rows of the Routh array (5 columns), each entry with an absolute error bound:
  // r[i][j] = r[i-2][j+1] - (r[i-2][0] / r[i-1][0]) r[i-1][j+1].
  std::array<std::array<double, 5>, 9> r{}, e{};
  for (std::size_t j = 0; j < 5; ++j) {
    r[0][j] = a[8 - 2 * j];
    e[0][j] = da[8 - 2 * j];
    if (2 * j + 1 <= 8) {
      r[1][j] = a[7 - 2 * j];
      e[1][j] = da[7 - 2 * j];
    }
  }
  for (std::size_t i = 0; i <= 8; ++i) {
    if (i >= 2) {
      const double c = r[i - 1][0], dc = e[i - 1][0];
      for (std::size_t j = 0; j + 1 < 5; ++j) {
        const double b = r[i - 2][0], db = e[i - 2][0];
        const double q = b / c;
        const double dq = (db + std::abs(q) * dc) / std::abs(c) + kU * std::abs(q);
        const double d = r[i - 1][j + 1], dd = e[i - 1][j + 1];
        const double qd = q * d;
        r[i][j] = r[i - 2][j + 1] - qd;
        e[i][j] = e[i - 2][j + 1] + std::abs(q) * dd + std::abs(d) * dq +
                  2 * kU * (std::abs(r[i - 2][j + 1]) + std::abs(qd));
      }
    }
    // Every first-column entry must be resolved: its sign is what counts.
    if (!(std::abs(r[i][0]) > 4 * e[i][0])) return result;
  }
  int changes = 0;
  for (std::size_t i = 1; i <= 8; ++i) changes += (r[i][0] > 0) != (r[i - 1][0] > 0);
  result.decided = true;
  result.n_unstable = changes;
  return result;
}

bool polish_root(const Polynomial& p, std::complex<double>& z) {
  // Real roots in real arithmetic (they stay exactly real); complex ones with the
  // quotient written out (std::complex's division and abs call libgcc and hypot).
  if (z.imag() == 0) {
    double w = z.real();
    for (int it = 0; it < 30; ++it) {
      double v = p.c[8], dv = 0, absolute = std::abs(p.c[8]), bound = p.error[8];
      const double aw = std::abs(w);
      for (int k = 7; k >= 0; --k) {
        dv = dv * w + v;
        v = v * w + p.c[std::size_t(k)];
        absolute = absolute * aw + std::abs(p.c[std::size_t(k)]);
        bound = bound * aw + p.error[std::size_t(k)];
      }
      if (!(dv != 0)) return false;
      const double step = v / dv;
      w -= step;
      if (!std::isfinite(w)) return false;
      if (std::abs(step) <= 1e-14 * std::abs(w) || std::abs(v) <= bound + 32 * kU * absolute) {
        z = w;
        return true;
      }
    }
    return false;
  }
  std::complex<double> w = z;
  for (int it = 0; it < 30; ++it) {
    const Evaluated v = evaluate(p, w);
    const double d2 = std::norm(v.dp);
    if (!(d2 > 0)) return false;
    const std::complex<double> step = v.p * std::conj(v.dp) / d2;
    w -= step;
    if (!std::isfinite(w.real()) || !std::isfinite(w.imag())) return false;
    if (std::norm(step) <= 1e-28 * std::norm(w) || std::norm(v.p) <= v.bound * v.bound) {
      z = w;
      return true;
    }
  }
  return false;
}

Polynomial shifted(const Polynomial& p, double alpha) {
  // Repeated synthetic division (Horner's Taylor shift), the magnitudes alongside: the
  // coefficient b_k = sum_j a_j C(j, k) alpha^(j-k) carries the errors of the a_j and the
  // rounding of at most 8 operations on terms of that size.
  Polynomial out = p;
  std::array<double, 9> size{};
  for (std::size_t k = 0; k <= 8; ++k) size[k] = std::abs(p.c[k]);
  const double a = std::abs(alpha);
  for (int i = 0; i < 8; ++i)
    for (int k = 7; k >= i; --k) {
      const auto K = std::size_t(k);
      out.c[K] += alpha * out.c[K + 1];
      out.error[K] += a * out.error[K + 1];
      size[K] += a * size[K + 1];
    }
  for (std::size_t k = 0; k <= 8; ++k) out.error[k] += 16 * kU * size[k];
  return out;
}

bool certified_abscissa(const Polynomial& p, std::complex<double>& rightmost) {
  std::complex<double> z = rightmost;
  if (!polish_root(p, z)) return false;
  // Just right of it: by more than its own error, far less than its size.
  const double margin = 1e-9 * std::abs(z);
  const RouthCount beyond = routh_count(shifted(p, z.real() + margin));
  if (!beyond.decided || beyond.n_unstable != 0) return false;
  rightmost = z;
  return true;
}

}  // namespace abu
