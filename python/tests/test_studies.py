"""abu.outcomes and abu.design (docs/model.md §21, §22) against the CLI's `outcomes` and `design`:
the same runs, the same statistics and recommendation, the same refusals."""
import csv
import io
import json
import subprocess

import pytest

import abu


def _rows(text):
    return list(csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")))


def test_outcomes_equal_the_cli(cli, source, tmp_path):
    scene = abu.load_scene(source / "data/scenes/default.toml")
    r = abu.outcomes(scene, ramp=(50, 900, 400), samples=12, uncertain=["mu=0.001:0.003"], threads=2)
    subprocess.run([cli, "outcomes", str(source / "data/scenes/default.toml"), "--ramp", "50:900:400", "--samples",
                    "12", "--uncertain", "mu=0.001:0.003", "-o", str(tmp_path), "--no-chart", "--quiet"], check=True)
    rows = _rows(open(tmp_path / "outcomes.csv").read())
    assert [float(x["residual_q"]) for x in rows] == list(r["residual_q"])  # bit for bit
    assert [x["outcome"] for x in rows] == r["outcome"]
    cli_json = json.load(open(tmp_path / "outcomes.json"))
    for key in ("residual_q", "ratio_bare", "below_limit", "stalled", "stuck_off_balance"):
        assert r["summary"][key] == cli_json[key]
    assert _rows(r["csv"]) == rows


def test_design_equals_the_cli(cli, source, tmp_path):
    scene = abu.load_scene(source / "data/scenes/default.toml")
    d = abu.design(scene, ["k=2000:12000:6"], objective="max:k", constraints=["stable=300:2000"])
    subprocess.run([cli, "design", str(source / "data/scenes/default.toml"), "--vary", "k=2000:12000:6", "--objective",
                    "max:k", "--constraint", "stable=300:2000", "-o", str(tmp_path), "--no-chart", "--quiet"],
                   check=True)
    c = json.load(open(tmp_path / "design.json"))
    assert d["recommended"] == c["recommended"]
    assert d["designs"][d["recommended"]]["values"] == c["designs"][c["recommended"]]["values"]
    assert d["binding"] == c["binding"]
    assert "recommended" in d["text"]


@pytest.mark.parametrize("call, words", [
    (lambda s: abu.outcomes(s, uncertain=["mu=0.003:0.001"]), "LOW <= HIGH"),
    (lambda s: abu.outcomes(s, samples=0), "at least one sample"),
    (lambda s: abu.design(s, ["k=5000:1000"]), "empty range"),
    (lambda s: abu.design(s, ["m=1e-5:3e-5"], constraints=["mass=1e-9"]), "no design of the box"),
    (lambda s: abu.design(s, ["mu=0.001:0.003"], uncertain=["mu=0.001:0.002"]), "both"),
])
def test_refusals_are_the_clis(source, call, words):
    scene = abu.load_scene(source / "data/scenes/default.toml")
    with pytest.raises(abu.InputError) as e:
        call(scene)
    assert words in str(e.value)
