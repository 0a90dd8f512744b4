#!/usr/bin/env bash
# The test command: installs the DEM codes the cross-code tests run and Chromium for the
# report test (Debian packages, idempotent), then runs every test in release mode.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dem-codes.sh
# Headless Chromium for the report test (opens index.html, fails on a console error).
if ! command -v chromium >/dev/null 2>&1; then
    SUDO=""
    [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get install -y --no-install-recommends chromium \
        || { $SUDO apt-get update && $SUDO apt-get install -y --no-install-recommends chromium; }
fi
cargo test --release
