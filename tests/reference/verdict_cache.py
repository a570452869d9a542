#!/usr/bin/python3
"""Verdicts of the reference checks, remembered within one CI run (.ci/run;
docs/developers.md, "CI").

CI runs every reference check twice: on the Release build, then on the sanitized build.
The two builds print the same bytes whenever they compute the same doubles, and then the
second check would repeat the first one's mpmath work (tens of seconds each) only to reach
the same verdict. When the environment variable ABU_REFERENCE_CACHE names a directory, a
check that passes records its key there; a check whose key is recorded passes without
recomputing the reference, and says so.

The key is the SHA-256 of
  * every file of tests/reference (the checks' code and the references they import),
  * the check's arguments, except the binary's path and the program's temporary output paths,
  * the bytes of every file an argument names (the scene),
  * the program's output, without its command line ('# command: ...' in CSV, '"command": ...'
    in JSON: the one line that names the binary and the temporary paths).
A recorded key therefore means: the same check, on the same scene, of the same printed
numbers, passed earlier in this run; a deterministic check gives the same verdict. Any byte
that differs (a wrong number from the sanitized build, or a last-digit difference between
optimization levels) misses, and the check runs in full against the reference.

Without ABU_REFERENCE_CACHE nothing is read or written. The directory is CI's temporary one,
never part of the tree.

As a wrapper of a comparison that reads the program's output from files:
    verdict_cache.py OUTPUT [OUTPUT ...] -- COMMAND [ARG ...]
passes at once if recorded, otherwise runs COMMAND and records its key if it exits 0; the
exit status is COMMAND's. Python checks that run the program themselves call key(),
recorded() and record().
"""
import hashlib
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ENV = "ABU_REFERENCE_CACHE"
# the program's own command line: the only line of its output that names the binary and the
# temporary output paths (neither is a result)
COMMAND_LINE = re.compile(rb'^(# command: |\s*"command": ).*$', re.MULTILINE)


def directory():
    d = os.environ.get(ENV, "")
    return d if d else None


def _update_file(h, path):
    with open(path, "rb") as f:
        data = f.read()
    h.update(b"%d:" % len(data))
    h.update(data)


def key(args, outputs):
    """The key of a check with these arguments (binary and temporary paths left out) of the
    program's outputs (bytes or str); None without ABU_REFERENCE_CACHE."""
    if directory() is None:
        return None
    h = hashlib.sha256(b"abu reference verdict 1\n")
    for name in sorted(os.listdir(HERE)):
        path = os.path.join(HERE, name)
        if os.path.isfile(path) and name.endswith((".py", ".sh")):
            h.update(name.encode() + b"\n")
            _update_file(h, path)
    for a in args:
        a = str(a)
        h.update(b"arg %d:%s\n" % (len(a.encode()), a.encode()))
        if os.path.isfile(a):
            _update_file(h, a)
    for out in outputs:
        data = out.encode() if isinstance(out, str) else bytes(out)
        data = COMMAND_LINE.sub(b"", data)
        h.update(b"output %d:" % len(data))
        h.update(data)
    return h.hexdigest()


def recorded(k):
    """True when the check of key k passed earlier in this run (and says so)."""
    if k is None:
        return False
    path = os.path.join(directory(), k)
    if not os.path.isfile(path):
        return False
    print(f"PASS (verdict cache): the program's output is byte for byte the one that passed this check "
          f"earlier in this run ({ENV}/{k[:16]}); the reference is not computed again")
    return True


def record(k):
    """Records a pass of the check of key k (atomic: checks run in parallel)."""
    if k is None:
        return
    d = directory()
    os.makedirs(d, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp")
    with os.fdopen(fd, "w") as f:
        f.write("pass\n")
    os.replace(tmp, os.path.join(d, k))


def main(argv):
    if "--" not in argv or argv.index("--") < 2 or argv.index("--") == len(argv) - 1:
        print("usage: verdict_cache.py OUTPUT [OUTPUT ...] -- COMMAND [ARG ...]", file=sys.stderr)
        return 2
    sep = argv.index("--")
    outputs, command = argv[1:sep], argv[sep + 1:]
    k = None
    if directory() is not None:
        args = list(command)
        for i, out in enumerate(outputs):
            args = [a.replace(out, f"@OUTPUT{i}") for a in args]
        data = []
        for out in outputs:
            with open(out, "rb") as f:
                data.append(f.read())
        k = key(args, data)
        if recorded(k):
            return 0
    sys.stdout.flush()
    rc = subprocess.run(command).returncode
    if rc == 0:
        record(k)
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv))
