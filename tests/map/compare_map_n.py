#!/usr/bin/python3
"""Checks of the n-ball map CSVs (tests/map/check_map_n.sh), every column by its header name.

  compare_map_n.py equilibria MAP_CSV SUMMARY_CSV BINARY SCENE XNAME YNAME
      every cell against `stability-scan equilibria --format csv --set X=x --set Y=y`
      (an independent path: the equilibria command's own analysis, scan.hpp analyze):
      the same equilibria (family, pattern, member), the same stable flag and
      n_structural_zero, spectral_abscissa, |q| and the angles to 1e-12 relative (the
      same algorithm on the same doubles gives the same bits; the tolerance only covers
      |q| recomputed here from the rounded q1, q2: a few ulps); the summary recomputed
      from those rows (balanced_stable_fraction, aligned, aligned_stable, n_stable, best).
  compare_map_n.py ballcount SUMMARY_N SUMMARY_TWO MASS RACE_RADIUS
      the `n` axis map: capacity = n m l (1e-12 relative: one product and a sum of n
      rounded terms), aligned = 2^n (every pattern has its two roots at these parameters,
      model.md §13.2), and the n = 2 row against the two-ball path's summary (the fast
      characteristic-polynomial decision, map.hpp): same balanced existence and
      stability, aligned = together + opposite, n_stable, best |q| to 1e-9 relative (two
      algorithms for the same equilibria, each polished to long-double rounding; 1e-9 is
      far above both and far below any physical difference).
"""
import csv
import io
import math
import subprocess
import sys


def rows(path_or_text, text=False):
    data = path_or_text if text else open(path_or_text).read()
    lines = [l for l in data.splitlines() if not l.startswith("#")]
    return list(csv.DictReader(io.StringIO("\n".join(lines))))


def close(a, b, rtol, atol=0.0):
    return abs(a - b) <= rtol * max(abs(a), abs(b)) + atol


failures = 0


def check(ok, what):
    global failures
    print(("ok   " if ok else "FAIL ") + what)
    failures += 0 if ok else 1


def key(r):
    return (r["family"], r["pattern"], int(r["member"]))


def equilibria_mode(map_csv, summary_csv, binary, scene, xname, yname):
    long_rows = rows(map_csv)
    cells = {}
    for r in long_rows:
        cells.setdefault((r["ix"], r["iy"]), []).append(r)
    summary = {(r["ix"], r["iy"]): r for r in rows(summary_csv)}
    bad_rows = bad_summary = 0
    for (ix, iy), mine in sorted(cells.items()):
        x, y = mine[0][xname], mine[0][yname]
        out = subprocess.run([binary, "equilibria", scene, "--format", "csv", "--set", f"{xname}={x}", "--set",
                              f"{yname}={y}"], capture_output=True, text=True, check=True).stdout
        ref = {key(r): r for r in rows(out, text=True)}
        got = {key(r): r for r in mine}
        if set(ref) != set(got):
            bad_rows += 1
            print(f"  cell ({ix},{iy}): equilibria differ: {sorted(set(ref) ^ set(got))[:5]}")
            continue
        n = int(mine[0]["balls"])
        for k, r in got.items():
            e = ref[k]
            q = math.hypot(float(e["q1"]), float(e["q2"]))
            ok = (r["stable"] == e["stable"] and r["n_structural_zero"] == e["n_structural_zero"]
                  and close(float(r["spectral_abscissa"]), float(e["spectral_abscissa"]), 1e-12)
                  and close(float(r["q_abs"]), q, 1e-12, 1e-300)
                  and all(close(float(r[f"beta{i}"]), float(e[f"beta{i}"]), 1e-12) for i in range(1, n + 1)))
            if not ok:
                bad_rows += 1
                print(f"  cell ({ix},{iy}) {k}: map {r} vs equilibria {e}")
        s = summary[(ix, iy)]
        bal = [r for r in mine if r["family"] == "balanced"]
        al = [r for r in mine if r["family"] != "balanced"]
        stable = [r for r in mine if r["stable"] == "1"]
        frac = (sum(r["stable"] == "1" for r in bal) / len(bal)) if bal else None
        best = min(stable, key=lambda r: float(r["q_abs"])) if stable else None
        ok = (int(s["balanced_samples"]) == len(bal) and int(s["aligned"]) == len(al)
              and int(s["aligned_stable"]) == sum(r["stable"] == "1" for r in al)
              and int(s["n_stable"]) == len(stable)
              and (s["balanced_stable_fraction"] == "" if frac is None else close(float(s["balanced_stable_fraction"]), frac, 1e-15))
              and (s["best_q_abs"] == "" if best is None else (s["best_q_abs"] == best["q_abs"] and s["best_family"] == best["family"])))
        if not ok:
            bad_summary += 1
            print(f"  cell ({ix},{iy}): summary {s}")
    check(bad_rows == 0, f"every equilibrium of {len(cells)} cells ({len(long_rows)} rows) agrees with `equilibria`")
    check(bad_summary == 0, "every summary row agrees with its cell's rows")


def ballcount_mode(summary_n, summary_two, mass, race_radius):
    sn = rows(summary_n)
    s2 = rows(summary_two)
    m, l = float(mass), float(race_radius)
    check(all(close(float(r["capacity"]), int(r["balls"]) * m * l, 1e-12) for r in sn), "capacity = n m l on every row")
    check(all(int(r["aligned"]) == 2 ** int(r["balls"]) for r in sn), "2^n aligned equilibria on every row")
    check(all(r["balls"] == r["n"] for r in sn), "the balls column is the n axis")
    two = [r for r in sn if r["balls"] == "2"]
    check(len(two) == len(s2) and len(two) > 0, f"an n = 2 row per two-ball cell ({len(two)}, {len(s2)})")
    for a, b in zip(sorted(two, key=lambda r: int(r["ix"])), sorted(s2, key=lambda r: int(r["ix"]))):
        frac = a["balanced_stable_fraction"]
        ok = (int(a["balanced_exists"]) == (int(b["balanced"]) > 0)
              and (b["balanced_stable"] == "" or (frac in ("0", "1") and frac == b["balanced_stable"]))
              and int(a["aligned"]) == int(b["together"]) + int(b["opposite"])
              and int(a["balanced_samples"]) == int(b["balanced"])
              and a["n_stable"] == b["n_stable"]
              and ((a["best_q_abs"] == "") == (b["best_q_abs"] == ""))
              and (a["best_q_abs"] == "" or close(float(a["best_q_abs"]), float(b["best_q_abs"]), 1e-9, 1e-300)))
        check(ok, f"n = 2 at x = {a[list(a)[2]]}: the n-ball analysis agrees with the two-ball path "
                  f"(balanced stable {frac} / {b['balanced_stable']}, n_stable {a['n_stable']} / {b['n_stable']})")


if __name__ == "__main__":
    if sys.argv[1] == "equilibria":
        equilibria_mode(*sys.argv[2:9])
    else:
        ballcount_mode(*sys.argv[2:6])
    sys.exit(1 if failures else 0)
