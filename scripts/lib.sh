# Sourced by the project's shell scripts (not run on its own).

# find_verify: build `verify` (release) with cargo and set VERIFY to where cargo put it
# (CARGO_TARGET_DIR and cargo's configuration honoured). Exits with a message, before the caller
# has written anything, when it cannot.
find_verify() {
  local root target
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  if ! command -v cargo >/dev/null 2>&1; then
    echo "$(basename "$0"): cargo not found: it builds the verify binary this script runs" >&2
    exit 1
  fi
  (cd "$root" && cargo build --release --quiet --bin verify) || {
    echo "$(basename "$0"): cargo could not build verify; nothing was written" >&2
    exit 1
  }
  target=$(cd "$root" && cargo metadata --format-version 1 --no-deps |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])') || {
    echo "$(basename "$0"): cargo metadata failed; nothing was written" >&2
    exit 1
  }
  VERIFY="$target/release/verify"
  if [ ! -x "$VERIFY" ]; then
    echo "$(basename "$0"): $VERIFY is not an executable after the build; nothing was written" >&2
    exit 1
  fi
}
