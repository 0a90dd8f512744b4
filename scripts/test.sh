#!/usr/bin/env bash
# The test command: installs the DEM codes the cross-code tests run (Debian packages,
# idempotent), then runs every test in release mode.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dem-codes.sh
bash scripts/install-sweep-tools.sh
cargo test --release
