"""REBOUND 5.2 port of examples/shearing_sheet/problem.c: SEI (Hill), shear-periodic
ghost boxes, tree collisions (+ optional tree self-gravity), hard spheres, Bridges eps(v).
usage: ring.py [--cor bridges_py|bridges_c|const] [--eps 0.5] [--grav tree|none] [--orbits 20]
       [--root 100 --nroot 2: box of nroot x nroot root boxes of side root (m)] [--seed 1] [--json FILE]
Runs shorter than one orbit sample every tenth of the run instead of every 0.1 orbit."""
import argparse, ctypes, json, math, os, time
import numpy as np, rebound
ap = argparse.ArgumentParser()
ap.add_argument("--cor", default="bridges_py", choices=["bridges_py", "bridges_c", "const"])
ap.add_argument("--eps", type=float, default=0.5); ap.add_argument("--grav", default="tree", choices=["tree", "none"])
ap.add_argument("--orbits", type=float, default=20.); ap.add_argument("--root", type=float, default=100.)
ap.add_argument("--nroot", type=int, default=2); ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--json", default=None); a = ap.parse_args()
OMEGA = 0.00013143527; P = 2 * math.pi / OMEGA          # 1/s, s
SIGMA, RHO, RMIN, RMAX, SLOPE = 400., 400., 1., 4., -3.  # kg/m^2, kg/m^3, m, m
sim = rebound.Simulation(); sim.rand_seed = a.seed
sim.integrator = "sei"; sim.OMEGA = OMEGA; sim.boundary = "shear"; sim.collision = "tree"
sim.gravity = a.grav; sim.opening_angle2 = .5; sim.G = 6.67428e-11; sim.softening = 0.1
sim.collision_resolve = "hardsphere"; sim.dt = 1e-3 * P
sim.root_size = a.root; sim.N_root_x = sim.N_root_y = a.nroot; sim.N_root_z = 1   # = configure_box(100,2,2,1)
sim.N_ghost_x = sim.N_ghost_y = 2; sim.N_ghost_z = 0; L = a.root * a.nroot
def cor_bridges(r, v):                                   # Bridges et al. 1984, v in m/s
    return min(1., max(0., 0.32 * pow(abs(v) * 100., -0.234)))
if a.cor == "bridges_py": sim.coefficient_of_restitution = cor_bridges
elif a.cor == "const": sim.coefficient_of_restitution = lambda r, v, e=a.eps: e
else:   # same law compiled in C (libcor.so), passed as a raw function pointer
    lib = ctypes.CDLL(os.path.join(os.path.dirname(os.path.abspath(__file__)), "libcor.so"))
    sim._corfp = rebound.simulation.CORFF(ctypes.cast(lib.cor_bridges_c, ctypes.c_void_p).value)
    sim._coefficient_of_restitution = sim._corfp
sim.minimum_collision_velocity = RMIN * OMEGA * 0.001
rng = np.random.default_rng(a.seed); mtot = 0.
while mtot < SIGMA * L * L:
    pmax, pmin = RMAX ** (SLOPE + 1), RMIN ** (SLOPE + 1)
    rad = ((pmax - pmin) * rng.uniform() + pmin) ** (1 / (SLOPE + 1)); m = RHO * 4 / 3 * math.pi * rad ** 3
    x = rng.uniform(-L / 2, L / 2)
    sim.add(m=m, r=rad, x=x, y=rng.uniform(-L / 2, L / 2), z=rng.normal(), vy=-1.5 * x * OMEGA); mtot += m
N = sim.N; print(f"N={N} box={L:.0f} m lambda_cr={4*math.pi**2*SIGMA*sim.G/OMEGA**2:.1f} m {a.cor} grav={a.grav}", flush=True)
def diag():
    X = np.zeros((N, 3)); V = np.zeros((N, 3)); m = np.zeros(N); r = np.zeros(N)
    sim.serialize_particle_data(xyz=X, vxvyvz=V, m=m, r=r)
    V[:, 1] += 1.5 * OMEGA * X[:, 0]; V -= np.average(V, axis=0, weights=m)   # remove Keplerian shear
    z = X[:, 2] - np.average(X[:, 2], weights=m); s2 = np.average(V ** 2, axis=0, weights=m)
    return dict(t_orb=sim.t / P, sx=s2[0] ** .5, sy=s2[1] ** .5, sz=s2[2] ** .5, c=(s2.sum() / 3) ** .5,
                c_num=(np.mean(V ** 2, axis=0).sum() / 3) ** .5, zrms=np.average(z ** 2, weights=m) ** .5,
                zrms_num=np.mean(z ** 2) ** .5, ff0=math.pi * np.clip(r ** 2 - z ** 2, 0, None).sum() / L ** 2,
                coll=sim.collisions_log_n, steps=sim.steps_done)            # ff0: volume filling factor at z=0
R = np.array([p.r for p in sim.particles]); tau = math.pi * (R ** 2).sum() / L ** 2; hist = []; w0 = time.perf_counter()
ds = min(0.1, a.orbits / 10)                             # sampling interval (orbits): 0.1, or 1/10 of a short run
for k in range(1, int(round(a.orbits / ds)) + 1):
    sim.integrate(k * ds * P, exact_finish_time=0); d = diag(); d["wall"] = time.perf_counter() - w0; hist.append(d)
    if k % 10 == 0 and ds == 0.1: print(f"orbit {d['t_orb']:5.1f} wall {d['wall']:7.1f}s c={d['c']*1e3:.3f} mm/s zrms={d['zrms']:.2f} m FF0={d['ff0']:.3f} coll={d['coll']}", flush=True)
wall = time.perf_counter() - w0; H = [h for h in hist if h["t_orb"] >= a.orbits / 2 - 1e-9]
h0 = [h for h in hist if h["t_orb"] < a.orbits / 2 - 1e-9][-1]; mean = lambda k: float(np.mean([h[k] for h in H]))
res = dict(N=N, box_m=L, cor=a.cor, grav=a.grav, orbits=a.orbits, wall_s=wall, steps_per_s=sim.steps_done / wall,
    wall_per_orbit_s=wall / a.orbits, first_orbit_wall_s=hist[min(9, len(hist) - 1)]["wall"], first_orbit_collisions=hist[min(9, len(hist) - 1)]["coll"],
    wall_per_orbit_2nd_half=(H[-1]["wall"] - h0["wall"]) / (H[-1]["t_orb"] - h0["t_orb"]),
    coll_per_wall_s_2nd_half=(H[-1]["coll"] - h0["coll"]) / (H[-1]["wall"] - h0["wall"]),
    coll_per_particle_per_orbit_2nd_half=(H[-1]["coll"] - h0["coll"]) / N / (H[-1]["t_orb"] - h0["t_orb"]),
    c_m_s=mean("c"), c_num_m_s=mean("c_num"), sx=mean("sx"), sy=mean("sy"), sz=mean("sz"),
    c_over_R1Omega=mean("c") / (RMIN * OMEGA), c_over_rmeanOmega=mean("c") / (R.mean() * OMEGA),
    zrms_m=mean("zrms"), zrms_num_m=mean("zrms_num"), ff0=mean("ff0"), tau_dyn=tau,
    Q_toomre=mean("sx") * OMEGA / (3.36 * sim.G * SIGMA), rebound=rebound.__version__)
print(json.dumps(res, indent=1))
if a.json: json.dump(dict(result=res, history=hist), open(a.json, "w"), indent=1)
