#!/usr/bin/env bash
# The test command: installs the DEM codes the cross-code tests run, Chromium for the report
# test and mdbook for the book (Debian packages, pinned PyPI builds and a pinned crate,
# idempotent), checks formatting and lints (Cargo.toml's [lints.clippy] adds
# cast_possible_truncation, cast_sign_loss and float_cmp), then runs every test in release mode
# (unit, integration, snapshot and doc-tests, and the book's examples; the examples are built),
# the example a user's own regression test starts from, and builds the book (docs/) and the API
# docs with warnings as errors.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dem-codes.sh
bash scripts/install-sweep-tools.sh
# Headless Chromium for the report test (opens index.html, fails on a console error).
if ! command -v chromium >/dev/null 2>&1; then
    SUDO=""
    [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get install -y --no-install-recommends chromium \
        || { $SUDO apt-get update && $SUDO apt-get install -y --no-install-recommends chromium; }
fi
# mdbook for the book, built once and kept in cargo's bin folder (0.5.4 needs rustc 1.88 or later).
mdbook="$(command -v mdbook || echo "${CARGO_HOME:-$HOME/.cargo}/bin/mdbook")"
if [ ! -x "$mdbook" ]; then
    cargo install mdbook --version 0.5.4 --locked --no-default-features --features search
fi
cargo fmt --check
cargo clippy --release --all-targets -- -D warnings \
    -W clippy::cast_possible_truncation -W clippy::cast_sign_loss -W clippy::float_cmp
cargo test --release
cargo run --release --example regression_test
"$mdbook" build docs
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps
