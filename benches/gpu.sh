#!/usr/bin/env bash
# The settled bed on the GPU against the CPU path on all cores of the same machine:
# `mdr-dem bench bed --law mdr --device gpu` (MDR + Mindlin + damping in f64, docs/gpu.md) on
# the reference bed tiled 3 × 3, 10 × 10 and 20 × 20 (90,000, 10⁶ and 4·10⁶ spheres), then the
# CPU path (`--threads` = every core) on the same beds with fewer steps; the 90,000-sphere GPU
# run is also compared with the CPU path (`--compare-cpu`: the largest position difference).
# Then the GPU path's other contact models on the 10⁶-sphere bed: Thornton's law, the adhesive
# MDR law, and MDR with rolling resistance (`--rolling 0.2`). Then two scenes through
# `bench scene --device gpu` (scenes/bed.toml, scenes/column.toml) against the CPU path.
# Prints one table: particle-steps per second, ms per step and bytes per sphere (device buffers
# for the GPU, the stepper's buffers for the CPU), and keeps every JSON line.
#
# Builds nothing and needs no network: it runs a release binary built beforehand
# (`cargo build --release`, then carry target/release/mdr-dem and benches/lammps/settled.data;
# docs/gpu.md says how to run it on a GPU machine). About 5 minutes on an H100 with 16 cores.
#
# Usage: benches/gpu.sh [--quick] [OUT_DIR]
#   --quick (or MDR_GPU_QUICK=1): the reference bed alone (10,000 spheres), a few steps: checks
#   the script on any Vulkan device, lavapipe included (its rates say nothing of a GPU's).
# Environment: MDR_DEM (the binary; default target/release/mdr-dem), THREADS (CPU threads;
# default: every core).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
quick=${MDR_GPU_QUICK:-0}
if [ "${1:-}" = "--quick" ]; then
  quick=1
  shift
fi
out=${1:-$repo/target/gpu-bench}
mkdir -p "$out"
bin=${MDR_DEM:-${CARGO_TARGET_DIR:-$repo/target}/release/mdr-dem}
if [ ! -x "$bin" ]; then
  echo "no binary at $bin: build it first (cargo build --release) or set MDR_DEM" >&2
  exit 1
fi
threads=${THREADS:-$(nproc)}
data=$repo/benches/lammps/settled.data
jsonl="$out/gpu.jsonl"
: > "$jsonl"

# case: tile gpu_steps gpu_warmup cpu_steps cpu_warmup
if [ "$quick" = 1 ]; then
  cases=("1 20 5 10 2")
else
  cases=("3 2000 200 200 20" "10 1000 100 40 10" "20 400 50 10 5")
fi

# A field of a JSON line: a quoted string whole, or a number.
field() {
  if grep -q "\"$1\":\"" <<< "$2"; then
    sed -E "s/.*\"$1\":\"([^\"]*)\".*/\1/" <<< "$2"
  else
    sed -E "s/.*\"$1\":([^,}]*).*/\1/" <<< "$2"
  fi
}

echo "machine: $(nproc) cores; binary $bin; $(date -u +%Y-%m-%dT%H:%MZ)"
printf '%-6s %-12s %10s %7s %16s %10s %14s %s\n' device law spheres steps "M part-steps/s" ms/step "bytes/sphere" note
for c in "${cases[@]}"; do
  read -r tile gsteps gwarm csteps cwarm <<< "$c"
  compare=()
  if [ "$tile" = 3 ] || [ "$quick" = 1 ]; then
    compare=(--compare-cpu --threads "$threads")
  fi
  line=$("$bin" bench bed --data "$data" --law mdr --device gpu --tile "$tile" \
    --steps "$gsteps" --warmup "$gwarm" "${compare[@]}" --json)
  echo "{\"case\":\"gpu_tile$tile\",${line:1}" >> "$jsonl"
  note="$(field gpu_adapter "$line")"
  if grep -q max_position_difference_diameters <<< "$line"; then
    note="$note; vs CPU: $(field max_position_difference_diameters "$line") diameters"
  fi
  printf '%-6s %-12s %10s %7s %16.2f %10.3f %14.0f %s\n' gpu mdr "$(field particles "$line")" \
    "$gsteps" "$(awk "BEGIN{print $(field particle_steps_per_s "$line")/1e6}")" \
    "$(field ms_per_step "$line")" "$(field device_bytes_per_particle "$line")" "$note"
  line=$("$bin" bench bed --data "$data" --law mdr --device cpu --tile "$tile" \
    --steps "$csteps" --warmup "$cwarm" --threads "$threads" --json)
  echo "{\"case\":\"cpu_tile$tile\",${line:1}" >> "$jsonl"
  printf '%-6s %-12s %10s %7s %16.2f %10.3f %14.0f %s\n' cpu mdr "$(field particles "$line")" \
    "$csteps" "$(awk "BEGIN{print $(field particle_steps_per_s "$line")/1e6}")" \
    "$(field ms_per_step "$line")" "$(field stepper_bytes_per_particle "$line")" "$threads threads"
done

# The other contact models on the GPU: law name, then its flags.
if [ "$quick" = 1 ]; then
  tile=1 msteps=10 mwarm=2
else
  tile=10 msteps=1000 mwarm=100
fi
for model in "thornton --law thornton" "adhesive-mdr --law adhesive-mdr" \
  "mdr+rolling --law mdr --rolling 0.2"; do
  read -r name flags <<< "$model"
  compare=()
  if [ "$quick" = 1 ]; then
    compare=(--compare-cpu --threads "$threads")
  fi
  # shellcheck disable=SC2086 # the flags are words
  line=$("$bin" bench bed --data "$data" $flags --device gpu --tile "$tile" \
    --steps "$msteps" --warmup "$mwarm" "${compare[@]}" --json)
  echo "{\"case\":\"gpu_${name}_tile$tile\",${line:1}" >> "$jsonl"
  note="$(field gpu_adapter "$line")"
  if grep -q max_position_difference_diameters <<< "$line"; then
    note="$note; vs CPU: $(field max_position_difference_diameters "$line") diameters"
  fi
  printf '%-6s %-12s %10s %7s %16.2f %10.3f %14.0f %s\n' gpu "$name" "$(field particles "$line")" \
    "$msteps" "$(awk "BEGIN{print $(field particle_steps_per_s "$line")/1e6}")" \
    "$(field ms_per_step "$line")" "$(field device_bytes_per_particle "$line")" "$note"
done

# Scenes on the GPU (`bench scene --device gpu`): the settled bed as a scene (10,000 spheres,
# periodic box, the floor plane), the column collapse (21,347 spheres on a floor, open space,
# rolling resistance) and the hopper discharging through its first orifice (20,734 spheres,
# exact cylinder and orifice plate; timed from step 20,000, t = 0.35 s, once the bed has
# formed), each against the CPU path on every core.
if [ "$quick" = 1 ]; then
  scases=("bed 20 5 10 2")
else
  scases=("bed 4000 200 400 20" "column 4000 1000 400 100" "hopper 4000 20000 1000 20000")
fi
for c in "${scases[@]}"; do
  read -r name gsteps gwarm csteps cwarm <<< "$c"
  for device in gpu cpu; do
    if [ "$device" = gpu ]; then
      steps=$gsteps warm=$gwarm
    else
      steps=$csteps warm=$cwarm
    fi
    line=$("$bin" bench scene "$repo/scenes/$name.toml" --device "$device" --threads "$threads" \
      --steps "$steps" --warmup "$warm" --json)
    echo "{\"case\":\"scene_${name}_$device\",${line:1}" >> "$jsonl"
    if [ "$device" = gpu ]; then
      note="$(field adapter "$line")" bytes="$(field device_bytes_per_particle "$line")"
    else
      note="$threads threads" bytes=0
    fi
    printf '%-6s %-12s %10s %7s %16.2f %10.3f %14.0f %s\n' "$device" "scene:$name" \
      "$(field particles "$line")" "$steps" \
      "$(awk "BEGIN{print $(field particle_steps_per_s "$line")/1e6}")" \
      "$(field ms_per_step "$line")" "$bytes" "$note"
  done
done
echo "JSON lines: $jsonl"
