"""`continue` on an unround race with an anisotropic support (docs/model.md §20.9), on the real
binary: the branches through the oval race's fold in its unroundness, every field finite, the
fold's critical multiplier +1, the end check, the chart; the options that do not apply and the
parameters the machine does not take refused with exit 2 and nothing written.

    python3 check_composed_continue.py BIN SRC
"""
import math
import os
import tempfile

from cli_checks import SRC, check, finish, rows_of, run

SCENE = os.path.join(SRC, "tests/scenes/composed/oval_anisotropic.toml")

with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "c")
    r = run("continue", SCENE, "--param", "unroundness", "--to", "1.38", "-o", out)
    check(f"exit 0 ({r.returncode}: {r.stderr[-300:]})", r.returncode == 0)
    rows = rows_of(os.path.join(out, "branch_unroundness.csv"))
    specials = rows_of(os.path.join(out, "special_unroundness.csv"))
    text = open(os.path.join(out, "branch_unroundness.csv")).read()
    check("no nan or inf in the branch rows", "nan" not in text.lower() and "inf" not in text.lower())
    check("the chart is written", os.path.getsize(os.path.join(out, "branch_unroundness.png")) > 10000)
    values = [float(row["unroundness"]) for row in rows]
    # The interval's ends bound every point (the edges located by the engine, to rounding).
    check("every point inside [1, 1.38]", all(1 - 1e-12 <= v <= 1.38 + 1e-12 for v in values))
    starts = {row["branch"]: float(row["start"]) for row in rows}
    ends = {}
    for row in rows:
        ends.setdefault(row["branch"], []).append(float(row["unroundness"]))
    # Each branch runs from one end to an end: 1 -> 1.38, or a fold's pair 1.38 -> 1.38.
    check("each branch starts and ends on an edge",
          all(min(abs(v[0] - 1), abs(v[0] - 1.38)) < 1e-12 and min(abs(v[-1] - 1), abs(v[-1] - 1.38)) < 1e-12
              for v in ends.values()))
    lp = [s for s in specials if s["kind"] == "LP"]
    check(f"one fold inside ({len(lp)})", len(lp) == 1 and 1.3 < float(lp[0]["unroundness"]) < 1.37)
    # Brent's bracket is 1e-10 of the chord, the multiplier linear along it: 1e-7 is wide.
    check("the fold's critical multiplier is +1 to 1e-7",
          all(abs(complex(float(s["mult_re"]), float(s["mult_im"])) - 1) < 1e-7 for s in lp))
    folded = [b for b, v in ends.items() if starts[b] == 1.38 and abs(v[0] - v[-1]) < 1e-12]
    check(f"the fold's pair is one branch from the far end ({len(folded)})", len(folded) == 1)
    check("stability is stated on every row", all(row["stability"] in ("stable", "unstable", "marginal") for row in rows))
    check("stderr names the fold", "LP at unroundness = 1.33580575" in r.stderr)

    for args, what in [
        (["--param2", "U", "--to2", "1e-6"], "--param2"),
        (["--cycles"], "--cycles"),
        (["--from-equilibrium", "balanced"], "--family"),
    ]:
        bad = os.path.join(tmp, "bad")
        r = run("continue", SCENE, "--param", "omega", "--to", "1200", *args, "-o", bad)
        check(f"{what}: exit 2, nothing written ({r.returncode})", r.returncode == 2 and not os.path.exists(bad))
        check(f"{what}: the message says what applies", "§20.9" in r.stderr)
    for param, rule in [("k", "anisotropic support's means"), ("n", "ball count")]:
        bad = os.path.join(tmp, "bad")
        r = run("continue", SCENE, "--param", param, "--to", "2", "-o", bad)
        check(f"--param {param}: exit 2, nothing written ({r.returncode})", r.returncode == 2 and not os.path.exists(bad))
        check(f"--param {param}: the rule is named", rule in r.stderr)
    r = run("continue", SCENE, "--param", "unroundness", "--to", "-1", "-o", os.path.join(tmp, "bad"))
    check(f"a negative unroundness factor: exit 2 ({r.returncode})", r.returncode == 2 and ">= 0" in r.stderr)
finish()
