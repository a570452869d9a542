"""abu.equilibria against the CLI's `equilibria` (CSV and JSON).

Tolerance: none. The module and the CLI call the same library functions (analyze) on the
same doubles, linked from the same objects; the CSV prints each double in its shortest
round-trip form, which float() reads back to the very same double. So every q, beta,
residual, abscissa and eigenvalue must be equal bit for bit; a difference means the two
paths do not compute the same thing (a different scene, option or code path).
"""
import concurrent.futures
import json

import numpy as np
import pytest

import abu
from conftest import read_csv, number, same


def compare_with_csv(eq, rows):
    n = eq.n_balls
    assert len(eq) == len(rows)
    for i, row in enumerate(rows):
        assert eq.family[i] == row["family"]
        assert eq.pattern[i] == row["pattern"]
        assert eq.member[i] == int(row["member"])
        assert same(eq.q[i, 0], number(row["q1"])) and same(eq.q[i, 1], number(row["q2"]))
        for b in range(n):
            assert same(eq.beta[i, b], number(row[f"beta{b + 1}"]))
        assert same(eq.residual[i], number(row["residual"]))
        assert same(eq.spectral_abscissa[i], number(row["spectral_abscissa"]))
        assert int(eq.stable[i]) == int(row["stable"])
        assert eq.n_structural_zero[i] == int(row["n_structural_zero"])
        for k in range(2 * n + 4):
            assert same(eq.eigenvalues[i, k].real, number(row[f"re{k + 1}"])), (i, k)
            assert same(eq.eigenvalues[i, k].imag, number(row[f"im{k + 1}"])), (i, k)


def test_default_scene_equals_cli_csv(run_cli, default_scene, tmp_path):
    run_cli("equilibria", default_scene, "--format", "csv", "-o", tmp_path / "eq.csv")
    eq = abu.equilibria(abu.load_scene(default_scene))
    assert list(eq.family) == ["balanced", "balanced", "together", "together", "opposite", "opposite"][:len(eq)]
    assert eq.eigenvalues.shape == (len(eq), 8) and eq.eigenvalues.dtype == np.complex128
    compare_with_csv(eq, read_csv(tmp_path / "eq.csv"))


def test_overrides_equal_cli_set(run_cli, default_scene, tmp_path):
    sets = ["omega=1200", "mu=0.01"]
    run_cli("equilibria", default_scene, "--format", "csv", "-o", tmp_path / "eq.csv", *sum((["--set", s] for s in sets), []))
    eq = abu.equilibria(abu.load_scene(default_scene, overrides=sets))
    compare_with_csv(eq, read_csv(tmp_path / "eq.csv"))
    # The same through Scene.set(name, value), with the value as a number.
    scene = abu.load_scene(default_scene).set("omega", 1200).set("mu", 0.01)
    compare_with_csv(abu.equilibria(scene), read_csv(tmp_path / "eq.csv"))


def test_error_estimates_and_condition_numbers_equal_cli_json(run_cli, default_scene):
    out = json.loads(run_cli("equilibria", default_scene, "--format", "json").stdout)
    eq = abu.equilibria(abu.load_scene(default_scene))
    assert len(out["equilibria"]) == len(eq)
    for i, e in enumerate(out["equilibria"]):
        assert eq.stability[i] == e["stability"]
        assert eq.n_unstable[i] == e["n_unstable"] and eq.n_marginal[i] == e["n_marginal"]
        assert bool(eq.converged[i]) == e["converged"] and eq.newton_iterations[i] == e["newton_iterations"]
        assert bool(eq.ill_conditioned[i]) == e["ill_conditioned"]
        assert eq.status[i] == "converged" and eq.reason[i] == ""
        for k, lam in enumerate(e["eigenvalues"]):
            assert same(eq.error[i, k], lam["error"])
            assert same(eq.condition[i, k], float("nan") if lam["condition"] is None else lam["condition"])
            assert bool(eq.structural[i, k]) == lam["structural"]


@pytest.mark.parametrize("name", ["n3_unequal_coulomb_k1e3", "n4_unequal_stribeck"])
def test_n_balls_equal_cli_csv(run_cli, source, tmp_path, name):
    scene = source / "tests" / "scenes" / "reference_n" / f"{name}.toml"
    run_cli("equilibria", scene, "--format", "csv", "-o", tmp_path / "eq.csv", "--set-samples", "16")
    eq = abu.equilibria(abu.load_scene(scene), samples_per_sheet=16)
    assert eq.n_balls == int(name[1])
    assert eq.balanced_set is not None and eq.balanced_set["dimension"] == eq.n_balls - 2
    compare_with_csv(eq, read_csv(tmp_path / "eq.csv"))


def test_table_is_the_cli_table(run_cli, default_scene):
    eq = abu.equilibria(abu.load_scene(default_scene))
    assert str(eq) == run_cli("equilibria", default_scene).stdout


def test_state_rows_are_equilibria_at_rest(default_scene):
    eq = abu.equilibria(abu.load_scene(default_scene))
    assert eq.state.shape == (len(eq), 8)
    assert np.array_equal(eq.state[:, :2], eq.q) and np.array_equal(eq.state[:, 2:4], eq.beta)
    assert not eq.state[:, 4:].any()


def test_threads_give_the_serial_numbers(default_scene):
    """The GIL is released during the computation: concurrent calls must not interfere."""
    scenes = [abu.load_scene(default_scene).set("omega", w) for w in (300, 600, 900, 1200)]
    serial = [abu.equilibria(s).eigenvalues for s in scenes]
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        parallel = list(pool.map(lambda s: abu.equilibria(s).eigenvalues, scenes))
    for a, b in zip(serial, parallel):
        assert np.array_equal(a, b)
