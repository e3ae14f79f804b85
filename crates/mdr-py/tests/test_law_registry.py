"""The law registry from Python: the normal laws a scene can name, their declared parameters,
and the demo linear-spring law (one file in mdr-contact and one registry line; the test script
builds the wheel with its `demo-laws` feature) run by `run_scene` as its analytic solution."""

import math
from pathlib import Path

import pytest

import mdr_dem

REPO = Path(__file__).resolve().parents[3]


def test_scene_laws_are_the_registry_with_the_published_names():
    laws = {law["name"]: law for law in mdr_dem.scene_laws()}
    assert list(laws)[:3] == ["mdr", "hertz", "thornton"]
    mdr = laws["mdr"]["parameters"]
    assert [p["key"] for p in mdr] == ["critical_line_load_n_per_m", "hardening_ratio"]
    # The published command-line flags and Python keywords of the same parameters.
    assert [p["flag"] for p in mdr] == ["--qc", "--theta-ratio"]
    assert [p["python"] for p in mdr] == ["qc", "theta_ratio"]
    assert mdr[1]["range"] == "[0, 1]" and mdr[0]["unit"] == "N/m"
    assert laws["hertz"]["parameters"] == []
    assert [p["key"] for p in laws["thornton"]["parameters"]] == ["yield_pressure_pa"]


def test_scene_laws_list_the_sub_models_with_their_published_names():
    laws = mdr_dem.scene_laws()
    kinds = [law["kind"] for law in laws]
    # The normal laws first, then the tangential, damping and rolling laws, in that order.
    assert kinds == sorted(kinds, key=["normal", "tangential", "damping", "rolling"].index)
    by_kind = {k: {law["name"]: law for law in mdr_dem.scene_laws(kind=k)} for k in set(kinds)}
    assert list(by_kind["tangential"]) == ["none", "mindlin"]
    # The demo damping law last (the wheel is built with the demo-laws feature).
    assert list(by_kind["damping"]) == ["none", "hertzian_viscous", "stiffness_viscous", "linear_dashpot"]
    assert list(by_kind["rolling"]) == ["none", "epsd"]
    (mu,) = by_kind["tangential"]["mindlin"]["parameters"]
    assert (mu["key"], mu["flag"], mu["python"], mu["lammps"]) == ("friction", "--mu", "mu", "friction")
    assert mu["default"] is None and mu["range"] == "[0, inf)"
    gamma, ratio = by_kind["damping"]["hertzian_viscous"]["parameters"]
    assert (gamma["key"], gamma["unit"], gamma["lammps"]) == ("damping_gamma_n_per_m_s", "1/(m·s)", "damping")
    assert (ratio["key"], ratio["default"], ratio["lammps"]) == ("damping_tangential_ratio", 0.0, "tangential_damping")
    (mu_r,) = by_kind["rolling"]["epsd"]["parameters"]
    assert (mu_r["key"], mu_r["python"], mu_r["lammps"], mu_r["default"]) == ("rolling_friction", "rolling", "rolling", 0.0)
    with pytest.raises(ValueError, match="kind"):
        mdr_dem.scene_laws(kind="normall")


def test_friction_is_checked_as_declared():
    with pytest.raises(ValueError, match=r"mu.*\[0, inf\).*Coulomb"):
        mdr_dem.oblique(1.0, [30.0], mu=-0.1, tangential="mindlin")


def test_demo_law_runs_in_a_scene_as_its_analytic_solution(tmp_path):
    laws = {law["name"]: law for law in mdr_dem.scene_laws()}
    assert "linear_spring" in laws, "the wheel is built with the demo-laws feature"
    k, r, rho, dt = 1.0e4, 0.005, 2500.0, 1.0e-6
    text = (REPO / "scenes" / "drop.toml").read_text()
    text = (
        text.replace("duration_s = 0.2", "duration_s = 0.03")
        .replace('dt_s = "auto"', f"dt_s = {dt}")
        .replace("max_speed_m_per_s = 1.0", "max_speed_m_per_s = 0.5")
        .replace("checkpoint_interval_s = 0.1", "")
        .replace("energy_interval_s = 0.0005", "energy_interval_s = 1.0e-5")
        .replace(
            'normal = "mdr"\ncritical_line_load_n_per_m = 3.8e5   # q_c, eq. (7)\n'
            "hardening_ratio = 0.37               # Θ/E*, eq. (12)",
            f'normal = "linear_spring"\nnormal_stiffness_n_per_m = {k}',
        )
        .replace("youngs_pa = 2.0e11", "youngs_pa = 1.0e9")
        .replace("density_kg_per_m3 = 7800.0", f"density_kg_per_m3 = {rho}")
        .replace("radius_m = 0.00635", f"radius_m = {r}")
        .replace("region_min_m = [-0.00635, -0.00635, 0.05]", f"region_min_m = [-{r}, -{r}, 0.001]")
        .replace("region_max_m = [0.00636, 0.00636, 0.0628]", "region_max_m = [0.00501, 0.00501, 0.01101]")
    )
    assert "linear_spring" in text and "0.001]" in text
    scene = tmp_path / "spring.toml"
    scene.write_text(text)
    headline = mdr_dem.run_scene(scene, tmp_path / "out", no_frames=True)
    # A linear spring without damping returns all its energy: e_n = 1 to O(dt).
    assert headline["restitution"] == pytest.approx(1.0, abs=2e-3)
    speed = headline["impact_speed_m_per_s"]
    assert speed == pytest.approx(math.sqrt(2 * 9.81 * 0.001), rel=0.01)
    # No MDR reference for another law.
    assert "law_energy_route_restitution" not in headline


def test_a_declared_range_error_names_the_scene_key(tmp_path):
    scene = tmp_path / "bad.toml"
    scene.write_text(
        (REPO / "scenes" / "drop.toml").read_text().replace("hardening_ratio = 0.37", "hardening_ratio = 1.5")
    )
    with pytest.raises(ValueError, match=r"hardening_ratio.*\[0, 1\]"):
        mdr_dem.run_scene(scene, tmp_path / "out")


def test_demo_law_runs_in_the_validator_as_its_analytic_solution():
    # The paper's steel ball on a half-space: the reduced mass is the ball's mass.
    k, r, rho = 1.0e4, 0.635e-2, 7800.0
    m = 4.0 / 3.0 * math.pi * r**3 * rho
    curve = mdr_dem.curve([0.1, 1.0], law="linear_spring", normal_stiffness_n_per_m=k)
    # An undamped linear spring: e_n = 1, half a period of contact, F_max = v0 √(k m).
    assert list(curve["e_n"]) == pytest.approx([1.0, 1.0], abs=1e-4)
    assert list(curve["contact_time_s"]) == pytest.approx([math.pi * math.sqrt(m / k)] * 2, rel=1e-3)
    assert list(curve["f_max_n"]) == pytest.approx([v * math.sqrt(k * m) for v in (0.1, 1.0)], rel=1e-3)


def test_demo_law_keywords_are_checked_as_declared():
    with pytest.raises(ValueError, match="normal_stiffness_n_per_m"):
        mdr_dem.curve([1.0], law="linear_spring")
    with pytest.raises(ValueError, match=r"normal_stiffness_n_per_m.*\(0, inf\)"):
        mdr_dem.curve([1.0], law="linear_spring", normal_stiffness_n_per_m=-1.0)
    with pytest.raises(ValueError, match="not a parameter of law=\"mdr\""):
        mdr_dem.curve([1.0], normal_stiffness_n_per_m=1.0e4)


def pushing_restitution(m, k, c):
    """The linear spring–dashpot's restitution when its contact only pushes: it lets go when
    k δ + c dδ/dt reaches 0, at ω_d t_e = π − 2 arctan(β/ω_d), with e_n = exp(−β t_e)
    (β = c/(2m), ω_d = √(k/m − β²); Schwager & Pöschel, Granular Matter 9 (2007) 465)."""
    beta = c / (2.0 * m)
    omega_d = math.sqrt(k / m - beta * beta)
    t_e = (math.pi - 2.0 * math.atan(beta / omega_d)) / omega_d
    return math.exp(-beta * t_e)


def test_demo_damping_law_runs_in_a_scene_as_its_analytic_restitution(tmp_path):
    # The demo damping law (its file in mdr-contact and one registry line) with the demo spring:
    # a 5 mm sphere thrown at 0.1 m/s onto a plane without gravity, damping ratio 0.2.
    laws = {law["name"]: law for law in mdr_dem.scene_laws(kind="damping")}
    (c_param,) = laws["linear_dashpot"]["parameters"]
    assert (c_param["key"], c_param["unit"], c_param["range"]) == ("damping_coefficient_n_s_per_m", "N·s/m", "[0, inf)")
    k, r, rho = 1.0e4, 0.005, 2500.0
    m = 4.0 / 3.0 * math.pi * r**3 * rho
    c = 2.0 * 0.2 * math.sqrt(m * k)
    text = (REPO / "scenes" / "drop.toml").read_text()
    text = (
        text.replace("duration_s = 0.2", "duration_s = 0.004")
        .replace('dt_s = "auto"', "dt_s = 1.0e-6")
        .replace("max_speed_m_per_s = 1.0", "max_speed_m_per_s = 0.5")
        .replace("checkpoint_interval_s = 0.1", "")
        .replace("[0.0, 0.0, -9.81]", "[0.0, 0.0, 0.0]")
        .replace(
            'normal = "mdr"\ncritical_line_load_n_per_m = 3.8e5   # q_c, eq. (7)\n'
            "hardening_ratio = 0.37               # Θ/E*, eq. (12)",
            f'normal = "linear_spring"\nnormal_stiffness_n_per_m = {k}\n'
            f'damping = "linear_dashpot"\ndamping_coefficient_n_s_per_m = {c}',
        )
        .replace("youngs_pa = 2.0e11", "youngs_pa = 1.0e9")
        .replace("density_kg_per_m3 = 7800.0", f"density_kg_per_m3 = {rho}")
        .replace("radius_m = 0.00635", f"radius_m = {r}")
        .replace("region_min_m = [-0.00635, -0.00635, 0.05]", f"region_min_m = [-{r}, -{r}, 0.0001]")
        .replace(
            "region_max_m = [0.00636, 0.00636, 0.0628]",
            "region_max_m = [0.00501, 0.00501, 0.01011]\nvelocity_m_per_s = [0.0, 0.0, -0.1]",
        )
    )
    assert "linear_dashpot" in text and "-0.1]" in text
    scene = tmp_path / "dashpot.toml"
    scene.write_text(text)
    headline = mdr_dem.run_scene(scene, tmp_path / "out", no_frames=True)
    assert headline["impact_speed_m_per_s"] == pytest.approx(0.1, abs=1e-12)
    e_n = headline["restitution"]
    # Symplectic Euler at ω₀ dt = 2.8e-3: e_n − e = −4e-4.
    assert e_n == pytest.approx(pushing_restitution(m, k, c), abs=1.2e-3)
    # Negative control: a dashpot 5 % stronger is told apart.
    assert abs(e_n - pushing_restitution(m, k, 1.05 * c)) > 5e-3
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace(f"damping_coefficient_n_s_per_m = {c}", "damping_coefficient_n_s_per_m = -1.0"))
    with pytest.raises(ValueError, match=r"damping_coefficient_n_s_per_m.*\[0, inf\)"):
        mdr_dem.run_scene(bad, tmp_path / "out-bad")
