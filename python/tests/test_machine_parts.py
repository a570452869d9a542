"""Scenes beyond the rigid rotor with a smooth law (a flexible shaft, LuGre, coulomb-set, an
unround race, an anisotropic support, and their compositions of docs/model.md §20):
abu.equilibria gives the CLI's `equilibria` analysis of each (its JSON object, its table),
and the module's other calls refuse what they do not model, with the CLI's reason, instead
of analysing the rigid rotor that is left when a part is dropped."""
import json

import pytest

import abu

# (scene, route): one of every route the CLI's `equilibria` takes beyond the rigid rotor.
MACHINES = [
    ("shaft/one_node.toml", "shaft"),
    ("lugre/three_balls.toml", "lugre"),
    ("stick/whole.toml", "set_valued"),
    ("anisotropic/base_viscous.toml", "anisotropic"),
    ("unround/oval_offset_viscous.toml", "unround"),
    ("composed/oval_anisotropic.toml", "unround_anisotropic"),
    ("composed/oval_coulomb_set.toml", "set_valued"),
    ("composed/shaft_coulomb_set.toml", "set_valued"),
    ("composed/shaft_runout.toml", "shaft"),
]


def without_command(obj):
    """The JSON object without the command line (the module has none to report)."""
    return {k: v for k, v in obj.items() if k != "command"}


@pytest.mark.parametrize("name,route", MACHINES)
def test_equilibria_is_the_cli_analysis(run_cli, source, name, route):
    scene_path = source / "tests" / "scenes" / name
    result = abu.equilibria(abu.load_scene(scene_path))
    assert isinstance(result, abu.MachineEquilibria) and result.route == route
    # The same report through the same writer: every number the CLI prints, bit for bit
    # (JSON's shortest round-trip doubles parse to the same values on both sides).
    cli_json = json.loads(run_cli("equilibria", scene_path, "--format", "json").stdout)
    assert without_command(result.json) == without_command(cli_json)
    cli_table = run_cli("equilibria", scene_path).stdout
    assert str(result) == cli_table


@pytest.mark.parametrize("name,route", MACHINES)
def test_other_calls_refuse_the_part_they_do_not_model(source, name, route):
    scene = abu.load_scene(source / "tests" / "scenes" / name)
    calls = {
        "continue_branches": lambda: abu.continue_branches(scene, "omega", scene.omega * 1.1, family="balanced"),
        "simulate": lambda: abu.simulate(scene, 0.01, balls=[0.0, 3.0] + [1.0] * (scene.n_balls - 2)),
        "map": lambda: abu.map(scene, x="omega:100:300:3", y="U:1e-6:2e-6:2"),
    }
    if route == "lugre":
        del calls["map"]  # the map of LuGre's z = 0 equilibria is the CLI's (below)
    if route in ("anisotropic", "unround", "unround_anisotropic"):
        del calls["simulate"]  # the rigid rotor's parts, integrated as the CLI's (below)
    for call, run in calls.items():
        # A shaft, a race, a support or a bristle state dropped would leave the rigid rotor's
        # answer to another question: each must be refused, naming the module's call.
        with pytest.raises((abu.NotSupportedError, abu.InputError)) as caught:
            run()
        assert f"abu.{call}" in str(caught.value), str(caught.value)


def test_lugre_map_is_the_cli_map(run_cli, source, tmp_path):
    scene_path = source / "tests" / "scenes" / "lugre" / "three_balls.toml"
    run_cli("map", scene_path, "--x", "omega:100:300:3", "--y", "U:1e-6:2e-6:2", "-o", tmp_path)
    rows = [line.split(",") for line in (tmp_path / "summary_omega_U.csv").read_text().splitlines()
            if not line.startswith("#")]
    header, rows = rows[0], rows[1:]
    stable = header.index("n_stable")
    m = abu.map(abu.load_scene(scene_path), x="omega:100:300:3", y="U:1e-6:2e-6:2")
    for row in rows:
        ix, iy = int(row[0]), int(row[1])
        assert m.n_stable[ix, iy] == int(row[stable])


@pytest.mark.parametrize("name,kind", [("anisotropic/base_viscous.toml", None),
                                       ("unround/oval_offset_viscous.toml", "unround_equilibrium"),
                                       ("composed/oval_anisotropic.toml", "periodic_orbit")])
def test_simulate_on_a_race_and_a_support_is_the_cli_run(run_cli, source, tmp_path, name, kind):
    # The same integration (the composed field of model.md §20) and the same naming of its end:
    # the race's equilibrium (§15.7) or, on an anisotropic support, its periodic orbit at the
    # end's spin angle (§20.8), by the one library call both use. The same doubles: no tolerance.
    scene_path = source / "tests" / "scenes" / name
    run_cli("simulate", scene_path, "--t-end", "20", "--balls", "1,2", "-o", tmp_path, "--no-chart", "--quiet",
            "--summary", tmp_path / "summary.json")
    cli = json.loads((tmp_path / "summary.json").read_text())
    sim = abu.simulate(abu.load_scene(scene_path), 20.0, balls=[1.0, 2.0])
    s = sim.summary
    assert (sim.status, s.outcome) == (cli["status"], cli["outcome"])
    assert list(s.state_end) == cli["state_end"]
    if kind is None:
        return
    assert s.outcome == ("equilibrium" if kind == "unround_equilibrium" else "orbit")
    assert getattr(s, kind) == cli[kind]
