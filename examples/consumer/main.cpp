// Every equilibrium of a two-ball scene with its stability, through the library's public
// API only (abu::load_scene, abu::params_of, abu::analyze): the example of docs/install.md.
//
//   abu_consumer SCENE.toml [NAME=VALUE ...]
//
// Prints a comment line (the library's version and the scene), then one CSV line per
// equilibrium, in the order and with the columns of `stability-scan equilibria SCENE
// --format csv` (a subset of them):
//   family,member,q1,q2,beta1,beta2,residual,spectral_abscissa,stable,re1,im1,...,re8,im8
// q [m] and beta [rad] (rotating frame), eigenvalues [1/s] (rotating frame); numbers in
// shortest round-trip form. Exit 2 on a bad scene (the library's message), 1 otherwise.
#include <abu/core/errors.hpp>
#include <abu/input/scene.hpp>
#include <abu/scan/scan.hpp>

#include <charconv>
#include <cstdio>
#include <exception>
#include <string>

namespace {
std::string number(double x) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;  // shortest round trip
  return std::string(buffer, end);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE.toml [NAME=VALUE ...]\n", argv[0]);
    return 2;
  }
  try {
    abu::Scene scene = abu::load_scene(argv[1]);
    for (int i = 2; i < argc; ++i) abu::apply_override(scene, argv[i]);
    const abu::Params p = abu::params_of<2>(scene);  // throws NotSupportedError unless two balls
    const abu::Analysis a = abu::analyze(p);
    const auto points = a.equilibria.points();
    std::printf("# abu %s, %s\n", ABU_VERSION, argv[1]);  // ABU_VERSION: defined by abu::abu
    std::printf("family,member,q1,q2,beta1,beta2,residual,spectral_abscissa,stable");
    for (int k = 1; k <= 8; ++k) std::printf(",re%d,im%d", k, k);
    std::printf("\n");
    for (std::size_t i = 0; i < points.size(); ++i) {
      const abu::Equilibrium& e = points[i];
      const abu::Spectrum& s = a.spectra[i];
      std::string line = std::string(abu::to_string(e.family)) + "," + std::to_string(e.member);
      for (int j = 0; j < 4; ++j) line += "," + number(double(e.position(j)));
      line += "," + number(e.residual) + "," + number(s.abscissa);
      line += s.stability == abu::Stability::stable ? ",1" : ",0";
      for (int k = 0; k < s.count; ++k)
        line += "," + number(s.eigenvalues[std::size_t(k)].real()) + "," + number(s.eigenvalues[std::size_t(k)].imag());
      std::printf("%s\n", line.c_str());
    }
    return 0;
  } catch (const abu::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
