#!/usr/bin/python3
"""Benchmark (not a test): the rightmost 10 eigenvalues of the gyroscopic chain pencil
(docs/model.md §19, tests/benchmarks/sparse_chain.hpp) against the number of states, by
abu's ARPACK shift-invert (bench_sparse_spectrum) and by scipy.sparse.linalg.eigs on the
SAME matrices (Matrix Market files the C++ side writes) in the same run, each size in fresh
processes so that their peak memory is their own; a dense solver where it fits.

    tests/benchmarks/sparse_spectrum_scipy.py build/tests/benchmarks/bench_sparse_spectrum \
        [--states 100 1000 10000 100000] [--dense-max 3000] [--repeat 3]

Both sides solve A v = lambda B v for the k = 10 eigenvalues nearest sigma = 0 (one real shift;
the chain's rightmost), tolerance 1e-12, no eigenvectors kept beyond the residuals. scipy:
eigs(A, k, M=B, sigma=0, tol=1e-12), i.e. ARPACK dnaupd mode 3 with SuperLU's splu of A
(real arithmetic); abu: znaupd on (A - 0 B)^-1 B with Eigen's SparseLU (complex arithmetic).
Memory: the peak resident size during the solve (VmHWM reset through /proc/self/clear_refs
before it) minus the resident size before it.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time


def status_kb(key):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return -1


def one_scipy(directory, n, k, dense):
    import numpy as np
    import scipy.io
    import scipy.linalg
    import scipy.sparse.linalg as sla

    a = scipy.io.mmread(os.path.join(directory, f"A_{n}.mtx")).tocsc()
    b = scipy.io.mmread(os.path.join(directory, f"B_{n}.mtx")).tocsc()
    before = status_kb("VmRSS")
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
    t0 = time.perf_counter()
    vals, vecs = sla.eigs(a, k=k, M=b, sigma=0.0, tol=1e-12)
    seconds = time.perf_counter() - t0
    peak = status_kb("VmHWM")
    res = [float(np.linalg.norm(a @ vecs[:, i] - vals[i] * (b @ vecs[:, i]))
                 / (abs(vals[i]) * np.linalg.norm(b @ vecs[:, i]))) for i in range(len(vals))]
    out = {"seconds": seconds, "peak_kb": peak - before, "values": [[v.real, v.imag] for v in vals],
           "worst_residual": max(res)}
    if dense:
        t0 = time.perf_counter()
        scipy.linalg.eigvals(a.toarray(), b.toarray())
        out["dense_seconds"] = time.perf_counter() - t0
    print(json.dumps(out))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bench", nargs="?", help="path of bench_sparse_spectrum")
    ap.add_argument("--states", type=int, nargs="+", default=[100, 1000, 10000, 100000])
    ap.add_argument("--k", type=int, default=10)
    ap.add_argument("--dense-max", type=int, default=3000)
    ap.add_argument("--repeat", type=int, default=3, help="runs per side and size; the fastest is reported")
    ap.add_argument("--one", nargs=2, help=argparse.SUPPRESS)  # internal: DIR N
    ap.add_argument("--dense", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.one:
        one_scipy(args.one[0], int(args.one[1]), args.k, args.dense)
        return 0
    if not args.bench:
        ap.error("the path of bench_sparse_spectrum is needed")
    import numpy as np
    import scipy
    print(f"# scipy {scipy.__version__}, numpy {np.__version__}; "
          f"OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', '(unset)')}")
    print("| states | nnz(A) | abu s | scipy s | scipy / abu | abu MB | scipy MB | abu dense s | scipy dense s "
          "| max rel. diff abu-scipy | abu worst residual | scipy worst residual | status |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rc = 0
    with tempfile.TemporaryDirectory() as d:
        for states in args.states:
            dense = states <= args.dense_max
            cmd = [args.bench, "--states", str(states), "--dir", d, "--k", str(args.k)] + (["--dense"] if dense else [])
            # Alternating runs, fresh processes each; the fastest of `repeat` per side (the
            # machine is shared: the minimum is the least disturbed), memory of the first.
            c = p = None
            for rep in range(args.repeat):
                r = subprocess.run(cmd if rep == 0 else [x for x in cmd if x != "--dense"],
                                   capture_output=True, text=True)
                if r.returncode not in (0, 3):
                    print(r.stderr, file=sys.stderr)
                    return 1
                cr = json.loads(r.stdout)
                n = cr["states"]
                s = subprocess.run([sys.executable, __file__, "--one", d, str(n), "--k", str(args.k)]
                                   + (["--dense"] if dense and rep == 0 else []), capture_output=True, text=True)
                if s.returncode != 0:
                    print(s.stderr, file=sys.stderr)
                    return 1
                pr = json.loads(s.stdout)
                if c is None:
                    c, p = cr, pr
                else:
                    c["seconds"] = min(c["seconds"], cr["seconds"])
                    p["seconds"] = min(p["seconds"], pr["seconds"])
            abu_vals = []
            with open(os.path.join(d, f"abu_{n}.csv")) as f:
                next(f)
                for line in f:
                    re_, im_, _ = line.split(",")
                    abu_vals.append(complex(float(re_), float(im_)))
            sp_vals = [complex(*v) for v in p["values"]]
            # abu returns the k rightmost (a pair the k-th splits whole), scipy the k nearest 0:
            # compare each scipy value with the nearest abu value.
            diff = max(min(abs(a - v) / abs(v) for a in abu_vals) for v in sp_vals)
            fmt = lambda x: f"{x:.3g}" if x is not None and x >= 0 else "-"
            print(f"| {n} | {c['nnz_A']} | {c['seconds']:.3g} | {p['seconds']:.3g} | {p['seconds'] / c['seconds']:.2f} "
                  f"| {c['peak_kb'] / 1024:.1f} | {p['peak_kb'] / 1024:.1f} | {fmt(c['dense_seconds'])} "
                  f"| {fmt(p.get('dense_seconds'))} | {diff:.1e} | {c['worst_residual']:.1e} "
                  f"| {p['worst_residual']:.1e} | {c['status']} |", flush=True)
            if c["status"] != "converged":
                rc = 3
            for key in os.listdir(d):
                os.remove(os.path.join(d, key))
    return rc


if __name__ == "__main__":
    sys.exit(main())
