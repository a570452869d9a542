// Prints the assembled matrices of one-element shafts (and one disc) for
// tests/reference/shaft_elements.py, which derives them independently from the shape
// functions and the kinetic and strain energies (model.md §18.1–§18.4).
// Output: one line per case "case <name> L D d E rho G kappa Phi", then lines
// "<matrix> i j value" for mass, stiffness, gyroscopic, damping (8 x 8, nonzeros), %.17g.
#include <cstdio>

#include <Eigen/Dense>

#include "abu/model/shaft.hpp"

namespace {

void dump(const char* name, const abu::ShaftSpec& spec) {
  const abu::ShaftMatrices m = abu::assemble_shaft(spec);
  const abu::ShaftElement e = spec.elements.empty() ? abu::ShaftElement{} : spec.elements[0];
  const double phi = spec.elements.empty() ? 0.0 : abu::beam_element_matrices(e).shear_parameter;
  std::printf("case %s %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", name, e.length, e.outer_diameter,
              e.inner_diameter, e.youngs_modulus, e.density, e.shear_modulus,
              spec.elements.empty() ? 0.0 : abu::shear_coefficient(e), phi);
  const std::pair<const char*, const Eigen::SparseMatrix<double>*> all[] = {
      {"mass", &m.mass}, {"stiffness", &m.stiffness}, {"gyroscopic", &m.gyroscopic}, {"damping", &m.damping}};
  for (const auto& [label, mat] : all) {
    const Eigen::MatrixXd d = Eigen::MatrixXd(*mat);
    for (Eigen::Index i = 0; i < d.rows(); ++i)
      for (Eigen::Index j = 0; j < d.cols(); ++j)
        if (d(i, j) != 0.0) std::printf("%s %d %d %.17g\n", label, int(i), int(j), d(i, j));
  }
}

}  // namespace

int main() {
  abu::ShaftSpec s;
  s.elements = {{0.25, 0.03, 0.0, 2.1e11, 7800.0, 0.0}};
  dump("euler_bernoulli_solid", s);
  s.elements = {{0.05, 0.08, 0.05, 2.0e11, 7850.0, 7.9e10}};
  dump("timoshenko_hollow", s);
  s.elements = {{0.4, 0.02, 0.012, 7.0e10, 2700.0, 2.6e10}};
  dump("timoshenko_slender_hollow", s);
  // A disc and a bearing on node 1 of a massive element: their entries add.
  s.elements = {{0.3, 0.05, 0.0, 2.1e11, 7800.0, 8.1e10}};
  s.discs = {{1, 2.5, 0.03, 0.016}};
  s.bearings = {{1, 1e7, 150.0, 2e4, 3.0}};
  dump("disc_and_bearing", s);
  return 0;
}
