#!/usr/bin/env python3
"""`continue` on an anisotropic scene with n >= 3 balls (docs/model.md §10.16).

  check_floquet_continue_n.py STABILITY_SCAN SCENE

1. Isotropic limit, against an independent path: the scene with stiffness_x = stiffness_y = k_bar,
   damping_x = damping_y = c_bar and no cross terms (still an anisotropic-support scene, so the
   Floquet route runs) and the same scene in the isotropic form (stiffness, damping: the
   eigenvalue continuation of model.md §13.7, Hopf points located by Brent on the crossing
   pair's real part). rho = exp(lambda pi/omega) (§10.7), so every balanced sample's Hopf point
   must be a Floquet crossing of the same sample and vice versa, to 1e-8 relative (Brent:
   1e-13 of the chord; the bisection: 1e-12 bracket, Magnus' ~1e-11 on ln|rho|).
2. The anisotropic scene: every row has deflated = n - 2; ln rho_abs_max changes sign across
   each crossing's bracket (stable on one side) in floquet_branch_omega.csv; at least one
   crossing (the window between the principal critical speeds, as for two balls).
3. --cycles and --param2 are refused (exit 2), nothing written.
"""
import csv
import io
import os
import re
import subprocess
import sys
import tempfile

exe, scene = sys.argv[1], sys.argv[2]
failures = []
SAMPLES = "4"  # per sheet: a quick run (the samples are those of §13.5)


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(io.StringIO("".join(l for l in f if not l.startswith("#")))))


def run(args, expect=0):
    r = subprocess.run([exe] + args, capture_output=True, text=True)
    if r.returncode != expect:
        failures.append(f"{' '.join(args)}: exit {r.returncode}, expected {expect}\n{r.stderr[-2000:]}")
    return r


text = open(scene).read()
kx = float(re.search(r"stiffness_x = (\S+)", text).group(1))
ky = float(re.search(r"stiffness_y = (\S+)", text).group(1))
cx = float(re.search(r"damping_x = (\S+)", text).group(1))
cy = float(re.search(r"damping_y = (\S+)", text).group(1))
k, c = (kx + ky) / 2, (cx + cy) / 2
with tempfile.TemporaryDirectory() as tmp:
    def variant(name, rotor):
        body = re.sub(r"stiffness_x = .*\nstiffness_y = .*\nstiffness_xy = .*\ndamping_x = .*\ndamping_y = .*\n"
                      r"damping_xy = .*\n", rotor, text)
        path = os.path.join(tmp, name)
        open(path, "w").write(body)
        return path

    iso_support = variant("iso_support.toml", f"stiffness_x = {k!r}\nstiffness_y = {k!r}\nstiffness_xy = 0.0\n"
                          f"damping_x = {c!r}\ndamping_y = {c!r}\ndamping_xy = 0.0\n")
    iso = variant("iso.toml", f"stiffness = {k!r}\ndamping = {c!r}\n")
    common = ["--param", "omega", "--to", "150", "--set-samples", SAMPLES, "--no-chart"]
    run(["continue", iso_support] + common + ["-o", os.path.join(tmp, "f")])
    run(["continue", iso] + common + ["-o", os.path.join(tmp, "e")])
    crossings = rows(os.path.join(tmp, "f", "floquet_crossings_omega.csv"))
    hopf = [r for r in rows(os.path.join(tmp, "e", "special_omega.csv")) if r["label"] == "HB" and r["family"] == "balanced"]
    if not hopf:
        failures.append("isotropic form: no Hopf point on a balanced sample (the comparison is empty)")
    for h in hopf:
        w = float(h["omega"])
        near = [cr for cr in crossings if cr["member"] == h["member"] and abs(float(cr["omega"]) - w) <= 1e-8 * w]
        print(f"sample {h['member']}: Hopf at {w!r}, Floquet crossing {[cr['omega'] for cr in near]}")
        if len(near) != 1:
            failures.append(f"sample {h['member']}: Hopf at omega = {w!r} has {len(near)} Floquet crossings within 1e-8")
    if len(crossings) != len(hopf):
        failures.append(f"{len(crossings)} Floquet crossings against {len(hopf)} Hopf points of balanced samples")

    out = os.path.join(tmp, "a")
    run(["continue", scene] + common + ["-o", out])
    n = len(re.findall(r"^\[\[ball\]\]", text, re.M))
    branch = rows(os.path.join(out, "floquet_branch_omega.csv"))
    if not branch or any(int(r["deflated"]) != n - 2 for r in branch):
        failures.append(f"anisotropic: rows missing or deflated != {n - 2}")
    found = rows(os.path.join(out, "floquet_crossings_omega.csv"))
    print(f"anisotropic: {len(branch)} branch points, {len(found)} crossings")
    if not found:
        failures.append("anisotropic: no crossing located")
    for cr in found:
        lo, hi = sorted((float(cr["bracket_lower"]), float(cr["bracket_upper"])))
        if not (lo <= float(cr["omega"]) <= hi) or hi - lo > 1e-10 * hi:
            failures.append(f"anisotropic crossing {cr}: value outside or bracket wider than 1e-10")

    for extra in (["--cycles"], ["--param2", "d", "--to2", "3e-3"]):
        bad = os.path.join(tmp, "bad")
        run(["continue", scene] + common + extra + ["-o", bad], expect=2)
        if os.path.exists(bad) and os.listdir(bad):
            failures.append(f"{extra[0]}: files written after a refusal")

if failures:
    print("FAIL:\n" + "\n".join(failures))
    sys.exit(1)
print("ok")
