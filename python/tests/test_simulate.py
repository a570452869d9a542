"""abu.simulate against the CLI's `simulate` (simulation.csv and the --summary JSON).

No tolerance: the same integration (GSL odeiv2, same options, same start) on the same
doubles; the CSV's shortest round-trip decimals read back to the doubles compared.
"""
import json

import numpy as np
import pytest

import abu
from conftest import read_csv, number, same


def compare(sim, tmp_path, n):
    rows = read_csv(tmp_path / "simulation.csv")
    assert len(sim.t) == len(rows)
    for i in (0, len(rows) // 2, len(rows) - 1):
        row = rows[i]
        assert same(sim.t[i], number(row["t"])) and same(sim.omega[i], number(row["omega"]))
        names = ["q1", "q2"] + [f"beta{k + 1}" for k in range(n)] + ["dq1", "dq2"] + [f"dbeta{k + 1}" for k in range(n)]
        for k, name in enumerate(names):
            assert same(sim.state[i, k], number(row[name])), (i, name)
    assert np.array_equal(sim.state[-1], sim.x_end)
    cli = json.loads((tmp_path / "summary.json").read_text())
    s = sim.summary
    assert (sim.status, sim.method, s.outcome, s.pattern, s.stalled) == (
        cli["status"], cli["method"], cli["outcome"], cli["pattern"], cli["stalled"])
    assert list(s.stalled_balls) == cli["stalled_balls"]
    for k in ("t_end", "max_q_abs", "t_max_q_abs", "omega_n", "omega_mean_window", "window_from"):
        assert same(getattr(s, k), cli[k]), k
    for k in ("settle_time", "max_q_abs_run_up"):
        assert (getattr(s, k) is None and cli[k] is None) or same(getattr(s, k), cli[k]), k
    assert all(same(a, b) for a, b in zip(s.state_end, cli["state_end"])) and len(s.state_end) == 2 * n + 4
    assert all(same(a, b) for a, b in zip(s.ball_speed_fixed, cli["ball_speed_fixed"]))
    assert same(sim.stiffness_ratio, cli["stiffness_ratio"]) and same(sim.spectral_radius, cli["spectral_radius"])
    return cli


def test_constant_speed_end_state_equals_cli(run_cli, default_scene, tmp_path):
    run_cli("simulate", default_scene, "--t-end", "0.3", "--balls", "2,4", "-o", tmp_path, "--no-chart", "--quiet",
            "--summary", tmp_path / "summary.json")
    sim = abu.simulate(abu.load_scene(default_scene), 0.3, balls=[2, 4])
    assert sim.status == "completed" and sim.state.shape == (len(sim.t), 8)
    compare(sim, tmp_path, 2)
    assert sim.text.strip() != ""


def test_run_up_equals_cli(run_cli, default_scene, tmp_path):
    run_cli("simulate", default_scene, "--t-end", "0.3", "--ramp", "100:400:2000", "--balls", "1,5", "-o", tmp_path,
            "--no-chart", "--quiet", "--summary", tmp_path / "summary.json")
    sim = abu.simulate(abu.load_scene(default_scene), 0.3, balls=[1, 5], ramp=(100, 400, 2000))
    compare(sim, tmp_path, 2)
    assert sim.omega[0] == 100 and sim.omega[-1] == 400
    assert sim.summary.max_q_abs_run_up is not None


def test_three_balls_from_equilibrium_equals_cli(run_cli, source, tmp_path):
    scene = source / "tests" / "scenes" / "continuation_n" / "ring3_coulomb.toml"
    run_cli("simulate", scene, "--t-end", "0.05", "--from-equilibrium", "balanced:1", "-o", tmp_path, "--no-chart",
            "--quiet", "--summary", tmp_path / "summary.json")
    sim = abu.simulate(abu.load_scene(scene), 0.05, from_equilibrium="balanced:1")
    assert sim.n_balls == 3
    compare(sim, tmp_path, 3)


def test_bad_simulation_input(default_scene):
    scene = abu.load_scene(default_scene)
    with pytest.raises(abu.InputError):
        abu.simulate(scene, 0.1)  # no start
    with pytest.raises(abu.InputError):
        abu.simulate(scene, -1.0, balls=[0, 1])
    with pytest.raises(abu.InputError):
        abu.simulate(scene, 0.1, balls=[0, 1], ramp=(100, 400, -1))
