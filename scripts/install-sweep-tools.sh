#!/usr/bin/env bash
# Installs the tools the sweep tests drive (Debian packages, once): GNU parallel, and Slurm
# with munge for the single-node job-array test. Safe to run again.
set -euo pipefail

need=()
command -v parallel >/dev/null 2>&1 || need+=(parallel)
command -v slurmctld >/dev/null 2>&1 || need+=(slurm-wlm)
command -v munged >/dev/null 2>&1 || need+=(munge)

if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  echo "installing: ${need[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
fi
