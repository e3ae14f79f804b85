#!/usr/bin/env python3
"""Thornton law vs LIGGGHTS `model thornton_ning` (benches/cross_code.sh): e(v) of a steel sphere
(R = 6.35 mm) on a steel plane over 0.1-32 x the yield speed. Usage:
thornton.py OURS_CMD... (the command that runs the mdr-verify `cross_code` example).

Yield pressure: LIGGGHTS 3.8 src/normal_model_thornton_ning.h sets the yield contact radius
a_y = coefficientYieldRatio * R_i (R_i = the particle's radius) and the yield stress
p_y = 2 E* a_y / (pi R) - sqrt(2 gamma E* / (pi a_y)); with surfaceEnergy gamma = 0 and a wall
(R = R_i), p_y = 2 E* yieldRatio / pi, which is the Hertz peak pressure at a = a_y, i.e. exactly the
p_y of our Thornton law (no fitted parameter). Our side is run twice: with Thornton's (1997)
unloading and with the unloading branch LIGGGHTS actually implements at gamma = 0
(ThorntonUnloading::LiggghtsThorntonNing, docs/theory.md 6.1)."""
import math, os, subprocess, sys, tempfile

here = os.path.dirname(os.path.abspath(__file__))
ours_cmd = sys.argv[1:]
E, nu, rho, R, yr = 2.0e11, 0.3, 7850.0, 0.00635, 0.01
STEPS = 40000  # LIGGGHTS steps per Hertz contact time (explicit incremental force update)
speeds = [0.002 * (0.6 / 0.002) ** (k / 11) for k in range(12)]
Es = E / (2 * (1 - nu * nu))  # LIGGGHTS Yeff of a sphere-wall pair of the same material
p_y = 2 * Es * yr / math.pi


def liggghts(v):
    work = tempfile.mkdtemp(prefix="lig_")
    m = rho * 4 / 3 * math.pi * R ** 3
    tc = 2.943 * (15 * m * v * v / (16 * Es * math.sqrt(R))) ** 0.4 / v
    dt = tc / STEPS
    args = ["liggghts", "-in", os.path.join(here, "in.thornton_ning"), "-log", "log.t",
            "-var", "E", str(E), "-var", "nu", str(nu), "-var", "rho", str(rho), "-var", "R", str(R),
            "-var", "v", str(v), "-var", "yr", str(yr), "-var", "dt", str(dt),
            "-var", "nsteps", str(int((1e-6 / v) / dt) + 3 * STEPS)]
    subprocess.run(args, cwd=work, check=True, stdout=subprocess.DEVNULL)
    last = [l for l in open(os.path.join(work, "t.out")) if not l.startswith("#")][-1]
    return float(last.split()[1]) / v


def ours(variant, vs):
    out = subprocess.run(ours_cmd + [variant, str(p_y), str(E), str(nu), str(rho), str(R)]
                         + [str(v) for v in vs], check=True, capture_output=True, text=True).stdout
    rows = [[float(x) for x in l.split()] for l in out.splitlines()]
    return [r[1] for r in rows], rows[0][2]


lig = [liggghts(v) for v in speeds]
t97, v_y = ours("thornton", speeds)
tln, _ = ours("thornton-liggghts", speeds)
print(f"\nThornton vs LIGGGHTS thornton_ning (yieldRatio {yr}, surfaceEnergy 0, {STEPS} steps per "
      f"contact): p_y = 2 E* yieldRatio / pi = {p_y:.6e} Pa = {p_y / Es:.6f} E*; "
      f"v_y = {v_y:.6e} m/s\n")
print("| v (m/s) | v/v_y | e, LIGGGHTS | e, mdr-dem LIGGGHTS branch | diff | "
      "e, mdr-dem Thornton 1997 | diff |")
print("|---|---|---|---|---|---|---|")
worst = 0.0
for v, a, b, c in zip(speeds, tln, lig, t97):
    d1 = 100 * (a - b) / b
    d2 = 100 * (c - b) / b
    worst = max(worst, abs(d1))
    print(f"| {v:.4g} | {v / v_y:.3g} | {b:.5f} | {a:.5f} | {d1:+.3f} % | {c:.5f} | {d2:+.2f} % |")
print(f"\nlargest |difference|, same unloading branch: {worst:.3f} % (target 1 %)")
