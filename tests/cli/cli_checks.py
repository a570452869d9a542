"""What the Python checks of the real binary share: the binary and source tree from argv, a check
that prints ok / FAIL and counts failures, a run of the binary, a CSV's rows by column name.

    from cli_checks import BIN, SRC, check, run, rows_of, finish
    check("exit 0", run("equilibria", scene).returncode == 0)
    finish()   # prints the count, exits 1 on any failure
"""
import csv
import os
import subprocess
import sys

BIN, SRC = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
_fails = [0]


def check(name, ok):
    print(("ok   " if ok else "FAIL ") + name)
    _fails[0] += 0 if ok else 1


def run(*args):
    return subprocess.run([BIN, *args], capture_output=True, text=True)


def rows_of(path):
    return list(csv.DictReader(line for line in open(path) if not line.startswith("#")))


def failures():
    return _fails[0]


def finish():
    print("all checks passed" if _fails[0] == 0 else f"{_fails[0]} failure(s)")
    sys.exit(1 if _fails[0] else 0)
