#!/usr/bin/env python3
"""The dry figures on every row of `sweep` and `continue` of a smooth coulomb / stribeck scene
(docs/model.md §14.10), checked on the real binary.

    check_dry_rows.py BINARY SOURCE_DIR

Contract:
- stderr leads with the dry verdict over the values ("dry friction as it is ..."), naming the
  worst V and where; the smooth law's lines come after it;
- each row's dry_* cells are `equilibria --format json`'s dry_friction figures at the row's value
  (the same stick set: equal to 1e-12 relative, the rounding of a printed double);
- dry_bare_rotor_q_abs is (16.5.1), U w^2 / |k - M w^2 + i c w| with M = M_r + sum m, computed
  here (1e-12 relative: a closed form in double); dry_worst_over_bare is V / that;
- every state of a value carries the same cells; a continuation's special rows too;
- an n-ball sweep's summary rows carry them; a stribeck scene says mu_i = mu_s; a viscous scene
  has no dry_* columns;
- --dry: auto leaves them out when more than 24 values need a scan of the torus (the bound
  (14.10.1) decides the others for free) and says so first; off leaves them out silently; a
  continuation's figures are the same bytes on 1 and 2 threads.
"""
import json
import os
import re
import tempfile

from cli_checks import BIN, SRC, check, finish, rows_of, run

DEFAULT = os.path.join(SRC, "data/scenes/default.toml")


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def equilibria_dry(scene, *sets):
    r = run("equilibria", scene, "--format", "json", *[x for s in sets for x in ("--set", s)])
    return json.loads(r.stdout)["dry_friction"]


with tempfile.TemporaryDirectory() as work:
    # mu small enough that the set is a few islands at some speeds and V passes the bare rotor
    low_mu = os.path.join(work, "low_mu.toml")
    open(low_mu, "w").write(re.sub(r"(?m)^mu = .*$", "mu = 0.00005", open(DEFAULT).read()))
    M_r, k, c, U, m = 0.12, 7500.0, 2.0, 6e-7, 2 * 3.3e-5

    out = os.path.join(work, "sweep")
    r = run("sweep", low_mu, "--param", "omega", "--from", "130", "--to", "1000", "--steps", "6", "-o", out, "--no-chart")
    check("sweep of a coulomb scene: exit 0", r.returncode == 0)
    check("sweep: stderr leads with the dry verdict over the values",
          r.stderr.startswith("dry friction as it is (coulomb-set with the same mu_i") and "at most V =" in
          r.stderr.splitlines()[0])
    rows = rows_of(os.path.join(out, "sweep_omega.csv"))
    by_value = {}
    for row in rows:
        by_value.setdefault(row["omega"], set()).add(tuple(row[c_] for c_ in row if c_.startswith("dry_")))
    check("sweep: every state of a value carries the same dry cells", all(len(v) == 1 for v in by_value.values()))
    for value in ("130", "420", "1000"):
        cells = dict(zip(("V", "V_E", "bare", "ratio", "fraction"), [float(x) if x else None for x in
                                                                      next(iter(by_value[value]))]))
        d = equilibria_dry(low_mu, f"omega={value}")
        w = float(value)
        bare = U * w * w / abs(complex(k - (M_r + m) * w * w, c * w))
        check(f"sweep at omega={value}: V, V_E, fraction are equilibria's (1e-12)",
              close(cells["V"], d["worst_q_abs"], 1e-12) and close(cells["V_E"], d["worst_q_abs_any"], 1e-12) and
              close(cells["fraction"], d["area_fraction"], 1e-12))
        check(f"sweep at omega={value}: the bare rotor is (16.5.1) (1e-12), the ratio V / bare",
              close(cells["bare"], bare, 1e-12) and close(cells["ratio"], cells["V"] / cells["bare"], 1e-12))

    # mu = 0.0008: the bound (14.10.1) does not decide (1.12 > 1), every value is scanned
    mid_mu = os.path.join(work, "mid_mu.toml")
    open(mid_mu, "w").write(re.sub(r"(?m)^mu = .*$", "mu = 0.0008", open(DEFAULT).read()))
    texts = []
    for threads in ("1", "2"):
        out = os.path.join(work, "continue" + threads)
        r = run("continue", mid_mu, "--param", "omega", "--to", "1000", "--dry", "on", "--threads", threads, "-o", out,
                "--no-chart")
        texts.append([line for line in open(os.path.join(out, "branch_omega.csv")) if not line.startswith("# command")])
    check("continue --dry on: exit 0, the same rows on 1 and 2 threads",
          r.returncode == 0 and texts[0] == texts[1] and len(texts[0]) > 10)
    check("continue: stderr leads with the dry verdict", r.stderr.find("dry friction as it is") >= 0 and
          r.stderr.find("dry friction as it is") < r.stderr.find("balanced state"))
    rows = rows_of(os.path.join(out, "branch_omega.csv"))
    check("continue: every row has its dry cells", len(rows) > 10 and all(x["dry_bare_rotor_q_abs"] for x in rows))
    for row in (rows[0], rows[len(rows) // 2], rows[-1]):
        d = equilibria_dry(mid_mu, f"omega={row['omega']}")
        check(f"continue at omega={float(row['omega']):.6g}: V, V_E, fraction are equilibria's (1e-12)",
              close(float(row["dry_worst_q_abs"]), d["worst_q_abs"], 1e-12) and
              close(float(row["dry_whole_set_q_abs"]), d["worst_q_abs_any"], 1e-12) and
              close(float(row["dry_stick_fraction"]), d["area_fraction"], 1e-12))
    out = os.path.join(work, "continue_auto")
    r = run("continue", low_mu, "--set", "omega=300", "--param", "omega", "--to", "600", "-o", out, "--no-chart")
    check("continue --dry auto, about 50 values to scan: not computed, said first with how to have them",
          r.returncode == 0 and r.stderr.find("not computed here") >= 0 and "--dry on" in r.stderr and
          r.stderr.find("dry friction") < r.stderr.find("balanced state") and
          "dry_" not in open(os.path.join(out, "branch_omega.csv")).read())

    out = os.path.join(work, "sweep_n")
    r = run("sweep", os.path.join(SRC, "data/scenes/drive.toml"), "--param", "n", "--from", "2", "--to", "3", "-o", out,
            "--no-chart")
    summary = rows_of(os.path.join(out, "summary_n.csv"))
    check("n-ball sweep: the summary rows carry the dry cells",
          r.returncode == 0 and len(summary) == 2 and all(x["dry_worst_over_bare"] for x in summary))

    stribeck = os.path.join(work, "stribeck.toml")
    text = re.sub(r"(?m)^mu = .*$", "mu_c = 0.001\nmu_s = 0.002\nv_s = 0.5",
                  open(DEFAULT).read().replace('law = "coulomb"', 'law = "stribeck"'))
    open(stribeck, "w").write(text)
    out = os.path.join(work, "stribeck")
    # 101 values whose sets the bound decides with mu_s (the smooth law has no mu): computed by --dry auto
    r = run("sweep", stribeck, "--param", "omega", "--from", "800", "--to", "1000", "--steps", "100", "-o", out,
            "--no-chart")
    head = open(os.path.join(out, "sweep_omega.csv")).read() if r.returncode == 0 else ""
    check("stribeck: the dry columns are those of mu_i = mu_s, 101 values the bound decides computed", "coulomb-set with mu_i = mu_s" in head and
          "dry_worst_q_abs" in head)

    viscous = os.path.join(work, "viscous.toml")
    text = open(DEFAULT).read().replace('law = "coulomb"', 'law = "viscous"')
    open(viscous, "w").write(re.sub(r"(?m)^kappa = .*$", "", re.sub(r"(?m)^mu = .*$", "d = 1e-5", text)))
    out = os.path.join(work, "viscous")
    r = run("sweep", viscous, "--param", "omega", "--from", "400", "--to", "900", "--steps", "2", "-o", out, "--no-chart")
    check("viscous: no dry columns, no dry verdict",
          r.returncode == 0 and "dry_" not in open(os.path.join(out, "sweep_omega.csv")).read() and
          "dry friction" not in r.stderr)

    out = os.path.join(work, "many")
    r = run("sweep", low_mu, "--param", "omega", "--from", "100", "--to", "1000", "--steps", "40", "-o", out,
            "--no-chart")
    check("sweep --dry auto, 41 values to scan: not computed, said first, no dry columns",
          r.returncode == 0 and r.stderr.startswith("dry friction as it is") and "41 of the 41 values" in r.stderr and
          "dry_" not in open(os.path.join(out, "sweep_omega.csv")).read())
    out = os.path.join(work, "whole")
    r = run("sweep", DEFAULT, "--param", "omega", "--from", "800", "--to", "1000", "--steps", "300", "-o", out,
            "--no-chart")
    check("sweep --dry auto, 301 values the bound decides: computed",
          r.returncode == 0 and "dry_worst_q_abs" in open(os.path.join(out, "sweep_omega.csv")).read())
    out = os.path.join(work, "off")
    r = run("sweep", DEFAULT, "--param", "U", "--from", "1e-7", "--to", "1e-6", "--steps", "2", "--dry", "off", "-o", out,
            "--no-chart")
    check("--dry off: no dry columns, no dry line",
          r.returncode == 0 and "dry friction" not in r.stderr and
          "dry_" not in open(os.path.join(out, "sweep_U.csv")).read())

finish()
