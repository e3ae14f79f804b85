#!/usr/bin/env bash
# Side by side on the settled 10,000-sphere bed: LAMMPS (benches/lammps/run.sh, one core)
# and `mdr-dem bench bed` (fast force-mode path, 1 and 2 threads), run one after the other.
# Prints both throughputs and their ratio for `hertzhist` vs `--law hertz` and LAMMPS `mdr`
# vs `--law mdr`. Quote the ratios: absolute figures depend on the machine and its load.
#
# Usage: benches/compare_lammps.sh [nbench] [threads...]   (default: 10000 steps; threads 1 2)
# Environment: LAMMPS_BENCH_DIR (default benches/lammps), MDR_DEM (the binary; default
# target/release/mdr-dem, built if missing), MDR_BENCH_FLAGS (extra `bench bed` flags, e.g.
# `--no-orientation`: LAMMPS atom_style sphere integrates no orientation either), MDR_NATIVE=1
# (build and run a binary compiled for this CPU, `RUSTFLAGS=-C target-cpu=native`, in
# target/native; same trajectories bit for bit, see `state_checksum` of `bench bed --json`).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
lammps_dir=${LAMMPS_BENCH_DIR:-$repo/benches/lammps}
nbench=${1:-10000}
shift || true
threads=("$@")
[ ${#threads[@]} -eq 0 ] && threads=(1 2)
if [ ! -x "$lammps_dir/run.sh" ]; then
  echo "error: $lammps_dir/run.sh not found (set LAMMPS_BENCH_DIR)" >&2
  exit 1
fi
if [ "${MDR_NATIVE:-0}" = 1 ]; then
  bin=${MDR_DEM:-$repo/target/native/release/mdr-dem}
  (cd "$repo" && RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$repo/target/native" \
    cargo build --release --bin mdr-dem)
else
  bin=${MDR_DEM:-${CARGO_TARGET_DIR:-$repo/target}/release/mdr-dem}
  if [ ! -x "$bin" ]; then
    (cd "$repo" && cargo build --release --bin mdr-dem)
  fi
fi

lammps_rate() { # model -> "wall M/s  per-CPU-second M/s" of the timed run (last Loop time)
  log=$("$lammps_dir/run.sh" "$1" "$nbench" | sed -n 's/^log: //p')
  python3 - "$log" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
perf = re.findall(r"([0-9.]+) (k|M)atom-step/s", text)[-1]
cpu = float(re.findall(r"([0-9.]+)% CPU use", text)[-1])
rate = float(perf[0]) * (1e-3 if perf[1] == "k" else 1.0)
print(f"{rate} {rate / (cpu / 100.0)}")
PY
}
ours_rate() { # law threads -> "wall M/s  per-CPU-second M/s"
  # shellcheck disable=SC2086 # MDR_BENCH_FLAGS is a list of flags
  "$bin" bench bed --law "$1" --threads "$2" --steps "$nbench" ${MDR_BENCH_FLAGS:-} --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print(d["particle_steps_per_s"]/1e6, d["particle_steps_per_cpu_s"]/1e6)'
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); bench bed flags: ${MDR_BENCH_FLAGS:-none}; binary: $bin"
# Wall: particle-steps per second of elapsed time (what a user sees on an idle machine).
# CPU: particle-steps per CPU second (LAMMPS: wall rate / its "% CPU use"; mdr-dem: user +
# system time of all threads) -- per-core figures that survive a loaded machine.
printf '%-10s %-6s %7s %11s %11s %10s %11s %11s %10s\n' LAMMPS ours threads \
  "LAMMPS wall" "ours wall" "wall ratio" "LAMMPS CPU" "ours CPU" "CPU ratio"
for pair in hertzhist:hertz mdr:mdr; do
  model=${pair%%:*}
  law=${pair##*:}
  read -r ref_wall ref_cpu < <(lammps_rate "$model")
  for t in "${threads[@]}"; do
    read -r mine_wall mine_cpu < <(ours_rate "$law" "$t")
    python3 -c "print(f'{\"$model\":<10} {\"$law\":<6} {$t:>7} {$ref_wall:>11.3f} {$mine_wall:>11.3f} {$mine_wall/$ref_wall:>10.2f} {$ref_cpu:>11.3f} {$mine_cpu:>11.3f} {$mine_cpu/$ref_cpu:>10.2f}')"
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
