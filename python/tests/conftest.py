"""Shared helpers of the Python package's tests: the repository's files and the `verify` binary."""

import json
import os
import pathlib
import shutil
import subprocess

import pytest

#: The repository (python/tests/ is two folders below it).
REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


def verify_binary():
    """The `verify` command line built from the same sources: RINGCONTACT_VERIFY, else
    target/release/verify. Tests comparing with it fail when RINGCONTACT_VERIFY names a missing
    file (as in CI), and are skipped only when neither is there."""
    given = os.environ.get("RINGCONTACT_VERIFY")
    if given:
        assert os.path.exists(given), f"RINGCONTACT_VERIFY={given} does not exist"
        return given
    built = REPOSITORY / "target" / "release" / "verify"
    if built.exists():
        return str(built)
    found = shutil.which("verify")
    if found:
        return found
    pytest.skip("no verify binary (cargo build --release, or set RINGCONTACT_VERIFY)")


def run_verify(*words, cwd=REPOSITORY):
    """Run `verify WORDS...`; its standard output parsed as JSON lines or one JSON document."""
    done = subprocess.run(
        [verify_binary(), *words], cwd=cwd, capture_output=True, text=True, check=False
    )
    assert done.returncode in (0, 1), done.stderr
    return done.stdout
