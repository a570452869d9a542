"""abu.map against the CLI's `map` (summary and long CSV).

No tolerance: the same cell analyzers on the same tiles (the cells do not depend on the
thread count), every double compared with its shortest round-trip decimal in the CSV.
"""
import numpy as np

import abu
from conftest import read_csv, number, same


def test_two_ball_map_equals_cli(run_cli, default_scene, tmp_path):
    run_cli("map", default_scene, "--long", "--x", "omega:50:2000:20", "--y", "mu:1e-4:0.1:7:log", "--threads", "2",
            "--no-chart", "--no-boundaries", "--quiet", "-o", tmp_path)
    m = abu.map(abu.load_scene(default_scene), x=("omega", 50, 2000, 20), y=("mu", 1e-4, 0.1, 7, "log"), threads=2)
    assert (m.x_name, m.y_name) == ("omega", "mu") and m.n_stable.shape == (20, 7)
    summary = read_csv(tmp_path / "summary_omega_mu.csv")
    assert len(summary) == 20 * 7
    for row in summary:
        ix, iy = int(row["ix"]), int(row["iy"])
        assert same(m.x[ix], number(row["omega"])) and same(m.y[iy], number(row["mu"]))
        for k in ("balanced", "together", "opposite", "n_stable", "degenerate"):
            assert m.summary[k][ix, iy] == int(row[k]), k
        assert same(m.balanced_stable[ix, iy], number(row["balanced_stable"]))
        assert m.best_family[ix, iy] == row["best_family"]
        assert m.best_member[ix, iy] == (int(row["best_member"]) if row["best_member"] else 0)
        assert same(m.best_q_abs[ix, iy], number(row["best_q_abs"]))
    rows = read_csv(tmp_path / "map_omega_mu.csv")
    t = m.equilibria
    assert len(t) == len(rows)
    for i, row in enumerate(rows):
        assert (t.ix[i], t.iy[i], t.family[i], t.member[i]) == (int(row["ix"]), int(row["iy"]), row["family"],
                                                                int(row["member"]))
        assert int(t.stable[i]) == int(row["stable"]) and t.n_unstable[i] == int(row["n_unstable"])
        assert same(t.spectral_abscissa[i], number(row["spectral_abscissa"]))
        assert same(t.q_abs[i], number(row["q_abs"]))
        assert same(t.beta[i, 0], number(row["beta1"])) and same(t.beta[i, 1], number(row["beta2"]))
        assert t.n_undecided[i] == int(row["n_undecided"])
    # Something happens on this map: stable and unstable cells both.
    assert m.n_stable.max() > 0 and (m.balanced_stable == 0).any()


def test_thread_count_does_not_change_the_map(default_scene):
    scene = abu.load_scene(default_scene)
    one = abu.map(scene, x="omega:100:1500:17", y="c:0.5:5:5", threads=1)
    three = abu.map(scene, x="omega:100:1500:17", y="c:0.5:5:5", threads=3)
    for k, v in one.summary.items():
        assert np.array_equal(v, three.summary[k], equal_nan=v.dtype.kind == "f"), k


def test_ball_count_axis_equals_cli(run_cli, source, tmp_path):
    ring = source / "data" / "scenes" / "ring11.toml"
    run_cli("map", ring, "--long", "--x", "omega:150:1500:3", "--y", "n:2:4:3", "--set-samples", "8", "--threads", "2",
            "--no-chart", "--no-boundaries", "--quiet", "-o", tmp_path)
    m = abu.map(abu.load_scene(ring), x=("omega", 150, 1500, 3), y=("n", 2, 4, 3), samples_per_sheet=8, threads=2)
    for row in read_csv(tmp_path / "summary_omega_n.csv"):
        ix, iy = int(row["ix"]), int(row["iy"])
        assert m.balls[ix, iy] == int(row["balls"]) == 2 + iy
        for k in ("balanced_samples", "aligned", "aligned_stable", "n_stable", "degenerate"):
            assert m.summary[k][ix, iy] == int(row[k]), k
        for k in ("capacity", "U", "balanced_stable_fraction", "normal_abscissa_max", "best_q_abs"):
            assert same(m.summary[k][ix, iy], number(row[k])), k
        assert (m.best_family[ix, iy], m.best_pattern[ix, iy]) == (row["best_family"], row["best_pattern"])


def test_bad_axis_raises_cli_message(run_cli, default_scene):
    p = run_cli("map", default_scene, "--x", "omega:50:2000:0", "--y", "mu:1e-4:0.1:3", "--quiet", check=False)
    assert p.returncode == 2
    try:
        abu.map(abu.load_scene(default_scene), x=("omega", 50, 2000, 0), y=("mu", 1e-4, 0.1, 3))
    except abu.InputError as e:
        assert p.stderr.startswith(f"stability-scan: error: {e}")
    else:
        raise AssertionError("a 0-count axis was accepted")


def test_undecided_rows_equal_cli(run_cli, default_scene, tmp_path):
    # kappa = 4e13 through resonance: the full method leaves 2 of 34,417 rows undecided
    # (tests/map/check_map_kappa.sh); the module says the same rows, and calls none stable.
    args = ("--x", "omega:50:3000:80", "--y", "mu:1e-4:0.1:72:log", "--set", "kappa=4e13")
    run_cli("map", default_scene, *args, "--method", "full", "--long", "--threads", "2", "--no-chart",
            "--no-boundaries", "--quiet", "-o", tmp_path)
    scene = abu.load_scene(default_scene, ["kappa=4e13"])
    t = abu.map(scene, x="omega:50:3000:80", y="mu:1e-4:0.1:72:log", method="full", threads=2).equilibria
    rows = read_csv(tmp_path / "map_omega_mu.csv")
    undecided = [(int(r["ix"]), int(r["iy"]), r["family"], int(r["member"])) for r in rows if int(r["n_undecided"])]
    mine = [(t.ix[i], t.iy[i], t.family[i], t.member[i]) for i in range(len(t)) if t.n_undecided[i]]
    assert mine == undecided and 0 < len(mine) <= len(rows) // 1000
    assert not any(t.stable[i] for i in range(len(t)) if t.n_undecided[i])
