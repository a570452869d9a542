"""abu.continue_orbits: `continue` on an unround race with an anisotropic support (docs/model.md
§20.9) through the same library call as the CLI's: the same branches, points and special points
(the CSV's shortest round-trip doubles parse to the same values: no tolerance), and the same
refusals."""
import csv

import numpy as np
import pytest

import abu


def csv_rows(path):
    return list(csv.DictReader(line for line in open(path) if not line.startswith("#")))


def test_the_branches_are_the_clis(run_cli, source, tmp_path):
    scene_path = source / "tests" / "scenes" / "composed" / "oval_anisotropic.toml"
    # A short interval of the damping d: 8 flat branches, ~23 points each, both ends searched.
    run_cli("continue", scene_path, "--param", "d", "--to", "2.05e-3", "--threads", "2", "--no-chart", "-o", tmp_path)
    rows = csv_rows(tmp_path / "branch_d.csv")
    run = abu.continue_orbits(abu.load_scene(scene_path), "d", 2.05e-3, threads=2)
    assert run.ok and run.param == "d" and run.from_value == 2e-3 and run.to_value == 2.05e-3
    assert len(run.branches) == len({r["branch"] for r in rows})
    for k, b in enumerate(run.branches):
        mine = [r for r in rows if int(r["branch"]) == k + 1]
        assert len(b) == len(mine)
        assert b.start == float(mine[0]["start"])
        np.testing.assert_array_equal(b.value, [float(r["d"]) for r in mine])
        np.testing.assert_array_equal(b.q_abs_max, [float(r["q_abs_max"]) for r in mine])
        np.testing.assert_array_equal(b.rho_abs_max, [float(r["rho_abs_max"]) for r in mine])
        assert list(b.stability) == [r["stability"] for r in mine]
        np.testing.assert_array_equal(b.state0[:, 0], [float(r["x0_1"]) for r in mine])
    specials = csv_rows(tmp_path / "special_d.csv")
    assert len(run.special_points) == len(specials)


def test_the_refusals_are_the_clis(source):
    scene = abu.load_scene(source / "tests" / "scenes" / "composed" / "oval_anisotropic.toml")
    with pytest.raises(abu.InputError, match="anisotropic support's means"):
        abu.continue_orbits(scene, "k", 2e4)
    with pytest.raises(abu.InputError, match="must differ from the start value"):
        abu.continue_orbits(scene, "omega", scene.omega)
    with pytest.raises(abu.InputError, match="unroundness factor is >= 0"):
        abu.continue_orbits(scene, "unroundness", -1)
    with pytest.raises(abu.NotSupportedError, match="abu.continue_branches"):
        abu.continue_orbits(abu.load_scene(source / "data" / "scenes" / "default.toml"), "omega", 1000)
