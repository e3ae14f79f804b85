//! `dt_s = "auto"` with the default 50 steps per contact: the step is the shortest contact's
//! Hertz time over 50, so a scene that takes it is never warned that its contact is resolved
//! with fewer than 50 steps, whatever the radius and speed make of that time's last bits.

use mdr_sim::scene::validate::parse_scene;
use std::path::Path;

fn scene(radius_m: f64, max_speed: f64) -> String {
    format!(
        r#"[run]
name = "auto"
duration_s = 0.01
dt_s = "auto"
max_speed_m_per_s = {max_speed:e}
output_interval_s = 0.005

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 1.0e7
poisson_ratio = 0.3
density_kg_per_m3 = 2500.0

[contact]
normal = "hertz"

[[particles]]
material = "grain"
count = 2
radius_m = {radius_m:e}
placement = "lattice"
region_min_m = [0.0, 0.0, 0.0]
region_max_m = [0.1, 0.1, 0.1]
gap_fraction = 0.25
jitter_fraction = 0.0
"#
    )
}

/// Over 400 radii and speeds the quotient `t_c / (t_c / 50)` falls below 50 in some cases
/// (counted in the loop, so the test cannot pass vacuously; the quotient's check warned the
/// second case, a radius of 1.02 mm at 1.24 m/s, "with 50.0 steps (fewer than 50)"); none is
/// warned.
#[test]
fn an_automatic_step_is_not_warned_for_its_own_steps_per_contact() {
    let mut below = 0;
    for k in 0..400 {
        let radius = 1e-3 * (1.0 + k as f64 / 97.0);
        let speed = 0.5 + (k % 13) as f64 * 0.37;
        let text = scene(radius, speed);
        let scene = parse_scene(Path::new("auto.toml"), &text).unwrap_or_else(|e| panic!("{e}"));
        assert!(scene.dt_auto);
        if scene.contact_time / scene.dt < 50.0 {
            below += 1;
        }
        let warned: Vec<_> = scene
            .warnings
            .iter()
            .filter(|w| w.message.contains("fewer than"))
            .collect();
        assert!(
            warned.is_empty(),
            "radius {radius}, speed {speed}: {warned:?}"
        );
    }
    assert!(
        below > 0,
        "no case rounds below 50: the test checks nothing"
    );
}
