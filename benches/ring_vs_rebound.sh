#!/usr/bin/env bash
# Planetary ring: mdr-dem's shearing box against REBOUND's shearing sheet (issue 8, docs/rings.md).
# For each seed, runs REBOUND (../shared/bench/rebound/run.sh --grav none) and `mdr-dem sim ring`
# one after the other on the same setup (Bridges law, 200 m box, Σ = 400 kg/m², 20 orbits), then
# the MDR ice law and a constant ε = 0.5 on seed 1, and prints the table of docs/rings.md §7 and
# the wall/CPU time ratio of docs/performance.md ("Planetary ring").
#
# Usage: benches/ring_vs_rebound.sh [SEEDS (default "1 2 3 4 5")] [ORBITS (default 20)]
# Outputs in $OUT (default target/ring_vs_rebound): rebound_s*.json, ours_s*/ (summary.json,
# timeseries.csv, equilibration.svg, restitution.svg), *.time (/usr/bin/time: wall, user, sys).
# Both codes run on one core (REBOUND is serial; rapier gets RAYON_NUM_THREADS=1), at nice 10.
# REUSE_REBOUND=DIR takes REBOUND's rebound_s*.json from an earlier run in DIR instead of running
# it again (REBOUND does not change; then the timing ratio is not printed).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seeds=${1:-"1 2 3 4 5"}
orbits=${2:-20}
out=${OUT:-$root/target/ring_vs_rebound}
rebound=${REBOUND_RUN:-$root/../shared/bench/rebound/run.sh}
mkdir -p "$out"
cargo build --release --bin mdr-dem --manifest-path "$root/Cargo.toml"
bin=${CARGO_TARGET_DIR:-$root/target}/release/mdr-dem
timed() { local t=$1; shift; /usr/bin/time -f "%e %U %S" -o "$t" nice -n 10 "$@"; }
for s in $seeds; do
  if [ -n "${REUSE_REBOUND:-}" ]; then
    cp "$REUSE_REBOUND/rebound_s$s.json" "$out/rebound_s$s.json"
    rm -f "$out/rebound_s$s.time"
  else
    timed "$out/rebound_s$s.time" "$rebound" --grav none --orbits "$orbits" --seed "$s" \
      --json "$out/rebound_s$s.json" > "$out/rebound_s$s.log"
  fi
  RAYON_NUM_THREADS=1 timed "$out/ours_s$s.time" "$bin" sim ring --law bridges --orbits "$orbits" \
    --seed "$s" --out "$out/ours_s$s" --frame-orbits "$orbits" --quiet --json > "$out/ours_s$s.json"
done
first=${seeds%% *}
for law in mdr constant; do
  RAYON_NUM_THREADS=1 timed "$out/${law}_s$first.time" "$bin" sim ring --law "$law" --eps 0.5 \
    --orbits "$orbits" --seed "$first" --out "$out/${law}_s$first" --frame-orbits "$orbits" --quiet \
    --json > "$out/${law}_s$first.json"
done
python3 - "$out" "$seeds" <<'PY'
import json, statistics as st, sys
out, seeds = sys.argv[1], sys.argv[2].split()
ours = [json.load(open(f"{out}/ours_s{s}.json")) for s in seeds]
rb = [json.load(open(f"{out}/rebound_s{s}.json"))["result"] for s in seeds]
def cpu(name):
    w, u, s = map(float, open(f"{out}/{name}.time").read().split()[-3:])
    return w, u + s
def ms(x): return (st.mean(x), st.stdev(x) if len(x) > 1 else float("nan"))
rows = [("c [mm/s]", "c_m_per_s", "c_m_s", 1e3), ("c, number-weighted [mm/s]", "c_number_m_per_s", "c_num_m_s", 1e3),
        ("sigma_x [mm/s]", "sigma_x_m_per_s", "sx", 1e3), ("sigma_y [mm/s]", "sigma_y_m_per_s", "sy", 1e3),
        ("sigma_z [mm/s]", "sigma_z_m_per_s", "sz", 1e3), ("c/(r_mean Omega)", "c_over_mean_r_omega", "c_over_rmeanOmega", 1),
        ("z_rms, mass-weighted [m]", "z_rms_m", "zrms_m", 1), ("z_rms, number-weighted [m]", "z_rms_number_m", "zrms_num_m", 1),
        ("filling factor at z = 0", "filling_factor_z0", "ff0", 1),
        ("collisions per particle per orbit", "collisions_per_particle_per_orbit", "coll_per_particle_per_orbit_2nd_half", 1),
        ("particles", "particles", "N", 1)]
print("| quantity | mdr-dem (mean ± sd) | REBOUND (mean ± sd) | difference | difference / sd of the mean difference |")
print("|---|---|---|---|---|")
for name, ko, kr, f in rows:
    a = ms([d[ko] * f for d in ours]); b = ms([d[kr] * f for d in rb])
    sd = (a[1] ** 2 / len(ours) + b[1] ** 2 / len(rb)) ** 0.5
    print(f"| {name} | {a[0]:.4g} ± {a[1]:.2g} | {b[0]:.4g} ± {b[1]:.2g} | {100 * (a[0] - b[0]) / b[0]:+.1f} % | {(a[0] - b[0]) / sd:+.1f} |")
for law in ("mdr", "constant"):
    d = json.load(open(f"{out}/{law}_s{seeds[0]}.json"))
    print(f"{law}: c = {d['c_m_per_s']*1e3:.4f} mm/s, z_rms = {d['z_rms_m']:.3f} m, FF0 = {d['filling_factor_z0']:.4f}, "
          f"collisions/particle/orbit = {d['collisions_per_particle_per_orbit']:.3f}")
import os
if not all(os.path.exists(f"{out}/rebound_s{s}.time") for s in seeds):
    sys.exit(0)  # REBOUND results reused: no timing comparison
wo = [cpu(f"ours_s{s}") for s in seeds]; wr = [cpu(f"rebound_s{s}") for s in seeds]
so, sr = sum(w for w, _ in wo), sum(w for w, _ in wr)
co, cr = sum(c for _, c in wo), sum(c for _, c in wr)
print(f"wall: mdr-dem {so:.1f} s, REBOUND {sr:.1f} s, REBOUND/mdr-dem = {sr/so:.2f}")
print(f"CPU:  mdr-dem {co:.1f} s, REBOUND {cr:.1f} s, REBOUND/mdr-dem = {cr/co:.2f}")
PY
