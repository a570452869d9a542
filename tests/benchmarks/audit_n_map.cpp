// The n-ball map cell's verdicts against the full spectra, class by class (model.md §13.9,
// §13.10): an omega x mu map of a ring scene with its ball count set to N, and for every
// class representative of every cell
//   - a balanced sample: the cell's normal verdict and abscissa against compute_normal_spectrum
//     (the tangent directions deflated, §13.5);
//   - an aligned equilibrium: the cell's verdict, unstable count and abscissa against
//     spectrum_verdict (the full refined path); where the two disagree, Eigen's plain QR of the
//     double Jacobian is the third opinion (counted where it is clear of the axis).
//
//   audit_n_map SCENE N [NX NY]      (omega 150 .. 2500 rad/s, mu 1e-4 .. 1e-1 log; 30 x 12)
#include <fmt/format.h>
#include <gsl/gsl_errno.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "abu/equilibria/ball_permutations.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/input/scene.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/linear/spectrum_verdict.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/map.hpp"
#include "abu/scan/scan.hpp"

namespace {

using ld = long double;

struct Tally {
  long balanced = 0, balanced_differ = 0, aligned = 0, aligned_differ = 0, full_wrong = 0, cell_wrong = 0, undecided = 0;
  double balanced_worst = 0, aligned_worst = 0;
};

// Eigen's QR count of Re > 0 and whether every eigenvalue is clear of the axis.
std::pair<int, bool> qr_count(const abu::ParamsN& q, const abu::EquilibriumN& e) {
  const auto J = abu::jacobian(q, abu::at_rest<double, abu::any_balls>(e.position_si()));
  Eigen::EigenSolver<Eigen::MatrixXd> qr(J, false);
  int count = 0;
  bool clear = true;
  for (Eigen::Index i = 0; i < J.rows(); ++i) {
    const auto z = qr.eigenvalues()(i);
    count += z.real() > 0;
    clear = clear && std::abs(z.real()) > 1e-6 * std::abs(z) && std::abs(z.real()) > 1e-9 * J.norm();
  }
  return {count, clear};
}

void audit_cell(const abu::ParamsN& q, const abu::MapCellN& cell, Tally& t) {
  const abu::EquilibriumSetN set = abu::find_equilibria(q);
  abu::PermutationClasses classes;
  abu::find_permutation_classes(abu::ball_kinds(q), set.points(), classes);
  const auto ql = q.cast<ld>();
  for (std::size_t k = 0; k < set.points().size(); ++k) {
    const abu::EquilibriumN& e = set.points()[k];
    const abu::MapEquilibriumN& m = cell.equilibria[k];
    if (classes.images[k].representative != int(k)) continue;
    if (e.on_balanced_set && e.family == abu::Family::balanced) {
      const auto sp = abu::compute_normal_spectrum(abu::linearize(ql, e.state()), abu::balanced_tangent_basis(q, e.position));
      ++t.balanced;
      if ((sp.stability == abu::Stability::stable) != m.stable || sp.n_unstable != m.n_unstable) ++t.balanced_differ;
      const double scale = std::abs(sp.eigenvalues[std::size_t(sp.n_structural)]) + std::abs(sp.abscissa);
      t.balanced_worst = std::max(t.balanced_worst, std::abs(m.abscissa - sp.abscissa) / scale);
    } else if (e.family != abu::Family::balanced) {
      const auto v = abu::spectrum_verdict(abu::linearize(ql, e.state()), e.structural_zeros);
      ++t.aligned;
      t.aligned_worst = std::max(t.aligned_worst, std::abs(m.abscissa - v.abscissa) / std::abs(v.abscissa));
      if ((v.stability == abu::Stability::stable) == m.stable && v.n_unstable == m.n_unstable) continue;
      ++t.aligned_differ;
      const auto [count, clear] = qr_count(q, e);
      if (!clear) ++t.undecided;
      t.full_wrong += clear && count != v.n_unstable;
      t.cell_wrong += clear && count != m.n_unstable;
      fmt::print("  differ: omega {} mu {} pattern {} member {}: full {} unstable, cell {}, QR {} ({})\n", q.omega,
                 q.balls[0].mu, abu::pattern_string(e.pattern, q.n_balls()), e.member, v.n_unstable, m.n_unstable,
                 count, clear ? "clear of the axis" : "not clear of the axis");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  gsl_set_error_handler_off();
  if (argc < 3) {
    fmt::print(stderr, "usage: audit_n_map SCENE N [NX NY]\n");
    return 2;
  }
  const int n = std::stoi(argv[2]);
  const int nx = argc > 3 ? std::stoi(argv[3]) : 30, ny = argc > 4 ? std::stoi(argv[4]) : 12;
  abu::Scene scene = abu::load_scene(argv[1]);
  abu::set_ball_count(scene, n, "audit_n_map");
  const abu::ParamsN p = abu::params_of<abu::any_balls>(scene);
  abu::Axis ax, ay;
  ax.param = *abu::parse_param("omega", n);
  ax.from = 150;
  ax.to = 2500;
  ax.count = nx;
  ay.param = *abu::parse_param("mu", n);
  ay.from = 1e-4;
  ay.to = 1e-1;
  ay.count = ny;
  ay.logarithmic = true;
  abu::CellAnalyzerN cells(p, {}, ax, ay, abu::BalancedSampling{});
  abu::MapCellN cell;
  Tally t;
  for (int ix = 0; ix < nx; ++ix)
    for (int iy = 0; iy < ny; ++iy) {
      cells.analyze(ix, iy, cell);
      audit_cell(cells.cell_params(ix, iy), cell, t);
    }
  fmt::print("n = {}: balanced class rows {}, verdicts differing {}, worst abscissa difference {:.2e} of the spectrum's scale\n",
             n, t.balanced, t.balanced_differ, t.balanced_worst);
  fmt::print("n = {}: aligned class rows {}, verdicts or counts differing {} (QR clear of the axis: full path wrong {}, "
             "cell wrong {}; QR not clear {}), worst relative abscissa difference {:.2e}\n",
             n, t.aligned, t.aligned_differ, t.full_wrong, t.cell_wrong, t.undecided, t.aligned_worst);
  return t.balanced_differ > 0 || t.cell_wrong > 0 ? 1 : 0;
}
