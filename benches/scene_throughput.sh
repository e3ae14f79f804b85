#!/usr/bin/env bash
# Scene throughput against the settled-bed benchmark on the same machine, one run after the
# other: `mdr-dem bench bed --law mdr` (the MDR law with Mindlin history on LAMMPS's settled
# 10,000-sphere bed), then `mdr-dem bench scene` on the same bed as a scene (scenes/bed.toml:
# what the scene machinery costs on the same system), on each built-in scene of ≥ 10⁴ spheres
# and on the funnel, timed in the state the scene's headline is measured in (after warm-up
# steps: the hopper's bed formed and draining, the column collapsing, the drum turning), each
# with 1 and 2 threads. Scene cases are named by their file (`bed.toml`, `hopper.toml`, …).
# The bed also runs as a scene with the contact sub-models of the hopper (stiffness-proportional
# damping instead of the Hertzian one) and of the drum (that damping and rolling resistance):
# `bed_hopper_law.toml` and `bed_drum_law.toml`, written into OUT_DIR from scenes/bed.toml, so that
# each scene is also compared with the resting bed under its own law.
# Prints one table: particle-steps per wall second and per CPU second, the ratio of the bed's
# one-thread rate to the scene's, and the two-thread speed-up; where each scene's step goes (the
# breakdown of `bench scene`); then each scene against the bed scene with its law.
#
# Usage: benches/scene_throughput.sh [OUT_DIR]   (JSON lines in OUT_DIR/scene_throughput.jsonl;
# default target/scene-throughput). Environment: MDR_DEM (the binary; default
# target/release/mdr-dem, built if missing).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$repo/target/scene-throughput}
mkdir -p "$out"
bin=${MDR_DEM:-${CARGO_TARGET_DIR:-$repo/target}/release/mdr-dem}
if [ ! -x "$bin" ]; then
  (cd "$repo" && cargo build --release --bin mdr-dem)
fi
jsonl="$out/scene_throughput.jsonl"
: > "$jsonl"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for t in 1 2; do
  echo "{\"case\":\"bed\",$("$bin" bench bed --law mdr --threads $t --json | cut -c2-)" >> "$jsonl"
done
# The bed scene under the hopper's and the drum's contact sub-models (the data file by its full
# path, as the copies live in OUT_DIR).
bed_law() {
  sed -e "s|^file = \"../benches/|file = \"$repo/benches/|" \
      -e 's|^damping = .*|damping = "stiffness_viscous"\ndamping_eta = 0.3|' \
      -e '/^damping_gamma_n_per_m_s/d' -e '/^damping_tangential_ratio/d' \
      "$repo/scenes/bed.toml"
}
bed_law > "$out/bed_hopper_law.toml"
bed_law | sed 's|^damping_eta = 0.3|damping_eta = 0.3\nrolling_friction = 0.1|' > "$out/bed_drum_law.toml"
# scene file  warm-up steps  timed steps
while read -r file warmup steps; do
  case $file in /*) path=$file ;; *) path=$repo/scenes/$file ;; esac
  for t in 1 2; do
    echo "{\"case\":\"$(basename "$file")\",$("$bin" bench scene "$path" --warmup "$warmup" \
      --steps "$steps" --threads $t --json | cut -c2-)" >> "$jsonl"
  done
done <<LIST
bed.toml 2000 10000
$out/bed_hopper_law.toml 2000 10000
$out/bed_drum_law.toml 2000 10000
hopper.toml 15000 3000
column.toml 5000 3000
drum.toml 20000 5000
funnel.toml 30000 20000
LIST
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$jsonl" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
one = {r["case"]: r for r in rows if r["threads"] == 1}
two = {r["case"]: r for r in rows if r["threads"] == 2}
bed = one["bed"]["particle_steps_per_s"]
print(f"{'case':20} {'spheres':>8} {'contacts/p':>10} {'1 thread':>10} {'per CPU s':>10} "
      f"{'bed/scene':>9} {'2 threads':>10} {'speed-up':>8}  (M particle-steps/s)")
for case, r in one.items():
    s2 = two[case]["particle_steps_per_s"]
    print(f"{case:20} {r['particles']:8d} {r['contacts_per_particle']:10.2f} "
          f"{r['particle_steps_per_s'] / 1e6:10.3f} "
          f"{r.get('cpu_particle_steps_per_s', r.get('particle_steps_per_cpu_s')) / 1e6:10.3f} "
          f"{bed / r['particle_steps_per_s']:9.2f} {s2 / 1e6:10.3f} "
          f"{s2 / r['particle_steps_per_s']:8.2f}")
print("where a step goes, one thread, ns per particle-step (bench scene's breakdown):")
print(f"  {'case':20} {'pairs':>7} {'builds':>7} {'walls':>7} {'integr.':>7} {'rapier':>7} {'rest':>7}")
for case, r in one.items():
    b = r.get("breakdown_ns_per_particle_step")
    if b:
        print(f"  {case:20} {b['pairs']:7.1f} {b['builds']:7.1f} {b['surfaces']:7.1f} "
              f"{b['integration']:7.1f} {b['rapier']:7.1f} {b['rest']:7.1f}")
print("each scene against the bed scene with its contact sub-models (one thread):")
for case, law in (("hopper.toml", "bed_hopper_law.toml"), ("drum.toml", "bed_drum_law.toml")):
    if case in one and law in one:
        print(f"  {case:20} {one[law]['particle_steps_per_s'] / one[case]['particle_steps_per_s']:.2f}"
              f"  ({law})")
PY
