"""Compares the consumer example's CSV with `stability-scan equilibria --format csv`.

   compare_equilibria.py CONSUMER_CSV CLI_CSV

Same number of equilibria, same family, member and stability verdict row by row, and every
number (q, beta, residual, spectral abscissa, eigenvalues) the same double: both programs
run the same library code on the same scene, so any difference is an install or link
defect (another build of the library, a mismatched header), not rounding. Prints the
count and the balanced states' stability (the default scene at 900 rad/s, above omega_n:
6 equilibria, both balanced states stable).
"""
import csv
import sys


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


consumer, cli = rows(sys.argv[1]), rows(sys.argv[2])
problems = []
if len(consumer) != len(cli) or not cli:
    problems.append(f"{len(consumer)} equilibria from the consumer, {len(cli)} from the CLI")
for i, (a, b) in enumerate(zip(consumer, cli)):
    for key in ("family", "member", "stable"):
        if a[key] != b[key]:
            problems.append(f"row {i + 1}: {key} {a[key]!r} (consumer) != {b[key]!r} (CLI)")
    for key in a:
        if key in ("family", "member", "stable"):
            continue
        if key not in b:
            problems.append(f"column {key} missing from the CLI's CSV")
        elif float(a[key]) != float(b[key]):
            problems.append(f"row {i + 1}: {key} {a[key]} (consumer) != {b[key]} (CLI)")
balanced = [r for r in cli if r["family"] == "balanced"]
print(f"{len(cli)} equilibria; balanced stable: {[r['stable'] for r in balanced]}")
for p in problems:
    print(p)
sys.exit(1 if problems else 0)
