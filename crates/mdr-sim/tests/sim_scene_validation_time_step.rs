//! The scene builder's checks of the run's length against its time step, each at its bound on
//! hand-written scenes (parsed only): at most 10¹⁰ steps, the particle-steps warning above 10¹²,
//! the energy interval against the step, and a fixed `dt_s` against the shortest contact (an
//! error below 5 steps per contact, a warning below 50). Steps and intervals are powers of two
//! times integers, so every quotient at a bound is exact.

use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::{Problems, Scene};
use std::path::Path;

/// 2⁻²⁰ s: exact in binary, about 0.95 µs.
const DT: f64 = 1.0 / 1_048_576.0;

/// Two spheres of 2 mm (or a lattice of `count`) on a Hertz contact at 1 m/s, with `run` added to
/// `[run]`.
fn scene(dt: f64, duration: f64, count: u32, run: &str) -> Result<Scene, Problems> {
    scene_at(1.0, dt, duration, count, run)
}

/// [`scene`] with the largest speed `speed` (m/s), which sets the shortest contact's time.
fn scene_at(speed: f64, dt: f64, duration: f64, count: u32, run: &str) -> Result<Scene, Problems> {
    let text = format!(
        r#"[run]
name = "steps"
duration_s = {duration:?}
dt_s = {dt:?}
max_speed_m_per_s = {speed:?}
output_interval_s = 0.005
{run}

[[material]]
name = "grain"
youngs_pa = 1.0e7
poisson_ratio = 0.3
density_kg_per_m3 = 2500.0

[contact]
normal = "hertz"

[[particles]]
material = "grain"
count = {count}
radius_m = 0.002
placement = "lattice"
region_min_m = [0.0, 0.0, 0.0]
region_max_m = [0.1, 0.1, 0.1]
gap_fraction = 0.25
jitter_fraction = 0.0
"#
    );
    parse_scene(Path::new("steps.toml"), &text)
}

fn messages(scene: &Scene) -> Vec<String> {
    scene.warnings.iter().map(|w| w.message.clone()).collect()
}

#[test]
fn a_run_of_exactly_ten_to_the_ten_steps_is_taken() {
    // 10¹⁰ 2⁻²⁰ s = 9536.7431640625 s, exact.
    let duration = 1e10 * DT;
    assert_eq!(duration / DT, 1e10);
    scene(DT, duration, 2, "").unwrap_or_else(|e| panic!("{e}"));
    let refused = scene(DT, duration * (1.0 + 1e-15), 2, "")
        .unwrap_err()
        .to_string();
    assert!(
        refused
            .contains("`run.duration_s`: the run would take 1.000e10 steps (allowed at most 1e10)"),
        "{refused}"
    );
}

#[test]
fn the_particle_steps_warning_starts_above_ten_to_the_twelve() {
    // 1,000 spheres for 10⁹ steps: 10¹² particle-steps, not warned; twice as long, warned.
    let duration = 1e9 * DT;
    let at_bound = scene(DT, duration, 1000, "").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(at_bound.particles.len(), 1000);
    assert!(
        !messages(&at_bound)
            .iter()
            .any(|m| m.contains("particle-steps")),
        "{:?}",
        at_bound.warnings
    );
    let above = scene(DT, 2.0 * duration, 1000, "").unwrap_or_else(|e| panic!("{e}"));
    assert!(
        messages(&above)
            .contains(&"the run is 2.00e12 particle-steps: hours to days of computing".to_owned()),
        "{:?}",
        above.warnings
    );
}

#[test]
fn an_energy_interval_of_one_step_is_not_warned() {
    let one_step = scene(DT, 0.01, 2, &format!("energy_interval_s = {DT:?}"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        !messages(&one_step)
            .iter()
            .any(|m| m.contains("shorter than the time step")),
        "{:?}",
        one_step.warnings
    );
    let half = scene(DT, 0.01, 2, &format!("energy_interval_s = {:?}", DT / 2.0))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        messages(&half).contains(&"is shorter than the time step: one row per step".to_owned()),
        "{:?}",
        half.warnings
    );
}

/// A largest speed and a step `dt` for which `contact_time / dt` is exactly `steps`: the step
/// is searched among the f64 neighbours of `contact_time / steps`, which for some contact times
/// all give a quotient a bit off, so the speed (and with it the contact time) is varied too.
fn exact_step(steps: f64) -> (f64, f64) {
    for k in 0..100 {
        let speed = 1.0 + 0.01 * k as f64;
        let contact_time = scene_at(speed, DT, 0.01, 2, "")
            .unwrap_or_else(|e| panic!("{e}"))
            .contact_time;
        let guess = contact_time / steps;
        if let Some(dt) = (-4i64..=4)
            .map(|j| f64::from_bits((guess.to_bits() as i64 + j) as u64))
            .find(|dt| contact_time / dt == steps)
        {
            return (speed, dt);
        }
    }
    panic!("no speed and step give exactly {steps} steps per contact");
}

#[test]
fn a_fixed_step_is_held_to_five_and_fifty_steps_per_contact_at_exactly_those() {
    // Exactly 5 steps: taken, with the warning; fewer: refused.
    let (speed, five) = exact_step(5.0);
    let at_five = scene_at(speed, five, 0.01, 2, "").unwrap_or_else(|e| panic!("{e}"));
    assert!(
        messages(&at_five)
            .iter()
            .any(|m| m.contains("with 5.0 steps (fewer than 50)")),
        "{:?}",
        at_five.warnings
    );
    let refused = scene_at(speed, five * (1.0 + 1e-12), 0.01, 2, "")
        .unwrap_err()
        .to_string();
    assert!(refused.contains("is far too large"), "{refused}");
    assert!(refused.contains("would take 5.00 steps"), "{refused}");
    // Exactly 50 steps: not warned; fewer: warned.
    let (speed, fifty) = exact_step(50.0);
    let at_fifty = scene_at(speed, fifty, 0.01, 2, "").unwrap_or_else(|e| panic!("{e}"));
    assert!(
        !messages(&at_fifty)
            .iter()
            .any(|m| m.contains("fewer than 50")),
        "{:?}",
        at_fifty.warnings
    );
    let below =
        scene_at(speed, fifty * (1.0 + 1e-12), 0.01, 2, "").unwrap_or_else(|e| panic!("{e}"));
    assert!(
        messages(&below)
            .iter()
            .any(|m| m.contains("with 50.0 steps (fewer than 50)")),
        "{:?}",
        below.warnings
    );
}
