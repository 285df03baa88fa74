#!/usr/bin/env bash
# Install Debian's chromium (headless browser for the report page's test, tests/suite/report_browser.rs)
# when missing. Idempotent.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if command -v chromium >/dev/null 2>&1; then
  echo "chromium already installed"
  exit 0
fi
export DEBIAN_FRONTEND=noninteractive
sudo_cmd=""
if [ "$(id -u)" != "0" ]; then sudo_cmd="sudo"; fi
$sudo_cmd apt-get update -qq
$sudo_cmd apt-get install -y -qq --no-install-recommends chromium >/dev/null
chromium --version
# The browser test is ignored when the build found no chromium (build.rs): touching build.rs
# makes the next build look again.
touch "$root/build.rs"
