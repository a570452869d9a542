#!/usr/bin/python3
"""The periodic orbits of `equilibria --format json` on an anisotropic two-ball scene with
EQUAL balls (docs/model.md §10.14): one object per aligned equilibrium of the mean system,
all found, 8 multipliers each sorted by modulus, and the two "opposite" orbits each other's
mirror (the balls swapped: an exact symmetry of the equations), so |q| and the multipliers
agree to 1e-9 relative (two separate continuations, each accurate to ~1e-10).

Usage: check_forced_orbits_json.py BINARY SCENE
"""
import json
import subprocess
import sys

out = subprocess.run([sys.argv[1], "equilibria", sys.argv[2], "--format", "json"], check=True,
                     capture_output=True, text=True).stdout
d = json.loads(out)
orbits = d["periodic_orbits"]
assert d["aligned_equilibria"] == len(orbits) == d["periodic_orbits_found"] == 4, (d["aligned_equilibria"], len(orbits))
for o in orbits:
    assert o["status"] == "converged", o
    mods = [abs(complex(*m)) for m in o["floquet_multipliers"]]
    assert len(mods) == 8 and mods == sorted(mods, reverse=True), mods
    assert o["q_abs_max"] >= o["q_abs_mean"] > 0, o
    assert o["periodicity"] < 1e-9, o["periodicity"]
opp = [o for o in orbits if o["kind"].startswith("opposite")]
assert len(opp) == 2
a, b = opp
assert abs(a["q_abs_max"] - b["q_abs_max"]) <= 1e-9 * a["q_abs_max"]
for ma, mb in zip(a["floquet_multipliers"], b["floquet_multipliers"]):
    za, zb = complex(*ma), complex(*mb)
    assert abs(za - zb) <= 1e-9 * abs(za), (za, zb)
print("ok: 4 orbits, mirror pair agrees")
