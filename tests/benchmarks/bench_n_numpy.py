#!/usr/bin/python3
"""numpy.linalg.eigvals on exactly the Jacobians that `bench_n` wrote, and the table.

For each ball count n, the double Jacobians of every equilibrium (aligned and balanced
samples) are stacked into one (count, 2n+4, 2n+4) array and passed to
numpy.linalg.eigvals (LAPACK dgeev per matrix, balancing on), median of --repeat runs,
reported in us per eigenproblem. Then numpy's eigenvalues are scored against the
analyzer's (refined, which agree with the 40-digit mpmath reference to 1e-8):

  worst rel. error  max of |lambda_np - lambda| / |lambda| over every eigenvalue of the
                    spectra whose refinement converged (the others keep some QR values;
                    their count and the max over all are printed below), paired
                    greedily, smallest analyzer modulus first, by relative distance (as
                    bench_errors.py); structural zeros of the balanced set (exactly 0 in
                    the analyzer) are left out and reported apart as max |lambda_np| /
                    max |lambda| over them.
  wrong verdicts    equilibria where numpy's max Re < 0 disagrees with the analyzer's
                    verdict (stable / unstable; the analyzer's marginal ones are left
                    out), "naive / zeros removed": naive takes every numpy eigenvalue,
                    zeros removed drops the ones paired with the analyzer's structural
                    zeros (what an engineer who knows the set's dimension would do).

    bench_n_numpy.py OUT.bin OUT.csv [--repeat 5]

Run with OPENBLAS_NUM_THREADS=1 (one core, as the analyzer's timing).
"""
import argparse
import csv
import time

import numpy as np


def read_blocks(path):
    blocks = {}
    with open(path, "rb") as f:
        while True:
            head = np.fromfile(f, dtype="<i8", count=4)
            if head.size == 0:
                break
            n, count, dim, _ = (int(v) for v in head)
            meta = np.fromfile(f, dtype="<i8", count=count * 4).reshape(count, 4)
            J = np.fromfile(f, dtype="<f8", count=count * dim * dim).reshape(count, dim, dim)
            ev = np.fromfile(f, dtype="<f8", count=count * dim * 2).reshape(count, dim, 2)
            structural = np.fromfile(f, dtype="<i8", count=count * dim).reshape(count, dim).astype(bool)
            qr = np.fromfile(f, dtype="<f8", count=count * dim * 2).reshape(count, dim, 2)
            blocks[n] = dict(meta=meta, J=J, ev=ev[..., 0] + 1j * ev[..., 1], structural=structural,
                             qr=qr[..., 0] + 1j * qr[..., 1])
    return blocks


def pair(ref, got):
    """Greedy pairing over a stack: ref, got (count, dim) complex. Returns got reordered
    so that out[:, k] is paired with ref[:, k]."""
    count, dim = ref.shape
    rows = np.arange(count)
    order = np.argsort(np.abs(ref), axis=1, kind="stable")
    used = np.zeros((count, dim), dtype=bool)
    out = np.empty_like(ref)
    for step in range(dim):
        k = order[:, step]
        r = ref[rows, k]
        scale = np.where(r != 0, np.abs(r), 1.0)
        d = np.abs(got - r[:, None]) / scale[:, None]
        d[used] = np.inf
        j = np.argmin(d, axis=1)
        used[rows, j] = True
        out[rows, k] = got[rows, j]
    return out


def score(b, got):
    ref, structural, meta = b["ev"], b["structural"], b["meta"]
    paired = pair(ref, got)
    big = np.abs(ref).max(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.abs(paired - ref) / np.abs(ref)
    rel = np.where(structural, 0.0, rel)
    converged = meta[:, 3] == 1
    worst = float(rel[converged].max()) if converged.any() else float("nan")
    worst_all = float(rel.max()) if rel.size else 0.0
    zeros = np.where(structural, np.abs(paired) / big[:, None], 0.0)
    worst_zero = float(zeros.max()) if structural.any() else None
    verdict = meta[:, 1]
    decided = verdict != 2
    ab_naive = got.real.max(axis=1)
    ab_clean = np.where(structural, -np.inf, paired.real).max(axis=1)
    analyzer_stable = verdict == 0
    wrong_naive = int(np.sum(decided & ((ab_naive < 0) != analyzer_stable)))
    wrong_clean = int(np.sum(decided & ((ab_clean < 0) != analyzer_stable)))
    return worst, worst_zero, wrong_naive, wrong_clean, int(np.sum(~decided)), worst_all


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin")
    ap.add_argument("csv")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    np.linalg.eigvals(np.eye(2))  # loads LAPACK
    libs = sorted({line.split()[-1] for line in open("/proc/self/maps")
                   if any(k in line for k in ("blas", "lapack", "mkl", "blis"))})
    blas = []
    try:
        from threadpoolctl import threadpool_info
        blas = [f"{lib.get('internal_api')} {lib.get('version')}, kernel {lib.get('architecture')}, "
                f"{lib.get('num_threads')} thread(s)" for lib in threadpool_info() if lib.get("user_api") == "blas"]
    except ImportError:
        pass
    print(f"# numpy {np.__version__}; BLAS/LAPACK loaded: {', '.join(libs) or '?'}; threadpoolctl: "
          f"{'; '.join(blas) or 'no BLAS it knows (reference BLAS/LAPACK: single-threaded)'}")
    blocks = read_blocks(args.bin)
    rows = {int(r["n"]): r for r in csv.DictReader(open(args.csv))}
    head = (f"{'n':>3} {'equilibria (al. + bal.)':>24} {'analyzer':>9} {'refined':>9} {'dense QR':>9} "
            f"{'numpy':>9} {'analyzer':>9} {'numpy worst':>11} {'wrong verdicts':>15} {'Eigen QR':>9}")
    units = (f"{'':>3} {'':>24} {'us/eq':>9} {'us/eq':>9} {'us/eq':>9} {'us/eq':>9} {'/ numpy':>9} "
             f"{'rel. error':>11} {'naive / -zeros':>15} {'rel. err':>9}")
    lines = []
    notes = []
    cell_lines = {}
    for n, b in sorted(blocks.items()):
        J = np.ascontiguousarray(b["J"])
        np.linalg.eigvals(J)  # warm-up
        times = []
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            got = np.linalg.eigvals(J)
            times.append(time.perf_counter() - t0)
        us = float(np.median(times)) / len(J) * 1e6
        if "map_cell_us" in rows.get(n, {}):
            cell_ms = float(rows[n]["map_cell_us"]) / 1e3
            np_ms = us * len(J) / 1e3
            cell_lines[n] = f"{n:>3} {len(J):>10} {cell_ms:>17.3f} {np_ms:>14.3f} {np_ms / cell_ms:>16.3f}x"
            if "map_cell_general_us" in rows[n]:
                general_ms = float(rows[n]["map_cell_general_us"]) / 1e3
                cell_lines[n] += f" {general_ms:>18.3f} {np_ms / general_ms:>16.3f}x"
        got = np.asarray(got, dtype=complex)
        worst, worst_zero, wrong_naive, wrong_clean, marginal, worst_all = score(b, got)
        qr_worst, qr_zero, qr_wrong_naive, qr_wrong_clean, _, _ = score(b, b["qr"])
        r = rows[n]
        aligned, balanced = int(r["aligned"]), int(r["balanced"])
        analyzer = float(r["analyze_us"])
        lines.append(f"{n:>3} {len(J):>8} ({aligned:>5} + {balanced:>5}) {analyzer:>9.2f} {float(r['refined_us']):>9.2f} "
                     f"{float(r['qr_us']):>9.2f} {us:>9.2f} {analyzer / us:>8.1f}x {worst:>11.2e} "
                     f"{wrong_naive:>7} / {wrong_clean:<5} {qr_worst:>9.2e}")
        split = (f"n = {n:>2}: analyze = find_equilibria {float(r['equilibria_us']):.2f} + spectra "
                 f"{float(r['refined_us']):.2f} us/eq (aligned {float(r['refined_aligned_us']):.2f}, balanced "
                 f"{float(r['refined_balanced_us']):.2f}); of a spectrum: linearize {float(r['linearize_us']):.2f}, "
                 f"structured QRs {float(r['structured_us']):.2f}; dense QR aligned {float(r['qr_aligned_us']):.2f}, "
                 f"balanced {float(r['qr_balanced_us']):.2f}")
        if worst_zero is not None:
            split += (f"; structural zeros: numpy max |lambda|/max|lambda| {worst_zero:.1e}, "
                      f"Eigen QR {qr_zero:.1e}, Eigen QR wrong verdicts {qr_wrong_naive} / {qr_wrong_clean}")
        flags = [f"{r[k]} {k.replace('_', ' ')}" for k in ("not_converged", "ill_conditioned") if int(r[k])]
        if int(r["spectrum_not_converged"]):
            flags.append(
                f"refinement not converged in {r['spectrum_not_converged']} spectra (aligned {r['nconv_aligned']}, "
                f"balanced {r['nconv_balanced']}; some eigenvalues kept at their QR value; left out of the "
                f"worst error, over all spectra numpy's is {worst_all:.2e}); refined us/eq converged / not: "
                f"aligned {float(r['refined_aligned_conv_us']):.0f} / {float(r['refined_aligned_nconv_us']):.0f}, "
                f"balanced {float(r['refined_balanced_conv_us']):.0f} / {float(r['refined_balanced_nconv_us']):.0f}")
        if int(r["timed_aligned"]) < aligned or int(r["timed_balanced"]) < balanced:
            flags.append(f"refined/structured timed on {r['timed_aligned']} aligned + {r['timed_balanced']} balanced")
        if marginal:
            flags.append(f"{marginal} marginal (left out of the verdicts)")
        if flags:
            split += "; " + ", ".join(flags)
        notes.append(split)
    print(f"# cost per equilibrium against n (ring scene, 1 thread, median of {args.repeat} for numpy, "
          f"of {rows[min(rows)]['repeats']} for the analyzer)")
    print(head)
    print(units)
    for line in lines:
        print(line)
    for note in notes:
        print(note)
    # A map cell (CellAnalyzerN::analyze: every equilibrium and spectrum of the cell)
    # against numpy's stacked eigvals of the same cell's Jacobians, one core each.
    print("# map cell cost against n: analyzer (one cell, 1 thread) vs numpy.linalg.eigvals of the cell's Jacobians "
          "(stacked, 1 thread; equilibria not counted for numpy); analyzer on a friction axis (the column keeps "
          "its equilibria) and on a general axis (U: every cell finds them again)")
    print(f"{'n':>3} {'equilibria':>10} {'analyzer ms/cell':>17} {'numpy ms/cell':>14} {'numpy / analyzer':>17}"
          f" {'general ms/cell':>18} {'numpy / general':>16}")
    for n, line in sorted(cell_lines.items()):
        print(line)


if __name__ == "__main__":
    main()
