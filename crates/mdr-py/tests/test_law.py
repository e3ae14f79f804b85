"""The law and the validator from Python, checked against the `mdr-dem` program and the paper.

References are independent of the binding: the CLI's output (the built program when present,
otherwise the values it printed, recorded below with their command), the Hertz closed form, and
synthetic data with known parameters.
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

# `mdr-dem impact curve --velocities 0.03,0.1,0.2,0.28,0.3,0.5,1,2,3,5,10,30 --csv - -q`
# (the paper's Fig. 2 defaults), column e_n, printed on 2026-11-23.
PAPER_SPEEDS = [0.03, 0.1, 0.2, 0.28, 0.3, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 30.0]
CLI_E_N = [
    1.0,
    1.0,
    0.9999999999999999,
    0.9998723734840991,
    0.9898251983355032,
    0.8538670185714711,
    0.7162965491528732,
    0.6501131825657825,
    0.6314339248112432,
    0.619005834805559,
    0.6119542128485171,
    0.6089288575042557,
]


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


def test_closed_form_restitution_equals_the_cli_at_the_papers_speeds():
    law = mdr_dem.MdrLaw()
    e = law.restitution(np.array(PAPER_SPEEDS))
    assert isinstance(e, np.ndarray) and e.shape == (12,)
    np.testing.assert_allclose(e, CLI_E_N, rtol=1e-12, atol=0)
    # A float in, a float out; docs/validation.md's rounded value at 1 m/s.
    assert isinstance(law.restitution(1.0), float)
    assert round(law.restitution(1.0), 4) == 0.7163
    # Shape kept: a 2-D array of speeds.
    grid = law.restitution(np.array(PAPER_SPEEDS).reshape(3, 4))
    assert grid.shape == (3, 4)
    fresh = cli_curve(["--velocities", ",".join(str(v) for v in PAPER_SPEEDS)])
    if fresh is not None:
        np.testing.assert_allclose(e, fresh["e_n"], rtol=1e-12, atol=0)


def test_curve_matches_the_cli_for_other_materials():
    kw = dict(radius=0.002, youngs=7.0e10, poisson=0.33, density=2700.0, qc=1.2e5, theta_ratio=0.25)
    speeds = np.array([0.2, 0.7, 2.5, 9.0])
    out = mdr_dem.curve(speeds, **kw)
    assert set(out) >= {
        "v0_m_per_s", "e_n", "e_n_scaled", "d_max_m", "d_residual_m", "contact_time_s", "f_max_n"
    }
    np.testing.assert_allclose(out["e_n_scaled"], 0.95 * out["e_n"], rtol=1e-15)
    np.testing.assert_allclose(out["e_n"], mdr_dem.MdrLaw(**kw).restitution(speeds), rtol=1e-12)
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
    assert trace.restitution == pytest.approx(law.restitution(1.0), abs=2e-3)
    assert trace.max_overlap == pytest.approx(np.max(trace.overlap), rel=1e-9)
    # docs/validation.md at 1 m/s: d_max 16.96 um, residual 7.234 um, t_c 46.31 us.
    assert trace.max_overlap == pytest.approx(16.96e-6, rel=2e-3)
    assert trace.residual_overlap == pytest.approx(7.234e-6, rel=5e-3)
    assert trace.contact_time == pytest.approx(46.31e-6, rel=5e-3)


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
    assert list(out) == ["angle_deg", "e_n", "e_t", "rebound_angle_deg", "omega_rad_per_s"]
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
