"""abu.continue_branches against the CLI's `continue` (special_NAME.csv, branch_NAME.csv).

No tolerance, as for the equilibria (test_equilibria.py): the same library call on the
same doubles; the CSVs hold shortest round-trip decimals of the very doubles compared.
"""
import math

import numpy as np

import abu
from conftest import read_csv, number, same


def compare_specials(run, rows):
    sp = run.special_points
    n = run.n_balls
    assert len(sp) == len(rows)
    for i, row in enumerate(rows):
        assert sp.branch[i] == int(row["branch"]) and sp.label[i] == row["label"]
        assert same(sp.parameter[i], number(row[run.param]))
        assert same(sp.q[i, 0], number(row["q1"])) and same(sp.q[i, 1], number(row["q2"]))
        for b in range(n):
            assert same(sp.beta[i, b], number(row[f"beta{b + 1}"]))
        assert same(sp.frequency[i], number(row["frequency"]))
        if row["label"] != "MX":
            assert same(sp.eigenvalue[i].real, number(row["re"])) and same(sp.eigenvalue[i].imag, number(row["im"]))
            assert int(sp.converged[i]) == int(row["converged"])
        if "lyapunov" in row:
            assert same(sp.lyapunov[i], number(row["lyapunov"]))
        assert sp.n_unstable_before[i] == int(row["n_unstable_before"])
        assert sp.n_unstable_after[i] == int(row["n_unstable_after"])


def test_default_scene_hopf_point_equals_cli(run_cli, default_scene, tmp_path):
    run_cli("continue", default_scene, "--set", "omega=50", "--param", "omega", "--to", "2000", "-o", tmp_path,
            "--no-chart")
    scene = abu.load_scene(default_scene).set("omega", 50)
    run = abu.continue_branches(scene, "omega", 2000)
    assert run.ok and run.param == "omega"
    rows = read_csv(tmp_path / "special_omega.csv")
    compare_specials(run, rows)
    # The Hopf point of the balanced branches: located, with omega_H and l1, near omega_n.
    hb = run.special_points.select(run.special_points.label == "HB")
    assert len(hb) >= 1 and hb.converged.all()
    omega_n = math.sqrt(7500.0 / (0.12 + 2 * 3.3e-5))
    assert np.all(np.abs(hb.parameter / omega_n - 1) < 0.1)
    assert np.all(hb.frequency > 0) and np.all(np.isfinite(hb.lyapunov))
    # Every branch point against branch_omega.csv: parameter, state, tracked eigenvalues.
    points = read_csv(tmp_path / "branch_omega.csv")
    assert sum(len(b) for b in run.branches) == len(points)
    i = 0
    for k, b in enumerate(run.branches):
        assert len(b.specials) == int(np.sum(run.special_points.branch == k + 1))
        for j in range(len(b)):
            row = points[i]
            i += 1
            assert int(row["branch"]) == k + 1 and int(row["point"]) == j and b.label[j] == row["label"]
            assert same(b.parameter[j], number(row["omega"]))
            assert same(b.beta[j, 0], number(row["beta1"])) and same(b.beta[j, 1], number(row["beta2"]))
            assert int(b.stable[j]) == int(row["stable"]) and b.point_family[j] == row["family"]
            for m in range(8):
                assert same(b.modes[j, m].real, number(row[f"re{m + 1}"]))
                assert same(b.modes[j, m].imag, number(row[f"im{m + 1}"]))


def test_three_balls_equal_cli(run_cli, source, tmp_path):
    scene_path = source / "tests" / "scenes" / "continuation_n" / "ring3_coulomb.toml"
    run_cli("continue", scene_path, "--param", "omega", "--to", "400", "--set-samples", "4", "-o", tmp_path,
            "--no-chart")
    run = abu.continue_branches(abu.load_scene(scene_path), "omega", 400, samples_per_sheet=4)
    assert run.n_balls == 3 and run.envelope is not None
    compare_specials(run, read_csv(tmp_path / "special_omega.csv"))
    points = read_csv(tmp_path / "branch_omega.csv")
    assert sum(len(b) for b in run.branches) == len(points)
    flat = np.concatenate([b.parameter for b in run.branches])
    assert all(same(a, number(r["omega"])) for a, r in zip(flat, points))


def test_bad_continuation_parameter(default_scene):
    scene = abu.load_scene(default_scene)
    for param, to, key in [("r", 1e-3, "r"), ("foo", 1.0, "foo"), ("omega", 900, "omega"), ("omega", -5, "omega")]:
        try:
            abu.continue_branches(scene, param, to)
        except abu.InputError as e:
            assert e.key == key
        else:
            raise AssertionError(f"{param} -> {to} accepted")


def test_one_family_equals_cli_from_equilibrium(run_cli, default_scene, tmp_path):
    run_cli("continue", default_scene, "--param", "omega", "--to", "200", "--from-equilibrium", "balanced", "-o",
            tmp_path, "--no-chart")
    run = abu.continue_branches(abu.load_scene(default_scene), "omega", 200, family="balanced")
    assert {b.family for b in run.branches} == {"balanced"}
    compare_specials(run, read_csv(tmp_path / "special_omega.csv"))
    points = read_csv(tmp_path / "branch_omega.csv")
    flat = np.concatenate([b.q_abs for b in run.branches])
    assert len(flat) == len(points) and all(same(a, number(r["q_abs"])) for a, r in zip(flat, points))


def test_start_selection_is_two_ball_only(source):
    ring3 = abu.load_scene(source / "tests" / "scenes" / "continuation_n" / "ring3_coulomb.toml")
    try:
        abu.continue_branches(ring3, "omega", 400, family="balanced")
    except abu.NotSupportedError as e:
        assert "3 balls" in str(e)
    else:
        raise AssertionError("a start family was accepted for 3 balls")
