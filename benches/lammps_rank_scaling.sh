#!/usr/bin/env bash
# 2 MPI ranks against 1 on the settled 10,000-sphere bed (benches/lammps/settled.data), for the
# plugin `pair_style mdrdem` (MDR + Mindlin + damping on LAMMPS's wall/gran hertz/history floor)
# and LAMMPS's own gran/hertz/history, in alternated runs: each pair runs the plugin on 1 and 2
# ranks, then Hertz on 1 and 2 ranks, so that a slow spell of a shared machine falls on both rank
# counts of a pair. Prints every run's rate (LAMMPS's Matom-step/s), then per style the median of
# the pairs' ratios, the ratio of the median rates and the ratio of the best rates.
# Usage: benches/lammps_rank_scaling.sh [pairs] [nbench] [nwarm]  (default 12 pairs, 2,000 timed
# steps after 2,000 warm-up steps).
# MDR_LAMMPS_PLUGIN, LAMMPS_LMP and LAMMPS_MPIRUN: a plugin and LAMMPS built elsewhere, for a
# machine without a toolchain or network (benches/lammps/plugin-setup.sh).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
pairs=${1:-12}
nbench=${2:-2000}
nwarm=${3:-2000}
# shellcheck source=benches/lammps/plugin-setup.sh
. "$repo/benches/lammps/plugin-setup.sh"
: > rates.txt
printf '%-5s %-10s %6s %12s\n' pair style ranks "M steps/s"
for i in $(seq "$pairs"); do
  for model in plugin hertzhist; do
    for np in 1 2; do
      "$mpirun" -np $np "$lmp" -in in.plugin -var model $model -var nbench "$nbench" -var nwarm "$nwarm" \
        -log log.$model.$np.$i -screen none
      r=$(rate log.$model.$np.$i)
      printf '%-5d %-10s %6d %12s\n' "$i" $model $np "$r"
      echo "$i $model $np $r" >> rates.txt
    done
  done
done
python3 - rates.txt <<'PY'
import statistics, sys
rates = {}
for line in open(sys.argv[1]):
    _, model, np, r = line.split()
    rates.setdefault((model, int(np)), []).append(float(r))
for model, name in (("plugin", "plugin mdrdem"), ("hertzhist", "LAMMPS gran/hertz/history")):
    one, two = rates[(model, 1)], rates[(model, 2)]
    pairs = [b / a for a, b in zip(one, two)]
    print(f"{name}: 2 ranks / 1 rank, median of {len(pairs)} pairs {statistics.median(pairs):.2f} "
          f"(pairs {min(pairs):.2f}-{max(pairs):.2f}); median rates {statistics.median(two):.3f} / "
          f"{statistics.median(one):.3f} = {statistics.median(two) / statistics.median(one):.2f}; "
          f"best rates {max(two):.3f} / {max(one):.3f} = {max(two) / max(one):.2f}")
PY
