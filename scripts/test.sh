#!/usr/bin/env bash
# The test command: installs the DEM codes the cross-code tests run, GNU parallel and Slurm for
# the sweep tests, Chromium for the report test and mdbook for the book (Debian packages, pinned
# PyPI builds and a pinned crate, idempotent), checks formatting and lints (Cargo.toml's
# [lints.clippy] adds cast_possible_truncation, cast_sign_loss and float_cmp), then runs the
# tests in release mode in two tiers, each test once:
#   - the fast tier, `cargo test --release` (unit, integration, snapshot, doc-tests and the
#     book's examples; the examples are built), which needs no DEM code: run by
#     scripts/fast-tier.sh with every DEM code and tool replaced by a tripwire, it fails if one
#     of them is started;
#   - the fuzz targets (scripts/fuzz.sh: the case reader and the four deck readers on arbitrary
#     input, a minute each, from their seeds; a panic or an input that does not end fails);
#   - the live tier, `cargo test --release -- --ignored`: the tests marked
#     `#[ignore = "live: ..."]`, which run LIGGGHTS, YADE, both LAMMPS builds and Kratos, GNU
#     parallel, Slurm and Chromium, and fail (not skip) when one is missing;
# then the example a user's own regression test starts from, the book (docs/) and the API docs
# with warnings as errors.
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
# `cargo fmt` formats only the modules it can reach from the crate roots; every tracked `.rs` file
# is checked on its own too, so a module declared where rustfmt does not look is still formatted.
find src tests benches examples fuzz -name target -prune -o -name '*.rs' -print0 | xargs -0 rustfmt --edition 2024 --check
cargo clippy --release --all-targets -- -D warnings \
    -W clippy::cast_possible_truncation -W clippy::cast_sign_loss -W clippy::float_cmp
# The property tests draw their inputs from a fixed seed here, as the fuzz targets do: a failure
# CI meets is met again by the same command on the same commit (PROPTEST_RNG_SEED=1). Run
# without it, they draw fresh inputs each time.
export PROPTEST_RNG_SEED="${PROPTEST_RNG_SEED:-1}"
bash scripts/fast-tier.sh
bash scripts/fuzz.sh
cargo test --release -- --ignored
cargo run --release --example regression_test
"$mdbook" build docs
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps
