"""Fit the MDR law's q_c, Θ/E* and scale to drop-test restitution data, and plot e(v).

    python examples/python/fit_drop_tests.py                     # synthetic data (known answer)
    python examples/python/fit_drop_tests.py measured.csv        # your data: v0_m_per_s,e_n
    python examples/python/fit_drop_tests.py measured.csv --radius 0.002 --youngs 7e10 \
        --poisson 0.33 --density 2700 --plot fit.png

Needs numpy (and matplotlib for --plot). The fit is `mdr-dem impact fit`'s.
"""

import argparse

import numpy as np

import mdr_dem


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data", nargs="?", help="CSV with header v0_m_per_s,e_n")
    for name, default, unit in [
        ("radius", 0.00635, "m"),
        ("density", 7800.0, "kg/m^3"),
        ("youngs", 2.0e11, "Pa"),
        ("poisson", 0.286, "-"),
    ]:
        parser.add_argument(f"--{name}", type=float, default=default, help=f"particle {name} ({unit})")
    parser.add_argument("--plot", help="write the figure to this file (.png, .svg, .pdf)")
    args = parser.parse_args()
    material = dict(radius=args.radius, density=args.density, youngs=args.youngs, poisson=args.poisson)

    if args.data:
        table = np.genfromtxt(args.data, delimiter=",", names=True)
        v0, e = table["v0_m_per_s"], table["e_n"]
    else:
        # Synthetic drop tests: q_c = 2.6e5 N/m, Θ/E* = 0.3, scale 0.92, 1 % noise.
        truth = mdr_dem.MdrLaw(qc=2.6e5, theta_ratio=0.3, **material)
        v0 = np.geomspace(0.05, 8.0, 25)
        e = 0.92 * truth.restitution(v0) + np.random.default_rng(1).normal(0, 0.005, v0.size)
        print("synthetic data from q_c = 2.6e5 N/m, theta_ratio = 0.3, scale = 0.92")

    result = mdr_dem.fit(v0, e, **material)
    print(f"q_c         = {result.qc:.4e} ± {result.qc_uncertainty:.1e} N/m")
    print(f"theta_ratio = {result.theta_ratio:.4f} ± {result.theta_ratio_uncertainty:.4f}")
    print(f"scale       = {result.scale:.4f} ± {result.scale_uncertainty:.4f}")
    print(f"rmse        = {result.rmse:.2e} over {result.n_points} points "
          f"({result.n_plastic} above the yield speed {result.yield_speed:.3f} m/s)")

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        v = np.geomspace(v0.min() / 2, v0.max() * 2, 300)
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.semilogx(v0, e, "o", label="measured")
        ax.semilogx(v, result.predict(v), "-",
                    label=f"MDR fit: $q_c$ = {result.qc:.3g} N/m, Θ/E* = {result.theta_ratio:.3f}")
        ax.axvline(result.yield_speed, ls=":", color="gray", label="yield speed")
        ax.set_xlabel("impact speed $v_0$ (m/s)")
        ax.set_ylabel("coefficient of restitution $e$")
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.plot, dpi=150)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
