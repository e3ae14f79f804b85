"""Rings, scenes and the bench bed from Python; the GIL is released during long runs."""

import json
import math
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import mdr_dem
from test_law import cli_binary

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
        # One sample per 0.1 orbit: long stretches in Rust; five orbits last several times the
        # 0.05 s the test needs to tell, even on a much faster machine.
        ring.run(5.0)
        elapsed = time.perf_counter() - start
        during = ticks - before
    finally:
        stop.set()
        worker.join()
    assert elapsed > 0.05, "the run is too short to tell"
    # With the GIL held, the counter would advance only at the 50 sample boundaries.
    assert during > 60 + 10 * elapsed, (during, elapsed)


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


def test_bench_bed_runs_thornton_adhesion_and_rolling_independent_of_threads(tmp_path):
    bed = small_bed_file(tmp_path)
    mdr = mdr_dem.bench_bed(bed, law="mdr", steps=50, warmup=10)
    for kw, name in [
        (dict(law="adhesive-mdr"), "adhesive-mdr"),
        (dict(law="thornton"), "thornton"),
        (dict(law="mdr", rolling=0.1), "mdr"),
    ]:
        one = mdr_dem.bench_bed(bed, steps=50, warmup=10, threads=1, **kw)
        two = mdr_dem.bench_bed(bed, steps=50, warmup=10, threads=2, **kw)
        assert one["law"] == name
        assert one["state_checksum"] == two["state_checksum"], kw
        if kw["law"] == "adhesive-mdr":
            # No contact of this pressed bed unloads past its touching radius in 60 steps, and
            # while the springs touch the adhesive law is the MDR law itself (docs/theory.md §9).
            assert one["state_checksum"] == mdr["state_checksum"], kw
        elif name != "mdr" or "rolling" in kw:
            # The law is applied: the bed ends elsewhere than with the MDR law.
            assert one["state_checksum"] != mdr["state_checksum"], kw


# The keys of `mdr-dem bench bed --json` (the CLI's contract), in its order.
CLI_BENCH_BED_KEYS = [
    "particle_steps_per_s",
    "ms_per_step",
    "contacts_per_particle",
    "peak_rss_mb",
    "threads",
    "particle_steps_per_cpu_s",
    "cpu_seconds",
    "wall_seconds",
    "law",
    "particles",
    "steps",
    "rebuilds",
    "floor_contacts",
    "plastic_contact_fraction",
    "stepper_bytes_per_particle",
    "orientation",
    "work_books",
    "state_checksum",
]


def small_bed_file(tmp_path, diameter="1"):
    """A LAMMPS data file of 4 × 4 spheres on the floor of a 3.96 × 3.96 periodic box, each
    pressed against its four neighbours (spacing 0.99); sphere 6 of diameter `diameter`."""
    lines = [
        "a small bed",
        "",
        "16 atoms",
        "1 atom types",
        "",
        "0 3.96 xlo xhi",
        "0 3.96 ylo yhi",
        "0 2 zlo zhi",
        "",
        "Atoms # sphere",
        "",
    ]
    for k in range(16):
        d = diameter if k == 5 else "1"
        lines.append(f"{k + 1} 1 {d} 1 {0.99 * (k % 4) + 0.495} {0.99 * (k // 4) + 0.495} 0.4999")
    path = tmp_path / "bed.data"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_bench_bed_gives_the_cli_figures_with_cpu_rate_and_peak_memory(tmp_path):
    out = mdr_dem.bench_bed(small_bed_file(tmp_path), steps=200, warmup=10, threads=2)
    assert list(out) == CLI_BENCH_BED_KEYS + ["cpu_particle_steps_per_s"]
    assert out["particles"] == 16 and out["steps"] == 200 and out["threads"] == 2
    assert out["floor_contacts"] == 16 and out["contacts_per_particle"] == 4.0
    for key in ("particle_steps_per_s", "ms_per_step", "wall_seconds", "stepper_bytes_per_particle"):
        assert math.isfinite(out[key]) and out[key] > 0, key
    assert out["particle_steps_per_s"] * out["ms_per_step"] / 1e3 == pytest.approx(16)
    assert out["cpu_particle_steps_per_s"] == out["particle_steps_per_cpu_s"]
    if sys.platform.startswith("linux"):
        # CPU rate: particle-steps over the CPU seconds of all threads.
        assert out["cpu_seconds"] > 0
        assert out["cpu_particle_steps_per_s"] * out["cpu_seconds"] == pytest.approx(16 * 200)
        # The process's peak resident memory: the interpreter, numpy and the run (MB).
        assert 1 < out["peak_rss_mb"] < 100_000
    binary = cli_binary()
    if binary is not None:
        cli = json.loads(
            subprocess.run(
                [binary, "bench", "bed", "--data", str(tmp_path / "bed.data"), "--steps", "5",
                 "--warmup", "0", "--json"],
                check=True,
                capture_output=True,
                text=True,
            ).stdout
        )
        # The CLI also names the device it ran on; the Python function runs the CPU path only.
        assert list(cli) == CLI_BENCH_BED_KEYS + ["device"] and cli["device"] == "cpu"


def test_bench_bed_names_bad_values(tmp_path):
    bed = small_bed_file(tmp_path)
    for kw, name in [
        (dict(steps=0), "steps"),
        (dict(tile=0), "tile"),
        (dict(tile=100_000), "tile"),
        (dict(tile=2**64 - 1), "tile"),
        (dict(skin=-0.1), "skin"),
        (dict(skin=float("nan")), "skin"),
        (dict(law="mdr", qc=-1.0), "qc"),
        (dict(law="granite"), "law"),
        (dict(law="thornton", yield_stress=-1.0), "yield_stress"),
        (dict(law="adhesive-mdr", work_of_adhesion=-1.0), "work_of_adhesion"),
        (dict(law="adhesive-mdr", work_of_adhesion=float("nan")), "work_of_adhesion"),
        (dict(rolling=-1.0), "rolling"),
        (dict(count=0), "count"),
        (dict(count=10**12), "count"),
    ]:
        with pytest.raises(ValueError, match=f"`{name}`"):
            mdr_dem.bench_bed(bed, steps=kw.pop("steps", 1), warmup=0, **kw)
    with pytest.raises(ValueError, match="`data`.*diameter 2"):
        mdr_dem.bench_bed(small_bed_file(tmp_path, diameter="2"), steps=1, warmup=0)
    with pytest.raises(OSError, match="nonexistent"):
        mdr_dem.bench_bed(tmp_path / "nonexistent.data", steps=1, warmup=0)


def test_bench_bed_defaults_to_the_repository_reference_bed():
    out = mdr_dem.bench_bed(steps=2, warmup=0)
    assert out["particles"] == 10_000 and out["steps"] == 2
    assert out["floor_contacts"] > 0


def test_ring_by_surface_density_draws_until_the_mass_is_reached():
    # REBOUND's rule: draw particles until their total mass reaches sigma L_x L_y.
    config = dict(surface_density=400.0, box=60.0, dt_orbits=2e-3, sample_orbits=0.1, seed=5)
    ring = mdr_dem.Ring(config, law="bridges")
    target = 400.0 * 60.0 * 60.0
    masses = ring.masses
    assert masses.sum() >= target > masses.sum() - masses[-1]
    # <r^3> of dN/dr ~ r^-3 on [1, 4] m is 6.4 m^3: about 134 particles expected.
    assert 60 < len(ring) < 300


def test_ring_with_self_gravity_runs_and_changes_the_motion():
    plain = mdr_dem.Ring(SMALL, law="bridges")
    plain.run(0.3)
    gravity = mdr_dem.Ring(dict(SMALL, gravity=True), law="bridges")
    np.testing.assert_array_equal(gravity.positions, mdr_dem.Ring(SMALL).positions)
    summary = gravity.run(0.3)
    assert set(summary) == SUMMARY_KEYS
    assert np.all(np.isfinite(gravity.velocities))
    assert not np.array_equal(gravity.velocities, plain.velocities)


def test_run_scene_stopped_and_resumed_ends_as_the_uninterrupted_run(tmp_path):
    scene = tmp_path / "drop.toml"
    text = (REPO / "scenes" / "drop.toml").read_text()
    text = text.replace("duration_s = 0.2", "duration_s = 0.11").replace(
        "steps_per_contact = 200", "steps_per_contact = 40"
    )
    scene.write_text(text)
    whole = mdr_dem.run_scene(scene, tmp_path / "whole", no_frames=True)
    first = mdr_dem.run_scene(scene, tmp_path / "first", no_frames=True, stop_at_step=200)
    assert first["stopped_early"] is True and first["step"] == 200
    assert Path(first["checkpoint"]).is_file()
    resumed = mdr_dem.run_scene(
        scene, tmp_path / "resumed", no_frames=True, resume=first["checkpoint"]
    )
    assert resumed["stopped_early"] is False
    assert resumed["step"] == whole["step"]
    # Restarts are bit-identical (docs/user-guide.md), so the headline is too.
    assert resumed["restitution"] == whole["restitution"]
    assert resumed["impact_speed_m_per_s"] == whole["impact_speed_m_per_s"]


def test_ctrl_c_stops_run_scene_with_a_checkpoint_and_raises_keyboard_interrupt(tmp_path):
    import os
    import signal

    scene = tmp_path / "drop.toml"
    # The drop scene run for 10 times its 0.2 s, so that it is still running when Ctrl-C
    # (SIGINT to this process) comes after 0.5 s on a fast machine too.
    text = (REPO / "scenes" / "drop.toml").read_text()
    assert "duration_s = 0.2 " in text
    scene.write_text(text.replace("duration_s = 0.2 ", "duration_s = 2.0 ", 1))
    # Python's own Ctrl-C handler for the test: a process started in the background by a
    # non-interactive shell inherits SIGINT ignored, and Python then installs none.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            mdr_dem.run_scene(scene, tmp_path / "out", no_frames=True)
    finally:
        timer.join()
        signal.signal(signal.SIGINT, previous)
    assert list((tmp_path / "out" / "checkpoints").glob("*.mdrck")), "no checkpoint written"
