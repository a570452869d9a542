#!/usr/bin/env python3
"""`continue` of a LuGre scene (docs/model.md §12.8): the branches are the frictionless
model's z = 0 branches, their stability the spectrum of (12.10) with c = 1.

Checks (three_balls.toml, omega from 640 to 560 rad/s):
  * every start point (EP, point 0) has exactly the eigenvalues `sweep` gives for the same
    state at the same omega, each to 1e-9 of its modulus (the sweep is checked against
    the 90-digit reference, reference_lugre/sweep_*; a branch judged by another
    linearization differs by O(1): the bristle modes, |lambda| ~ 5e3 1/s, exist only here);
  * every branch point's spectral_abscissa is below 0 iff `stable` is 1, and its residual
    is at rounding level (the frictionless equations hold along the branch);
  * two balls, --param2 and --cycles are refused for LuGre with exit 2.
Usage: check_continue_lugre.py BINARY SOURCE_DIR      exit 0 pass, 1 fail.
"""
import csv
import os
import subprocess
import sys
import tempfile


def rows(path):
    with open(path) as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith("#")))


def eigen(row, count):
    return [complex(float(row[f"re{k}"]), float(row[f"im{k}"])) for k in range(1, count + 1)]


def main():
    binary, src = sys.argv[1], sys.argv[2]
    scene = os.path.join(src, "tests", "scenes", "lugre", "three_balls.toml")
    fails = []
    with tempfile.TemporaryDirectory() as tmp:
        common = ["--set-samples", "3"]
        r = subprocess.run([binary, "continue", scene, "--param", "omega", "--to", "560", "-o", tmp + "/c", "--no-chart"]
                           + common, capture_output=True, text=True)
        if r.returncode != 0:
            print(f"FAIL: continue exited {r.returncode}: {r.stderr}")
            return 1
        r = subprocess.run([binary, "sweep", scene, "--param", "omega", "--from", "640", "--to", "641", "--steps", "1",
                            "-o", tmp + "/s"] + common, capture_output=True, text=True)
        if r.returncode != 0:
            print(f"FAIL: sweep exited {r.returncode}: {r.stderr}")
            return 1
        branch = rows(tmp + "/c/branch_omega.csv")
        sweep = [s for s in rows(tmp + "/s/sweep_omega.csv") if float(s["omega"]) == 640.0]
        n = 3
        starts = [b for b in branch if b["point"] == "0"]
        for b in starts:
            q = (float(b["q1"]), float(b["q2"]), *(float(b[f"beta{i}"]) for i in range(1, n + 1)))
            match = [s for s in sweep if s["family"] == b["family"] and
                     max(abs(float(s["q1"]) - q[0]), abs(float(s["q2"]) - q[1])) <= 1e-12 and
                     max(abs(float(s[f"beta{i}"]) - q[1 + i]) for i in range(1, n + 1)) <= 1e-9]
            if len(match) != 1:
                fails.append(f"branch {b['branch']} start ({b['family']} {b['pattern']}): {len(match)} sweep states")
                continue
            got = sorted(eigen(b, 2 * n + 4), key=lambda z: (z.real, z.imag))
            ref = sorted(eigen(match[0], 2 * n + 4), key=lambda z: (z.real, z.imag))
            worst = max(abs(a - c) / abs(c) for a, c in zip(got, ref))
            if not worst <= 1e-9:
                fails.append(f"branch {b['branch']} start: eigenvalues differ from the sweep's by {worst:.2e}")
        big = max(abs(z) for b in starts for z in eigen(b, 2 * n + 4))
        if not big > 1e3:
            fails.append(f"largest |lambda| {big:.3g}: the bristle modes are missing")
        for b in branch:
            if b["label"] in ("", "EP") and b["spectral_abscissa"]:
                if (float(b["spectral_abscissa"]) < 0) != (b["stable"] == "1"):
                    fails.append(f"branch {b['branch']} point {b['point']}: abscissa {b['spectral_abscissa']} but stable {b['stable']}")
                if not float(b["residual"]) <= 1e-12:
                    fails.append(f"branch {b['branch']} point {b['point']}: residual {b['residual']}")
        print(f"{len(starts)} start points against the sweep, {len(branch)} branch rows, largest |lambda| {big:.4g} 1/s")
        two = os.path.join(src, "tests", "scenes", "lugre", "two_balls.toml")
        for args in ([two, "--param", "omega", "--to", "700"],
                     [scene, "--param", "omega", "--to", "600", "--param2", "k", "--to2", "9000"],
                     [scene, "--param", "omega", "--to", "600", "--cycles"]):
            r = subprocess.run([binary, "continue", *args, "-o", tmp + "/x"], capture_output=True, text=True)
            if r.returncode != 2 or "lugre" not in r.stderr or os.path.exists(tmp + "/x"):
                fails.append(f"continue {' '.join(args[1:])}: exit {r.returncode}, expected a LuGre refusal (2)")
    for f in fails:
        print("FAIL", f)
    print("PASS" if not fails else "FAIL")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
