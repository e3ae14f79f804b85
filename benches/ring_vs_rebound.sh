#!/usr/bin/env bash
# Planetary ring: mdr-dem's shearing box against REBOUND's shearing sheet (docs/rings.md), without
# and with self-gravity. For each gravity mode and seed, runs REBOUND (benches/rebound/run.sh
# --grav MODE) and `mdr-dem sim ring --gravity MODE` one after the other on the same setup (Bridges
# law, 200 m box, Σ = 400 kg/m², 20 orbits), then the MDR ice law and a constant ε = 0.5 on the
# first seed, and prints the table of docs/rings.md §7 and the wall/CPU time ratios of
# docs/performance.md ("Planetary ring vs REBOUND").
#
# Usage: benches/ring_vs_rebound.sh [SEEDS (default "1 2 3 4 5")] [ORBITS (default 20)]
#        [MODES (default "none tree"; none = no self-gravity, tree = tree gravity in both codes)]
# Outputs in $OUT (default target/ring_vs_rebound): rebound_<mode>_s*.json, ours_<mode>_s*/
# (summary.json, timeseries.csv, equilibration.svg, restitution.svg, frames/), *.time
# (/usr/bin/time: wall, user, sys). Both codes run on one core (REBOUND is serial; rapier and the
# tree get RAYON_NUM_THREADS=1), at nice 10, one after the other.
# REUSE_REBOUND=DIR takes REBOUND's rebound_<mode>_s*.json from an earlier run in DIR instead of
# running it again (REBOUND does not change; then the timing ratio is not printed).
# REBOUND_RUN overrides the REBOUND runner (default benches/rebound/run.sh, which installs
# REBOUND 5.2.2 from PyPI into a cached virtual environment on first use).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seeds=${1:-"1 2 3 4 5"}
orbits=${2:-20}
modes=${3:-"none tree"}
out=${OUT:-$root/target/ring_vs_rebound}
rebound=${REBOUND_RUN:-$root/benches/rebound/run.sh}
mkdir -p "$out"
cargo build --release --bin mdr-dem --manifest-path "$root/Cargo.toml"
bin=${CARGO_TARGET_DIR:-$root/target}/release/mdr-dem
timed() { local t=$1; shift; /usr/bin/time -f "%e %U %S" -o "$t" nice -n 10 "$@"; }
first=${seeds%% *}
for mode in $modes; do
  for s in $seeds; do
    if [ -n "${REUSE_REBOUND:-}" ]; then
      cp "$REUSE_REBOUND/rebound_${mode}_s$s.json" "$out/rebound_${mode}_s$s.json"
      rm -f "$out/rebound_${mode}_s$s.time"
    else
      timed "$out/rebound_${mode}_s$s.time" "$rebound" --grav "$mode" --orbits "$orbits" --seed "$s" \
        --json "$out/rebound_${mode}_s$s.json" > "$out/rebound_${mode}_s$s.log"
    fi
    RAYON_NUM_THREADS=1 timed "$out/ours_${mode}_s$s.time" "$bin" sim ring --law bridges \
      --gravity "$mode" --orbits "$orbits" --seed "$s" --out "$out/ours_${mode}_s$s" \
      --frame-orbits "$orbits" --quiet --json > "$out/ours_${mode}_s$s.json"
  done
  for law in mdr constant; do
    RAYON_NUM_THREADS=1 timed "$out/${law}_${mode}_s$first.time" "$bin" sim ring --law "$law" \
      --eps 0.5 --gravity "$mode" --orbits "$orbits" --seed "$first" \
      --out "$out/${law}_${mode}_s$first" --frame-orbits "$orbits" --quiet \
      --json > "$out/${law}_${mode}_s$first.json"
  done
done
python3 - "$out" "$seeds" "$modes" <<'PY'
import json, os, statistics as st, sys
out, seeds, modes = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
def cpu(name):
    w, u, s = map(float, open(f"{out}/{name}.time").read().split()[-3:])
    return w, u + s
def ms(x): return (st.mean(x), st.stdev(x) if len(x) > 1 else float("nan"))
rows = [("c [mm/s]", "c_m_per_s", "c_m_s", 1e3), ("c, number-weighted [mm/s]", "c_number_m_per_s", "c_num_m_s", 1e3),
        ("sigma_x [mm/s]", "sigma_x_m_per_s", "sx", 1e3), ("sigma_y [mm/s]", "sigma_y_m_per_s", "sy", 1e3),
        ("sigma_z [mm/s]", "sigma_z_m_per_s", "sz", 1e3), ("c/(r_mean Omega)", "c_over_mean_r_omega", "c_over_rmeanOmega", 1),
        ("z_rms, mass-weighted [m]", "z_rms_m", "zrms_m", 1), ("z_rms, number-weighted [m]", "z_rms_number_m", "zrms_num_m", 1),
        ("filling factor at z = 0", "filling_factor_z0", "ff0", 1), ("Toomre Q", "toomre_q", "Q_toomre", 1),
        ("collisions per particle per orbit", "collisions_per_particle_per_orbit", "coll_per_particle_per_orbit_2nd_half", 1),
        ("particles", "particles", "N", 1)]
for mode in modes:
    ours = [json.load(open(f"{out}/ours_{mode}_s{s}.json")) for s in seeds]
    rb = [json.load(open(f"{out}/rebound_{mode}_s{s}.json"))["result"] for s in seeds]
    print(f"\n## gravity {mode}\n")
    print("| quantity | mdr-dem (mean ± sd) | REBOUND (mean ± sd) | difference | difference / sd of the mean difference |")
    print("|---|---|---|---|---|")
    for name, ko, kr, f in rows:
        a = ms([d[ko] * f for d in ours]); b = ms([d[kr] * f for d in rb])
        sd = (a[1] ** 2 / len(ours) + b[1] ** 2 / len(rb)) ** 0.5
        print(f"| {name} | {a[0]:.4g} ± {a[1]:.2g} | {b[0]:.4g} ± {b[1]:.2g} | {100 * (a[0] - b[0]) / b[0]:+.1f} % | {(a[0] - b[0]) / sd:+.1f} |")
    pitch = [d["wake_pitch_deg"] for d in ours if d.get("wake_pitch_deg") is not None]
    lam = [d["wake_wavelength_m"] for d in ours if d.get("wake_wavelength_m") is not None]
    ani = [d["wake_anisotropy"] for d in ours if d.get("wake_anisotropy") is not None]
    if pitch:
        print(f"mdr-dem wakes: pitch {st.mean(pitch):.1f} deg, wavelength {st.mean(lam) if lam else float('nan'):.1f} m "
              f"({len(lam)}/{len(ours)} runs with a side maximum), anisotropy {st.mean(ani):.2f}")
    for law in ("bridges", "mdr", "constant"):
        d = ours[0] if law == "bridges" else json.load(open(f"{out}/{law}_{mode}_s{seeds[0]}.json"))
        print(f"{law}: c = {d['c_m_per_s']*1e3:.4f} mm/s, z_rms = {d['z_rms_m']:.3f} m, FF0 = {d['filling_factor_z0']:.4f}, "
              f"Q = {d['toomre_q']:.2f}, collisions/particle/orbit = {d['collisions_per_particle_per_orbit']:.3f}, "
              f"wake anisotropy = {d['wake_anisotropy']}, pitch = {d['wake_pitch_deg']}, wavelength = {d['wake_wavelength_m']}")
    if not all(os.path.exists(f"{out}/rebound_{mode}_s{s}.time") for s in seeds):
        continue  # REBOUND results reused: no timing comparison
    wo = [cpu(f"ours_{mode}_s{s}") for s in seeds]; wr = [cpu(f"rebound_{mode}_s{s}") for s in seeds]
    so, sr = sum(w for w, _ in wo), sum(w for w, _ in wr)
    co, cr = sum(c for _, c in wo), sum(c for _, c in wr)
    print(f"wall: mdr-dem {so:.1f} s, REBOUND {sr:.1f} s, mdr-dem/REBOUND = {so/sr:.2f}")
    print(f"CPU:  mdr-dem {co:.1f} s, REBOUND {cr:.1f} s, mdr-dem/REBOUND = {co/cr:.2f}")
PY
