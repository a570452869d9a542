// Shared by the two translation units of the compiled part of the Python module, abu._abu
// (module.cpp: errors, scenes, equilibria, maps; runs.cpp: continuation, simulation).
// These functions return plain dicts of numpy arrays and lists; python/abu/__init__.py
// wraps them in the documented result classes. Long computations run with the GIL
// released: results are computed into C++ values first and converted afterwards.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <complex>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "abu/core/errors.hpp"
#include "abu/core/status.hpp"
#include "abu/input/scene.hpp"

namespace abu::python {

namespace py = pybind11;

/// The module analyses the model of model.md §3 (isotropic support, round race): a scene
/// with an anisotropic support (§10) or an unround race (§11) is refused, as the CLI's
/// sweep, continue, map and simulate refuse it, rather than analysed without them.
inline void require_base_model(const Scene& scene, std::string_view what) {
  if (scene.support || !scene.race.round())
    throw NotSupportedError(std::string(what) + ": " + scene.file + " has an " +
                            (scene.support ? "anisotropic support (model.md §10)" : "unround race (model.md §11)") +
                            "; the Python module does not analyse it yet (the CLI's `equilibria` does)");
}

/// Registers continue_branches and simulate (runs.cpp).
void bind_runs(py::module_& m);

/// A new C-ordered array of the given shape, zero-filled.
template <class T>
py::array_t<T> zeros(std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  std::fill(a.mutable_data(), a.mutable_data() + a.size(), T{});
  return a;
}

/// A 1-D array holding `values`.
template <class T>
py::array_t<T> array_of(const std::vector<T>& values) {
  py::array_t<T> a(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}
/// std::vector<bool> has no data(): a bool array element by element.
inline py::array_t<bool> bool_array_of(const std::vector<bool>& values) {
  py::array_t<bool> a(static_cast<py::ssize_t>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) a.mutable_data()[i] = values[i];
  return a;
}

/// "converged", "not converged", "numerical issue".
inline std::string outcome_name(const Status& s) { return std::string(to_string(s.outcome)); }

/// Polls Python's signal handlers (Ctrl-C) from a thread that does not hold the GIL;
/// true if one raised (the exception stays set for the caller to rethrow).
inline bool python_signal_pending() {
  py::gil_scoped_acquire gil;
  return PyErr_CheckSignals() != 0;
}

}  // namespace abu::python
