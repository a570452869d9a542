#!/usr/bin/python3
"""Independent check of the creep-mode flags (model.md (6.11)).

For the smooth coulomb and stribeck laws the program flags an eigenvalue as a creep mode
of the regularization when its analytic sensitivity s = d log|lambda| / d log kappa
(first-order perturbation with left and right eigenvectors) is within 0.1 of -1. Here s
is found with nothing of the program's: the equilibria and the Jacobian from
mp_reference.py (mpmath, model.md §5-§6), every eigenvalue of the dense Jacobian by
mpmath's QR at 80 digits at kappa e^{+h} and kappa e^{-h}, and the central difference of
log|lambda| with h = 1e-4 (truncation ~h^2 = 1e-8, rounding ~1e-70 / h: both far below
the tolerance). Each scene is checked at kappa, 10 kappa and 100 kappa ("several kappa":
the flags must not depend on where in the regime kappa sits).

Asserted: for every equilibrium and every eigenvalue the program's `creep` flag equals
|s_ref + 1| <= 0.1 (the flags, "the 1/kappa modes flagged and no others"), and its
`kappa_log_slope` equals s_ref within 1e-3 absolute (s is O(1); first-order perturbation
against a central difference, both accurate to ~1e-8 here; 1e-3 leaves room for the
double-precision eigenvectors of the program on modes 16 decades apart). An eigenvalue
with |s_ref + 1| within 0.02 of the threshold would be ambiguous: none must be.

usage: kappa_creep_reference.py STABILITY_SCAN SCENE.toml [SCENE.toml ...]
"""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_reference as R  # noqa: E402
from mpmath import mp, mpf, log  # noqa: E402

H = mpf("1e-4")
TOL_SLOPE = 1e-3
CREEP_TOL = 0.1


def spectrum_at(p, state, kappa):
    saved = p.kappa
    p.kappa = float(kappa) if not isinstance(kappa, float) else kappa
    try:
        return R.eigenvalues(R.jacobian(p, state))
    finally:
        p.kappa = saved


def nearest(z, candidates):
    return min(candidates, key=lambda c: abs(mp.log(c / z)) if c != 0 and z != 0 else abs(c - z))


def check(exe, scene, factor):
    p = R.load_scene(scene, [])
    kappa = p.kappa * factor
    p.kappa = kappa
    out = subprocess.run([exe, "equilibria", scene, "--format", "json", "--set", f"kappa={kappa!r}"],
                         capture_output=True, text=True, check=True)
    prog = json.loads(out.stdout)["equilibria"]
    ref_eq = R.equilibria(p)
    failures, flagged = [], 0
    for e in ref_eq:
        # the program's equilibrium of the same family at the same angles
        match = [x for x in prog if x["family"] == e.family and
                 abs(mp.sin((x["beta1"] - e.b1) / 2)) < 1e-8 and abs(mp.sin((x["beta2"] - e.b2) / 2)) < 1e-8]
        if len(match) != 1:
            failures.append(f"{e.family} at ({float(e.b1):.6f}, {float(e.b2):.6f}): {len(match)} program matches")
            continue
        x = match[0]
        lam0 = R.eigenvalues(R.jacobian(p, e.state))
        up = spectrum_at(p, e.state, mpf(kappa) * mp.exp(H))
        down = spectrum_at(p, e.state, mpf(kappa) * mp.exp(-H))
        for ev in x["eigenvalues"]:
            if ev.get("structural"):
                continue
            z = mp.mpc(ev["re"], ev["im"])
            if z == 0:
                continue
            z_ref = nearest(z, lam0)
            s = (log(abs(nearest(z_ref, up))) - log(abs(nearest(z_ref, down)))) / (2 * H)
            s = float(s)
            ref_creep = abs(s + 1) <= CREEP_TOL
            if abs(abs(s + 1) - CREEP_TOL) < 0.02:
                failures.append(f"{e.family}: lambda {complex(z):.6g} has s = {s:.4f}, too close to the threshold")
            flagged += ref_creep
            where = f"kappa={kappa:g} {e.family} lambda={complex(z):.6g}"
            if bool(ev["creep"]) != ref_creep:
                failures.append(f"{where}: program creep={ev['creep']}, reference s = {s:.6f}")
            if ev["kappa_log_slope"] is None or abs(ev["kappa_log_slope"] - s) > TOL_SLOPE:
                failures.append(f"{where}: program s = {ev['kappa_log_slope']}, reference {s:.6f}")
            print(f"  {where}: s_ref {s:+.6f}, program {ev['kappa_log_slope']:+.6f}, creep {ev['creep']}")
    print(f"{scene} at kappa = {kappa:g}: {len(ref_eq)} equilibria, {flagged} creep modes")
    return failures


def main():
    exe = sys.argv[1]
    bad = []
    for scene in sys.argv[2:]:
        for factor in (1.0, 10.0, 100.0):
            bad += [f"{scene}: {f}" for f in check(exe, scene, factor)]
    for f in bad:
        print("FAIL", f)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
