"""abu: the automatic ball balancer's stability analyzer (abu-stability) from Python.

The functions call the same library functions as the command line `stability-scan`
(scene parser, equilibria and spectra, continuation, maps, simulation), so they give the
CLI's numbers, as numpy arrays. Units are SI, eigenvalues in 1/s in the rotating frame,
states in the order of docs/model.md (q1, q2, beta_1..beta_n, then their rates).

    import abu
    scene = abu.load_scene("data/scenes/default.toml")
    scene.set("omega", 1200)                  # as --set omega=1200
    eq = abu.equilibria(scene)                # eq.family, eq.q, eq.beta, eq.eigenvalues, ...
    run = abu.continue_branches(scene, "omega", 2000)
    m = abu.map(scene, x=("omega", 50, 2000, 100), y=("mu", 1e-4, 0.1, 50, "log"))
    sim = abu.simulate(scene, 2.0, balls=[2.0, 4.0])

Errors: bad input raises abu.InputError (a ValueError) whose message is the one the CLI
prints ("FILE:LINE: key 'KEY': RULE"); a numerical failure raises abu.NumericalError (a
RuntimeError). The long computations release the GIL (run them in threads) and Ctrl-C
stops maps and simulations. See docs/python.md.
"""

import json as _json
import math as _math
import numbers as _numbers
import os as _os
import re as _re

import numpy as _np

from . import _abu
from ._abu import InputError, NotSupportedError, NumericalError, Scene
from .studies import design, outcomes

__version__ = _abu.__version__

__all__ = [
    "InputError", "NumericalError", "NotSupportedError", "Scene",
    "load_scene", "scene_from_dict", "scene_toml", "parameter_symbols",
    "equilibria", "continue_branches", "continue_orbits", "map", "simulate", "outcomes", "design",
    "Equilibria", "MachineEquilibria", "Continuation", "Branch", "OrbitBranches", "Table", "StabilityMap", "Simulation",
    "Result",
]


def _input_error(file, line, key, rule):
    """An InputError built like the library's: message 'FILE:LINE: key 'KEY': RULE'."""
    where = file or "input"
    if line > 0:
        where += f":{line}"
    e = InputError(f"{where}: key '{key}': {rule}" if key else f"{where}: {rule}")
    e.file, e.line, e.key, e.rule = file, line, key, rule
    return e


def _strings(values):
    """A list of str as a numpy str array (also when empty)."""
    return _np.array(list(values), dtype=str)


# ---------------------------------------------------------------------------------------
# Scenes

def parameter_symbols():
    """The parameter symbols that Scene.set/get, continuation and map axes take (docs/model.md)."""
    return _abu.parameter_symbols()


def load_scene(path, overrides=()):
    """Reads and validates a scene file (TOML, SI units), as the CLI does.

    path: the file (str or os.PathLike). overrides: `NAME=VALUE` strings applied in order,
    as the CLI's `--set NAME=VALUE` options. Returns an abu.Scene. Raises InputError with
    the CLI's message (file, line, key, rule) on any invalid input.
    """
    scene = _abu.load_scene(_os.fspath(path))
    for assignment in [overrides] if isinstance(overrides, str) else overrides:
        scene.set(assignment)
    return scene


_BARE_KEY = _re.compile(r"[A-Za-z0-9_-]+\Z")


def _toml_key(key, path):
    if not isinstance(key, str):
        raise _input_error("<dict>", 0, ".".join(path + [str(key)]), "keys must be strings")
    return key if _BARE_KEY.match(key) else _json.dumps(key)


def _toml_value(value, path):
    if isinstance(value, _np.ndarray):
        value = value.tolist()
    elif isinstance(value, _np.generic):
        value = value.item()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, _numbers.Integral):
        return str(int(value))
    if isinstance(value, _numbers.Real):
        x = float(value)
        if _math.isnan(x):
            return "nan"
        if _math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)  # shortest round-trip form, always with '.' or 'e': stays a float
    if isinstance(value, str):
        return _json.dumps(value, ensure_ascii=False)
    if isinstance(value, dict):
        items = ", ".join(f"{_toml_key(k, path)} = {_toml_value(v, path + [str(k)])}" for k, v in value.items())
        return "{" + items + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v, path) for v in value) + "]"
    raise _input_error("<dict>", 0, ".".join(path), f"a value of type {type(value).__name__} has no TOML form")


def _is_table_array(value):
    return isinstance(value, (list, tuple)) and len(value) > 0 and all(isinstance(v, dict) for v in value)


def _toml_table(table, path, header, lines):
    if header:
        lines.append(header)
    nested = []
    for k, v in table.items():
        if isinstance(v, dict) or _is_table_array(v):
            nested.append((k, v))
        else:
            lines.append(f"{_toml_key(k, path)} = {_toml_value(v, path + [str(k)])}")
    for k, v in nested:
        sub = path + [str(k)]
        name = ".".join(_toml_key(p, path) for p in sub)
        if isinstance(v, dict):
            _toml_table(v, sub, f"[{name}]", lines)
        else:
            for element in v:
                _toml_table(element, sub, f"[[{name}]]", lines)


def scene_toml(data):
    """The TOML text of a scene given as a dict with the scene file's layout.

    Keys in dict order, one per line: the top-level values, then each table ([rotor],
    [friction], ...), a list of dicts as an array of tables ([[ball]]). Python ints stay
    integers (so `count = 11.0` is still refused), floats are written in their shortest
    round-trip form. The line numbers of scene_from_dict's errors are lines of this text.
    """
    if not isinstance(data, dict):
        raise _input_error("<dict>", 0, "", f"a scene is a dict, got {type(data).__name__}")
    lines = []
    _toml_table(data, [], "", lines)
    return "\n".join(lines) + "\n"


def scene_from_dict(data, overrides=(), name="<dict>"):
    """A scene from a dict with the layout of a scene file, by the same parser and rules.

    data: e.g. {"rotor": {"mass": 0.12, ...}, "ball": [{"mass": 3.3e-5, ...}, {...}],
    "friction": {"law": "coulomb", "mu": 0.002, "kappa": 1e3}, "speed": {"omega": 900}}
    (tomllib.load of a scene file gives such a dict). The dict is written as TOML
    (scene_toml) and parsed as a file named NAME, so an invalid scene raises InputError with
    the message a file would give: file NAME, the line in scene_toml(data), the dotted key
    and the rule. overrides: `NAME=VALUE` strings, as load_scene's.
    """
    scene = _abu.parse_scene(scene_toml(data), name)
    for assignment in [overrides] if isinstance(overrides, str) else overrides:
        scene.set(assignment)
    return scene


# ---------------------------------------------------------------------------------------
# Results

class Result:
    """Base of the result classes: the fields are attributes (see each class's doc);
    as_dict() gives them as a dict."""

    def __init__(self, data):
        self.__dict__.update(data)

    def as_dict(self):
        """The fields as a dict (arrays are not copied)."""
        return dict(self.__dict__)

    def _shapes(self):
        parts = []
        for k, v in self.__dict__.items():
            if isinstance(v, _np.ndarray):
                parts.append(f"{k}{list(v.shape)}")
        return ", ".join(parts)

    def __repr__(self):
        return f"<abu.{type(self).__name__}: {self._shapes()}>"


class Table(Result):
    """Columns of equal length as numpy arrays (one row per item); len() is the row count,
    rows() the rows as dicts, select(mask) the rows where MASK is true."""

    def __len__(self):
        for v in self.__dict__.values():
            if isinstance(v, _np.ndarray):
                return len(v)
        return 0

    def select(self, mask):
        """A Table of the rows where the boolean array MASK is true."""
        mask = _np.asarray(mask, dtype=bool)
        return Table({k: v[mask] if isinstance(v, _np.ndarray) else v for k, v in self.__dict__.items()})

    def rows(self):
        """The rows as a list of dicts (numpy scalars and arrays per row)."""
        return [{k: v[i] for k, v in self.__dict__.items() if isinstance(v, _np.ndarray)} for i in range(len(self))]


class Equilibria(Table):
    """Every equilibrium of one parameter point with its spectrum (abu.equilibria).

    Rows in the order of the CLI's `equilibria` output (two balls: balanced, together,
    opposite; n >= 3: the balanced set's samples, then aligned by pattern and member); the
    numbers are the doubles the CLI's CSV prints.

    Per equilibrium (count rows):
      family        'balanced', 'together', 'opposite' (two balls) or 'aligned' (n >= 3)
      pattern       the balls' signs along q ('+-+', ball 1 '+'), '' for balanced
      member        root of the pattern (1 or 2), or the balanced sample's index
      q             (count, 2) rotor centre [m], rotating frame;  q_abs = |q| [m]
      beta          (count, n) ball angles [rad] in [0, 2 pi)
      state         (count, 2n+4) the state at rest (q, beta, zero rates), model.md order
      residual      static residual, dimensionless (~1e-16 at rounding level)
      newton_iterations, converged   the polish (Newton in long double)
      is_set, on_balanced_set        U = 0 circle representative / point of the balanced set
      eigenvalues   (count, 2n+4) complex [1/s], rotating frame, sorted by real part
                    descending, then imaginary part descending
      error         (count, 2n+4) estimated absolute error of each eigenvalue [1/s]
      condition     (count, 2n+4) componentwise condition number (NaN: structural zero)
      structural    (count, 2n+4) bool: zero by construction (the balanced set's directions)
      on_axis       (count, 2n+4) bool: inside the marginal band around the imaginary axis
      spectral_abscissa   largest real part [1/s] (structural zeros left out)
      stability     'stable', 'unstable' or 'marginal';  stable: bool (stability == 'stable')
      n_unstable, n_marginal, n_structural_zero
      ill_conditioned, spectrum_converged
      status        'converged', 'not converged' or 'numerical issue' (polish and spectrum)
      reason        why not converged ('' if converged)
    For the whole point: n_balls, omega [rad/s], degeneracy (bit flags) and degeneracies
    (sentences), warnings (what the CLI prints on stderr), table (the CLI's table output,
    also str(result)), and for n >= 3 balanced_set (exists, dimension, grid, grid_points,
    samples).
    """

    def __init__(self, data):
        for k in ("family", "pattern", "stability", "status", "reason"):
            data[k] = _strings(data[k])
        data.setdefault("balanced_set", None)
        super().__init__(data)

    @property
    def state(self):
        """(count, 2n+4): q, beta and zero rates, the equilibria as states of model.md §2."""
        count = len(self.family)
        return _np.hstack([self.q, self.beta, _np.zeros((count, self.n_balls + 2))])

    def __str__(self):
        return self.table

    def __repr__(self):
        return f"<abu.Equilibria: {len(self)} equilibria of {self.n_balls} balls at omega = {self.omega} rad/s>"


class MachineEquilibria(Result):
    """The states of a scene beyond the rigid rotor with a smooth law (abu.equilibria of a
    flexible shaft, LuGre or coulomb-set friction, an unround race, an anisotropic support,
    an unround race on an anisotropic support, coulomb-set balls on an unround race).

      route     which of these the scene is: 'shaft', 'lugre', 'set_valued', 'unround',
                'anisotropic', 'unround_anisotropic' (docs/cli.md, "Which command answers what")
      json      the CLI's `equilibria --format json` object of the same analysis, parsed
                (its keys and units as docs/cli.md documents them for that scene kind)
      table     the CLI's table output (also str(result))
      warnings  what the CLI prints on stderr
    """

    def __repr__(self):
        return f"<abu.MachineEquilibria: route {self.route}>"

    def __str__(self):
        return self.table


class Branch(Result):
    """One equilibrium branch of a continuation, points ordered along its arclength.

      family, pattern, member   of the start equilibrium (pattern '' for balanced); images:
                                n >= 3, equilibria this branch also stands for (permutations)
      start_parameter
      parameter     (P,) the continuation parameter at each point
      q             (P, 2) [m];  q_abs (P,) [m]
      beta          (P, n) [rad] wrapped to [0, 2 pi), as branch_NAME.csv
      beta_unwrapped (P, n) [rad] as followed along the branch (continuous)
      eigenvalues   (P, 2n+4) complex [1/s], rotating frame, sorted as in abu.Equilibria
      modes         (P, 8) complex, two balls: the eigenvalues in tracked order (column k is
                    the same mode all along, as branch_NAME.csv's re_k/im_k); None for n >= 3
      spectral_abscissa, stable, stability, n_unstable, n_structural_zero  per point
      residual      (P,) n >= 3: static residual per point; None for two balls
      label         (P,) 'EP' at the ends, '' elsewhere; point_family (P,) family per point
      stop          (start side, far side): 'end of range', 'max steps', 'step underflow', ...
      stop_detail   why, in words
      specials      the run's special points on this branch (a Table, see Continuation)
    """

    def __init__(self, data):
        for k in ("stability", "label", "point_family"):
            data[k] = _strings(data[k])
        data["stop"] = tuple(data["stop"])
        data["stop_detail"] = tuple(data["stop_detail"])
        super().__init__(data)

    def __len__(self):
        return len(self.parameter)

    def __repr__(self):
        name = f"{self.family} {self.pattern} {self.member}".replace("  ", " ")
        lo, hi = (float(self.parameter.min()), float(self.parameter.max())) if len(self) else (0.0, 0.0)
        return f"<abu.Branch {name}: {len(self)} points, parameter {lo:.6g} .. {hi:.6g}, {len(self.specials)} special points>"


class Continuation(Result):
    """A continuation run (abu.continue_branches), as the CLI's `continue` writes it.

      param, from_value, to_value, n_balls
      branches        list of Branch, in the CLI's order (branch k is row `branch` = k + 1)
      special_points  Table, one row per special point in special_NAME.csv's order:
                      branch (1-based), label ('LP' fold, 'BP' branch point, 'HB' Hopf,
                      'MX' a branch end that failed), parameter, family, pattern, member,
                      q (K, 2), beta (K, n) wrapped, q_abs, frequency (HB: omega_H [rad/s],
                      rotating frame; NaN otherwise), eigenvalue (the critical one, complex
                      [1/s]; NaN on MX), lyapunov (two balls, HB located: the first Lyapunov
                      coefficient, < 0 supercritical; NaN otherwise), converged (bool),
                      n_unstable_before, n_unstable_after, bracket_from, bracket_to, note
      envelope        n >= 3: the balanced set's stability envelope (dict: intervals with
                      from, to, stable, samples; samples; samples_with_hopf); None for two balls
      ok              False if a branch ended in a step underflow (the CLI's exit code 3)
      warnings        what the CLI prints on stderr about the branch ends
      stats, notes    counts of the run; notes (e.g. start equilibria already covered)
    """

    def __init__(self, data):
        specials = data["special_points"]
        for k in ("label", "family", "pattern", "note"):
            specials[k] = _strings(specials[k])
        data["special_points"] = Table(specials)
        branches = []
        for k, b in enumerate(data["branches"]):
            branch = Branch(b)
            branch.specials = data["special_points"].select(data["special_points"].branch == k + 1)
            branches.append(branch)
        data["branches"] = branches
        super().__init__(data)

    def __repr__(self):
        return (f"<abu.Continuation in {self.param} from {self.from_value} to {self.to_value}: "
                f"{len(self.branches)} branches, {len(self.special_points)} special points>")


class StabilityMap(Result):
    """A stability map over two parameters (abu.map), the CLI's `map` cells.

      x_name, y_name  the axes' symbols ('n' for the ball count); x (nx,), y (ny,) values
      Summary, 2-D arrays indexed [ix, iy] (the summary CSV's columns; use .T for
      matplotlib's pcolormesh(x, y, Z)):
        two balls:  balanced, together, opposite (how many of each family exist),
                    balanced_stable (1.0 / 0.0, NaN where no balanced state exists)
        n balls:    balls, capacity [kg m], U [kg m], balanced_exists, balanced_samples,
                    balanced_stable_fraction, normal_abscissa_max [1/s] (NaN without
                    samples), aligned, aligned_stable, best_pattern
        both:       n_stable, best_family ('' if nothing is stable), best_member (0 then),
                    best_q_abs [m] (NaN then), degenerate (bit flags), fallbacks
      equilibria  Table, one row per equilibrium per cell (the long CSV): ix, iy, balls,
                  family, pattern, member, stable, n_unstable, n_structural_zero,
                  spectral_abscissa [1/s], q_abs [m], beta (rows, max n) [rad] (NaN beyond
                  a cell's ball count), n_undecided (two balls: eigenvalues within their
                  error bound of the axis that neither the refined spectrum nor the
                  certified Routh count places; stable is then 0, n_unstable a lower bound)
      summary     the summary arrays as a dict
    """

    def __init__(self, data):
        summary = data["summary"]
        shape = (len(data["x"]), len(data["y"]))
        for k in ("best_family", "best_pattern"):
            if k in summary:
                summary[k] = _strings(summary[k]).reshape(shape)
        rows = data["equilibria"]
        for k in ("family", "pattern"):
            rows[k] = _strings(rows[k])
        data["equilibria"] = Table(rows)
        data.update(summary)
        super().__init__(data)

    def __repr__(self):
        return f"<abu.StabilityMap {self.x_name} x {self.y_name}: {len(self.x)} x {len(self.y)} cells>"


class Simulation(Result):
    """A trajectory and what it ends in (abu.simulate), as the CLI's `simulate`.

      t (S,) [s], omega (S,) [rad/s] the spin speed at each sample
      state (S, 2n+4): q1, q2 [m], beta_1..beta_n [rad] (continuous), dq [m/s], dbeta [rad/s]
      q (S, 2), beta (S, n), q_abs (S,)   views of state
      x_end (2n+4,) the state at t_reached [s]
      status 'completed', 'interrupted' or 'failed' (then reason says where and why; the
             samples up to there are kept, as the CLI keeps them)
      method the integrator used; spectral_radius [1/s], stiffness_ratio, displacement_scale [m]
      start_below_resolution  start components below 1e-3 of their absolute tolerance,
             integrated as 0 (a start such as a 1e-200 perturbation is the equilibrium itself)
      summary: Result with outcome ('balanced', 'aligned', 'stuck', 'periodic', 'not settled';
             on an unround race 'equilibrium' with unround_equilibrium {member, q_abs,
             distance}, with an anisotropic support too 'orbit' with periodic_orbit {member,
             q_abs_max, distance}: model.md §15.7, §20.8),
             pattern, note, t_end, state_end, max_q_abs [m], t_max_q_abs [s], settle_time [s]
             (None unless settled), window_from, stalled, stalled_balls (1-based),
             ball_speed_fixed [rad/s], omega_mean_window, omega_n, t_omega_n,
             max_q_abs_run_up (None at constant speed), speed_changing_at_end
      speed  the speed profile in words; stats: integrator counts; text: the CLI's summary
    """

    def __init__(self, data):
        data["summary"] = Result(data["summary"])
        super().__init__(data)

    @property
    def q(self):
        """(S, 2) rotor centre [m], rotating frame."""
        return self.state[:, :2]

    @property
    def beta(self):
        """(S, n) ball angles [rad], continuous."""
        return self.state[:, 2:2 + self.n_balls]

    @property
    def q_abs(self):
        """(S,) |q| [m]."""
        return _np.hypot(self.state[:, 0], self.state[:, 1])

    def __str__(self):
        return self.text

    def __repr__(self):
        return (f"<abu.Simulation {self.speed}: {len(self.t)} samples to t = {self.t_reached} s, "
                f"{self.status}, outcome {self.summary.outcome}>")


# ---------------------------------------------------------------------------------------
# Computations

def equilibria(scene, samples_per_sheet=64):
    """Every real equilibrium of SCENE with its spectrum: the CLI's `equilibria`.

    samples_per_sheet: n >= 3 balls, samples per sheet of the balanced set (the CLI's
    --set-samples; 1..100000). Returns an abu.Equilibria (arrays; see its doc). Runs with
    the GIL released. A scene with a flexible shaft, LuGre or coulomb-set friction, an unround
    race or an anisotropic support (alone or composed as the CLI takes them) gives an
    abu.MachineEquilibria: the CLI's JSON object of the same analysis.
    """
    data = _abu.equilibria(scene, int(samples_per_sheet))
    if data.get("kind") == "machine":
        del data["kind"]
        return MachineEquilibria(data)
    return Equilibria(data)


def continue_branches(scene, param, to, *, family=None, state=None, ds=0.01, ds_min=1e-9, ds_max=0.2,
                      max_steps=5000, samples_per_sheet=64):
    """Pseudo-arclength continuation of every equilibrium branch: the CLI's `continue`.

    Follows the branches from the scene's value of PARAM (a model.md symbol: omega, U, mu,
    m2, ...) to TO, in both directions through folds, with the eigenvalues tracked and the
    special points (LP, BP, HB with omega_H and the first Lyapunov coefficient) located.
    family ('balanced', 'together', 'opposite') or state ((q1, q2, beta1, beta2), SI) start
    from one family or a given configuration (two balls only, as the CLI's
    --from-equilibrium / --from-state). ds, ds_min, ds_max, max_steps: the step control
    (scaled arclength, the interval is 1), the CLI's defaults. n >= 3 balls: every aligned
    equilibrium and every balanced sample (samples_per_sheet) is continued, with the
    balanced set's Hopf envelope. Returns an abu.Continuation. A branch that ends in a step
    underflow does not raise: run.ok is False and run.warnings says where (the CLI exits 3).
    Runs with the GIL released.
    """
    if state is not None:
        state = [float(v) for v in state]
    return Continuation(_abu.continue_branches(scene, str(param), float(to), family, state, float(ds),
                                               float(ds_min), float(ds_max), int(max_steps),
                                               int(samples_per_sheet)))


class OrbitBranches(Result):
    """Branches of periodic orbits (abu.continue_orbits), as the CLI's `continue` writes them on an
    unround race with an anisotropic support (docs/model.md §20.9).

      param, unit, from_value, to_value   the parameter and the interval (from: the scene's value)
      orbits_at_start, orbits_at_end      the orbits `equilibria` finds at each end
      branches        list of Table, in the CLI's order (branch k is row `branch` = k + 1 of
                      branch_NAME.csv), one row per point: value, orbit (its start orbit's name),
                      stability ('stable', 'unstable', 'marginal'), rho_abs_max, q_abs_max,
                      q_abs_min [m], band, multipliers (K, 2n + 4) complex over pi/omega (rotating
                      frame), state0 (K, 2n + 4) x(0) in SI; and as attributes start, end_forward,
                      end_backward, ok, reason
      special_points  Table: branch (1-based), kind ('LP', 'BP', 'PD', 'NS'), value, q_abs_max,
                      multiplier (the critical one, complex)
      ok, reason      False with where and why if a branch ended early or an orbit at an end ends
                      no branch or two (the CLI's exit code 3)
    """

    def __init__(self, data):
        branches = []
        for b in data["branches"]:
            rows = {k: b[k] for k in ("value", "rho_abs_max", "q_abs_max", "q_abs_min", "band", "multipliers",
                                      "state0")}
            rows["orbit"] = _strings(b["orbit"])
            rows["stability"] = _strings(b["stability"])
            table = Table(rows)
            for k in ("start", "end_forward", "end_backward", "ok", "reason"):
                setattr(table, k, b[k])
            branches.append(table)
        data["branches"] = branches
        specials = data["special_points"]
        specials["kind"] = _strings(specials["kind"])
        data["special_points"] = Table(specials)
        super().__init__(data)


def continue_orbits(scene, param, to, *, ds=0.01, ds_min=1e-9, ds_max=0.2, max_steps=5000, threads=1):
    """Pseudo-arclength continuation of every periodic orbit of an unround race on an anisotropic
    support: the CLI's `continue` on that machine (docs/model.md §20.9).

    Follows each orbit `equilibria` finds at the scene's value of PARAM (omega, U, a ball's
    parameter, kappa, or 'unroundness', the race's amplitudes times a factor from 1; not k, c or
    the ball count) to TO through its folds, with the fold (LP), branch (BP), flip (PD) and
    Neimark-Sacker (NS) points located; then the orbits at TO that no branch reached. ds, ds_min,
    ds_max (capped at 0.05), max_steps: the step control, the CLI's defaults; threads: the orbits
    of one end traced at once (the same result on any count). Returns an abu.OrbitBranches. Runs
    with the GIL released.
    """
    return OrbitBranches(_abu.continue_orbits(scene, str(param), float(to), float(ds), float(ds_min), float(ds_max),
                                              int(max_steps), int(threads)))


def _axis_spec(axis, name):
    if isinstance(axis, str):
        return axis
    axis = list(axis)
    if len(axis) not in (4, 5):
        raise _input_error(name, 0, "", "an axis is (NAME, FROM, TO, N) or (NAME, FROM, TO, N, 'log'), "
                                        "or the CLI's 'NAME:FROM:TO:N[:log]'")
    parts = [str(axis[0])]
    for v in axis[1:3]:
        parts.append(str(v) if isinstance(v, (_numbers.Integral, str)) else _abu.format_number(float(v)))
    parts.append(str(axis[3]))
    if len(axis) == 5:
        parts.append(str(axis[4]))
    return ":".join(parts)


def map(scene, x, y, *, method="fast", threads=None, samples_per_sheet=64):  # noqa: A001 (the CLI's name)
    """A stability map over two parameters: the cells of the CLI's `map`.

    x, y: axes (NAME, FROM, TO, N) or (NAME, FROM, TO, N, 'log'), or the CLI's strings
    'NAME:FROM:TO:N[:log]'; ('n', 2, 12, 11) is the ball count of a [balls] ring scene.
    method: 'fast' (characteristic polynomial, full eigenvalues near the boundary) or
    'full'. threads: worker threads (default: every core); the cells do not depend on it.
    Returns an abu.StabilityMap of 2-D arrays [ix, iy]. The fold/Hopf boundary curves and
    the charts of the CLI are not computed. Runs with the GIL released; Ctrl-C stops it
    after the tiles in progress (KeyboardInterrupt).
    """
    if threads is None:
        threads = _os.cpu_count() or 1
    return StabilityMap(_abu.map(scene, _axis_spec(x, "x"), _axis_spec(y, "y"), str(method),
                                 int(samples_per_sheet), int(threads)))


def simulate(scene, t_end=1.0, *, balls=None, state=None, from_equilibrium=None, perturb=None, ramp=None,
             speed_profile=None, method="auto", rtol=1e-7, every=0.0, max_steps=200_000_000, settle_tol=1e-3):
    """Integrates the equations of motion: the CLI's `simulate`.

    One start: balls (angles [rad] of balls at rest in the rotor frame, rotor at rest), state
    (the 2n + 4 values q1, q2, beta.., dq1, dq2, dbeta..) or from_equilibrium ('balanced[:K]',
    'together[:K]', 'opposite[:K]', 'aligned:PATTERN[:K]', displaced along its rightmost
    eigenmode by perturb, default 1e-3 scaled). Speed: the scene's omega, or ramp =
    (omega0, omega1, alpha) [rad/s, rad/s, rad/s^2], or speed_profile = [(t, omega), ...]
    piecewise linear. method: 'auto', 'bdf', 'rk8pd', 'rk4imp', 'bsimp', 'rkf45'; rtol,
    every (output interval [s], 0: t_end / 2000), max_steps and settle_tol as the CLI's
    options. Returns an abu.Simulation; a failed integration is status 'failed' with the
    reason (samples kept), not an exception. Runs with the GIL released; Ctrl-C stops it.
    """
    if balls is not None:
        balls = [float(b) for b in balls]
    if state is not None:
        state = [float(v) for v in state]
    if ramp is not None:
        ramp = [float(v) for v in ramp]
    if speed_profile is not None:
        speed_profile = [(float(t), float(w)) for t, w in speed_profile]
    return Simulation(_abu.simulate(scene, float(t_end), balls, state, from_equilibrium,
                                    None if perturb is None else float(perturb), ramp, speed_profile, str(method),
                                    float(rtol), float(every), int(max_steps), float(settle_tol)))
