"""mdr_dem: the MDR elasto-plastic contact law (Lyashenko & Popov 2018) from Python.

All quantities are SI (m, kg, s, N, Pa). The Rust crates of mdr-dem do the work; this package
converts numpy arrays and Python values, raises ValueError naming the offending argument, and
releases the GIL during long runs.

- ``MdrLaw(**kw)``: the law bound to one pair (keyword arguments as the CLI's flags: radius,
  density, youngs, poisson, target_radius, target_density, target_youngs, target_poisson, qc,
  theta_ratio; defaults: the paper's Fig. 2), with ``force``, ``force_curve``, ``restitution``
  and ``impact``; ``MdrState``: one contact's history.
- ``curve``, ``fit``, ``oblique``: the single-impact validator (``mdr-dem impact ...``).
- ``Ring``: a planetary-ring shearing box (``mdr-dem sim ring``).
- ``run_scene``, ``bench_bed``: granular scenes from TOML files and the throughput bench;
  ``scene_laws``: the laws a scene can name (normal, tangential, damping, rolling), with their
  declared parameters.

See docs/python.md.
"""

from ._native import (
    PAPER_SCALE,
    FitResult,
    ImpactTrace,
    MdrLaw,
    MdrState,
    Ring,
    bench_bed,
    curve,
    fit,
    oblique,
    run_scene,
    scene_laws,
)

__all__ = [
    "PAPER_SCALE",
    "FitResult",
    "ImpactTrace",
    "MdrLaw",
    "MdrState",
    "Ring",
    "bench_bed",
    "curve",
    "fit",
    "oblique",
    "run_scene",
    "scene_laws",
]
