#!/usr/bin/env bash
# Regenerates reference/: every DEM code on every canonical case at η = 0 (elastic), 0.35 (the
# paper's) and 0.7, at the default time step (elastic contact time / 1000).
# Each LAMMPS build is probed first; its records carry the conventions it was set up with.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dem-codes.sh
cargo build --release --quiet
for code in liggghts liggghts-paper yade yade-paper lammps lammps-2025 lammps-paper kratos kratos-paper; do
  for case in ball_plate ball_ball rod_end; do
    for eta in 0 0.35 0.7; do
      ./target/release/millimpact reference --code "$code" "cases/$case.toml" \
        --loss-coefficient "$eta" --save --format json > /dev/null
      echo "stored $code $case η=$eta"
    done
  done
done

# Chung & Ooi's benchmark (`millimpact benchmark chung-ooi`): every code on the six cases of
# cases/benchmarks/ at 1000 steps per contact, tests 1 and 2 elastic, test 3 at each COR set
# (η = (1 − e²)/(1 + e²), written to 17 digits so that the run is found at the benchmark's η).
# Test 2 runs twice: on each code's rigid plane, and on the same-material wall (the trap, the
# *_same_material cases). They are a store of their own, reference/benchmarks/<code>/<case>.json
# (reference/README.md). A new code build joins by its name in this list.
for code in liggghts liggghts-paper yade yade-paper lammps lammps-2025 lammps-paper kratos kratos-paper; do
  for case in chung_ooi_1_glass chung_ooi_1_limestone chung_ooi_2_aluminium chung_ooi_2_magnesium \
    chung_ooi_2_aluminium_same_material chung_ooi_2_magnesium_same_material; do
    ./target/release/millimpact reference --code "$code" "cases/benchmarks/$case.toml" \
      --loss-coefficient 0 --steps-per-contact 1000 --save --reference reference/benchmarks \
      --format json > /dev/null
    echo "stored $code $case η=0"
  done
  for case in chung_ooi_3_alumina chung_ooi_3_cast_iron; do
    for cor in 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9 1.0; do
      eta=$(awk -v e="$cor" 'BEGIN { printf "%.17g", (1 - e * e) / (1 + e * e) }')
      ./target/release/millimpact reference --code "$code" "cases/benchmarks/$case.toml" \
        --loss-coefficient "$eta" --steps-per-contact 1000 --save --reference reference/benchmarks \
        --format json > /dev/null
      echo "stored $code $case COR=$cor η=$eta"
    done
  done
done
