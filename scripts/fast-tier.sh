#!/usr/bin/env bash
# The fast tier (`cargo test --release`, the live tests ignored), run so that it proves it
# starts no DEM code and no sweep tool: every program a live test needs is replaced by a
# tripwire that records its start and exits 1, and the run fails if any tripwire was started.
#
#   bash scripts/fast-tier.sh                  # tripwires first on PATH and as the codes' folder
#   bash scripts/fast-tier.sh --without-codes  # no DEM code, sweep tool or browser reachable at all
#
# The tripwires shadow `liggghts`, `yade`, `lmp`, GNU `parallel`, Slurm, munge and Chromium on
# PATH, and stand in for the project's own builds (MILLIMPACT_CODES_DIR: the Kratos python, which
# kratos and kratos-paper both run, the LAMMPS 2025 binary and LIGGGHTS with the paper's law);
# MILLIMPACT_<CODE>_BINARY is unset.
# `--without-codes` instead leaves those programs out of PATH (a copy of PATH's folders without
# them) and points MILLIMPACT_CODES_DIR at an empty folder: the fast tier as a machine without
# the codes runs it.
# Extra arguments go to `cargo test`.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=tripwire
if [ "${1:-}" = --without-codes ]; then
  mode=absent
  shift
fi

# What a live test starts (and what the fast tier must not).
PROGRAMS=(liggghts yade lmp parallel sbatch srun salloc squeue scontrol slurmctld slurmd munged
  chromium chromium-browser)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin" "$work/codes"
for v in $(compgen -e | grep -E '^MILLIMPACT_.*_BINARY$' || true); do unset "$v"; done
unset MILLIMPACT_CODES_DIR

if [ "$mode" = tripwire ]; then
  log="$work/started"
  : >"$log"
  tripwire() {
    mkdir -p "$(dirname "$1")"
    cat >"$1" <<EOF
#!/bin/sh
# A tripwire of scripts/fast-tier.sh: records its start, with the command line of what started
# it (millimpact's, or the test binary's), and fails.
echo "\$0 \$* (started by: \$(tr '\0' ' ' </proc/\$PPID/cmdline))" >>'$log'
echo "tripwire: \$0 started in the fast tier" >&2
exit 1
EOF
    chmod +x "$1"
  }
  for p in "${PROGRAMS[@]}"; do tripwire "$work/bin/$p"; done
  tripwire "$work/codes/kratos/bin/python"
  tripwire "$work/codes/lammps-2025/lib/python3.0/site-packages/lammps/lmp"
  tripwire "$work/codes/liggghts-paper/bin/liggghts-paper"
  tripwire "$work/codes/lammps-paper/lib/paperplugin.so"
  export PATH="$work/bin:$PATH"
  export MILLIMPACT_CODES_DIR="$work/codes"
  status=0
  cargo test --release "$@" || status=$?
  if [ -s "$log" ]; then
    echo "fast tier: these DEM codes or tools were started (a live test lacks #[ignore]):" >&2
    sort "$log" | uniq -c >&2
    exit 1
  fi
  exit "$status"
fi

# --without-codes: PATH's folders, each as a folder of links to its programs but those above.
shadow=()
IFS=: read -r -a dirs <<<"$PATH"
for i in "${!dirs[@]}"; do
  d="${dirs[$i]}"
  [ -d "$d" ] || continue
  s="$work/path$i"
  mkdir -p "$s"
  for f in "$d"/*; do
    name=$(basename "$f")
    [[ " ${PROGRAMS[*]} " == *" $name "* ]] && continue
    [ -e "$s/$name" ] || ln -s "$f" "$s/$name"
  done
  shadow+=("$s")
done
PATH=$(IFS=:; echo "${shadow[*]}")
export PATH
export MILLIMPACT_CODES_DIR="$work/codes"
for p in "${PROGRAMS[@]}"; do
  if command -v "$p" >/dev/null 2>&1; then
    echo "fast tier: $p is still reachable at $(command -v "$p")" >&2
    exit 1
  fi
done
cargo test --release "$@"
