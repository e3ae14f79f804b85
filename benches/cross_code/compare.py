#!/usr/bin/env python3
"""Cross-code comparison driver (benches/cross_code.sh): runs LAMMPS on the decks in this
directory and compares with our validator's values (from the `cross_code` example of mdr-verify,
read from the file given as first argument). Prints a Markdown table."""
import math, os, subprocess, sys, tempfile

here = os.path.dirname(os.path.abspath(__file__))
lmp = sys.argv[2] if len(sys.argv) > 2 else "lmp"
ours = {}
for line in open(sys.argv[1]):
    p = line.split()
    ours[p[0]] = [float(x) for x in p[1:]]

def hertz_tc(E, nu, rho, R, v, wall):
    Es = E / (2 * (1 - nu * nu))
    m = rho * 4 / 3 * math.pi * R ** 3
    if wall:
        Rs, ms = R, m
    else:
        Rs, ms = R / 2, m / 2
    dmax = (15 * ms * v * v / (16 * Es * math.sqrt(Rs))) ** 0.4
    return 2.943 * dmax / v

def run(deck, variables, out):
    work = tempfile.mkdtemp(prefix="xcode_")
    args = [lmp, "-in", os.path.join(here, deck), "-log", "log.lammps", "-screen", "none"]
    for k, v in variables.items():
        args += ["-var", k, str(v)]
    subprocess.run(args, cwd=work, check=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    rows = [[float(x) for x in l.split()] for l in open(os.path.join(work, out)) if not l.startswith("#")]
    return rows, work

rows_out = []
def row(case, quantity, mine, theirs):
    err = abs(mine - theirs) / abs(theirs) if theirs != 0 else abs(mine)
    rows_out.append(f"| {case} | {quantity} | {mine:.6g} | {theirs:.6g} | {100*err:.3f} % |")

# Glass pair, R = 10 mm, 20 m/s relative.
E, nu, rho, R, v = 4.8e10, 0.20, 2800.0, 0.01, 20.0
steps = 20000
dt = hertz_tc(E, nu, rho, R, v, False) / steps
rows, work = run("in.pair", dict(E=E, nu=nu, rho=rho, R=R, v=v, dt=dt, nsteps=3 * steps), "pair.out")
f = [abs(r[0]) for r in rows]
tc = sum(1 for x in f if x > 0) * dt
fmax = max(f)
en = (rows[-1][2] - rows[-1][1]) / v
tc_o, f_o, en_o, _, _ = ours["pair"]
row("glass pair 20 m/s", "contact time (s)", tc_o, tc)
row("glass pair 20 m/s", "peak force (N)", f_o, fmax)
row("glass pair 20 m/s", "e_n", en_o, en)

# Alumina sphere on an alumina plane, R = 2.5 mm, 3.9 m/s, mu = 0.092.
E, nu, rho, R, V, mu = 3.8e11, 0.23, 4000.0, 0.0025, 3.9, 0.092
tmodel = os.environ.get("TANGENTIAL", "mindlin_rescale")
for angle in (0, 20, 45, 70):
    a = math.radians(angle)
    vn, vt = V * math.cos(a), V * math.sin(a)
    dt = hertz_tc(E, nu, rho, R, vn, True) / steps
    rows, work = run("in.wall", dict(E=E, nu=nu, rho=rho, R=R, vn=vn, vt=vt, mu=mu, dt=dt,
                                     nsteps=3 * steps, tmodel=tmodel), "wall.out")
    fz = [r[0] for r in rows]
    tc = sum(1 for x in fz if x > 0) * dt
    fmax = max(fz)
    last = rows[-1]
    en = last[2] / vn
    tc_o, f_o, en_o, et_o, w_o = ours[f"wall{angle}"]
    case = f"alumina on plane, {angle} deg"
    row(case, "contact time (s)", tc_o, tc)
    row(case, "peak force (N)", f_o, fmax)
    row(case, "e_n", en_o, en)
    if angle > 0:
        row(case, "e_t", et_o, last[1] / vt)
        row(case, "spin (rad/s)", w_o, last[3])

print("| case | quantity | mdr-dem (validator) | LAMMPS | difference |")
print("|---|---|---|---|---|")
print("\n".join(rows_out))
