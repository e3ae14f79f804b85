"""Rings, scenes and the bench bed from Python; the GIL is released during long runs."""

import threading
import time
from pathlib import Path

import numpy as np
import pytest

import mdr_dem

REPO = Path(__file__).resolve().parents[3]

# A small ring: 60 particles in a 60 m box, steps of 2e-3 orbit, a sample every 0.1 orbit.
SMALL = dict(particles=60, box=60.0, dt_orbits=2e-3, sample_orbits=0.1, seed=3)

SUMMARY_KEYS = {
    "particles",
    "c_m_per_s",
    "c_number_m_per_s",
    "sigma_x_m_per_s",
    "sigma_y_m_per_s",
    "sigma_z_m_per_s",
    "c_over_mean_r_omega",
    "z_rms_m",
    "z_rms_number_m",
    "filling_factor_z0",
    "collisions_per_particle_per_orbit",
    "wall_s_per_orbit",
    "optical_depth",
    "toomre_q",
}


def test_short_ring_run_returns_the_summary_keys():
    ring = mdr_dem.Ring(SMALL, law="bridges")
    assert len(ring) == 60
    positions = ring.positions
    assert positions.shape == (60, 3) and ring.velocities.shape == (60, 3)
    assert np.all(np.abs(positions[:, :2]) <= 30.0 + 1e-9)
    assert ring.radii.shape == (60,) and np.all((ring.radii >= 1.0) & (ring.radii <= 4.0))
    # rho = 400 kg/m^3 spheres.
    np.testing.assert_allclose(ring.masses, 400.0 * 4.0 / 3.0 * np.pi * ring.radii**3, rtol=1e-12)
    seen = []
    summary = ring.run(0.5, callback=seen.append)
    assert set(summary) == SUMMARY_KEYS
    assert summary["particles"] == 60
    assert summary["c_m_per_s"] > 0 and summary["optical_depth"] > 0
    assert len(seen) == 5 and seen[-1]["t_orbits"] == pytest.approx(0.5)
    assert set(seen[0]) >= {"t_orbits", "c", "sigma_x", "z_rms", "collisions"}
    assert ring.time_orbits == pytest.approx(0.5)
    samples = ring.samples
    np.testing.assert_allclose(samples["t_orbits"], [0.1, 0.2, 0.3, 0.4, 0.5])
    np.testing.assert_allclose(samples["c"], [s["c"] for s in seen])
    assert ring.collisions > 0


def test_python_restitution_callback_is_called_and_its_values_used():
    speeds = []

    def half(v):
        speeds.append(v)
        return 0.5

    by_callback = mdr_dem.Ring(SMALL, law=half)
    summary_callback = by_callback.run(0.5)
    assert by_callback.law_name == "python"
    assert len(speeds) == by_callback.law_calls == by_callback.collisions > 0
    assert all(v > 0 for v in speeds)
    # The same impacts with the built-in constant 0.5: identical trajectories.
    constant = mdr_dem.Ring(SMALL, law=0.5)
    summary_constant = constant.run(0.5)
    assert summary_callback["c_m_per_s"] == summary_constant["c_m_per_s"]
    np.testing.assert_array_equal(by_callback.velocities, constant.velocities)
    # Another value changes the outcome: the callback's values are what the ring uses.
    elastic = mdr_dem.Ring(SMALL, law=lambda v: 1.0)
    elastic.run(0.5)
    assert not np.array_equal(elastic.velocities, constant.velocities)


def test_a_failing_callback_raises_its_exception():
    def broken(v):
        raise ZeroDivisionError("boom")

    ring = mdr_dem.Ring(SMALL, law=broken)
    with pytest.raises(ZeroDivisionError, match="boom"):
        ring.run(0.5)
    bad_value = mdr_dem.Ring(SMALL, law=lambda v: 2.0)
    with pytest.raises(ValueError, match="`law`"):
        bad_value.run(0.5)


@pytest.mark.parametrize(
    "call, argument",
    [
        (lambda: mdr_dem.Ring(dict(SMALL, box=-5.0)), "box"),
        (lambda: mdr_dem.Ring(dict(SMALL, dt_orbits=0.5)), "dt_orbits"),
        (lambda: mdr_dem.Ring(dict(SMALL, boxx=50.0)), "boxx"),
        (lambda: mdr_dem.Ring(SMALL, law=1.5), "law"),
        (lambda: mdr_dem.Ring(SMALL, law="elastic"), "law"),
        (lambda: mdr_dem.Ring(SMALL, law="mdr", youngs=-1.0), "youngs"),
        (lambda: mdr_dem.Ring(SMALL).run(-1.0), "orbits"),
    ],
)
def test_bad_ring_parameters_raise_value_error_naming_the_parameter(call, argument):
    with pytest.raises(ValueError, match=f"`{argument}`"):
        call()


def test_gil_is_released_during_a_long_run():
    """A second Python thread keeps counting while the ring steps in Rust."""
    ring = mdr_dem.Ring(dict(SMALL, particles=120, box=80.0), law="mdr")
    ticks = 0
    stop = threading.Event()

    def count():
        nonlocal ticks
        while not stop.is_set():
            ticks += 1
            time.sleep(0.001)

    worker = threading.Thread(target=count)
    worker.start()
    try:
        before = ticks
        start = time.perf_counter()
        ring.run(1.0)  # one sample per 0.1 orbit: long stretches in Rust
        elapsed = time.perf_counter() - start
        during = ticks - before
    finally:
        stop.set()
        worker.join()
    assert elapsed > 0.05, "the run is too short to tell"
    # With the GIL held, the counter would advance only at the 10 sample boundaries.
    assert during > 20 + 10 * elapsed, (during, elapsed)


def test_run_scene_returns_the_headline(tmp_path):
    scene = tmp_path / "drop.toml"
    text = (REPO / "scenes" / "drop.toml").read_text()
    # A shorter run of the built-in drop: 0.11 s (the bounce), coarser steps, no frames.
    text = text.replace("duration_s = 0.2", "duration_s = 0.11").replace(
        "steps_per_contact = 200", "steps_per_contact = 40"
    )
    scene.write_text(text)
    headline = mdr_dem.run_scene(scene, tmp_path / "out", no_frames=True)
    assert headline["stopped_early"] is False
    assert headline["time_s"] == pytest.approx(0.11, rel=1e-3)
    # The drop's headline: the first bounce's e_n next to the law's closed form at that speed.
    speed = headline["impact_speed_m_per_s"]
    assert speed == pytest.approx((2 * 9.81 * 0.05) ** 0.5, rel=0.01)
    reference = mdr_dem.MdrLaw().restitution(speed)
    assert headline["law_energy_route_restitution"] == pytest.approx(reference, rel=1e-12)
    assert headline["restitution"] == pytest.approx(reference, abs=0.01)
    assert "e_n" in headline["text"]


def test_run_scene_rejects_a_bad_file(tmp_path):
    scene = tmp_path / "bad.toml"
    scene.write_text((REPO / "scenes" / "drop.toml").read_text().replace("youngs_pa = 2.0e11", "youngs_pa = -2.0"))
    with pytest.raises(ValueError, match="youngs_pa"):
        mdr_dem.run_scene(scene, tmp_path / "out")


def test_bench_bed_on_a_small_generated_bed():
    out = mdr_dem.bench_bed(count=200, settle_steps=500, steps=20, warmup=5)
    assert out["particles"] == 200 and out["steps"] == 20 and out["law"] == "hertz"
    assert out["particle_steps_per_s"] > 0
    assert len(out["state_checksum"]) == 16
    again = mdr_dem.bench_bed(count=200, settle_steps=500, steps=20, warmup=5)
    assert again["state_checksum"] == out["state_checksum"]
    mdr = mdr_dem.bench_bed(count=200, settle_steps=500, steps=20, warmup=5, law="mdr")
    assert mdr["law"] == "mdr"
    with pytest.raises(ValueError, match="`threads`"):
        mdr_dem.bench_bed(count=200, threads=0)


def test_bench_bed_defaults_to_the_repository_reference_bed():
    out = mdr_dem.bench_bed(steps=2, warmup=0)
    assert out["particles"] == 10_000 and out["steps"] == 2
    assert out["floor_contacts"] > 0
