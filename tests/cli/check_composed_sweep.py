#!/usr/bin/python3
"""`sweep` on an unround race with an anisotropic support (docs/model.md §20.6), its contract on
tests/scenes/composed/oval_anisotropic.toml:
  * omega 210 -> 215 (one step) exits 0; the CSVs have no NaN or inf; every converged row has
    2n + 4 = 8 multipliers and x(0), its rho_abs_max the modulus of the first multiplier and its
    stability the side of 1 (the band is ~1e-11);
  * the two orbits whose max |rho| changes side between the two values (the Neimark-Sacker
    crossings of the lower critical speed, sqrt(k_y / M) ~ 212 rad/s) have each a crossing
    located strictly between 210 and 215 inside its final bracket, |multiplier| = 1 to 1e-6
    (the bisection's bracket is 1e-10 relative), a complex pair (neimark-sacker), and the
    direction of the grid values' change; no other crossing;
  * --param n and --param k are refused (exit 2) with one message naming the two parts, and
    nothing is written.
Usage: check_composed_sweep.py BINARY SCENE"""
import csv
import math
import os
import subprocess
import sys
import tempfile


def rows(path):
    with open(path) as fh:
        return list(csv.DictReader(ln for ln in fh if not ln.startswith("#")))


def main(binary, scene):
    fails = []
    with tempfile.TemporaryDirectory() as tmp:
        run = subprocess.run([binary, "sweep", scene, "--param", "omega", "--from", "210", "--to", "215", "--steps",
                              "1", "-o", tmp], capture_output=True, text=True)
        if run.returncode != 0:
            print(run.stderr)
            return f"exit {run.returncode}"
        for name in ("sweep_omega.csv", "floquet_crossings_omega.csv"):
            text = open(os.path.join(tmp, name)).read().lower()
            if "nan" in text or "inf" in text:
                fails.append(f"{name} has a NaN or inf")
        if not os.path.getsize(os.path.join(tmp, "sweep_omega.png")):
            fails.append("no chart")
        sweep = rows(os.path.join(tmp, "sweep_omega.csv"))
        by = {}
        for r in sweep:
            if r["status"] != "converged":
                continue
            mult = [complex(float(r[f"mult_re{k}"]), float(r[f"mult_im{k}"])) for k in range(1, 9)]
            x0 = [float(r[f"x0_{k}"]) for k in range(1, 9)]
            if not all(math.isfinite(v) for v in x0):
                fails.append(f"row {r}: x(0) not finite")
            rho = float(r["rho_abs_max"])
            if abs(rho - abs(mult[0])) > 1e-15 * rho:
                fails.append(f"omega={r['omega']} track {r['track']}: rho_abs_max {rho} is not |mult1| {abs(mult[0])}")
            if r["stability"] != ("stable" if rho < 1 else "unstable"):
                fails.append(f"omega={r['omega']} track {r['track']}: {r['stability']} with max|rho| {rho}")
            by[(float(r["omega"]), int(r["track"]))] = rho
        changing = sorted(t for (w, t), rho in by.items()
                          if w == 210.0 and (215.0, t) in by and (rho - 1) * (by[(215.0, t)] - 1) < 0)
        crossings = rows(os.path.join(tmp, "floquet_crossings_omega.csv"))
        if sorted(int(c["orbit"]) for c in crossings) != changing or len(changing) != 2:
            fails.append(f"crossings of orbits {[c['orbit'] for c in crossings]}, sign changes of {changing}")
        for c in crossings:
            w, lo, hi = float(c["omega"]), float(c["bracket_lower"]), float(c["bracket_upper"])
            if not (210 < lo <= w <= hi < 215):
                fails.append(f"crossing {c}: not inside its bracket within (210, 215)")
            if abs(float(c["mult_abs"]) - 1) > 1e-6 or c["kind"] != "neimark-sacker":
                fails.append(f"crossing {c}: not a complex pair on the unit circle")
            grows = by[(215.0, int(c["orbit"]))] > by[(210.0, int(c["orbit"]))]
            if (c["direction"] == "to_unstable") != grows:
                fails.append(f"crossing {c}: direction against the grid values")
        for param, word in (("n", "ball count"), ("k", "anisotropic support's means")):
            out = os.path.join(tmp, f"refused_{param}")
            run = subprocess.run([binary, "sweep", scene, "--param", param, "--from", "1", "--to", "2", "--steps", "1",
                                  "-o", out], capture_output=True, text=True)
            if run.returncode != 2 or os.path.exists(out) or word not in run.stderr or \
                    "unround race on an anisotropic support" not in run.stderr:
                fails.append(f"--param {param}: exit {run.returncode}, {run.stderr.strip()!r}")
    return "; ".join(fails)


if __name__ == "__main__":
    problem = main(sys.argv[1], sys.argv[2])
    print(problem or "composed sweep: contract kept (two Neimark-Sacker crossings inside (210, 215))")
    sys.exit(1 if problem else 0)
