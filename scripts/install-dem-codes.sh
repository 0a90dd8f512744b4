#!/usr/bin/env bash
# Installs the reference DEM codes (LIGGGHTS, YADE, LAMMPS) from Debian packages, once, and
# prints their versions. Safe to run again: it installs only what is missing.
set -euo pipefail

need=()
command -v liggghts >/dev/null 2>&1 || need+=(liggghts)
command -v yade >/dev/null 2>&1 || need+=(yade)
command -v lmp >/dev/null 2>&1 || need+=(lammps)

if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  echo "installing: ${need[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
fi

dpkg-query -W -f='${Package} ${Version}\n' liggghts yade lammps
