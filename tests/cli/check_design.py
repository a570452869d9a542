#!/usr/bin/env python3
"""`stability-scan design` (docs/model.md §22), checked on the real binary.

    check_design.py BINARY SOURCE_DIR [grid]

Contract (default):
- a problem with a known optimum: the stiffest support whose balanced state stays stable over
  [300, 2000] rad/s, for the scene's unbalance and for every unbalance of a range; its optimum is
  the Hopf point of a continuation in k at omega = 300 rad/s (`continue --param k`, located by
  the continuation's own test function), the smallest over the range's ends: 1e-6 relative;
- the same bytes on 1 and 2 threads for a study with runs; the recommended design is the best
  feasible row of the CSV;
- bad input (an empty design space, contradictory uncertainties, infeasible constraints, a
  variable the scene cannot take, an unknown objective): exit 2, nothing written.

grid (slow): a two-variable study (k, f) of the default scene's run-up minimizing the 90th
percentile residual: NLopt from a 3 x 3 grid against a brute-force 9 x 9 grid; the optimizer's
objective is no worse than the fine grid's best by more than the fine grid's own resolution (the
largest change of the objective from its best cell to a neighbouring cell).
"""
import json
import os
import sys
import tempfile

from cli_checks import BIN, SRC, check, failures, rows_of, run

MODE = sys.argv[3] if len(sys.argv) > 3 else "contract"
DEFAULT = os.path.join(SRC, "data/scenes/default.toml")


def hopf_k(work, U):
    out = os.path.join(work, f"cont{U}")
    r = run("continue", DEFAULT, "--dry", "off", "--set", "omega=300", "--set", "k=2000", "--set", f"U={U}", "--param", "k", "--to",
            "20000", "-o", out, "--no-chart")
    ks = [float(x["k"]) for x in rows_of(os.path.join(out, "special_k.csv"))
          if x["label"] == "HB" and x["family"] == "balanced" and x["converged"] == "1"]
    check(f"continue in k at omega = 300, U = {U:g}: a located balanced Hopf point", r.returncode == 0 and len(ks) > 0)
    return min(ks) if ks else float("nan")


def best_of(out):
    s = json.load(open(os.path.join(out, "design.json")))
    return s, s["designs"][s["recommended"]]


def contract(work):
    k_ref = hopf_k(work, 6e-7)
    out = os.path.join(work, "k")
    r = run("design", DEFAULT, "--vary", "k=2000:12000:6", "--objective", "max:k", "--constraint", "stable=300:2000",
            "-o", out, "--no-chart")
    s, b = best_of(out)
    rel = abs(b["values"][0] / k_ref - 1)
    check(f"stiffest stable support: {b['values'][0]:.10g} against the Hopf point {k_ref:.10g} ({rel:.1e} <= 1e-6)",
          r.returncode == 0 and rel <= 1e-6 and b["feasible"])
    check(f"binding constraint named: {s['binding']}", "stable balanced state" in s["binding"])
    # Every unbalance of [3e-7, 6e-7] (the study holds five of them, ends included): the smallest
    # of their Hopf points.
    refs = [hopf_k(work, 3e-7 + i * 0.75e-7) for i in range(5)]
    out = os.path.join(work, "kU")
    r = run("design", DEFAULT, "--vary", "k=2000:12000:6", "--objective", "max:k", "--constraint", "stable=300:2000",
            "--uncertain", "U=3e-7:6e-7", "-o", out, "--no-chart")
    s, b = best_of(out)
    ref = min(refs)
    rel = abs(b["values"][0] / ref - 1)
    check(f"over U in [3e-7, 6e-7]: {b['values'][0]:.10g} against the least of {', '.join(f'{k:.10g}' for k in refs)} "
          f"({rel:.1e} <= 1e-6)", r.returncode == 0 and rel <= 1e-6)

    # Runs: threads give the same bytes; the recommended row is the best feasible one.
    outs = []
    for t in (1, 2):
        o = os.path.join(work, f"t{t}")
        r = run("design", DEFAULT, "--ramp", "50:900:400", "--vary", "k=4000:10000:3", "--objective", "p90",
                "--samples", "8", "--max-evaluations", "6", "--threads", str(t), "-o", o, "--no-chart")
        check(f"a study with runs, {t} thread(s): exit 0", r.returncode == 0)
        outs.append(o)
    strip = lambda text: "".join(l for l in text.splitlines(True) if "command" not in l)
    for name in ("design.csv", "design.json"):
        a, b2 = (open(os.path.join(o, name)).read() for o in outs)
        check(f"{name}: 1 and 2 threads the same bytes (but the command line)", strip(a) == strip(b2))
    rows = rows_of(os.path.join(outs[0], "design.csv"))
    feasible = [x for x in rows if x["feasible"] == "1"]
    best = min(feasible, key=lambda x: float(x["objective"]))
    rec = [x for x in rows if x["recommended"] == "1"]
    check("the recommended row is the smallest feasible 90th percentile",
          len(rec) == 1 and float(rec[0]["objective"]) == float(best["objective"]))
    check("objective = the row's residual_p90", all(x["objective"] == x["residual_p90"] for x in feasible))
    check("no nan in the CSV", "nan" not in open(os.path.join(outs[0], "design.csv")).read().lower())

    # Bad input: exit 2, the reason named, nothing written.
    ring = os.path.join(SRC, "data/scenes/ring11.toml")
    for scene, args, word in (
            (DEFAULT, ["--vary", "k=5000:1000"], "empty range"),
            (DEFAULT, ["--vary", "mu=0.001:0.003", "--uncertain", "mu=0.001:0.002"], "both"),
            (DEFAULT, ["--vary", "k=2000:12000", "--uncertain", "U=3e-7:1e-7"], "LOW <= HIGH"),
            (DEFAULT, ["--vary", "m=1e-5:3e-5", "--constraint", "mass=1e-9"], "no design of the box"),
            (DEFAULT, ["--vary", "k=20000:40000", "--objective", "max:k", "--constraint", "stable=300:2000"],
             "no design of the box"),
            (DEFAULT, ["--vary", "n=2:4"], "[balls] ring"),
            (DEFAULT, ["--vary", "k=2000:12000", "--objective", "max:m"], "not one of the --vary"),
            (DEFAULT, ["--vary", "k=2000:12000", "--objective", "best"], "expected below"),
            (ring, ["--vary", "n=2:13"], "integers in 2..12"),
            (DEFAULT, ["--vary", "k=1000:2000:1000", "--vary", "c=1:2:1000", "--vary", "M_r=0.1:0.2:1000"],
             "the design study")):
        o = os.path.join(work, "bad")
        r = run("design", scene, *args, "-o", o)
        check(f"{' '.join(args)}: exit 2 naming '{word}', nothing written",
              r.returncode == 2 and word in r.stderr and not os.path.exists(o))


def grid(work):
    common = ["design", DEFAULT, "--ramp", "50:900:400", "--objective", "p90", "--samples", "16", "--no-chart"]
    fine = os.path.join(work, "fine")
    r = run(*common, "--vary", "k=4000:12000:9", "--vary", "f=1e-6:4e-6:9", "--grid-only", "-o", fine)
    check("brute force 9 x 9: exit 0", r.returncode == 0)
    rows = [x for x in rows_of(os.path.join(fine, "design.csv")) if x["origin"] == "grid"]
    value = {(float(x["k"]), float(x["f"])): float(x["objective"]) for x in rows}
    ks, fs = sorted({k for k, _ in value}), sorted({f for _, f in value})
    (kb, fb), best = min(value.items(), key=lambda kv: kv[1])
    i, j = ks.index(kb), fs.index(fb)
    near = [value[(ks[a], fs[b])] for a in range(max(0, i - 1), min(len(ks), i + 2))
            for b in range(max(0, j - 1), min(len(fs), j + 2))]
    resolution = max(abs(v - best) for v in near)
    coarse = os.path.join(work, "coarse")
    r = run(*common, "--vary", "k=4000:12000:3", "--vary", "f=1e-6:4e-6:3", "--max-evaluations", "40", "-o", coarse)
    _, b = best_of(coarse)
    opt = b["objective"]
    print(f"     fine grid best {best * 1e6:.4f} µm at k = {kb:g}, f = {fb:g} (resolution {resolution * 1e6:.4f} µm); "
          f"optimizer {opt * 1e6:.4f} µm at k = {b['values'][0]:.6g}, f = {b['values'][1]:.6g}")
    check("optimizer within the fine grid's resolution of its best", r.returncode == 0 and opt <= best + resolution)


with tempfile.TemporaryDirectory() as work:
    (grid if MODE == "grid" else contract)(work)
print(f"{failures()} failure(s)")
sys.exit(1 if failures() else 0)
