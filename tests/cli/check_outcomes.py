#!/usr/bin/env python3
"""`stability-scan outcomes` (docs/model.md §21), checked on the real binary.

    check_outcomes.py BINARY SOURCE_DIR [statistics]

Contract (default): the same bytes on 1 and 2 threads; every row's bare rotor against (16.5.1)
computed here; the JSON's medians, 90th percentiles and their order-statistic intervals
recomputed from the CSV with scipy's binomial distribution, the proportions with Wilson's
formula; no NaN or inf; the other machines run; bad input exits 2 with nothing written.

statistics (slow): the probability that a run-up of the default scene ends below the bare
rotor's vibration, estimated by the study at 64, 256 and 1024 independent points and at 1024
Sobol points, lies inside each stated 95 % interval around a second algorithm's value (`basin`
on a 64 x 64 grid of start angles, the fraction of cells ending below it), and the interval
narrows as 1/sqrt(N) (64 -> 1024: a factor 4, accepted within [3.2, 4.8]).
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

from scipy.stats import binom

BIN, SRC = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
MODE = sys.argv[3] if len(sys.argv) > 3 else "contract"
DEFAULT = os.path.join(SRC, "data/scenes/default.toml")
RAMP = "50:900:400"
fails = 0


def check(name, ok):
    global fails
    print(("ok   " if ok else "FAIL ") + name)
    fails += 0 if ok else 1


def run(*args, cwd=None):
    return subprocess.run([BIN, "outcomes", *args], capture_output=True, text=True, cwd=cwd)


def rows_of(path):
    lines = [line for line in open(path) if not line.startswith("#")]
    r = list(csv.DictReader(lines))
    return r


def bare_rotor(w, M=0.12 + 2 * 3.3e-5, k=7500.0, c=2.0, U=6e-7):
    return U * w * w / abs(complex(k - M * w * w, c * w))


def ranks(n, p, conf=0.95):
    """1-based (l, u) as docs/model.md §21.3 defines them, from scipy's binomial cdf."""
    tail = (1 - conf) / 2
    low = max([l for l in range(1, n + 1) if binom.cdf(l - 1, n, p) <= tail], default=0)
    high = min([u for u in range(1, n + 1) if binom.sf(u - 1, n, p) <= tail], default=n + 1)
    return low, high


def wilson(k, n, z=1.959963984540054):
    c = (k + z * z / 2) / (n + z * z)
    h = z / (n + z * z) * math.sqrt(k * (n - k) / n + z * z / 4)
    return (0.0 if k == 0 else max(0.0, c - h)), (1.0 if k == n else min(1.0, c + h))


def contract(work):
    outs = {}
    for threads in (1, 2):
        out = os.path.join(work, f"t{threads}")
        r = run(DEFAULT, "--ramp", RAMP, "--samples", "40", "--uncertain", "U=4e-7:8e-7", "--threads", str(threads),
                "-o", out, "--no-chart")
        check(f"threads {threads}: exit 0", r.returncode == 0)
        check(f"threads {threads}: the verdict leads the summary", "verdict:" in r.stderr.splitlines()[1])
        outs[threads] = out
    strip = lambda text: "".join(l for l in text.splitlines(True) if not l.startswith("# command:") and '"command"' not in l)
    for name in ("outcomes.csv", "outcomes.json"):
        a, b = (open(os.path.join(outs[t], name)).read() for t in (1, 2))
        check(f"{name}: 1 and 2 threads the same bytes (but the command line)", strip(a) == strip(b))
    text = open(os.path.join(outs[1], "outcomes.csv")).read().lower()
    check("no nan or inf in the CSV", "nan" not in text and "inf" not in text)
    rows = rows_of(os.path.join(outs[1], "outcomes.csv"))
    check("40 rows", len(rows) == 40)
    worst = 0
    for r in rows:
        U = float(r["U"])
        worst = max(worst, abs(float(r["bare_rotor_q"]) / bare_rotor(900.0, U=U) - 1))
    check(f"bare rotor (16.5.1) per row, its own U: {worst:.2e} <= 1e-12", worst <= 1e-12)
    check("U drawn inside its range", all(4e-7 <= float(r["U"]) <= 8e-7 for r in rows))
    check("residual <= peak in every row", all(float(r["residual_q"]) <= float(r["peak_q"]) for r in rows))
    s = json.load(open(os.path.join(outs[1], "outcomes.json")))
    res = sorted(float(r["residual_q"]) for r in rows)
    n = len(res)
    for key, p in (("median", 0.5), ("p90", 0.9)):
        q = s["residual_q"][key]
        l, u = ranks(n, p)
        check(f"residual {key}: x_(ceil(p n))", q["value"] == res[math.ceil(p * n) - 1])
        check(f"residual {key}: interval x_({l}), x_({u})",
              q["low"] == (res[l - 1] if l >= 1 else None) and q["high"] == (res[u - 1] if u <= n else None))
    check("worst = the largest residual", s["residual_q"]["worst"] == res[-1])
    below = sum(float(r["residual_q"]) <= float(r["bare_rotor_q"]) for r in rows)
    lo, hi = wilson(below, n)
    b = s["below_limit"]
    check(f"below the bare rotor: {below} of {n}, Wilson [{lo:.4f}, {hi:.4f}]",
          b["events"] == below and abs(b["low"] - lo) < 1e-12 and abs(b["high"] - hi) < 1e-12)
    stuck = sum(r["stuck_off_balance"] == "1" for r in rows)
    check("stuck away from balance = the rows' flags", s["stuck_off_balance"]["events"] == stuck)

    # Other machines: an anisotropic support, an unround race, coulomb-set balls, three balls.
    for scene, extra in (("tests/scenes/anisotropic/ref_coulomb.toml", []),
                         ("tests/scenes/unround/oval_offset_viscous.toml", []),
                         ("tests/scenes/composed/oval_anisotropic.toml", []),
                         ("tests/scenes/stickslip/runup.toml", []),
                         ("data/scenes/ring11.toml", ["--set", "omega=900"])):
        path = os.path.join(SRC, scene)
        if not os.path.exists(path):
            check(f"{scene} exists", False)
            continue
        out = os.path.join(work, os.path.basename(scene))
        r = run(path, *extra, "--samples", "4", "--t-end", "0.3", "-o", out, "--no-chart")
        body = open(os.path.join(out, "outcomes.csv")).read().lower() if r.returncode == 0 else ""
        check(f"{scene}: exit 0, 4 rows, no nan ({r.stderr.strip().splitlines()[-1][:120] if r.stderr else ''})",
              r.returncode == 0 and len(rows_of(os.path.join(out, "outcomes.csv"))) == 4 and "nan" not in body)

    # The scene's [uncertain] table: the same study as --uncertain; the option replaces an entry.
    declared = os.path.join(work, "declared.toml")
    open(declared, "w").write(open(DEFAULT).read() + "\n[uncertain]\nU = [4e-7, 8e-7]\nmu = [0.5, 0.6]\n")
    o = os.path.join(work, "declared")
    r = run(declared, "--ramp", RAMP, "--samples", "40", "--uncertain", "mu=0.002:0.002", "-o", o, "--no-chart",
            "--quiet")
    a = [x["residual_q"] for x in rows_of(os.path.join(o, "outcomes.csv"))] if r.returncode == 0 else [r.stderr]
    o2 = os.path.join(work, "declared_flags")
    r = run(DEFAULT, "--ramp", RAMP, "--samples", "40", "--uncertain", "U=4e-7:8e-7", "--uncertain", "mu=0.002:0.002",
            "-o", o2, "--no-chart", "--quiet")
    b = [x["residual_q"] for x in rows_of(os.path.join(o2, "outcomes.csv"))] if r.returncode == 0 else []
    check("[uncertain] in the scene = --uncertain (U drawn, mu replaced by the option)", a == b and len(a) == 40)
    open(declared, "w").write(open(DEFAULT).read() + "\n[uncertain]\nr = [1e-3, 0.02]\n")
    r = run(declared, "-o", os.path.join(work, "bad"))
    line = len(open(DEFAULT).read().splitlines()) + 3  # a blank line, [uncertain], then r
    check(f"[uncertain] r beyond the race radius: exit 2 at the scene's line {line} and key",
          r.returncode == 2 and f"declared.toml:{line}:" in r.stderr and "uncertain.r" in r.stderr and
          not os.path.exists(os.path.join(work, "bad")))

    # The runout as an uncertain input: a factor 0 is the round race (its scene without [race]).
    oval = os.path.join(SRC, "tests/scenes/unround/oval_offset_viscous.toml")
    text = open(oval).read()
    open(os.path.join(work, "round.toml"), "w").write(text[:text.index("[race]")])
    res = []
    for scene, extra in ((oval, ["--uncertain", "unroundness=0:0"]), (os.path.join(work, "round.toml"), [])):
        o = os.path.join(work, "unr" + str(len(res)))
        r = run(scene, *extra, "--samples", "4", "--t-end", "0.5", "-o", o, "--no-chart", "--quiet")
        res.append([x["residual_q"] for x in rows_of(os.path.join(o, "outcomes.csv"))] if r.returncode == 0 else r.stderr)
    check("unroundness 0: the round race's runs", res[0] == res[1] and len(res[0]) == 4)
    o = os.path.join(work, "unr_range")
    r = run(oval, "--uncertain", "unroundness=0:1", "--samples", "4", "--t-end", "0.5", "-o", o, "--no-chart", "--quiet")
    check("unroundness over [0, 1]: exit 0", r.returncode == 0)
    r = run(DEFAULT, "--uncertain", "unroundness=0:1", "-o", os.path.join(work, "bad"))
    check("unroundness on a round race: exit 2 naming the [race]", r.returncode == 2 and "[race]" in r.stderr)

    # `simulate` and `basin` report the same figures (model.md §21.1).
    first = rows[0]
    j = os.path.join(work, "sim.json")
    r = subprocess.run([BIN, "simulate", DEFAULT, "--ramp", RAMP, "--t-end", "4.125", "--set", f"U={first['U']}",
                        "--balls", f"{first['beta1_0']},{first['beta2_0']}", "--summary", j, "-o",
                        os.path.join(work, "sim"), "--no-chart", "--quiet"], capture_output=True, text=True)
    sim = json.load(open(j)) if r.returncode == 0 else {}
    check("simulate from run 0's start: the same residual bit for bit",
          sim.get("residual_q_abs") == float(first["residual_q"]))
    check("simulate: the bare rotor (16.5.1) and the balls held as the study's row",
          sim.get("bare_rotor_q_abs") == float(first["bare_rotor_q"]) and
          sim.get("balls_held_q_abs") == float(first["balls_fixed_q"]))
    # A ramp from rest typed in rpm is the same run as in rad/s.
    outs = []
    for units, ramp in (("rad/s", "0:1000:1000"), ("rpm", f"0:{1000 * 30 / math.pi!r}:{1000 * 30 / math.pi!r}")):
        o = os.path.join(work, "rpm" + units.replace("/", ""))
        r = subprocess.run([BIN, "simulate", DEFAULT, "--units", units, "--ramp", ramp, "--t-end", "0.5", "--balls",
                            "1,2", "-o", o, "--no-chart", "--quiet"], capture_output=True, text=True)
        outs.append(rows_of(os.path.join(o, "simulation.csv")) if r.returncode == 0 else [])
    # The rpm values convert to 1000 rad/s within an ulp: the rows agree to 1e-9 of each column's scale.
    worst = 1.0 if len(outs[0]) != len(outs[1]) or not outs[0] else 0.0
    for key in ("t", "omega", "q1", "q2", "beta1", "beta2"):
        a = [float(x[key]) for x in outs[0]]
        d = [float(x[key]) for x in outs[1]] if not worst else a
        scale = max(abs(v) for v in a) or 1.0
        worst = max([worst] + [abs(u - v) / scale for u, v in zip(a, d)])
    check(f"a ramp from rest in rpm: the rad/s run's rows ({worst:.1e} <= 1e-9 of the scale)",
          worst <= 1e-9 and len(outs[0]) > 100)
    b = os.path.join(work, "basin")
    r = subprocess.run([BIN, "basin", DEFAULT, "--grid", "5", "--ramp", RAMP, "--t-end", "4.125", "-o", b, "--no-chart",
                        "--quiet"], capture_output=True, text=True)
    cells = sorted(float(c["q_abs_end"]) for c in rows_of(os.path.join(b, "basin.csv")))
    res = json.load(open(os.path.join(b, "basin.json")))["residual_q"] if r.returncode == 0 else {}
    check("basin: the median and worst |q| at the cells' ends, the bare rotor",
          res.get("median", [None])[0] == cells[math.ceil(0.5 * len(cells)) - 1] and res.get("worst") == cells[-1]
          and abs(res.get("bare_rotor", 0) / bare_rotor(900.0) - 1) < 1e-12)

    # Bad input: exit 2, the option named, nothing written.
    for args, word in ((["--uncertain", "mu=0.003:0.001"], "--uncertain"), (["--uncertain", "omega=1:2"], "profile"),
                       (["--uncertain", "zeta=1:2"], "zeta"), (["--samples", "0"], "--samples"),
                       (["--uncertain", "mu"], "NAME=LOW:HIGH"), (["--confidence", "1.5"], "--confidence"),
                       (["--samples", "2000000000"], "--samples")):
        out = os.path.join(work, "bad")
        r = run(DEFAULT, *args, "-o", out)
        check(f"{' '.join(args)}: exit 2 naming {word}, nothing written",
              r.returncode == 2 and word in r.stderr and not os.path.exists(out))
    r = run(os.path.join(SRC, "data/scenes/shaft.toml"), "-o", os.path.join(work, "bad"))
    check("a shaft: exit 2 naming what answers it", r.returncode == 2 and "basin" in r.stderr)


def statistics(work):
    grid = os.path.join(work, "grid")
    r = subprocess.run([BIN, "basin", DEFAULT, "--grid", "64", "--ramp", RAMP, "--t-end", "4.125", "-o", grid, "--quiet",
                        "--no-chart"], capture_output=True, text=True)
    check("basin 64 x 64: exit 0", r.returncode == 0)
    cells = rows_of(os.path.join(grid, "basin.csv"))
    p_ref = sum(float(c["q_abs_end"]) <= bare_rotor(900.0) for c in cells) / len(cells)
    print(f"     second algorithm: {len(cells)} grid cells, P(residual <= bare rotor) = {p_ref:.4f}")
    widths = {}
    for design, n in (("random", 64), ("random", 256), ("random", 1024), ("sobol", 1024)):
        out = os.path.join(work, f"{design}{n}")
        r = run(DEFAULT, "--ramp", RAMP, "--samples", str(n), "--design", design, "-o", out, "--quiet", "--no-chart")
        b = json.load(open(os.path.join(out, "outcomes.json")))["below_limit"]
        check(f"{design} {n}: {b['value']:.4f} in [{b['low']:.4f}, {b['high']:.4f}] holds {p_ref:.4f}",
              r.returncode == 0 and b["low"] <= p_ref <= b["high"])
        widths[(design, n)] = b["high"] - b["low"]
    ratio = widths[("random", 64)] / widths[("random", 1024)]
    check(f"interval 64 -> 1024 narrows by {ratio:.2f} (1/sqrt(N): 4)", 3.2 <= ratio <= 4.8)
    ratio = widths[("random", 256)] / widths[("random", 1024)]
    check(f"interval 256 -> 1024 narrows by {ratio:.2f} (1/sqrt(N): 2)", 1.6 <= ratio <= 2.4)


with tempfile.TemporaryDirectory() as work:
    (statistics if MODE == "statistics" else contract)(work)
print(f"{fails} failure(s)")
sys.exit(1 if fails else 0)
