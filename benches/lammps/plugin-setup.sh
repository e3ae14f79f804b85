# Sourced by the plugin's benchmarks (compare_lammps_plugin.sh, lammps_rank_scaling.sh), with
# `repo` set: the plugin (`plugin`), LAMMPS and its launcher (`lmp`, `mpirun`), a scratch folder
# removed on exit that holds the settled bed, in.bench and its plugin variant in.plugin (the
# current directory afterwards), and `rate LOG`, the timed run's rate in M particle-steps/s.
# The plugin is built and LAMMPS installed on first use (build-plugin.sh, install-lammps.sh). On
# a machine without a toolchain or network they are taken from elsewhere instead:
# MDR_LAMMPS_PLUGIN (the plugin's .so), LAMMPS_LMP (the lmp executable) and LAMMPS_MPIRUN (its
# mpirun), with LD_LIBRARY_PATH naming LAMMPS's MPI library.
if [ -n "${MDR_LAMMPS_PLUGIN:-}" ]; then
  plugin=$MDR_LAMMPS_PLUGIN
else
  plugin=$("$repo/crates/mdr-lammps/build-plugin.sh" | tail -1)
fi
if [ -n "${LAMMPS_LMP:-}" ]; then
  lmp=$LAMMPS_LMP
  mpirun=${LAMMPS_MPIRUN:-mpirun}
else
  venv=$("$repo/crates/mdr-lammps/install-lammps.sh" | tail -1)
  export LD_LIBRARY_PATH="$venv/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  lmp=$venv/bin/lmp
  mpirun=$venv/bin/mpirun
fi
export OMP_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$repo/benches/lammps/in.bench" "$repo/benches/lammps/settled.data" "$work/"
cd "$work"
"$repo/benches/lammps/plugin-input.sh" "$plugin" > in.plugin
# LAMMPS's Performance line gives the rate in Matom-step/s, or in katom-step/s below 1 M (as for
# the slower granular mdr model): both as M particle-steps/s.
rate() {
  grep -A2 "^Loop time" "$1" | tail -1 | awk '{for (i=1;i<=NF;i++) {
    if ($i=="Matom-step/s") printf "%.4f\n", $(i-1);
    if ($i=="katom-step/s") printf "%.4f\n", $(i-1) / 1000.0 } }' | tail -1
}
