// Shared by the two translation units of the compiled part of the Python module, abu._abu
// (module.cpp: errors, scenes, equilibria, maps; runs.cpp: continuation, simulation;
// studies.cpp: outcome and design studies).
// These functions return plain dicts of numpy arrays and lists; python/abu/__init__.py
// wraps them in the documented result classes. Long computations run with the GIL
// released: results are computed into C++ values first and converted afterwards.
#pragma once

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <complex>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "abu/analysis/machine_parts.hpp"
#include "abu/core/errors.hpp"
#include "abu/core/status.hpp"
#include "abu/input/scene.hpp"

namespace abu::python {

namespace py = pybind11;

/// The parts a call of the module answers for (machine_parts.hpp), refused otherwise with the
/// CLI's message naming the commands that do: `equilibria` takes every scene the CLI's
/// `equilibria` takes; `map` the base model and LuGre (its z = 0 equilibria, as the CLI);
/// `continue_branches` and `simulate` the base model of model.md §3 only (a shaft, an
/// anisotropic support, an unround race, LuGre or coulomb-set friction are refused rather than
/// dropped).
/// The refusal says it is the module's call that does not take the scene (the CLI's command of
/// the same name may: its message lists the CLI's commands).
inline void require_parts(const Scene& scene, std::string_view call, Handles handles) {
  const std::string note = fmt::format(" (the Python module's abu.{} takes less than the CLI's command: "
                                       "abu.equilibria takes every scene `equilibria` takes)",
                                       call);
  try {
    refuse_unmodelled(scene, call, handles);
  } catch (const InputError& e) {
    throw InputError(e.file(), e.line(), e.key(), e.rule() + note);
  } catch (const NotSupportedError& e) {
    throw NotSupportedError(e.what() + note);
  }
}

/// Registers continue_branches and simulate (runs.cpp).
void bind_runs(py::module_& m);
/// Registers outcomes and design (studies.cpp).
void bind_studies(py::module_& m);
/// Registers continue_orbits (orbits.cpp).
void bind_orbits(py::module_& m);

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
