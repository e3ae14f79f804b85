#!/usr/bin/env bash
# Ring shearing box: wall time per orbit against the number of particles, mdr-dem against REBOUND,
# without and with tree self-gravity (docs/rings.md §11). The box grows at fixed Σ = 400 kg/m²
# (τ ≈ 0.35): REBOUND --root 100 --nroot K (box 100 K m), mdr-dem --box 100K.
#
# Usage: benches/ring_scaling.sh [ROOTS (default "2 5 16": 200, 500, 1600 m; ≈ 1.5k, 9k, 96k
#        particles)] [ORBITS per size (default "1 0.2 0.02")] [THREADS for mdr-dem (default 1)]
# Both codes start from their cold initial conditions and run the same number of orbits, one after
# the other, at nice 10; REBOUND is serial. Prints a markdown table (seconds of wall time per orbit).
# REUSE_REBOUND=DIR takes REBOUND's rebound_<mode>_<box>.json from an earlier run's output
# directory instead of running REBOUND again (its results do not depend on mdr-dem).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
roots=(${1:-2 5 16})
orbits=(${2:-1 0.2 0.02})
threads=${3:-1}
out=${OUT:-$root/target/ring_scaling}
rebound=${REBOUND_RUN:-$root/benches/rebound/run.sh}
mkdir -p "$out"
cargo build --release --bin mdr-dem --manifest-path "$root/Cargo.toml"
bin=${CARGO_TARGET_DIR:-$root/target}/release/mdr-dem
echo "| box [m] | particles | gravity | orbits | mdr-dem [s/orbit] | REBOUND [s/orbit] | mdr-dem / REBOUND |"
echo "|---|---|---|---|---|---|---|"
for k in "${!roots[@]}"; do
  n=${roots[$k]}; o=${orbits[$k]}; box=$((100 * n))
  for mode in none tree; do
    tag=${mode}_$box
    if [ -n "${REUSE_REBOUND:-}" ]; then
      [ "$REUSE_REBOUND" -ef "$out" ] || cp "$REUSE_REBOUND/rebound_$tag.json" "$out/rebound_$tag.json"
    else
      nice -n 10 "$rebound" --grav "$mode" --orbits "$o" --root 100 --nroot "$n" \
        --json "$out/rebound_$tag.json" > "$out/rebound_$tag.log"
    fi
    RAYON_NUM_THREADS=$threads nice -n 10 "$bin" sim ring --box "$box" --gravity "$mode" \
      --orbits "$o" --quiet --json > "$out/ours_$tag.json"
    python3 - "$out/ours_$tag.json" "$out/rebound_$tag.json" "$box" "$mode" "$o" <<'PY'
import json, sys
ours = json.load(open(sys.argv[1])); rb = json.load(open(sys.argv[2]))["result"]
a, b = ours["wall_s_per_orbit"], rb["wall_per_orbit_s"]
print(f"| {sys.argv[3]} | {ours['particles']} / {rb['N']} | {sys.argv[4]} | {sys.argv[5]} | {a:.2f} | {b:.2f} | {a / b:.2f} |")
PY
  done
done
