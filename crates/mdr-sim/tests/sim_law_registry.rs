//! The law registry: a normal law added as its file in `mdr-contact` and one registry line (the
//! demo linear spring, `demo-laws` feature, which the workspace's tests switch on) runs in
//! scenes on both force paths, with its scene key, help text and range error derived from its
//! declaration, and checkpoints bit-identically; the registered laws' declarations reproduce
//! the scene keys scene files use.
#![cfg(feature = "demo-laws")]

mod common;

use mdr_contact::normal::{Hertz, LinearSpring, MdrElastoPlastic, Thornton};
use mdr_contact::params::Declared;
use mdr_sim::laws::registry::{normal_law, normal_law_names};
use mdr_sim::{run_scene, scene::validate::parse_scene, RunOptions, RunSummary};
use std::f64::consts::PI;

const RADIUS: f64 = 0.005;
const DENSITY: f64 = 2500.0;
/// `k_n` (N/m): with a 5 mm glass-density sphere, `m = 1.309e-3 kg`, the contact lasts
/// `π √(m/k) = 1.137 ms`.
const STIFFNESS: f64 = 1.0e4;
const DT: f64 = 1.0e-6;

/// A sphere dropped from 1 mm above a plane (impact speed √(2 g h) = 0.140 m/s) onto
/// `normal`, without friction or damping; energy rows every 10 µs.
fn drop(normal: &str, force_path: &str) -> String {
    format!(
        r#"
[run]
name = "spring"
seed = 1
duration_s = 0.03
dt_s = {DT}
max_speed_m_per_s = 0.5
output_interval_s = 0.01
energy_interval_s = 1.0e-5
headline = "drop"
force_path = "{force_path}"

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "glass"
youngs_pa = 1.0e9
poisson_ratio = 0.25
density_kg_per_m3 = {DENSITY}

[contact]
{normal}

[[particles]]
material = "glass"
count = 1
radius_m = {RADIUS}
placement = "lattice"
region_min_m = [-{RADIUS}, -{RADIUS}, 0.001]
region_max_m = [0.00501, 0.00501, 0.01101]

[[walls]]
kind = "plane"
material = "glass"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#
    )
}

fn spring() -> String {
    format!("normal = \"linear_spring\"\nnormal_stiffness_n_per_m = {STIFFNESS}")
}

fn run(tag: &str, text: &str, options: impl FnOnce(RunOptions) -> RunOptions) -> RunSummary {
    let dir = common::temp_dir(tag);
    let path = common::write(&dir, "scene.toml", text);
    let scene = parse_scene(&path, text).unwrap_or_else(|p| panic!("{tag}: {p}"));
    run_scene(
        &scene,
        &options(RunOptions::new(dir.join("out")).quiet(true).no_frames(true)),
    )
    .unwrap_or_else(|e| panic!("{tag}: {e}"))
}

/// Duration of the first contact (s), from the energy rows where the spring holds energy,
/// and the largest elastic energy (J).
fn first_contact(summary: &RunSummary) -> (f64, f64) {
    let rows = &summary.energy;
    let start = rows.iter().position(|r| r.elastic_normal_j > 0.0).unwrap();
    let end = start
        + rows[start..]
            .iter()
            .position(|r| r.elastic_normal_j == 0.0)
            .unwrap();
    let peak = rows[start..end]
        .iter()
        .map(|r| r.elastic_normal_j)
        .fold(0.0, f64::max);
    (rows[end].time_s - rows[start].time_s, peak)
}

/// The spring's analytic solution, on both force paths: the sphere oscillates about the
/// overlap `δ_g = m g / k` where the spring carries its weight, with amplitude
/// `A = √(δ_g² + (v/ω)²)`, `ω = √(k/m)`, so the contact lasts `(π + 2 asin(δ_g/A)) / ω` and
/// stores `k (δ_g + A)² / 2` at its deepest; `e_n = 1`. Hertz's contact at the same speed lasts
/// another time (its own `2.87 (m²/(E*² R v))^{1/5}`), so the check tells which law ran.
#[test]
fn demo_law_runs_in_scenes_on_both_force_paths_as_its_analytic_solution() {
    let m = 4.0 / 3.0 * PI * RADIUS.powi(3) * DENSITY;
    let omega = (STIFFNESS / m).sqrt();
    let contact_time = |v: f64| {
        let weight = m * 9.81 / STIFFNESS;
        let amplitude = weight.hypot(v / omega);
        let time = (PI + 2.0 * (weight / amplitude).asin()) / omega;
        (time, 0.5 * STIFFNESS * (weight + amplitude).powi(2))
    };
    let mut t_c = 0.0;
    for path in ["neighbour_list", "rapier"] {
        let summary = run(&format!("spring-{path}"), &drop(&spring(), path), |o| o);
        let e_n = summary.headline.get("restitution").unwrap();
        let v = summary.headline.get("impact_speed_m_per_s").unwrap();
        // Symplectic Euler keeps the energy to O(dt): 1000 steps per contact.
        assert!((e_n - 1.0).abs() < 2e-3, "{path}: e_n = {e_n}");
        let (duration, peak) = first_contact(&summary);
        let (expected, deepest) = contact_time(v);
        t_c = expected;
        // The rows are 10 µs apart: the measured duration is within one row of the solution.
        assert!(
            (duration - expected).abs() < 1.1e-5,
            "{path}: {duration} vs {expected}"
        );
        // A row within 5 µs of the deepest point: (ω · 5 µs)² / 2 < 1e-4 below the peak.
        assert!(
            (peak / deepest - 1.0).abs() < 1e-3,
            "{path}: {peak} vs {deepest}"
        );
    }
    // Negative control: the same drop on Hertz does not last π √(m/k).
    let hertz = run(
        "spring-hertz",
        &drop("normal = \"hertz\"", "neighbour_list"),
        |o| o,
    );
    let (duration, _) = first_contact(&hertz);
    assert!(
        (duration - t_c).abs() > 1e-4,
        "Hertz lasted {duration}, t_c = {t_c}"
    );
}

/// A run of the demo law stopped in the middle of its contact and resumed from the checkpoint
/// ends bit for bit where the uninterrupted run ends, on both force paths.
#[test]
fn demo_law_checkpoints_restart_bit_identically() {
    for path in ["neighbour_list", "rapier"] {
        let text = drop(&spring(), path);
        let whole = run(&format!("spring-whole-{path}"), &text, |o| o);
        // The contact starts after ~14.3 ms of fall (1 mm): stop 0.5 ms into it.
        let dir = common::temp_dir(&format!("spring-resume-{path}"));
        let file = common::write(&dir, "scene.toml", &text);
        let scene = parse_scene(&file, &text).unwrap();
        let options = RunOptions::new(dir.join("out")).quiet(true).no_frames(true);
        let first = run_scene(&scene, &options.clone().stop_at_step(Some(14_800))).unwrap();
        assert!(first.stopped_early);
        let last = first.energy.last().unwrap();
        assert!(
            last.elastic_normal_j > 0.0,
            "{path}: stopped outside the contact"
        );
        let resumed = run_scene(&scene, &options.resume(Some(first.checkpoint.unwrap()))).unwrap();
        assert_eq!(resumed.particles, whole.particles, "{path}");
        assert_eq!(
            resumed.energy.last().unwrap(),
            whole.energy.last().unwrap(),
            "{path}"
        );
    }
}

/// The scene key, its help line and its range error all come from the law's declaration.
#[test]
fn demo_law_scene_keys_and_errors_come_from_its_declaration() {
    let dir = common::temp_dir("spring-errors");
    let check = |normal: &str| {
        let text = drop(normal, "neighbour_list");
        let path = common::write(&dir, "scene.toml", &text);
        parse_scene(&path, &text)
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    let out_of_range = check("normal = \"linear_spring\"\nnormal_stiffness_n_per_m = -5.0");
    assert!(
        out_of_range.contains("normal_stiffness_n_per_m")
            && out_of_range.contains("(0, inf)")
            && out_of_range.contains("k_n (N/m"),
        "{out_of_range}"
    );
    let missing = check("normal = \"linear_spring\"");
    assert!(
        missing.contains("missing key `normal_stiffness_n_per_m`"),
        "{missing}"
    );
    // Another law's parameter is refused by name; a typo gets the nearest declared key.
    let foreign = check(&format!("{}\nhardening_ratio = 0.3", spring()));
    assert!(
        foreign.contains("hardening_ratio")
            && foreign.contains("not used by normal = \"linear_spring\""),
        "{foreign}"
    );
    let typo = check("normal = \"linear_spring\"\nnormal_stifness_n_per_m = 1.0e4");
    assert!(
        typo.contains("did you mean `normal_stiffness_n_per_m`"),
        "{typo}"
    );
    let unknown = check("normal = \"linear_sprin\"");
    assert!(
        unknown.contains("did you mean `linear_spring`") && unknown.contains("`mdr`"),
        "{unknown}"
    );
}

/// The registry holds the built-in laws and the demo law, by their declared names; their
/// declared scene keys are the keys scene files use.
#[test]
fn registry_declarations_reproduce_the_scene_keys() {
    assert_eq!(
        normal_law_names(),
        ["mdr", "hertz", "thornton", "adhesive_mdr", "linear_spring"]
    );
    let keys = |name: &str| -> Vec<&str> {
        normal_law(name)
            .unwrap()
            .declaration
            .params
            .iter()
            .map(|p| p.key)
            .collect()
    };
    assert_eq!(
        keys("mdr"),
        ["critical_line_load_n_per_m", "hardening_ratio"]
    );
    assert!(keys("hertz").is_empty());
    assert_eq!(keys("thornton"), ["yield_pressure_pa"]);
    assert_eq!(keys("linear_spring"), ["normal_stiffness_n_per_m"]);
    assert_eq!(MdrElastoPlastic::DECLARATION.name, "mdr");
    assert_eq!(Hertz::DECLARATION.name, "hertz");
    assert_eq!(Thornton::DECLARATION.name, "thornton");
    assert_eq!(LinearSpring::DECLARATION.name, "linear_spring");
}

/// A sphere thrown at `speed_m_per_s` onto a plane 0.1 mm away, without gravity, with the demo
/// spring and `damping`; energy rows every 10 µs.
fn throw(damping: &str, force_path: &str, speed_m_per_s: f64) -> String {
    format!(
        r#"
[run]
name = "dashpot"
seed = 1
duration_s = 0.004
dt_s = {DT}
max_speed_m_per_s = 0.5
output_interval_s = 0.001
energy_interval_s = 1.0e-5
headline = "drop"
force_path = "{force_path}"

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, 0.0]

[[material]]
name = "glass"
youngs_pa = 1.0e9
poisson_ratio = 0.25
density_kg_per_m3 = {DENSITY}

[contact]
{spring}
{damping}

[[particles]]
material = "glass"
count = 1
radius_m = {RADIUS}
placement = "lattice"
region_min_m = [-{RADIUS}, -{RADIUS}, 0.0001]
region_max_m = [0.00501, 0.00501, 0.01011]
velocity_m_per_s = [0.0, 0.0, -{speed_m_per_s}]

[[walls]]
kind = "plane"
material = "glass"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#,
        spring = spring()
    )
}

/// The restitution of the linear spring–dashpot (mass `m`, stiffness `k`, dashpot `c`) whose
/// contact only pushes: it lets go when `k δ + c dδ/dt` reaches 0, at
/// `ω_d t_e = π − 2 arctan(β/ω_d)`, with `e_n = exp(−β t_e)` (`β = c/(2m)`,
/// `ω_d = √(k/m − β²)`; the derivation is in `mdr_contact::damping::LinearDashpot`'s file;
/// Schwager & Pöschel, Granular Matter 9 (2007) 465).
fn pushing_restitution(m: f64, k: f64, c: f64) -> f64 {
    let beta = c / (2.0 * m);
    let omega_d = (k / m - beta * beta).sqrt();
    let t_e = (PI - 2.0 * (beta / omega_d).atan()) / omega_d;
    (-beta * t_e).exp()
}

/// The demo damping law, added as its file in `mdr-contact` and one line in the registry's
/// damping list, runs in scenes on both force paths: with the demo spring, the rebound of a
/// thrown sphere is the linear spring–dashpot's analytic one. Damping ratio `ζ = 0.2`
/// (`c = 2 ζ √(m k)`), 1140 steps per contact.
#[test]
fn demo_damping_law_runs_in_scenes_on_both_force_paths_as_its_analytic_restitution() {
    let m = 4.0 / 3.0 * PI * RADIUS.powi(3) * DENSITY;
    let zeta = 0.2;
    let c = 2.0 * zeta * (m * STIFFNESS).sqrt();
    let expected = pushing_restitution(m, STIFFNESS, c);
    let damping = format!("damping = \"linear_dashpot\"\ndamping_coefficient_n_s_per_m = {c}");
    for path in ["neighbour_list", "rapier"] {
        let summary = run(
            &format!("dashpot-{path}"),
            &throw(&damping, path, 0.1),
            |o| o,
        );
        let e_n = summary.headline.get("restitution").unwrap();
        let v = summary.headline.get("impact_speed_m_per_s").unwrap();
        assert_eq!(v, 0.1, "{path}: no gravity, the sphere keeps its speed");
        // Symplectic Euler at ω₀ dt = 2.8e-3: e_n − e = −4e-4 on both paths.
        assert!(
            (e_n - expected).abs() < 1.2e-3,
            "{path}: e_n = {e_n}, analytic {expected}"
        );
        // Negative controls: a dashpot 5 % stronger, and a contact that also pulls (the
        // textbook exp(−πζ/√(1−ζ²)), 0.527), are told apart.
        let stronger = pushing_restitution(m, STIFFNESS, 1.05 * c);
        assert!((e_n - stronger).abs() > 5e-3, "{path}: {e_n} vs {stronger}");
        let pulling = (-PI * zeta / (1.0 - zeta * zeta).sqrt()).exp();
        assert!((e_n - pulling).abs() > 2e-2, "{path}: {e_n} vs {pulling}");
    }
    // The scene's damping decides: the same throw undamped bounces back whole.
    let undamped = run("dashpot-none", &throw("", "neighbour_list", 0.1), |o| o);
    let e_n = undamped.headline.get("restitution").unwrap();
    assert!((e_n - 1.0).abs() < 1e-3, "undamped e_n = {e_n}");
}

/// The demo damping law's scene key, help line and range error come from its declaration.
#[test]
fn demo_damping_law_scene_key_and_errors_come_from_its_declaration() {
    let dir = common::temp_dir("dashpot-errors");
    let check = |damping: &str| {
        let text = throw(damping, "neighbour_list", 0.1);
        let path = common::write(&dir, "scene.toml", &text);
        parse_scene(&path, &text)
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    let out_of_range = check("damping = \"linear_dashpot\"\ndamping_coefficient_n_s_per_m = -1.0");
    assert!(
        out_of_range.contains("damping_coefficient_n_s_per_m")
            && out_of_range.contains("[0, inf)")
            && out_of_range.contains("c (N·s/m"),
        "{out_of_range}"
    );
    let missing = check("damping = \"linear_dashpot\"");
    assert!(
        missing.contains("damping_coefficient_n_s_per_m"),
        "{missing}"
    );
    let unknown = check("damping = \"linear_dashpt\"");
    assert!(
        unknown.contains("did you mean `linear_dashpot`"),
        "{unknown}"
    );
}
