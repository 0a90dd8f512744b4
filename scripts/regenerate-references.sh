#!/usr/bin/env bash
# Regenerates reference/: every DEM code on every canonical case at η = 0 (elastic), 0.35 (the
# paper's) and 0.7, at the default time step (elastic contact time / 1000).
# Each LAMMPS build is probed first; its records carry the conventions it was set up with.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dem-codes.sh
cargo build --release --quiet
for code in liggghts liggghts-paper yade lammps lammps-2025 kratos; do
  for case in ball_plate ball_ball rod_end; do
    for eta in 0 0.35 0.7; do
      ./target/release/millimpact reference --code "$code" "cases/$case.toml" \
        --loss-coefficient "$eta" --save --format json > /dev/null
      echo "stored $code $case η=$eta"
    done
  done
done
