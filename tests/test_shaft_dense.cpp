// Dense cross-check of the flexible rotor's sparse spectra (model.md
// §19.6): shaft scenes that are not in the repository, generated here from a fixed seed
// (segments, discs, bearings, Euler–Bernoulli or Timoshenko, 1–3 balls, viscous or
// coulomb, 100–400 states), each at a balanced and an aligned equilibrium. The library's
// rightmost eigenvalues (the ARPACK ladder with the refinement of §19.5, as `equilibria`
// runs it) against a dense solve of the same pencil (18.7.3): Eigen's QR of the explicit
// J = b^-1 a for every eigenvalue, each then refined by inverse iteration on the dense
// pencil with a dense LU (none of the sparse code: not ARPACK, not SparseLU).
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "abu/equilibria/shaft_equilibria.hpp"
#include "abu/linear/sparse_spectrum.hpp"
#include "abu/model/shaft.hpp"
#include "abu/model/shaft_system.hpp"

using namespace abu;

namespace {

using cplx = std::complex<double>;

// A fixed generator (splitmix64), not std:: distributions: the same scenes on every
// standard library.
struct Draw {
  std::uint64_t state;
  double uniform(double lo, double hi) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * double(z >> 11) * 0x1.0p-53;
  }
  int integer(int lo, int hi) { return std::min(hi, lo + int(uniform(0.0, 1.0) * (hi - lo + 1))); }
};

struct Scene {
  ShaftSpec spec;
  ParamsN balancer;
  std::string what;
};

// A steel shaft of `elements` segments of varying length and section on two bearings,
// one to three discs, the balancer at one of them.
Scene make_scene(int index) {
  Draw d{0xABC0FFEEull + 7919ull * std::uint64_t(index)};
  Scene s;
  const int nb = 1 + index % 3;
  const bool timoshenko = index % 2 == 1;
  const int elements = d.integer(11, 47);  // 2 (4 (elements + 1) + nb) states: 98 .. 390
  const double E = 2.1e11, rho = 7800.0, length = d.uniform(0.4, 1.2);
  const double outer = d.uniform(0.025, 0.06), inner = d.uniform(0.0, 1.0) < 0.5 ? 0.0 : d.uniform(0.3, 0.6) * outer;
  for (int e = 0; e < elements; ++e) {
    const double f = d.uniform(0.9, 1.1);  // a stepped shaft
    s.spec.elements.push_back(
        {length / elements * d.uniform(0.7, 1.3), outer * f, inner * f, E, rho, timoshenko ? E / 2.6 : 0.0});
  }
  const int nodes = elements + 1;
  const int n_discs = d.integer(1, 3);
  std::vector<int> disc_nodes;
  while (int(disc_nodes.size()) < n_discs) {
    const int node = d.integer(1, nodes - 1);
    if (std::find(disc_nodes.begin(), disc_nodes.end(), node) == disc_nodes.end()) disc_nodes.push_back(node);
  }
  for (int node : disc_nodes) {
    const double m = d.uniform(0.5, 6.0), r = d.uniform(0.06, 0.15), h = d.uniform(0.01, 0.04);
    s.spec.discs.push_back({node, m, m * r * r / 2, m * (3 * r * r + h * h) / 12});
  }
  const int b0 = d.integer(0, nodes / 4), b1 = d.integer(3 * nodes / 4, nodes - 1);
  s.spec.bearings.push_back({b0, d.uniform(5e6, 5e7), d.uniform(100.0, 2000.0), 0.0, 0.0});
  s.spec.bearings.push_back({b1, d.uniform(5e6, 5e7), d.uniform(100.0, 2000.0), d.uniform(0.0, 1e3), 0.0});
  const ShaftDisc& bal = s.spec.discs[std::size_t(d.integer(0, n_discs - 1))];
  s.spec.balancer_node = bal.node;

  ParamsN& p = s.balancer;
  p.law = index % 4 < 2 ? FrictionLaw::viscous : FrictionLaw::coulomb;
  p.kappa = 1e2;
  p.omega = d.uniform(150.0, 1500.0);
  p.rotor = {bal.mass, 0.0, 0.0, 2e-5 * bal.mass};  // in a shaft scene the rotor gives the unbalance only
  p.balls.resize(std::size_t(nb));
  for (int i = 0; i < nb; ++i) {
    const double f = 1 + 0.07 * i;
    p.balls[std::size_t(i)] = {0.004 * bal.mass * f, 0.05 * (1 + 0.01 * i), 0.004, 1.4, 0.002 * f, 1e-2 * f, 0.001 * f,
                               0.003 * f, 0.1 * f};
  }
  char buf[200];
  std::snprintf(buf, sizeof buf, "scene %d: %d elements, %d discs, %d balls, %s, %s, omega %.1f", index, elements,
                n_discs, nb, timoshenko ? "Timoshenko" : "Euler-Bernoulli",
                p.law == FrictionLaw::viscous ? "viscous" : "coulomb", p.omega);
  s.what = buf;
  return s;
}

// Every eigenvalue of a v = lambda b v, dense: QR of J = b^-1 a, then each value s refined
// by inverse iteration x <- (a - s b)^-1 b x, lambda = s + 1 / (x^H y), with one dense LU
// (the QR's absolute error ~eps ||J|| is too large for the slow ball modes; the refined
// value is good to ~1e-14 of itself, model.md §19.6). Only values with Re >= re_min are
// refined (the others are far left of those compared). `qr` keeps the unrefined values.
std::vector<cplx> dense_spectrum(const ShaftPencil& pen, double re_min, std::vector<cplx>& qr) {
  const Eigen::MatrixXd a(pen.a), b(pen.b);
  const Eigen::MatrixXd j = b.partialPivLu().solve(a);
  Eigen::EigenSolver<Eigen::MatrixXd> es(j, false);
  REQUIRE(es.info() == Eigen::Success);
  const Eigen::MatrixXcd ac = a.cast<cplx>(), bc = b.cast<cplx>();
  const Eigen::Index n = a.rows();
  std::vector<cplx> out;
  qr.clear();
  for (Eigen::Index i = 0; i < n; ++i) {
    const cplx s = es.eigenvalues()(i);
    qr.push_back(s);
    if (s.real() < re_min) {  // far left of the rightmost: not compared, not refined
      out.push_back(s);
      continue;
    }
    // Rayleigh-quotient steps: the QR value can be 1e-4 off (eps ||J||, ||J|| ~ 1e12 with
    // stiff bearings), so the shift moves to each new value (a new LU), up to six times.
    Eigen::VectorXcd x = Eigen::VectorXcd::Ones(n) / std::sqrt(double(n));
    cplx lam = s;
    for (int f = 0; f < 6; ++f) {
      const cplx shift = lam;
      const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(ac - shift * bc);
      bool settled = false;
      for (int it = 0; it < 3 && !settled; ++it) {
        const Eigen::VectorXcd y = lu.solve(bc * x);
        const cplx theta = x.dot(y);
        const double yn = y.norm();
        if (!(std::abs(theta) > 0.0) || !std::isfinite(yn)) break;
        const cplx next = shift + 1.0 / theta;
        settled = it > 0 && std::abs(next - lam) <= 1e-15 * std::abs(next);
        lam = next;
        x = y / yn;
      }
      if (settled) break;
    }
    out.push_back(lam);
  }
  return out;
}

}  // namespace

// Asserted, per scene and equilibrium: the ladder converged; every returned eigenvalue is a
// dense one to 1e-8 of its modulus (the acceptance's tolerance; measured at most ~1e-13), one to
// one; and every dense eigenvalue in the certified region right of the k-th returned
// (Re >= Re_k, coverage rectangle) is among those returned (the coverage claim of (19.5)).
// A structural zero (three balls: the balanced set's direction, a defective double zero
// that rounding splits by ~sqrt(eps) of the scale) is matched to 1e-6 of the largest
// returned modulus instead.
// Hidden from the discovered tests ([.]): ctest runs it as shaft/dense_crosscheck with the
// slow label (~35 s CPU idle, the dense refinement of ~40 values per state at 100–400 states).
TEST_CASE("shaft dense cross-check: rightmost eigenvalues of generated shafts against a dense solve",
          "[.][shaft-dense]") {
  double worst = 0.0, worst_qr = 0.0;
  int compared = 0;
  for (int index = 0; index < 4; ++index) {
    const Scene scene = make_scene(index);
    const ShaftSystem sys = make_shaft_system(scene.spec, scene.balancer);
    const ShaftEquilibriumSet set = find_shaft_equilibria(sys);
    std::vector<const ShaftEquilibrium*> picked;
    for (const auto& e : set.list)  // the first, and the first of another family (else the second)
      if (e.status.ok() && picked.size() < 2 && (picked.empty() || picked.front()->family != e.family))
        picked.push_back(&e);
    if (picked.size() == 1 && set.list.size() > 1 && set.list[1].status.ok()) picked.push_back(&set.list[1]);
    INFO(scene.what << ": " << set.list.size() << " equilibria");
    REQUIRE(picked.size() >= 2);
    for (const ShaftEquilibrium* e : picked) {
      const ShaftPencil pen = shaft_pencil(linearize_shaft(sys, e->state()));
      const int states = int(pen.a.rows());
      INFO(scene.what << ", " << states << " states, family " << int(e->family));
      CHECK(states >= 98);
      CHECK(states <= 400);
      RightmostOptions ro;
      ro.max_frequency = 10.0 * scene.balancer.omega;  // what `equilibria` asks (its default band)
      SparseSpectrum sp = rightmost_eigenvalues(pen.a, pen.b, 10, ro);
      merge_shift_copies(sp, 1e-6);
      INFO("status " << sp.status.reason);
      REQUIRE(sp.status.ok());
      std::vector<cplx> qr;
      double largest = 0.0;
      for (const auto& pr : sp.eigenpairs) largest = std::max(largest, std::abs(pr.value));
      const std::vector<cplx> dense = dense_spectrum(pen, sp.eigenpairs.back().value.real() - 1e-3 * largest, qr);
      const double zero_floor = 1e-6 * largest;
      std::vector<bool> used(dense.size(), false);
      // Matched one to one, the largest first: a structural zero must not take another's partner.
      std::vector<SparseEigenpair> by_modulus = sp.eigenpairs;
      std::stable_sort(by_modulus.begin(), by_modulus.end(),
                       [](const auto& l, const auto& r) { return std::abs(l.value) > std::abs(r.value); });
      for (const auto& pr : by_modulus) {
        if (std::abs(pr.value) <= zero_floor) {
          // A structural zero: near a dense zero (copies of the defective zero not one to one).
          double bz = 1e300;
          for (const cplx& z : dense) bz = std::min(bz, std::abs(z - pr.value));
          INFO("structural zero " << pr.value);
          CHECK(bz <= zero_floor);
          continue;
        }
        std::size_t best = 0;
        double bd = 1e300;
        for (std::size_t i = 0; i < dense.size(); ++i)
          if (!used[i] && std::abs(dense[i] - pr.value) < bd) bd = std::abs(dense[i] - pr.value), best = i;
        used[best] = true;
        INFO("eigenvalue " << pr.value << " residual " << pr.residual << " refined " << pr.refined << " dense "
                           << dense[best]);
        const bool zero = std::abs(pr.value) <= zero_floor && std::abs(dense[best]) <= zero_floor;
        CHECK(bd <= (zero ? zero_floor : 1e-8 * std::abs(pr.value)));
        if (!zero) {
          worst = std::max(worst, bd / std::abs(pr.value));
          double bq = 1e300;
          for (const cplx& z : qr) bq = std::min(bq, std::abs(z - pr.value));
          worst_qr = std::max(worst_qr, bq / std::abs(pr.value));
          ++compared;
        }
      }
      // Completeness in the certified region right of the k-th.
      const double re_k = sp.eigenpairs.back().value.real();
      for (std::size_t i = 0; i < dense.size(); ++i) {
        const cplx z = dense[i];
        const bool inside = z.real() > re_k + 1e-8 * std::abs(z) && z.real() <= sp.coverage.real_max &&
                            std::abs(z.imag()) <= sp.coverage.imag_max;
        if (!inside || used[i]) continue;
        bool found = false;
        for (const auto& pr : sp.eigenpairs)
          found = found || std::abs(pr.value - z) <= std::max(1e-8 * std::abs(z), zero_floor);
        INFO("dense eigenvalue " << z << " in the covered region, right of the k-th");
        CHECK(found);
      }
    }
  }
  std::printf("shaft dense cross-check: %d eigenvalues, largest difference %.2g of the modulus (%.2g before the "
              "dense reference's refinement)\n",
              compared, worst, worst_qr);
}
