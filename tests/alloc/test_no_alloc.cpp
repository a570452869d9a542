// The n-ball hot path allocates nothing: the model (vector field, linearization,
// Jacobian) and the refined spectra for a run-time ball count use bounded-dynamic Eigen
// types (fixed storage for max_balls, model.hpp), so a map cell or an integration step
// costs no heap traffic. Checked by counting calls to malloc (this executable's malloc
// forwards to glibc's and counts while `counting` is set: symbol interposition, so calls
// from inside the library, Eigen and GSL are counted too). A separate executable, since
// the interposition must not meet a sanitizer's own malloc (not built with ABU_SANITIZE).
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "abu/analysis/shaft_states.hpp"
#include "abu/dynamics/shaft_simulation.hpp"
#include "abu/dynamics/simulation.hpp"
#include "abu/equilibria/equilibria_n.hpp"
#include "abu/input/race_scene.hpp"
#include "abu/input/scene.hpp"
#include "abu/linear/spectrum.hpp"
#include "abu/model/model.hpp"
#include "abu/scan/map.hpp"

extern "C" void* __libc_malloc(std::size_t);
static bool counting = false;
static long allocations = 0;
extern "C" void* malloc(std::size_t size) {
  if (counting) ++allocations;
  return __libc_malloc(size);
}

namespace {

int failures = 0, passes = 0;

void check(bool ok, const std::string& what) {
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what.c_str());
  ++(ok ? passes : failures);
}

// Runs `work` twice (the first time may initialize statics) and counts the mallocs of
// the second run.
template <class F>
long mallocs_of(F&& work) {
  work();
  allocations = 0;
  counting = true;
  work();
  counting = false;
  return allocations;
}

void check_ball_count(const std::string& scene_file, int n) {
  abu::Scene scene = abu::load_scene(scene_file);
  abu::set_ball_count(scene, n, "test");
  const abu::ParamsN p = abu::params_of<abu::any_balls>(scene);
  const auto set = abu::find_equilibria(p);  // (allocates: the list of equilibria, outside the hot path)
  const abu::EquilibriumN* aligned = nullptr;
  const abu::EquilibriumN* balanced = nullptr;
  for (const auto& e : set.points()) {
    if (e.family == abu::Family::balanced && !balanced) balanced = &e;
    if (e.family != abu::Family::balanced && !aligned) aligned = &e;
  }
  check(aligned && balanced, "n = " + std::to_string(n) + ": an aligned and a balanced equilibrium exist");
  if (!aligned || !balanced) return;
  const auto pl = p.cast<long double>();
  abu::State<double, abu::any_balls> x = aligned->state().cast<double>();
  for (int i = 0; i < x.size(); ++i) x(i) += 1e-3 * (i + 1);  // off equilibrium: every term of §3 and §6
  double sink = 0;
  const long model = mallocs_of([&] {
    sink += abu::vector_field(p, x).sum();
    sink += abu::jacobian(p, x).sum();
    sink += abu::linearize(pl, aligned->state()).stiffness.sum();
  });
  check(model == 0, "n = " + std::to_string(n) + ": vector field, Jacobian, linearization: " + std::to_string(model) +
                        " mallocs");
  const auto lin = abu::linearize(pl, aligned->state());
  const long spectrum = mallocs_of([&] { sink += abu::compute_spectrum(lin).abscissa; });
  check(spectrum == 0, "n = " + std::to_string(n) + ": refined spectrum of an aligned equilibrium: " +
                           std::to_string(spectrum) + " mallocs");
  const auto lin_b = abu::linearize(pl, balanced->state());
  const auto tangent = abu::balanced_tangent_basis(p, balanced->position);
  const long normal = mallocs_of([&] { sink += abu::compute_normal_spectrum(lin_b, tangent).abscissa; });
  check(normal == 0, "n = " + std::to_string(n) + ": normal spectrum of a balanced sample: " + std::to_string(normal) +
                         " mallocs");
  if (sink == 12345.678) std::printf("(unlikely)\n");
}

// A cell of an n-ball map (CellAnalyzerN, model.md §13.8): equilibria, linearizations and
// every spectrum of the cell. The analyzer's equilibrium list and the cell's rows keep
// their storage, so once a cell of this size has been computed the next allocates
// nothing (the first cell of a thread grows them: that is the warm-up run).
void check_map_cell(const std::string& scene_file, int n) {
  abu::Scene scene = abu::load_scene(scene_file);
  abu::set_ball_count(scene, n, "test");
  const abu::ParamsN p = abu::params_of<abu::any_balls>(scene);
  abu::Axis x, y;
  x.param = *abu::parse_param("omega", n);
  x.from = 800, x.to = 900, x.count = 2;
  y.param = *abu::parse_param("mu", n);
  y.from = 1e-3, y.to = 2e-3, y.count = 2;
  abu::CellAnalyzerN cells(p, {}, x, y, abu::BalancedSampling{});
  abu::MapCellN cell;
  cells.analyze(0, 0, cell);  // a first cell of the same size: grows the storage
  const long mallocs = mallocs_of([&] { cells.analyze(1, 1, cell); });
  check(mallocs == 0 && !cell.equilibria.empty(),
        "n = " + std::to_string(n) + ": a map cell (" + std::to_string(cell.equilibria.size()) +
            " equilibria with their spectra): " + std::to_string(mallocs) + " mallocs");
}

// A simulation (model.md §15.1): GSL's stepper, control and evolve objects are allocated once,
// the field, the Jacobian and the dense output's interpolant work on bounded storage, and the
// samples' vector is reserved from t_end / every. So a run four times as long with the same
// number of samples (more steps) makes exactly as many allocations: none per step. With
// rk8pd: GSL 2.7's gsl_linalg_LU_decomp allocates its pivot vector (3 mallocs a call), so the
// implicit steppers (bsimp: one LU per extrapolation stage) allocate inside GSL.
void check_simulation(const std::string& scene_file, int n) {
  abu::Scene scene = abu::load_scene(scene_file);
  abu::set_ball_count(scene, n, "test");
  const abu::ParamsN p = abu::params_of<abu::any_balls>(scene);
  std::vector<double> beta;
  for (int i = 0; i < n; ++i) beta.push_back(0.7 * i + 0.3);
  const abu::State<double, abu::any_balls> x0 = abu::start_at_rest(p, beta);
  // A run-up that ends (at 0.01 s) within both runs: the same breakpoints, the dense output across one.
  const abu::SpeedProfile speed = abu::SpeedProfile::ramp(0.5 * p.omega, p.omega, 50 * p.omega);
  for (bool record : {false, true}) {
    long mallocs[2] = {0, 0};
    unsigned long steps[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      abu::SimulationOptions o;
      o.t_end = 0.02 * (1 + 3 * k);
      o.every = o.t_end / 50;
      o.record = record;
      o.method = abu::IntegrationMethod::rk8pd;
      mallocs[k] = mallocs_of([&] { steps[k] = abu::simulate(p, speed, x0, o).stats.steps; });
    }
    check(mallocs[0] == mallocs[1] && steps[1] > steps[0] + 10,
          "n = " + std::to_string(n) + (record ? ", 50 samples" : ", nothing recorded") + ": simulate over " +
              std::to_string(steps[0]) + " and " + std::to_string(steps[1]) + " steps: " + std::to_string(mallocs[0]) +
              " and " + std::to_string(mallocs[1]) + " mallocs");
  }
}

// A flexible shaft's simulation (model.md §18.16): the structured field works on storage sized
// once per run, the dense output's stepper is allocated once per run, and with rk8pd the
// Jacobian is evaluated only by the stiffness probe (it allocates: linearize_shaft's sparse
// matrices). So a run-up four times as long with the same samples makes as many allocations.
void check_shaft_simulation(const std::string& scene_file) {
  const abu::Scene scene = abu::load_scene(scene_file);
  const abu::ShaftSystem sys = abu::shaft_system_of(scene);
  const abu::RaceShape race = abu::race_shape(scene);  // an unround race: the balls on its paths (§18.20)
  const std::vector<double> angles{0.5, 2.0, 4.0, 5.0};
  const Eigen::VectorXd x0 =
      abu::shaft_start_at_rest(sys, std::vector<double>(angles.begin(), angles.begin() + sys.n_balls()));
  const double w = sys.balancer.omega;
  const abu::SpeedProfile speed = abu::SpeedProfile::ramp(0.5 * w, w, 50 * w);  // ends at 0.01 s
  long mallocs[2] = {0, 0};
  unsigned long steps[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    abu::SimulationOptions o;
    o.t_end = 0.02 * (1 + 3 * k);
    o.every = o.t_end / 50;
    o.method = abu::IntegrationMethod::rk8pd;
    if (!race.round()) o.race = &race;
    mallocs[k] = mallocs_of([&] { steps[k] = abu::simulate_shaft(sys, speed, x0, o).run.stats.steps; });
  }
  check(mallocs[0] == mallocs[1] && steps[1] > steps[0] + 10,
        std::string(abu::has_anisotropic_bearings(sys.spec) ? "flexible shaft on anisotropic bearings"
                    : !race.round()                          ? "flexible shaft with an unround race"
                                                             : "flexible shaft") +
            ", 50 samples: simulate over " + std::to_string(steps[0]) + " and " + std::to_string(steps[1]) +
            " steps: " + std::to_string(mallocs[0]) + " and " + std::to_string(mallocs[1]) + " mallocs");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s RING_SCENE SHAFT_SCENE...\n", argv[0]);
    return 2;
  }
  // The counter itself: one deliberate allocation must be seen, or the interposition is
  // not in effect and every check above would pass vacuously.
  // The block escapes through a volatile store: a malloc/free pair whose block is never
  // used may be removed by the optimizer (clang does), which would hide the counter.
  static void* volatile escaped = nullptr;
  const long probe = mallocs_of([] {
    escaped = std::malloc(64);
    std::free(escaped);
  });
  check(probe == 1, "the malloc counter sees a deliberate allocation (" + std::to_string(probe) + ")");
  for (int n : {3, 4, 12}) check_ball_count(argv[1], n);
  for (int n : {3, 5}) check_map_cell(argv[1], n);
  for (int n : {2, 5}) check_simulation(argv[1], n);
  for (int k = 2; k < argc; ++k) check_shaft_simulation(argv[k]);  // isotropic, anisotropic bearings, a race (§18.20)
  std::printf("%d passed, %d failed\n", passes, failures);
  return failures == 0 ? 0 : 1;
}
