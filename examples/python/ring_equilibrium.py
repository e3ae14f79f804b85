"""Run a small planetary-ring shearing box and plot its equilibration: the velocity dispersion
c(t) and the thickness z_rms(t) with the Bridges law, the MDR ice law and a Python law.

    python examples/python/ring_equilibrium.py                   # 200 particles, 5 orbits each
    python examples/python/ring_equilibrium.py --orbits 20 --plot ring.png

Needs numpy (and matplotlib for --plot). Defaults otherwise REBOUND's shearing sheet
(docs/rings.md).
"""

import argparse

import mdr_dem


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--particles", type=int, default=200)
    parser.add_argument("--box", type=float, default=100.0, help="box side (m)")
    parser.add_argument("--orbits", type=float, default=5.0)
    parser.add_argument("--plot", help="write the figure to this file")
    args = parser.parse_args()
    config = dict(particles=args.particles, box=args.box, seed=1)

    def half_below_1mm_per_s(v):
        """A user's law: ε = 0.5 above 1 mm/s, elastic below (v in m/s)."""
        return 0.5 if v > 1e-3 else 1.0

    runs = {}
    for label, law in [("Bridges", "bridges"), ("MDR ice", "mdr"), ("Python law", half_below_1mm_per_s)]:
        ring = mdr_dem.Ring(config, law=law)
        summary = ring.run(args.orbits, callback=lambda s: print(
            f"  {label}: t = {s['t_orbits']:.1f} orbits, c = {1e3 * s['c']:.3f} mm/s", end="\r"))
        print(f"{label:>11}: c = {1e3 * summary['c_m_per_s']:.3f} mm/s, "
              f"z_rms = {summary['z_rms_m']:.2f} m, "
              f"{summary['collisions_per_particle_per_orbit']:.2f} collisions/particle/orbit")
        runs[label] = ring.samples

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(6, 5))
        for label, s in runs.items():
            top.plot(s["t_orbits"], 1e3 * s["c"], label=label)
            bottom.plot(s["t_orbits"], s["z_rms"], label=label)
        top.set_ylabel("c (mm/s)")
        bottom.set_ylabel("$z_{rms}$ (m)")
        bottom.set_xlabel("time (orbits)")
        top.legend()
        fig.tight_layout()
        fig.savefig(args.plot, dpi=150)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
