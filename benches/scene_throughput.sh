#!/usr/bin/env bash
# Scene throughput against the settled-bed benchmark on the same machine, one run after the
# other: `mdr-dem bench bed --law mdr` (the MDR law with Mindlin history on LAMMPS's settled
# 10,000-sphere bed), then `mdr-dem bench scene` on the same bed as a scene (scenes/bed.toml:
# what the scene machinery costs on the same system), on each built-in scene of ≥ 10⁴ spheres
# and on the funnel, timed in the state the scene's headline is measured in (after warm-up
# steps: the hopper's bed formed and draining, the column collapsing, the drum turning), each
# with 1 and 2 threads. Scene cases are named by their file (`bed.toml`, `hopper.toml`, …).
# Prints one table: particle-steps per wall second and per CPU second, the ratio of the bed's
# one-thread rate to the scene's, and the two-thread speed-up.
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
# scene  warm-up steps  timed steps
while read -r scene warmup steps; do
  for t in 1 2; do
    echo "{\"case\":\"$scene.toml\",$("$bin" bench scene "$repo/scenes/$scene.toml" --warmup "$warmup" \
      --steps "$steps" --threads $t --json | cut -c2-)" >> "$jsonl"
  done
done <<'LIST'
bed 2000 10000
hopper 15000 3000
column 5000 3000
drum 20000 5000
funnel 30000 20000
LIST
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$jsonl" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
one = {r["case"]: r for r in rows if r["threads"] == 1}
two = {r["case"]: r for r in rows if r["threads"] == 2}
bed = one["bed"]["particle_steps_per_s"]
print(f"{'case':12} {'spheres':>8} {'contacts/p':>10} {'1 thread':>10} {'per CPU s':>10} "
      f"{'bed/scene':>9} {'2 threads':>10} {'speed-up':>8}  (M particle-steps/s)")
for case, r in one.items():
    s2 = two[case]["particle_steps_per_s"]
    print(f"{case:12} {r['particles']:8d} {r['contacts_per_particle']:10.2f} "
          f"{r['particle_steps_per_s'] / 1e6:10.3f} "
          f"{r.get('cpu_particle_steps_per_s', r.get('particle_steps_per_cpu_s')) / 1e6:10.3f} "
          f"{bed / r['particle_steps_per_s']:9.2f} {s2 / 1e6:10.3f} "
          f"{s2 / r['particle_steps_per_s']:8.2f}")
PY
