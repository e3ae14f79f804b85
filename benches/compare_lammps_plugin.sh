#!/usr/bin/env bash
# Side by side on the settled 10,000-sphere bed (benches/lammps/settled.data), one run after the
# other on this machine: LAMMPS gran/hertz/history, LAMMPS granular mdr (Zunker–Kamrin), the
# plugin pair_style mdrdem (MDR + Mindlin + damping, the parameters of `mdr-dem bench bed --law
# mdr`) on LAMMPS's wall/gran hertz/history floor and on a fix wall/mdrdem floor (the same law,
# R = r), each with 1 and 2 MPI ranks; then `mdr-dem bench bed --law mdr`; then LAMMPS's drum
# example with the plugin (examples/lammps/in.drum) on 2 ranks with and without fix balance.
# The Modify column is LAMMPS's time in fixes (average over ranks, seconds of the timed run):
# nve/sphere, gravity and the floor, so plugin against plugin-wall compares the two floors.
# Usage: benches/compare_lammps_plugin.sh [nbench] [drum]  (timed steps after 2,000 warm-up steps;
# default 10000; drum: yes (default) or no). Prints one table of particle-steps per second
# (LAMMPS's Matom-step/s) and the drum's loop times, then the ratios the targets are stated in:
# the plugin's pair per core against gran/hertz/history, the wall/mdrdem floor's fix time
# against wall/gran hertz/history's, 2 ranks against 1, and the drum with fix balance against
# without. MDR_LAMMPS_PLUGIN, LAMMPS_LMP and LAMMPS_MPIRUN: a plugin and LAMMPS built elsewhere
# (benches/lammps/plugin-setup.sh); MDR_DEM: the mdr-dem binary (default: built here).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
nbench=${1:-10000}
drum=${2:-yes}
# shellcheck source=benches/lammps/plugin-setup.sh
. "$repo/benches/lammps/plugin-setup.sh"
# LAMMPS's average time in fixes (Modify row of the task timing breakdown) of the timed run
modify_time() {
  awk '/^Modify /{t=$5} END{print t}' "$1"
}
printf '%-28s %6s %14s %14s %12s\n' law ranks "M steps/s" "per core" "Modify s"
for model in hertzhist mdr plugin pluginwall; do
  for np in 1 2; do
    "$mpirun" -np $np "$lmp" -in in.plugin -var model $model -var nbench "$nbench" \
      -log log.$model.$np -screen none
    r=$(rate log.$model.$np)
    declare "rate_${model}_$np=$r" "modify_${model}_$np=$(modify_time log.$model.$np)"
    printf '%-28s %6d %14s %14s %12s\n' "lammps-$model" $np "$r" "$(python3 -c "print(f'{$r/$np:.3f}')")" \
      "$(modify_time log.$model.$np)"
  done
done
cd "$repo"
bin=${MDR_DEM:-${CARGO_TARGET_DIR:-$repo/target}/release/mdr-dem}
[ -n "${MDR_DEM:-}" ] || cargo build -q --release --locked --bin mdr-dem
json=$("$bin" bench bed --law mdr --data benches/lammps/settled.data --steps "$nbench" --json)
r=$(python3 -c "import json,sys; d=json.loads(sys.argv[1]); print(f\"{d['particle_steps_per_s']/1e6:.3f}\")" "$json" 2>/dev/null || echo "?")
printf '%-28s %6d %14s %14s\n' "mdr-dem bench bed --law mdr" 1 "$r" "$r"
echo "json: $json"
if [ "$drum" = yes ]; then
  cd "$work"
  for balance in no yes; do
    "$mpirun" -np 2 "$lmp" -in "$repo/examples/lammps/in.drum" -var plugin "$plugin" \
      -var balance $balance -log log.drum.$balance -screen none
    loop=$(awk '/^Loop time/{s+=$4} END{print s}' log.drum.$balance)
    declare "drum_$balance=$loop"
    printf 'drum (examples/lammps/in.drum), 2 ranks, fix balance %-3s: loop time %s s (fill + turn)\n' "$balance" \
      "$loop"
  done
fi
ratio() { python3 -c "import sys; a, b = map(float, sys.argv[1:]); print(f'{a / b:.3f}')" "$1" "$2" 2>/dev/null || echo "?"; }
echo "plugin pair / gran/hertz/history, per core, 1 rank: $(ratio "$rate_plugin_1" "$rate_hertzhist_1") (target >= 1.0)"
echo "wall/gran hertz/history floor's fix time / wall/mdrdem floor's (Modify s, 1 rank): $(ratio "$modify_plugin_1" "$modify_pluginwall_1") (target >= 1.0)"
echo "plugin 2 ranks / 1 rank: $(ratio "$rate_plugin_2" "$rate_plugin_1") (target >= 1.8); gran/hertz/history: $(ratio "$rate_hertzhist_2" "$rate_hertzhist_1")"
if [ "$drum" = yes ]; then
  echo "drum on 2 ranks, loop time without / with fix balance: $(ratio "$drum_no" "$drum_yes") (target > 1)"
fi
