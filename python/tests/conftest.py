"""pytest fixtures for the abu Python module: the CLI binary to compare with and the
source tree's scenes. CTest passes both (python/CMakeLists.txt); by hand:

    PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests \
        --abu-cli=build/stability-scan --abu-source=.
"""
import csv
import io
import math
import os
import pathlib
import subprocess

import pytest


def pytest_addoption(parser):
    parser.addoption("--abu-cli", default=os.environ.get("ABU_CLI"), help="the stability-scan binary")
    parser.addoption("--abu-source", default=os.environ.get("ABU_SOURCE_DIR"), help="the source tree")


@pytest.fixture(scope="session")
def source(request):
    given = request.config.getoption("--abu-source")
    return pathlib.Path(given) if given else pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli(request, source):
    given = request.config.getoption("--abu-cli")
    path = pathlib.Path(given) if given else source / "build" / "stability-scan"
    if not path.exists():
        pytest.fail(f"no stability-scan binary at {path} (pass --abu-cli)")
    return str(path)


@pytest.fixture(scope="session")
def default_scene(source):
    return source / "data" / "scenes" / "default.toml"


@pytest.fixture
def run_cli(cli):
    """Runs the CLI with ARGS; returns the CompletedProcess (text mode)."""
    def run(*args, check=True):
        p = subprocess.run([cli, *map(str, args)], capture_output=True, text=True, timeout=600)
        if check and p.returncode != 0:
            raise AssertionError(f"stability-scan {' '.join(map(str, args))} exited {p.returncode}: {p.stderr}")
        return p
    return run


def read_csv(path_or_text):
    """The rows of one of the CLI's CSVs (comment lines '#' skipped) as dicts of strings."""
    text = path_or_text if "\n" in str(path_or_text) else pathlib.Path(path_or_text).read_text()
    lines = [line for line in text.splitlines() if not line.startswith("#")]
    return list(csv.DictReader(io.StringIO("\n".join(lines) + "\n")))


def number(cell):
    """A CSV cell as a float; an empty cell (not applicable) as NaN."""
    return float(cell) if cell != "" else math.nan


def same(a, b):
    """Bit-identical doubles (NaN equals NaN: both 'not applicable')."""
    a, b = float(a), float(b)
    return (math.isnan(a) and math.isnan(b)) or a == b
