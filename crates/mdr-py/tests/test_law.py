"""The law and the validator from Python, checked against independent references.

The references are written out here from docs/theory.md, not taken from the Rust code: the MDR
energy route of §4 (load to `W_load(D) = K`, return `W_stored(D)`), Hertz's force and contact
time, Thornton's closed form (§6, his eq. 31), the elastic limit `e = 1` below the yield speed
and the high-speed limit `e → √θ`; plus synthetic data with known parameters for the fit. The
`mdr-dem` program's output, when it is built, is a further consistency check of the binding.
"""

import csv
import io
import math
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import mdr_dem

REPO = Path(__file__).resolve().parents[3]

PAPER_SPEEDS = [0.03, 0.1, 0.2, 0.28, 0.3, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 30.0]


def cli_binary():
    """The built `mdr-dem` program, if there is one."""
    for candidate in (
        os.environ.get("MDR_DEM_BIN"),
        REPO / "target" / "release" / "mdr-dem",
        REPO / "target" / "debug" / "mdr-dem",
        shutil.which("mdr-dem"),
    ):
        if candidate and Path(candidate).is_file() and os.access(candidate, os.X_OK):
            return str(candidate)
    return None


def cli_curve(args):
    """`mdr-dem impact curve ARGS --csv - -q` as columns, or None without the program."""
    binary = cli_binary()
    if binary is None:
        return None
    out = subprocess.run(
        [binary, "impact", "curve", *args, "--csv", "-", "-q"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


# The paper's steel ball on a steel plate (docs/theory.md §7): E = 2e11 Pa, nu = 0.286 for both
# bodies, R = 0.635 cm, rho = 7800 kg/m^3, q_c = 3.8e5 N/m, theta = 0.37.
PAPER = dict(youngs=2.0e11, poisson=0.286, radius=0.635e-2, density=7800.0, qc=3.8e5, theta=0.37)


def paper_constants(youngs, poisson, radius, density, qc, theta):
    """E* (eq. 16, two equal bodies), R, m (ball on a half-space), u_c (eq. 11), theta."""
    e_star = youngs / (2.0 * (1.0 - poisson**2))
    mass = 4.0 / 3.0 * math.pi * radius**3 * density
    u_c = math.pi * qc / (2.0 * e_star)
    return e_star, radius, mass, u_c, theta


def energy_route_restitution(v, youngs, poisson, radius, density, qc, theta):
    """e_n of a first impact at `v` from docs/theory.md §4, written out independently."""
    return energy_route(v, *paper_constants(youngs, poisson, radius, density, qc, theta))


def energy_route(v, e_star, r, m, u_c, th):
    """docs/theory.md §4 for a fresh contact: load to W_load(D) = m v^2/2, return W_stored(D)."""
    c = 4.0 / 3.0 * e_star * math.sqrt(r)

    def w_load(d):
        return 0.4 * c * (d**2.5 - (1.0 - th) * max(d - u_c, 0.0) ** 2.5)

    k = 0.5 * m * v * v
    if k <= w_load(u_c):
        return 1.0
    lo, hi = u_c, 2.0 * u_c
    while w_load(hi) < k:
        hi *= 2.0
    for _ in range(200):  # bisection to the last bit
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if w_load(mid) < k else (lo, mid)
    d = 0.5 * (lo + hi)
    s = d - u_c
    e_r = (1.0 - th) * s
    stored = 0.4 * c * th**-0.5 * (s - e_r) ** 2.5
    stored += 0.4 * c * (d**2.5 - s**2.5) - (1.0 - th) * c * s**1.5 * (d - s)
    return math.sqrt(stored / k)


def test_curve_equals_the_energy_route_written_out_from_the_theory():
    speeds = np.array(PAPER_SPEEDS + [300.0])
    e = mdr_dem.curve(speeds)["e_n"]
    reference = [energy_route_restitution(v, **PAPER) for v in speeds]
    # Both solve the same equation to rounding: measured largest relative difference 5.5e-16.
    np.testing.assert_allclose(e, reference, rtol=1e-12, atol=0)
    e_star, r, m, u_c, th = paper_constants(**PAPER)
    # Yield speed: Hertz energy at d = u_c (eq. 15 integrated once); elastic just below it.
    v_y = math.sqrt(2.0 * 0.4 * 4.0 / 3.0 * e_star * math.sqrt(r) * u_c**2.5 / m)
    below = mdr_dem.curve(np.array([0.01 * v_y, 0.5 * v_y, 0.999 * v_y]))
    np.testing.assert_allclose(below["e_n"], 1.0, rtol=0, atol=1e-12)
    assert below["yield_speed_m_per_s"] == pytest.approx(v_y, rel=1e-12)
    assert mdr_dem.curve(np.array([1.001 * v_y]))["e_n"][0] < 1.0
    # High-speed limit sqrt(theta) (theory §4): e(3 km/s) - sqrt(0.37) is 1e-4 and shrinking.
    fast = mdr_dem.curve(np.array([300.0, 3000.0]))["e_n"]
    assert 0 < fast[1] - math.sqrt(th) < fast[0] - math.sqrt(th) < 2e-3


def test_curve_hertz_and_thornton_laws_against_their_closed_forms():
    speeds = np.array([0.05, 0.3, 1.0, 3.0, 10.0])
    e_star, r, m, u_c, th = paper_constants(**PAPER)
    hertz = mdr_dem.curve(speeds, law="hertz")
    # Elastic, time-integrated (2,000 steps per contact): e_n = 1 to 3.1e-9; Hertz's contact time
    # c (m^2 / (R E*^2 v))^(1/5) with c = 2 (15/16)^(2/5) sqrt(pi) Gamma(7/5) / Gamma(9/10), and
    # peak force (4/3) E* sqrt(R) d_max^(3/2) with d_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5), to
    # the integrator's ~1e-7.
    np.testing.assert_allclose(hertz["e_n"], 1.0, rtol=0, atol=1e-8)
    c = 2.0 * (15.0 / 16.0) ** 0.4 * math.sqrt(math.pi) * math.gamma(1.4) / math.gamma(0.9)
    t_c = c * (m * m / (r * e_star**2 * speeds)) ** 0.2
    np.testing.assert_allclose(hertz["contact_time_s"], t_c, rtol=1e-6)
    d_max = (15.0 * m * speeds**2 / (16.0 * e_star * math.sqrt(r))) ** 0.4
    np.testing.assert_allclose(hertz["d_max_m"], d_max, rtol=1e-6)
    np.testing.assert_allclose(
        hertz["f_max_n"], 4.0 / 3.0 * e_star * math.sqrt(r) * d_max**1.5, rtol=1e-6
    )
    # Thornton with the default yield stress, whose yield overlap is the MDR law's u_c, so its
    # yield speed is the MDR one; his eq. (31) above it, e = 1 below it.
    v_y = math.sqrt(2.0 * 0.4 * 4.0 / 3.0 * e_star * math.sqrt(r) * u_c**2.5 / m)
    thornton = mdr_dem.curve(speeds, law="thornton")
    for v, e in zip(speeds, thornton["e_n"]):
        if v < v_y:
            assert e == pytest.approx(1.0, abs=1e-6), v
            continue
        x = v_y / v
        published = math.sqrt(6.0 * math.sqrt(3.0) / 5.0 * (1.0 - x * x / 6.0)) * (
            x / (x + 2.0 * math.sqrt(6.0 / 5.0 - x * x / 5.0))
        ) ** 0.25
        assert e == pytest.approx(published, abs=3e-7), v


def test_curve_with_the_spring_bed_agrees_with_the_closed_form():
    speeds = np.array([0.1, 0.5, 2.0, 10.0])
    closed = [energy_route_restitution(v, **PAPER) for v in speeds]
    springs = mdr_dem.curve(speeds, method="springs")
    # 2,000 springs, time-integrated: measured largest |difference| 7.4e-8.
    np.testing.assert_allclose(springs["e_n"], closed, rtol=0, atol=3e-7)
    coarse = mdr_dem.curve(np.array([2.0]), method="springs", springs=8)
    assert abs(coarse["e_n"][0] - closed[2]) > 1e-3 or abs(
        coarse["d_max_m"][0] - springs["d_max_m"][2]
    ) > 1e-3 * springs["d_max_m"][2]
    with pytest.raises(ValueError, match="`method`"):
        mdr_dem.curve(speeds, method="springs", law="thornton")


def test_closed_form_restitution_at_the_papers_speeds():
    law = mdr_dem.MdrLaw()
    e = law.restitution(np.array(PAPER_SPEEDS))
    assert isinstance(e, np.ndarray) and e.shape == (12,)
    reference = [energy_route_restitution(v, **PAPER) for v in PAPER_SPEEDS]
    np.testing.assert_allclose(e, reference, rtol=1e-12, atol=0)
    # A float in, a float out; docs/validation.md's rounded value at 1 m/s.
    assert isinstance(law.restitution(1.0), float)
    assert round(law.restitution(1.0), 4) == 0.7163
    # Shape kept: a 2-D array of speeds.
    grid = law.restitution(np.array(PAPER_SPEEDS).reshape(3, 4))
    assert grid.shape == (3, 4)
    fresh = cli_curve(["--velocities", ",".join(str(v) for v in PAPER_SPEEDS)])
    if fresh is not None:
        np.testing.assert_allclose(e, fresh["e_n"], rtol=1e-12, atol=0)


def test_curve_for_other_materials():
    kw = dict(radius=0.002, youngs=7.0e10, poisson=0.33, density=2700.0, qc=1.2e5, theta_ratio=0.25)
    speeds = np.array([0.2, 0.7, 2.5, 9.0])
    out = mdr_dem.curve(speeds, **kw)
    assert set(out) >= {
        "v0_m_per_s", "e_n", "e_n_scaled", "d_max_m", "d_residual_m", "contact_time_s", "f_max_n"
    }
    np.testing.assert_allclose(out["e_n_scaled"], 0.95 * out["e_n"], rtol=1e-15)
    # An aluminium-like ball on a half-space of the same material, from docs/theory.md §4.
    reference = [
        energy_route_restitution(v, youngs=7.0e10, poisson=0.33, radius=0.002, density=2700.0,
                                 qc=1.2e5, theta=0.25)
        for v in speeds
    ]
    np.testing.assert_allclose(out["e_n"], reference, rtol=1e-12)
    assert min(reference) < 0.9  # plastic at these speeds: not trivially e = 1
    flags = ["--radius", "0.002", "--youngs", "7e10", "--poisson", "0.33", "--density", "2700",
             "--qc", "1.2e5", "--theta-ratio", "0.25", "--velocities", "0.2,0.7,2.5,9"]
    fresh = cli_curve(flags)
    if fresh is None:
        pytest.skip("no built mdr-dem program to compare with (cargo build --release)")
    for key in ("e_n", "d_max_m", "d_residual_m", "contact_time_s", "f_max_n"):
        np.testing.assert_allclose(out[key], fresh[key], rtol=1e-12, err_msg=key)


def test_force_is_hertz_below_yield_and_loses_force_on_unloading():
    law = mdr_dem.MdrLaw()
    e_star, r = law.effective_modulus, law.effective_radius
    # E* of two steels with nu = 0.286: E / (2 (1 - nu^2)), eq. (3).
    assert e_star == pytest.approx(2.0e11 / (2 * (1 - 0.286**2)), rel=1e-14)
    d = 0.5 * law.yield_overlap
    assert law.force(d) == pytest.approx(4.0 / 3.0 * e_star * math.sqrt(r) * d**1.5, rel=1e-13)
    # u_c = pi q_c / (2 E*), eq. (11).
    assert law.yield_overlap == pytest.approx(math.pi * 3.8e5 / (2 * e_star), rel=1e-14)
    state = mdr_dem.MdrState()
    loaded = law.force(8e-6, state)
    assert state.max_overlap == 8e-6
    unloaded = law.force(7e-6, state)
    assert unloaded < loaded
    assert state.max_overlap == 8e-6
    assert 0 < law.residual_overlap(state) < 8e-6
    # The vectorised path visits the overlaps with one history.
    path = np.concatenate([np.linspace(0, 8e-6, 50), np.linspace(8e-6, 0, 50)])
    curve_state = mdr_dem.MdrState()
    forces = law.force_curve(path, curve_state)
    one_by_one = mdr_dem.MdrState()
    expected = [law.force(x, one_by_one) for x in path]
    np.testing.assert_array_equal(forces, expected)
    assert curve_state.max_overlap == 8e-6
    assert forces[-1] == 0.0


def test_impact_trace_agrees_with_the_closed_form():
    law = mdr_dem.MdrLaw()
    trace = law.impact(1.0, steps=2000)
    for name in ("t", "overlap", "velocity", "force", "contact_radius", "plastic_work"):
        arr = getattr(trace, name)
        assert isinstance(arr, np.ndarray) and arr.shape == trace.t.shape and arr.size > 100
    assert np.all(np.diff(trace.t) > 0)
    # Time integration (2,000 steps per contact) against the closed form: measured 3.2e-8.
    assert trace.restitution == pytest.approx(energy_route_restitution(1.0, **PAPER), abs=1e-7)
    assert trace.max_overlap == pytest.approx(np.max(trace.overlap), rel=1e-9)
    # docs/validation.md at 1 m/s, rounded to 4 digits there: d_max 16.96 um, residual
    # 7.234 um, t_c 46.31 us (measured 2.1e-4, 1.5e-5, 7.6e-5 from the rounded values).
    assert trace.max_overlap == pytest.approx(16.96e-6, rel=5e-4)
    assert trace.residual_overlap == pytest.approx(7.234e-6, rel=1e-4)
    assert trace.contact_time == pytest.approx(46.31e-6, rel=2e-4)


def test_fit_recovers_the_parameters_of_synthetic_data():
    truth = dict(qc=2.6e5, theta_ratio=0.3)
    scale = 0.92
    v = np.geomspace(0.05, 8.0, 30)
    e_model = scale * mdr_dem.MdrLaw(**truth).restitution(v)
    rng = np.random.default_rng(7)
    noise = 0.002
    e = e_model + rng.normal(0.0, noise, v.size)
    result = mdr_dem.fit(v, e)  # starts from the paper's q_c, theta_ratio, scale
    assert result.free == ["qc", "theta_ratio", "scale"]
    for name, true_value in (("qc", truth["qc"]), ("theta_ratio", truth["theta_ratio"]), ("scale", scale)):
        value, sigma = getattr(result, name), getattr(result, name + "_uncertainty")
        assert sigma > 0
        assert abs(value - true_value) < 4 * sigma, (name, value, sigma, true_value)
    assert result.residuals.shape == v.shape
    np.testing.assert_allclose(result.residuals, e - result.predict(v), atol=1e-12)
    assert result.rmse == pytest.approx(np.sqrt(np.mean(result.residuals**2)), rel=1e-9)
    assert result.rmse < 2 * noise
    assert result.n_points == 30
    # Noise-free data: the values themselves.
    exact = mdr_dem.fit(v, e_model)
    assert exact.qc == pytest.approx(truth["qc"], rel=1e-3)
    assert exact.theta_ratio == pytest.approx(truth["theta_ratio"], rel=1e-3)
    assert exact.scale == pytest.approx(scale, rel=1e-4)
    assert exact.law.restitution(1.0) == pytest.approx(mdr_dem.MdrLaw(**truth).restitution(1.0), rel=1e-3)


def test_fit_with_fixed_parameters_keeps_them():
    v = np.geomspace(0.1, 5.0, 12)
    e = 0.95 * mdr_dem.MdrLaw(qc=5e5).restitution(v)
    result = mdr_dem.fit(v, e, free=["qc"], theta_ratio=0.37, scale=0.95)
    assert result.qc == pytest.approx(5e5, rel=1e-4)
    assert result.theta_ratio == 0.37 and result.scale == 0.95
    assert result.theta_ratio_uncertainty is None and result.scale_uncertainty is None
    assert result.to_dict()["uncertainty"].keys() == {"q_c"}


def test_oblique_head_on_limit_and_columns():
    out = mdr_dem.oblique(1.0, [0.0, 30.0, 60.0], tangential="mindlin", method="closed")
    assert list(out) == [
        "angle_deg",
        "e_n",
        "e_t",
        "rebound_angle_deg",
        "omega_rad_per_s",
        "stuck",
    ]
    np.testing.assert_array_equal(out["angle_deg"], [0.0, 30.0, 60.0])
    # Mindlin with a closed-form normal law: the normal restitution does not depend on friction.
    assert out["e_n"][0] == pytest.approx(mdr_dem.MdrLaw().restitution(1.0), abs=2e-3)
    assert math.isnan(out["e_t"][0])
    assert np.all(out["e_t"][1:] <= 1.0)
    assert np.all(out["omega_rad_per_s"][1:] > 0)


@pytest.mark.parametrize(
    "call, argument",
    [
        (lambda: mdr_dem.MdrLaw(youngs=-1.0), "youngs"),
        (lambda: mdr_dem.MdrLaw(poisson=0.7), "poisson"),
        (lambda: mdr_dem.MdrLaw(radius=0.0), "radius"),
        (lambda: mdr_dem.MdrLaw(density=float("nan")), "density"),
        (lambda: mdr_dem.MdrLaw(qc=-5.0), "qc"),
        (lambda: mdr_dem.MdrLaw(theta_ratio=1.5), "theta_ratio"),
        (lambda: mdr_dem.MdrLaw(target_youngs=0.0), "target_youngs"),
        (lambda: mdr_dem.MdrLaw(target_poisson=-2.0), "target_poisson"),
        (lambda: mdr_dem.MdrLaw(target_radius=0.01), "target_radius"),
        (lambda: mdr_dem.MdrLaw(target_radius=-0.01, target_density=7800.0), "target_radius"),
        (lambda: mdr_dem.MdrLaw(target_density=-1.0, target_radius=0.01), "target_density"),
        (lambda: mdr_dem.MdrLaw().restitution([1.0, -2.0]), "v0"),
        (lambda: mdr_dem.MdrLaw().restitution("fast"), "v0"),
        (lambda: mdr_dem.MdrLaw().impact(0.0), "v0"),
        (lambda: mdr_dem.MdrLaw().impact(1.0, steps=3), "steps"),
        (lambda: mdr_dem.MdrLaw().impact(1.0, method="magic"), "method"),
        (lambda: mdr_dem.curve([1.0], law="plastic"), "law"),
        (lambda: mdr_dem.curve([1.0], scale=0.0), "scale"),
        (lambda: mdr_dem.curve(v_min=1.0, v_max=0.5), "v_max"),
        (lambda: mdr_dem.curve([1.0], youngs=-1.0), "youngs"),
        (lambda: mdr_dem.fit([1.0, 2.0, 3.0], [0.7, 0.6]), "e"),
        (lambda: mdr_dem.fit([1.0, 2.0], [0.7, 0.6]), "v0"),
        (lambda: mdr_dem.fit([1.0, 2.0, 3.0, 4.0], [0.7, 0.6, 0.6, 0.6], free=["q"]), "free"),
        (lambda: mdr_dem.oblique(1.0, [95.0]), "angles"),
        (lambda: mdr_dem.oblique(1.0, mu=-0.1, tangential="mindlin"), "mu"),
        (lambda: mdr_dem.oblique(-1.0), "speed"),
    ],
)
def test_bad_parameters_raise_value_error_naming_the_parameter(call, argument):
    with pytest.raises(ValueError, match=f"`{argument}`"):
        call()


def test_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError, match="youngs_modulus"):
        mdr_dem.curve([1.0], youngs_modulus=2e11)


def test_yield_speed_and_a_target_sphere_from_the_pair_formulas():
    e_star, r, m, u_c, th = paper_constants(**PAPER)
    law = mdr_dem.MdrLaw()
    v_y = math.sqrt(2.0 * 0.4 * 4.0 / 3.0 * e_star * math.sqrt(r) * u_c**2.5 / m)
    assert law.yield_speed == pytest.approx(v_y, rel=1e-12)
    assert law.half_space
    # The paper's ball on a steel sphere of radius 1 cm (E = 210 GPa, nu = 0.3, 7850 kg/m^3):
    # 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (eq. 3), R = R1 R2/(R1 + R2), m = m1 m2/(m1 + m2).
    target = mdr_dem.MdrLaw(target_radius=0.01, target_density=7850.0, target_youngs=2.1e11,
                            target_poisson=0.3)
    assert not target.half_space
    e_pair = 1.0 / ((1 - 0.286**2) / 2.0e11 + (1 - 0.3**2) / 2.1e11)
    r_pair = 0.635e-2 * 0.01 / (0.635e-2 + 0.01)
    m1 = 4.0 / 3.0 * math.pi * 0.635e-2**3 * 7800.0
    m2 = 4.0 / 3.0 * math.pi * 0.01**3 * 7850.0
    m_pair = m1 * m2 / (m1 + m2)
    assert target.effective_modulus == pytest.approx(e_pair, rel=1e-14)
    assert target.effective_radius == pytest.approx(r_pair, rel=1e-14)
    assert target.reduced_mass == pytest.approx(m_pair, rel=1e-14)
    # Its restitution: the energy route with those pair values.
    c = 4.0 / 3.0 * e_pair * math.sqrt(r_pair)
    u_c_pair = math.pi * 3.8e5 / (2.0 * e_pair)
    v_y_pair = math.sqrt(2.0 * 0.4 * c * u_c_pair**2.5 / m_pair)
    assert target.yield_speed == pytest.approx(v_y_pair, rel=1e-12)
    assert target.restitution(0.99 * v_y_pair) == 1.0
    speeds = np.array([0.5, 2.0, 8.0])
    reference = [energy_route(v, e_pair, r_pair, m_pair, u_c_pair, 0.37) for v in speeds]
    np.testing.assert_allclose(target.restitution(speeds), reference, rtol=1e-12)
