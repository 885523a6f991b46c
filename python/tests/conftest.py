"""Shared helpers of the Python package's tests: the repository, the `lacuna` binary (the same
library behind the command line) and a runner that returns its exit code and JSON."""

import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parent / "data"


def _binary() -> Path:
    """The built binary: $LACUNA_BIN, else $CARGO_TARGET_DIR/debug/lacuna, else target/debug."""
    if os.environ.get("LACUNA_BIN"):
        return Path(os.environ["LACUNA_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    exe = target / "debug" / "lacuna"
    if not exe.exists():
        subprocess.run(["cargo", "build", "--quiet", "--bin", "lacuna"], cwd=REPO, check=True)
    return exe


@pytest.fixture(scope="session")
def cli():
    """Runs `lacuna ARGS…`: returns (exit code, parsed JSON of standard output or None)."""
    exe = _binary()

    def run(*args):
        p = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, cwd=REPO)
        try:
            data = json.loads(p.stdout) if p.stdout.strip() else None
        except json.JSONDecodeError:
            data = None
        return p.returncode, data

    return run


@pytest.fixture(scope="session")
def cli_text():
    """Runs `lacuna ARGS…`: returns (exit code, standard output as text)."""
    exe = _binary()

    def run(*args):
        p = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, cwd=REPO)
        return p.returncode, p.stdout

    return run
