#!/usr/bin/env bash
# Build the Python package (python/) as a user would, `pip install ./python`, into the virtual
# environment .venv-python (made here if absent), and run its tests (pytest, including the
# notebook-style example python/examples/quickstart.py). Needs Python >= 3.9 with venv and pip;
# pip fetches maturin, NumPy, pandas and pytest from PyPI. The tests compare the package with
# the `verify` binary built from the same sources.
set -euo pipefail
cd "$(dirname "$0")/.."

python3 -m venv .venv-python
.venv-python/bin/python -m pip install --quiet --upgrade pip
.venv-python/bin/python -m pip install --quiet "./python[test]"
cargo build --release --bin verify
# From the repository's root, so that `import ringcontact` is the installed package.
RINGCONTACT_VERIFY="$PWD/target/release/verify" .venv-python/bin/python -m pytest python/tests -q "$@"
