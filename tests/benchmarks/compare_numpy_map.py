#!/usr/bin/python3
"""Stability flags of the numpy baseline's map against `stability-scan map` on the same grid.

    compare_numpy_map.py NUMPY_CSV MAP_CSV --binary BIN --scene SCENE [--verify 5]

Both files list cells with omega outer and the friction parameter inner; they are read in
lockstep, one cell at a time. Per cell and family the number of stable equilibria is
compared. For up to --verify cells where they differ, the analyzer's equilibria and every
eigenvalue at that cell are checked against the independent 40-digit mpmath computation
(tests/reference/check_scene.sh, 1e-8 relative): where it passes, the analyzer's flag is
the right one and the baseline's is wrong.
"""
import argparse
import csv
import itertools
import os
import subprocess
import sys

FAMILIES = ("balanced", "together", "opposite")


def cells(path, x_col, y_col, family_col, stable_col, abscissa_col):
    """Yields (x, y, {family: stable count}, [abscissas]) per cell, in file order."""
    with open(path, newline="") as f:
        rows = csv.reader(line for line in f if not line.startswith("#"))
        header = next(rows)
        ix, iy = header.index(x_col), header.index(y_col)
        fam, st, sa = header.index(family_col), header.index(stable_col), header.index(abscissa_col)
        for key, group in itertools.groupby(rows, key=lambda r: (r[ix], r[iy])):
            counts = dict.fromkeys(FAMILIES, 0)
            present = dict.fromkeys(FAMILIES, 0)
            abscissas = []
            for r in group:
                present[r[fam]] += 1
                counts[r[fam]] += int(r[st])
                abscissas.append(float(r[sa]))
            yield float(key[0]), float(key[1]), counts, present, abscissas


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("numpy_csv")
    ap.add_argument("map_csv")
    ap.add_argument("--binary", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--param", default="mu")
    ap.add_argument("--verify", type=int, default=5)
    a = ap.parse_args()
    ours = cells(a.map_csv, "omega", a.param, "family", "stable", "spectral_abscissa")
    theirs = cells(a.numpy_csv, "omega", "param", "family", "stable", "spectral_abscissa")
    n_cells = n_differ = n_missing = 0
    differing = []
    for (x, y, c_ours, p_ours, _), (xn, yn, c_np, p_np, _) in zip(ours, theirs):
        n_cells += 1
        if abs(x - xn) > 1e-9 * abs(x) or abs(y - yn) > 1e-9 * abs(y):
            sys.exit(f"grids differ at cell {n_cells}: ({x}, {y}) vs ({xn}, {yn})")
        if p_ours != p_np:
            n_missing += 1
            continue
        if c_ours != c_np:
            n_differ += 1
            differing.append((x, y, c_ours, c_np))
    print(f"{n_cells} cells compared; the baseline's stable counts differ from the analyzer's in {n_differ} cells "
          f"({100.0 * n_differ / max(n_cells, 1):.3f}%); {n_missing} cells with different equilibrium counts")
    if not differing:
        return 0
    here = os.path.dirname(os.path.abspath(__file__))
    check = os.path.join(here, "..", "reference", "check_scene.sh")
    step = max(1, len(differing) // a.verify)
    verified = 0
    for x, y, c_ours, c_np in differing[::step][: a.verify]:
        r = subprocess.run(["sh", check, a.binary, a.scene, "--set", f"omega={x!r}", "--set", f"{a.param}={y!r}",
                            "--rtol", "1e-8"], capture_output=True, text=True)
        ok = r.returncode == 0
        verified += ok
        print(f"  omega={x!r} {a.param}={y!r}: stable per family analyzer {c_ours}, numpy {c_np}; "
              f"analyzer's eigenvalues vs 40 digits: {'agree to 1e-8' if ok else 'MISMATCH'}")
    print(f"{verified} of {min(a.verify, len(differing))} differing cells checked at 40 digits: the analyzer is right "
          f"there, the baseline's flag is wrong")
    return 0 if verified == min(a.verify, len(differing)) else 1


if __name__ == "__main__":
    sys.exit(main())
