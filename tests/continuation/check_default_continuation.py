#!/usr/bin/env python3
"""The default scene's continuation over 0.2 .. 8 omega_n, the command the benchmark times
(docs/benchmarks-continuation.md): its special points against the mpmath reference, and the
same bytes whatever the thread count.

    check_default_continuation.py BINARY SOURCE_DIR

Reference (tests/reference/mp_special.py data/scenes/default.toml --param omega
--from 49.98625566927664 --to 1999.4502267710656, 50- and 80-digit locations agreeing; 600 s
of mpmath, so the values are kept here, rounded to 17 digits): one Hopf point of the balanced
family (met by both balanced branches) and two folds of the together family. Tolerance
1e-12 relative: the continuation locates them to the rounding level (3.8e-17 measured), so
1e-12 fails on any loss of digits beyond the fourth-to-last, yet passes on a last-bit change.
"""
import csv
import os
import subprocess
import sys
import tempfile

REFERENCE = [("HB", 249.93374034470624), ("LP", 236.1030736838683), ("LP", 264.56938031859784)]
RTOL = 1e-12


def run(binary, src, out, threads):
    cmd = [binary, "continue", os.path.join(src, "data/scenes/default.toml"), "--set", "omega=49.98625566927664",
           "--param", "omega", "--to", "1999.4502267710656", "--no-chart", "--threads", str(threads), "-o", out]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}: {r.stderr}")


def body(path):  # the file without its command line (it names the output directory)
    with open(path) as f:
        return [line for line in f if not line.startswith("# command:")]


def main():
    binary, src = sys.argv[1], sys.argv[2]
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        dirs = {t: os.path.join(tmp, f"t{t}") for t in (1, 2, 0)}
        for t, d in dirs.items():
            run(binary, src, d, t)
        for name in ("branch_omega.csv", "special_omega.csv"):
            for t in (2, 0):
                if body(os.path.join(dirs[1], name)) != body(os.path.join(dirs[t], name)):
                    print(f"FAIL: {name} with --threads {t} differs from --threads 1")
                    failures += 1
        with open(os.path.join(dirs[1], "special_omega.csv")) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    found = [(r["label"], float(r["omega"]), r["converged"]) for r in rows]
    for label, omega in REFERENCE:
        near = [p for (l, p, c) in found if l == label and c == "1" and abs(p - omega) <= RTOL * omega]
        if near:
            print(f"PASS {label} at {omega!r}: {len(near)} row(s), worst rel. error "
                  f"{max(abs(p - omega) / omega for p in near):.1e}")
        else:
            print(f"FAIL {label} at {omega!r} not found to {RTOL:g}")
            failures += 1
    for label, p, _ in found:
        if not any(l == label and abs(p - o) <= RTOL * o for l, o in REFERENCE):
            print(f"FAIL invented: {label} at {p!r}")
            failures += 1
    print("PASS" if failures == 0 else f"FAIL ({failures})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
