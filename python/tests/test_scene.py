"""Scenes from files and dicts, --set-style overrides, and input errors: the CLI's parser,
rules and messages."""
import pathlib
import re
import tomllib

import numpy as np
import pytest

import abu


def equal_results(a, b):
    for k, v in a.as_dict().items():
        if isinstance(v, np.ndarray):
            assert np.array_equal(v, b.as_dict()[k], equal_nan=v.dtype.kind in "fc"), k


def test_exceptions_are_python_ones():
    assert issubclass(abu.InputError, ValueError)
    assert issubclass(abu.NumericalError, RuntimeError)
    assert issubclass(abu.NotSupportedError, NotImplementedError)


@pytest.mark.parametrize("name", ["default", "ring11", "engineer"])
def test_scene_from_dict_equals_scene_from_file(source, name):
    path = source / "data" / "scenes" / f"{name}.toml"
    with open(path, "rb") as f:
        data = tomllib.load(f)
    from_file, from_dict = abu.load_scene(path), abu.scene_from_dict(data)
    assert from_dict.file == "<dict>"
    assert from_dict.n_balls == from_file.n_balls and from_dict.is_ring == from_file.is_ring
    assert from_dict.describe() == from_file.describe()
    if name != "ring11":  # engineer: diameter, f, surface_radius pass through the dict (model.md §1.1)
        equal_results(abu.equilibria(from_file), abu.equilibria(from_dict))
    else:  # 11 balls: the ring kept, the ball count changed the same way on both
        equal_results(abu.equilibria(from_file.set_ball_count(3), samples_per_sheet=8),
                      abu.equilibria(from_dict.set_ball_count(3), samples_per_sheet=8))


def test_invalid_dict_names_dict_line_and_key(default_scene):
    with open(default_scene, "rb") as f:
        data = tomllib.load(f)
    data["rotor"]["mass"] = -0.12
    with pytest.raises(abu.InputError) as info:
        abu.scene_from_dict(data)
    e = info.value
    text = abu.scene_toml(data).splitlines()
    assert (e.file, e.key) == ("<dict>", "rotor.mass")
    assert text[e.line - 1] == "mass = -0.12"  # the line of scene_toml(data) that holds it
    assert str(e) == f"<dict>:{e.line}: key 'rotor.mass': {e.rule}"


def test_dict_keeps_integer_and_float_apart(source):
    with open(source / "data" / "scenes" / "ring11.toml", "rb") as f:
        data = tomllib.load(f)
    data["balls"]["count"] = 11.0  # a float is not a ball count, as in a file
    with pytest.raises(abu.InputError) as info:
        abu.scene_from_dict(data)
    assert info.value.key == "balls.count"
    with pytest.raises(abu.InputError):
        abu.scene_from_dict({"rotor": {"mass": None}})


def cli_message(run_cli, *args):
    p = run_cli(*args, check=False)
    assert p.returncode == 2, p.stderr
    prefix = "stability-scan: error: "
    assert p.stderr.startswith(prefix), p.stderr
    return p.stderr[len(prefix):].rstrip("\n")


def test_every_invalid_scene_raises_the_cli_message(run_cli, source):
    """tests/scenes/invalid: one defect each; the exception's text is the CLI's message
    and its parts are the file, line and key each scene's first line expects."""
    scenes = sorted((source / "tests" / "scenes" / "invalid").glob("*.toml"))
    assert len(scenes) >= 60
    for path in scenes:
        expect = dict(re.findall(r"(\w+)=(\S*)", path.read_text().splitlines()[0]))
        with pytest.raises(abu.InputError) as info:
            abu.load_scene(path)
        e = info.value
        assert str(e) == cli_message(run_cli, "equilibria", path, "--format", "csv"), path.name
        assert e.file == str(path) and e.line == int(expect["line"]) and e.key == expect.get("key", ""), path.name


def test_override_errors_are_the_cli_messages(run_cli, default_scene):
    for assignment in ["omega=-1", "foo=1", "mu3=0.1", "omega=abc", "omega", "d=0.1"]:
        scene = abu.load_scene(default_scene)
        with pytest.raises(abu.InputError) as info:
            scene.set(assignment)
        assert str(info.value) == cli_message(run_cli, "equilibria", default_scene, "--set", assignment)
        assert info.value.file == "--set"
        assert scene.get("omega") == 900  # unchanged


def test_set_by_name_and_value(default_scene):
    scene = abu.load_scene(default_scene)
    assert scene.set("omega", 1234.5) is scene
    assert scene.get("omega") == 1234.5 == scene.omega
    scene.set("m2", 4e-5)
    assert scene.get("m2") == 4e-5 and scene.get("m1") == 3.3e-5
    with pytest.raises(abu.InputError) as info:
        scene.set("omega", 0.0)
    assert info.value.key == "omega"
    copy = scene.copy()
    copy.set("omega", 100)
    assert scene.omega == 1234.5


def test_unreadable_file(tmp_path):
    with pytest.raises(abu.InputError) as info:
        abu.load_scene(tmp_path / "missing.toml")
    assert info.value.line == 0 and "cannot read file" in str(info.value)


RING_WITH_OVERRIDES = """\
[rotor]
mass = 0.12
stiffness = 7500
damping = 2.0
unbalance = 6.0e-7

[balls]
count = 4
total_mass = 1.32e-4
race_radius = 0.018
radius = 1.0e-3
mu = 0.003

[[balls.override]]
ball = 2
mass = 4.0e-5

[[balls.override]]
ball = 4
race_radius = 0.02
rolling = false

[friction]
law = "coulomb"
mu = 0.002
kappa = 1.0e3

[speed]
omega = 700
"""


def test_ring_with_overrides_from_dict_equals_file(tmp_path):
    path = tmp_path / "ring.toml"
    path.write_text(RING_WITH_OVERRIDES)
    from_file = abu.load_scene(path)
    from_dict = abu.scene_from_dict(tomllib.loads(RING_WITH_OVERRIDES))
    assert from_file.n_balls == from_dict.n_balls == 4
    assert from_dict.describe() == from_file.describe()
    assert "[[balls.override]]" in abu.scene_toml(tomllib.loads(RING_WITH_OVERRIDES))
    equal_results(abu.equilibria(from_file, samples_per_sheet=4), abu.equilibria(from_dict, samples_per_sheet=4))
    # A rule broken inside an override is reported at its key, as for a file.
    data = tomllib.loads(RING_WITH_OVERRIDES)
    data["balls"]["override"][1]["race_radius"] = 5e-4
    with pytest.raises(abu.InputError) as info:
        abu.scene_from_dict(data)
    assert info.value.key == "balls.override[2].race_radius"
