"""One table of values outside the numerical range (docs/robustness.md "Numerical range",
include/abu/input/ranges.hpp), driven through the CLI and the Python module: both refuse
each one (the CLI with exit 2 and nothing written, the module with abu.InputError) with the
same rule, from the same library check — never a result computed from it (a speed of 1e155
rad/s called stable, rows that are no equilibria, a creep mode's sign flipped)."""
import re

import pytest

import abu

# (parameter, value, the words of the rule both must give)
BAD = [
    ("omega", 1e155, "omega / omega_n must lie in"),
    ("omega", 1e-200, "omega / omega_n must lie in"),
    ("U", 1e-22, "U must be 0 or >= 1e-12"),
    ("kappa", 1e200, "kappa omega_n"),
    ("c", 1e12, "the damping ratio"),
]


def rule_of(text):
    """The rule after "key 'NAME': " in a message (the origins differ: --set, abu.CALL)."""
    m = re.search(r"key '([^']+)': (.*)", text)
    assert m, text
    return m.group(1), m.group(2).strip()


@pytest.mark.parametrize("key,value,words", BAD)
def test_cli_and_module_refuse_the_same_values(run_cli, default_scene, tmp_path, key, value, words):
    p = run_cli("equilibria", default_scene, "--set", f"{key}={value!r}", "--format", "csv", "-o", tmp_path / "e.csv",
                check=False)
    assert p.returncode == 2 and not (tmp_path / "e.csv").exists(), p.stderr
    cli_key, cli_rule = rule_of(p.stderr)
    assert words in cli_rule
    calls = {
        "equilibria": lambda s: abu.equilibria(s),
        "simulate": lambda s: abu.simulate(s, 0.01, balls=[1.0, 2.0]),
        "continue_branches": lambda s: abu.continue_branches(s, "mu", 0.02, family="balanced"),
    }
    for call, run in calls.items():
        scene = abu.load_scene(default_scene)
        scene.set(key, value)
        with pytest.raises(abu.InputError) as caught:
            run(scene)
        text = str(caught.value)
        assert f"abu.{call}" in text, text
        assert rule_of(text) == (cli_key, cli_rule), (call, text, p.stderr)


@pytest.mark.parametrize("key,value,words", [b for b in BAD if b[0] in ("omega", "U", "kappa")])
def test_continuation_end_value_refused_by_both(run_cli, default_scene, tmp_path, key, value, words):
    # The end of a continuation (--to / to) is checked by the same library call (checked_param).
    p = run_cli("continue", default_scene, "--param", key, "--to", repr(value), "-o", tmp_path / "c", check=False)
    assert p.returncode == 2 and not (tmp_path / "c").exists(), p.stderr
    cli_key, cli_rule = rule_of(p.stderr)
    assert words in cli_rule
    with pytest.raises(abu.InputError) as caught:
        abu.continue_branches(abu.load_scene(default_scene), key, value, family="balanced")
    assert rule_of(str(caught.value)) == (cli_key, cli_rule)


def test_absent_family_refused_by_both(run_cli, default_scene, tmp_path):
    # U = 2e-6 is more than the balls' capacity 1.188e-6: no balanced state at either end.
    # `continue --from-equilibrium balanced` wrote empty branch files and exited 0; now both
    # front ends refuse it with the library's one rule (the families that do exist named).
    p = run_cli("continue", default_scene, "--set", "U=2e-6", "--set", "omega=100", "--param", "omega", "--to",
                "200", "--from-equilibrium", "balanced", "--no-chart", "-o", tmp_path / "c", check=False)
    assert p.returncode == 2 and not (tmp_path / "c").exists(), p.stderr
    cli_key, cli_rule = rule_of(p.stderr)
    assert cli_key == "balanced" and "no balanced equilibrium" in cli_rule and "together, opposite" in cli_rule
    scene = abu.load_scene(default_scene, ["U=2e-6", "omega=100"])
    with pytest.raises(abu.InputError) as caught:
        abu.continue_branches(scene, "omega", 200, family="balanced")
    assert rule_of(str(caught.value)) == (cli_key, cli_rule)
    # A family that exists is continued as before.
    assert len(abu.continue_branches(scene, "omega", 200, family="together").branches) > 0


def test_endless_scene_refused_by_both(run_cli, tmp_path):
    # /dev/zero was read without limit by both; the library's reader stops at 16 MiB.
    p = run_cli("equilibria", "/dev/zero", "--format", "csv", "-o", tmp_path / "e.csv", check=False)
    assert p.returncode == 2 and not (tmp_path / "e.csv").exists(), p.stderr
    with pytest.raises(abu.InputError) as caught:
        abu.load_scene("/dev/zero")
    assert "larger than 16 MiB" in str(caught.value) and str(caught.value) in p.stderr
