"""Type stubs of mdr_dem (SI units throughout: m, kg, s, N, Pa)."""

from os import PathLike
from typing import Any, Callable, Mapping, Optional, Sequence, TypedDict, Union, overload

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
StrPath = Union[str, "PathLike[str]"]

PAPER_SCALE: float
"""The scale factor the paper applies to the model's e_n (0.95)."""

class MdrState:
    """History of one MDR contact."""

    max_overlap: float
    """Largest overlap so far, d_max (m)."""
    contact_radius: float
    """Radius of the attached springs (m); with adhesion positive while the contact holds."""
    adhesive_work: float
    """Energy the springs held when they let go, summed (J)."""
    def __init__(
        self, max_overlap: float = 0.0, contact_radius: float = 0.0, adhesive_work: float = 0.0
    ) -> None: ...

class ImpactTrace:
    """Time history of one head-on impact (one point per time step)."""

    t: FloatArray
    """Time since first contact (s)."""
    overlap: FloatArray
    """Overlap d (m)."""
    velocity: FloatArray
    """Approach velocity (m/s), positive towards the target."""
    force: FloatArray
    """Normal force (N)."""
    contact_radius: FloatArray
    """Contact radius (m)."""
    plastic_work: FloatArray
    """Plastic work dissipated so far (J)."""
    restitution: float
    """Coefficient of restitution e_n of the integration."""
    max_overlap: float
    """Largest overlap (m)."""
    residual_overlap: float
    """Residual (plastic) overlap after separation (m)."""
    contact_time: float
    """Contact time (s)."""
    peak_force: float
    """Peak force (N)."""
    stuck: bool
    """Whether the sphere stuck (adhesion; restitution 0)."""
    pull_off_force: float
    """Largest tensile force (N, ≥ 0)."""
    release_overlap: float
    """Overlap at which the contact let go (m); NaN when stuck."""

class MdrLaw:
    """The MDR elasto-plastic law (Lyashenko & Popov 2018) bound to one pair.

    Defaults: the paper's Fig. 2 (steel ball R = 6.35 mm on a steel half-space,
    q_c = 3.8e5 N/m, Θ/E* = 0.37). Without target_radius/target_density the target is a
    half-space; target_youngs/target_poisson default to the particle's.
    """

    def __init__(
        self,
        *,
        radius: float = 0.00635,
        density: float = 7800.0,
        youngs: float = 2.0e11,
        poisson: float = 0.286,
        target_radius: Optional[float] = None,
        target_density: Optional[float] = None,
        target_youngs: Optional[float] = None,
        target_poisson: Optional[float] = None,
        qc: float = 3.8e5,
        theta_ratio: float = 0.37,
        work_of_adhesion: float = 0.0,
    ) -> None:
        """radius (m), density (kg/m³), youngs (Pa), poisson (-), target_* likewise, qc: critical
        line load (N/m, eq. 7), theta_ratio: hardening ratio Θ/E* (eq. 12), work_of_adhesion:
        Δγ (J/m², ≥ 0; Heß's adhesion rule on the springs)."""
    def parameters(self) -> dict[str, Optional[float]]:
        """The keyword arguments this law was built with."""
    @property
    def qc(self) -> float:
        """Critical line load q_c (N/m)."""
    @property
    def theta_ratio(self) -> float:
        """Hardening ratio Θ/E*."""
    @property
    def effective_modulus(self) -> float:
        """E* (Pa), eq. (3)."""
    @property
    def effective_radius(self) -> float:
        """Effective radius R (m)."""
    @property
    def reduced_mass(self) -> float:
        """Reduced mass m (kg)."""
    @property
    def yield_overlap(self) -> float:
        """u_c = π q_c / (2 E*) (m), eq. (11)."""
    @property
    def yield_speed(self) -> float:
        """Impact speed below which a first impact is elastic (m/s)."""
    @property
    def half_space(self) -> bool:
        """Whether the target is a half-space."""
    @property
    def work_of_adhesion(self) -> float:
        """Work of adhesion Δγ (J/m²)."""
    @property
    def pull_off_force(self) -> float:
        """Elastic (JKR) pull-off force (3/2) π Δγ R (N)."""
    def detachment_overlap(self, state: MdrState) -> float:
        """Overlap (m) below which a contact with history `state` has let go (negative while an
        adhesive contact holds)."""
    def force(self, overlap: float, state: Optional[MdrState] = None) -> float:
        """Normal force (N) at overlap (m); advances `state` in place when given."""
    @overload
    def force_curve(self, overlaps: float, state: Optional[MdrState] = None) -> float: ...
    @overload
    def force_curve(self, overlaps: ArrayLike, state: Optional[MdrState] = None) -> FloatArray: ...
    def force_curve(self, overlaps: Any, state: Optional[MdrState] = None) -> Any:
        """Forces (N) along a loading path of overlaps (m), visited in order by one history."""
    def residual_overlap(self, state: MdrState) -> float:
        """Residual (plastic) overlap (m) of a contact with history `state`."""
    @overload
    def restitution(self, v0: float) -> float: ...
    @overload
    def restitution(self, v0: ArrayLike) -> FloatArray: ...
    def restitution(self, v0: Any) -> Any:
        """e_n of a first impact at v0 (m/s), unscaled (`impact curve` column e_n): closed form,
        or with adhesion time-integrated, 0 where the sphere sticks."""
    def impact(
        self,
        v0: float,
        *,
        method: str = "closed",
        springs: Optional[int] = None,
        steps: int = 2000,
    ) -> ImpactTrace:
        """Integrate one head-on impact at v0 (m/s) in time; method "closed" or "springs"."""

class CurveResult(TypedDict):
    v0_m_per_s: FloatArray
    e_n: FloatArray
    e_n_scaled: FloatArray
    d_max_m: FloatArray
    d_residual_m: FloatArray
    contact_time_s: FloatArray
    f_max_n: FloatArray
    stuck: FloatArray
    yield_speed_m_per_s: float

def curve(
    v0: Optional[ArrayLike] = None,
    *,
    v_min: float = 0.01,
    v_max: float = 30.0,
    points: int = 200,
    law: str = "mdr",
    method: str = "closed",
    springs: Optional[int] = None,
    steps: int = 2000,
    scale: float = 0.95,
    elastic: bool = False,
    yield_stress: Optional[float] = None,
    radius: float = ...,
    density: float = ...,
    youngs: float = ...,
    poisson: float = ...,
    target_radius: Optional[float] = ...,
    target_density: Optional[float] = ...,
    target_youngs: Optional[float] = ...,
    target_poisson: Optional[float] = ...,
    qc: float = ...,
    theta_ratio: float = ...,
) -> CurveResult:
    """e_n(v0) sweep as `mdr-dem impact curve` (speeds in m/s; law "mdr", "thornton", "hertz";
    yield_stress: Thornton's p_y in Pa)."""

class FitResult:
    """Result of `fit`."""

    qc: float
    """Fitted q_c (N/m)."""
    theta_ratio: float
    """Fitted Θ/E*."""
    scale: float
    """Fitted scale factor."""
    qc_uncertainty: Optional[float]
    """1σ of q_c (N/m); None if fixed."""
    theta_ratio_uncertainty: Optional[float]
    """1σ of Θ/E*; None if fixed."""
    scale_uncertainty: Optional[float]
    """1σ of the scale; None if fixed."""
    work_of_adhesion: float
    """Fitted (or fixed) work of adhesion Δγ (J/m²)."""
    work_of_adhesion_uncertainty: Optional[float]
    """1σ of Δγ (J/m²); None if fixed."""
    residuals: FloatArray
    """Measured e minus the fitted model at each point."""
    rmse: float
    """Root-mean-square residual."""
    n_points: int
    n_plastic: int
    """Points above the fitted yield speed."""
    yield_speed: float
    """Fitted yield speed (m/s)."""
    free: list[str]
    """The fitted parameters."""
    @property
    def law(self) -> MdrLaw:
        """The fitted law."""
    @overload
    def predict(self, v0: float) -> float: ...
    @overload
    def predict(self, v0: ArrayLike) -> FloatArray: ...
    def predict(self, v0: Any) -> Any:
        """scale · e_n(v0) of the fitted model (v0 in m/s)."""
    def to_dict(self) -> dict[str, Any]:
        """The keys of `mdr-dem impact fit --json`."""

def fit(
    v0: ArrayLike,
    e: ArrayLike,
    *,
    free: Optional[Sequence[str]] = None,
    scale: float = 0.95,
    radius: float = ...,
    density: float = ...,
    youngs: float = ...,
    poisson: float = ...,
    target_radius: Optional[float] = ...,
    target_density: Optional[float] = ...,
    target_youngs: Optional[float] = ...,
    target_poisson: Optional[float] = ...,
    qc: float = ...,
    theta_ratio: float = ...,
) -> FitResult:
    """Least-squares fit of q_c, Θ/E* and the scale (`free`, default all three) to measured
    restitution e at speeds v0 (m/s), as `mdr-dem impact fit`."""

class ObliqueResult(TypedDict):
    angle_deg: FloatArray
    e_n: FloatArray
    e_t: FloatArray
    rebound_angle_deg: FloatArray
    omega_rad_per_s: FloatArray
    stuck: FloatArray

def oblique(
    speed: float,
    angles: Optional[ArrayLike] = None,
    *,
    tangential: Optional[str] = None,
    spin: float = 0.0,
    mu: float = 0.2,
    method: Optional[str] = None,
    springs: Optional[int] = None,
    steps: int = 2000,
    law: str = "mdr",
    elastic: bool = False,
    yield_stress: Optional[float] = None,
    radius: float = ...,
    density: float = ...,
    youngs: float = ...,
    poisson: float = ...,
    target_youngs: Optional[float] = ...,
    target_poisson: Optional[float] = ...,
    qc: float = ...,
    theta_ratio: float = ...,
) -> ObliqueResult:
    """Oblique impacts on a half-space at `speed` (m/s) and `angles` (degrees from the normal),
    friction mu, initial spin (rad/s), as `mdr-dem impact oblique`."""

class RingConfig(TypedDict, total=False):
    particles: int
    surface_density: float
    """Σ (kg/m²)."""
    box: float
    """Side of the square box (m)."""
    seed: int
    omega: float
    """Orbital frequency Ω (1/s)."""
    dt_orbits: float
    sample_orbits: float
    density: float
    """Particle density (kg/m³)."""
    gravity: bool

class RingSummary(TypedDict):
    particles: int
    c_m_per_s: float
    c_number_m_per_s: float
    sigma_x_m_per_s: float
    sigma_y_m_per_s: float
    sigma_z_m_per_s: float
    c_over_mean_r_omega: float
    z_rms_m: float
    z_rms_number_m: float
    filling_factor_z0: float
    collisions_per_particle_per_orbit: float
    wall_s_per_orbit: float
    optical_depth: float

class Ring:
    """A planetary-ring shearing box (REBOUND's shearing-sheet defaults)."""

    def __init__(
        self,
        config: Optional[Union[RingConfig, Mapping[str, Any]]] = None,
        law: Union[str, float, Callable[[float], float], None] = None,
        *,
        youngs: float = 9.0e9,
        poisson: float = 0.33,
        qc: float = 8.0e3,
        theta_ratio: float = 0.2,
    ) -> None:
        """law: "bridges" (default), "mdr" (ice: youngs Pa, poisson, qc N/m, theta_ratio), a
        constant ε in [0, 1], or a callable law(v) -> ε of the approach speed v (m/s)."""
    def run(
        self, orbits: float, callback: Optional[Callable[[dict[str, float]], Any]] = None
    ) -> RingSummary:
        """Run `orbits` orbits; second-half averages. callback(sample) at every sample."""
    @property
    def positions(self) -> FloatArray:
        """(N, 3) centres (m)."""
    @property
    def velocities(self) -> FloatArray:
        """(N, 3) velocities (m/s)."""
    @property
    def radii(self) -> FloatArray:
        """Radii (m)."""
    @property
    def masses(self) -> FloatArray:
        """Masses (kg)."""
    @property
    def time_orbits(self) -> float: ...
    @property
    def collisions(self) -> int: ...
    @property
    def law_name(self) -> str: ...
    @property
    def law_calls(self) -> int: ...
    @property
    def samples(self) -> dict[str, FloatArray]:
        """Every sample so far as arrays (t_orbits, sigma_x, …, c, z_rms, collisions, wall_s)."""
    def __len__(self) -> int: ...

def scene_laws(kind: Optional[str] = None) -> list[dict[str, Any]]:
    """The laws a scene can name, as the law registry declares them: the normal laws
    (``[contact] normal = "…"``), then the tangential, damping and rolling laws
    (``tangential = "…"``, ``damping = "…"``, ``rolling = "…"``); ``kind`` (``"normal"``,
    ``"tangential"``, ``"damping"``, ``"rolling"``) keeps one kind. Each a dict with ``name``,
    ``kind``, ``summary`` and ``parameters``, a list of dicts with the scene ``key``,
    ``symbol``, ``unit``, allowed ``range``, ``default`` (None: required), ``doc`` (what it is,
    with its equation), command-line ``flag``, ``python`` keyword and ``lammps`` keyword."""

def run_scene(
    path: StrPath,
    out_dir: Optional[StrPath] = None,
    *,
    resume: Optional[StrPath] = None,
    stop_at_step: Optional[int] = None,
    no_frames: bool = False,
    quiet: bool = True,
) -> dict[str, Any]:
    """Run a scene file; the headline quantities by name, plus text, step, time_s,
    wall_seconds, stopped_early, checkpoint."""

class BenchBedResult(TypedDict):
    """Figures of one `bench_bed` run: the keys of `mdr-dem bench bed --json`, plus
    `cpu_particle_steps_per_s`. A particle-step is one particle advanced one step."""

    particle_steps_per_s: float
    """Particle-steps per wall-clock second of the timed steps."""
    ms_per_step: float
    """Wall-clock milliseconds per timed step."""
    contacts_per_particle: float
    """Sphere-sphere contacts per particle at the last step (2 × pairs / particles)."""
    peak_rss_mb: float
    """Peak resident memory of the whole Python process so far (MB, VmHWM); 0 where
    unavailable."""
    threads: int
    """Worker threads."""
    particle_steps_per_cpu_s: float
    """Particle-steps per CPU second (user + system, all threads); NaN where the process CPU
    clock is unavailable."""
    cpu_particle_steps_per_s: float
    """The same number as `particle_steps_per_cpu_s`, under the name `mdr-dem bench scene`
    uses."""
    cpu_seconds: float
    """CPU time of the timed steps (s, all threads)."""
    wall_seconds: float
    """Wall-clock time of the timed steps (s)."""
    law: str
    """Either "hertz" or "mdr"."""
    particles: int
    """Spheres (after tiling)."""
    steps: int
    """Timed steps."""
    rebuilds: int
    """Neighbour-list builds during the timed steps."""
    floor_contacts: int
    """Sphere-floor contacts at the last step."""
    plastic_contact_fraction: float
    """Fraction of the touching sphere-sphere pairs that have yielded (d_max > u_c)."""
    stepper_bytes_per_particle: float
    """The stepper's buffers per particle (bytes)."""
    orientation: bool
    """Whether orientations were integrated."""
    work_books: bool
    """Whether the pair histories booked friction and damping work."""
    state_checksum: str
    """FNV-1a hash (16 hex digits) of the final positions and velocities: equal iff two runs
    gave the same trajectories."""

def bench_bed(
    data: Optional[StrPath] = None,
    *,
    law: str = "hertz",
    steps: int = 10_000,
    warmup: int = 2_000,
    threads: int = 1,
    tile: int = 1,
    qc: float = 10.0,
    skin: float = 0.1,
    no_orientation: bool = False,
    no_work_books: bool = False,
    count: Optional[int] = None,
    settle_steps: int = 40_000,
    seed: int = 1,
) -> BenchBedResult:
    """Throughput of the neighbour-list path on a settled bed: the run of `mdr-dem bench bed`
    (reduced units: sphere diameter 1, density 1, dt = 1e-4).

    data: LAMMPS data file of the bed (default: the repository's 10,000-sphere reference bed);
    count: instead, pour `count` spheres and settle them with `settle_steps` steps (untimed;
    `seed` jitters the lattice); law: "hertz" or "mdr" (q_c = `qc`, force/length, Θ = 0.37 E*);
    steps: timed steps after `warmup` untimed ones; threads: worker threads; tile: repeat the
    bed tile × tile times in x and y; skin: neighbour skin (length); no_orientation,
    no_work_books: as the CLI's flags. The GIL is released during the run."""
