"""Adhesion (Heß's rule on the MDR springs) from Python, against the JKR formulas evaluated here:
the unloading branch δ(a) = a²/R − √(2π a Δγ/E*), F(a) = 4E*a³/(3R) − √(8π Δγ E* a³), the
pull-off force (3/2) π Δγ R, and the energy balance of an adhesive impact."""

import math

import numpy as np
import pytest

import mdr_dem

GLASS = dict(radius=5e-6, density=2500.0, youngs=63e9, poisson=0.2)
GAMMA = 0.1


def elastic_law(gamma=GAMMA):
    return mdr_dem.MdrLaw(qc=1e12, theta_ratio=1.0, work_of_adhesion=gamma, **GLASS)


def test_pull_off_force_is_jkr():
    law = elastic_law()
    assert law.work_of_adhesion == GAMMA
    assert law.pull_off_force == pytest.approx(1.5 * math.pi * GAMMA * 5e-6, rel=1e-14)
    assert mdr_dem.MdrLaw(**GLASS).pull_off_force == 0.0


def test_force_curve_follows_the_jkr_branch_through_detachment():
    law = elastic_law()
    e_star, r = law.effective_modulus, law.effective_radius
    state = mdr_dem.MdrState()
    overlaps = np.linspace(2e-9, -4e-9, 3001)
    law.force(2e-9, state)
    forces = law.force_curve(overlaps, state)
    # Where the edge retreats, (δ, F) lies on JKR's parametric curve: recover a from δ.
    a_s = (math.pi * GAMMA * r * r / (8 * e_star)) ** (1 / 3)
    delta = lambda a: a * a / r - math.sqrt(2 * math.pi * a * GAMMA / e_star)
    jkr = lambda a: 4 * e_star * a**3 / (3 * r) - math.sqrt(8 * math.pi * GAMMA * e_star * a**3)
    checked = 0
    for d, f in zip(overlaps, forces):
        if f < -1e-3 * law.pull_off_force and d < delta(math.sqrt(r * 2e-9)):
            lo, hi = a_s, math.sqrt(r * 2e-9)
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if delta(mid) < d else (lo, mid)
            assert f == pytest.approx(jkr(0.5 * (lo + hi)), rel=1e-7, abs=1e-9 * law.pull_off_force)
            checked += 1
    assert checked > 100
    # The largest tension is the pull-off force; it lets go at the snap-off overlap.
    assert -forces.min() == pytest.approx(law.pull_off_force, rel=1e-5)
    snap = delta(a_s)
    assert forces[overlaps < snap * 1.001].max() == 0.0
    assert state.contact_radius == 0.0 and state.adhesive_work > 0.0


def test_zero_adhesion_is_the_plain_law():
    plain, zero = mdr_dem.MdrLaw(), mdr_dem.MdrLaw(work_of_adhesion=0.0)
    path = np.concatenate([np.linspace(0, 1e-5, 50), np.linspace(1e-5, -1e-6, 50)])
    assert np.array_equal(plain.force_curve(path), zero.force_curve(path))
    v = [0.1, 1.0, 10.0]
    assert np.array_equal(plain.restitution(v), zero.restitution(v))


def test_restitution_is_zero_where_the_sphere_sticks():
    law = elastic_law()
    e_star, r, m = law.effective_modulus, law.effective_radius, law.reduced_mass
    a_s = (math.pi * GAMMA * r * r / (8 * e_star)) ** (1 / 3)
    d_s = a_s * a_s / r - math.sqrt(2 * math.pi * a_s * GAMMA / e_star)
    snap = e_star * (d_s**2 * a_s - 2 / 3 * d_s * a_s**3 / r + a_s**5 / (5 * r * r))

    def expected(v):
        kinetic = 0.5 * m * v * v
        a_max = (15 * r * r * kinetic / (8 * e_star)) ** 0.2
        loss = math.pi * GAMMA * (a_max**2 - a_s**2) + snap
        return math.sqrt(max(0.0, 1 - loss / kinetic))

    speeds = [0.01, 0.03, 0.1, 0.3, 1.0]
    e = law.restitution(speeds)
    assert e[0] == 0.0 and e[1] == 0.0
    for v, got in zip(speeds[2:], e[2:]):
        assert got**2 == pytest.approx(expected(v) ** 2, abs=3e-4)
    trace = law.impact(0.02)
    assert trace.stuck and trace.restitution == 0.0
    rebound = law.impact(0.3)
    assert not rebound.stuck and rebound.release_overlap < 0.0
    assert rebound.pull_off_force == pytest.approx(law.pull_off_force, rel=1e-3)


def test_curve_reports_stuck():
    result = mdr_dem.curve([0.01, 1.0], work_of_adhesion=GAMMA, elastic=True, **GLASS)
    assert list(result["stuck"]) == [1.0, 0.0]
    assert result["e_n"][0] == 0.0


@pytest.mark.parametrize("name", ["adhesive_mdr", "adhesive-mdr"])
@pytest.mark.parametrize("elastic", [False, True])
def test_adhesive_mdr_by_name_takes_the_work_of_adhesion(name, elastic):
    speeds = [0.01, 0.3, 1.0, 20.0]
    mdr = mdr_dem.curve(speeds, law="mdr", work_of_adhesion=GAMMA, elastic=elastic, **GLASS)
    adhesive = mdr_dem.curve(speeds, law=name, work_of_adhesion=GAMMA, elastic=elastic, **GLASS)
    assert mdr["stuck"][0] == 1.0 and mdr["e_n"][0] == 0.0
    for column in ("e_n", "stuck"):
        assert list(adhesive[column]) == list(mdr[column])
    with pytest.raises(ValueError, match="work_of_adhesion"):
        mdr_dem.curve(speeds, law=name, **GLASS)


@pytest.mark.parametrize("bad", [-0.1, float("nan"), float("inf")])
def test_bad_work_of_adhesion_is_refused_by_name(bad):
    with pytest.raises(ValueError, match="work_of_adhesion"):
        mdr_dem.MdrLaw(work_of_adhesion=bad)
    with pytest.raises(ValueError, match="work_of_adhesion"):
        mdr_dem.curve([1.0], work_of_adhesion=bad)
