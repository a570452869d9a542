#!/usr/bin/env python3
"""`continue` on an n-ball scene, checked against `equilibria` at fixed parameters (an
independent path: closed forms, polish and spectra at one value, no continuation).

  check_continue_n.py STABILITY_SCAN SCENE

1. Every balanced sample's branch has its Hopf point(s) located; just either side of
   each (omega_H (1 -+ 1e-5)) `equilibria --set-samples 16` reports that sample's normal
   stability with the counts the special point states. 1e-5: the location is Brent's
   to 1e-13 of the bracket, and the crossing pair's real part moves by ~1e-5 omega_H
   dRe/domega there, far outside the marginal band (~1e-15 |lambda|) yet close enough
   that no other eigenvalue crosses in between.
2. Every LP of an aligned branch: the number of equilibria of its pattern differs by 2
   at omega_LP (1 -+ 1e-6) (a fold joins two of them).
3. The envelope's fraction stable is 0 below the first sample's Hopf point and 1 above
   the last one, where step 1 says so, and its pieces tile the interval.
4. Two-parameter curves in (omega, mu): a fold curve keeps omega constant to 1e-9
   relative (friction does not move equilibria, docs/model.md §4; the curve's points are
   Newton solutions to ~1e-12); at the middle point of every balanced sample's Hopf
   curve, `equilibria` at omega (1 -+ 1e-5) with that mu finds the sample stable on one
   side and unstable on the other.
5. --param2 equal to --param is refused (exit 2), nothing written.
"""
import csv
import io
import os
import subprocess
import sys
import tempfile

exe, scene = sys.argv[1], sys.argv[2]
failures = []


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(io.StringIO("".join(l for l in f if not l.startswith("#")))))


def equilibria(omega):
    out = subprocess.run([exe, "equilibria", scene, "--format", "csv", "--set-samples", "16", "--set",
                          f"omega={omega!r}"], check=True, capture_output=True, text=True).stdout
    return list(csv.DictReader(io.StringIO("".join(l for l in out.splitlines(True) if not l.startswith("#")))))


with tempfile.TemporaryDirectory() as tmp:
    d = os.path.join(tmp, "c")
    subprocess.run([exe, "continue", scene, "--param", "omega", "--to", "100", "--set-samples", "16", "-o", d,
                    "--no-chart"], check=True, capture_output=True)
    specials = rows(os.path.join(d, "special_omega.csv"))
    envelope = rows(os.path.join(d, "envelope_omega.csv"))
    branches = rows(os.path.join(d, "branch_omega.csv"))

    samples = {r["member"] for r in branches if r["family"] == "balanced"}
    hopf = [r for r in specials if r["label"] == "HB" and r["family"] == "balanced"]
    if not samples:
        failures.append("no balanced-sample branches")
    if {r["member"] for r in hopf} != samples:
        failures.append(f"samples without a Hopf point: {sorted(samples - {r['member'] for r in hopf})}")
    for r in hopf:
        if r["converged"] != "1" or not r["frequency"]:
            failures.append(f"sample {r['member']}: HB not converged or without frequency: {r}")
        w = float(r["omega"])
        # The special point's counts are along the branch (omega decreasing from 900).
        for omega, expected in ((w * (1 + 1e-5), int(r["n_unstable_before"])), (w * (1 - 1e-5), int(r["n_unstable_after"]))):
            eq = [e for e in equilibria(omega) if e["family"] == "balanced" and e["member"] == r["member"]]
            if len(eq) != 1:
                failures.append(f"sample {r['member']} missing at omega={omega}")
                continue
            stable = eq[0]["stable"] == "1"
            if stable != (expected == 0):
                failures.append(f"sample {r['member']} at omega={omega}: stable={stable}, continuation says "
                                f"{expected} unstable")

    folds = [r for r in specials if r["label"] == "LP" and r["family"] == "aligned"]
    if not folds:
        failures.append("no fold on the aligned branches (the +++ family folds twice near omega_n)")
    for r in folds:
        w = float(r["omega"])
        counts = [sum(1 for e in equilibria(omega) if e["family"] == "aligned" and e["pattern"] == r["pattern"])
                  for omega in (w * (1 - 1e-6), w * (1 + 1e-6))]
        if abs(counts[0] - counts[1]) != 2:
            failures.append(f"LP {r['pattern']} at omega={w}: {counts} equilibria either side, expected a difference of 2")

    lo = [float(e["from"]) for e in envelope]
    hi = [float(e["to"]) for e in envelope]
    if abs(lo[0] - 100) > 1e-9 or abs(hi[-1] - 900) > 1e-9 or any(abs(a - b) > 0 for a, b in zip(hi[:-1], lo[1:])):
        failures.append(f"envelope pieces do not tile [100, 900]: {list(zip(lo, hi))}")
    first, last = min(float(r["omega"]) for r in hopf), max(float(r["omega"]) for r in hopf)
    for e in envelope:
        mid = (float(e["from"]) + float(e["to"])) / 2
        if mid < first and e["fraction_stable"] != "0":
            failures.append(f"envelope below the first Hopf point: {e}")
        if mid > last and e["fraction_stable"] != "1":
            failures.append(f"envelope above the last Hopf point: {e}")

    d2 = os.path.join(tmp, "c2")
    subprocess.run([exe, "continue", scene, "--param", "omega", "--to", "100", "--set-samples", "16", "--param2", "mu",
                    "--to2", "0.02", "-o", d2, "--no-chart"], check=True, capture_output=True)
    curves = rows(os.path.join(d2, "boundary_omega_mu.csv"))
    by_curve = {}
    for r in curves:
        by_curve.setdefault(r["curve"], []).append(r)
    kinds = {(c[0]["kind"], c[0]["family"]) for c in by_curve.values()}
    if ("LP", "aligned") not in kinds or ("HB", "balanced") not in kinds:
        failures.append(f"boundary curves: expected aligned fold and balanced Hopf curves, got {kinds}")
    for k, c in by_curve.items():
        mus = [float(r["mu"]) for r in c]
        if max(mus) < 0.019:
            failures.append(f"curve {k} does not reach mu = 0.02 (max {max(mus)})")
        if c[0]["kind"] == "LP":
            w = [float(r["omega"]) for r in c]
            if (max(w) - min(w)) > 1e-9 * max(w):
                failures.append(f"fold curve {k}: omega varies with mu by {max(w) - min(w)}")
        elif c[0]["family"] == "balanced":
            mid = c[len(c) // 2]
            w, mu = float(mid["omega"]), mid["mu"]
            verdicts = []
            for omega in (w * (1 - 1e-5), w * (1 + 1e-5)):
                out = subprocess.run([exe, "equilibria", scene, "--format", "csv", "--set-samples", "16", "--set",
                                      f"omega={omega!r}", "--set", f"mu={mu}"], check=True, capture_output=True,
                                     text=True).stdout
                eq = [e for e in csv.DictReader(io.StringIO("".join(l for l in out.splitlines(True) if not l.startswith("#"))))
                      if e["family"] == "balanced" and e["member"] == mid["member"]]
                verdicts.append(eq[0]["stable"] if len(eq) == 1 else "missing")
            if sorted(verdicts) != ["0", "1"]:
                failures.append(f"Hopf curve {k} (sample {mid['member']}) at mu={mu}, omega={w}: stable either side {verdicts}")

    bad = os.path.join(tmp, "bad")
    r = subprocess.run([exe, "continue", scene, "--param", "omega", "--to", "100", "--param2", "omega", "--to2", "300",
                        "-o", bad], capture_output=True, text=True)
    if r.returncode != 2 or os.path.exists(bad) or "must differ" not in r.stderr:
        failures.append(f"--param2 = --param: exit {r.returncode}, stderr {r.stderr!r}, wrote {os.path.exists(bad)}")

print(f"{len(hopf)} Hopf points of {len(samples)} samples, {len(folds)} folds, {len(by_curve)} boundary curves "
      "checked against `equilibria`")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
