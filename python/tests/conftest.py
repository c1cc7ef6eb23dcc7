"""Shared helpers: the command-line binary the Python API is compared with."""

import csv
import io
import os
import re
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
WAVY = Path(os.environ.get("WAVY_BIN", REPO / "target" / "release" / "wavy"))


def cli(*args, check_rc=None):
    """Runs `wavy ARGS`: (exit code, stdout, stderr)."""
    if not WAVY.exists():
        pytest.fail(f"{WAVY} is missing: build it with `cargo build --release` (make test does)")
    p = subprocess.run([str(WAVY), *map(str, args)], capture_output=True, text=True, cwd=REPO)
    if check_rc is not None:
        assert p.returncode == check_rc, (args, p.returncode, p.stderr)
    return p.returncode, p.stdout, p.stderr


def cli_rows(*args):
    """The CSV rows of a successful `wavy ARGS`, as dicts of strings."""
    _, out, _ = cli(*args, check_rc=0)
    return list(csv.DictReader(io.StringIO(out)))


def cli_error(*args):
    """The message of a failed `wavy ARGS` (stderr without `error: `) and its exit code."""
    rc, _, err = cli(*args)
    assert rc != 0, args
    assert err.startswith("error: "), err
    return err[len("error: "):].rstrip("\n"), rc


def python_words(message):
    """A command-line message as Python says it: each flag `--some-name` is the argument
    `some_name` (docs/python.md, Errors)."""
    return re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_"), message)
