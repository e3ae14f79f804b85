//! The box scene of the GPU tests that run it with each normal law (its `[contact]` keys in
//! [`LAWS`]) and a damping law: 27 spheres of radius 2 mm (E = 2 MPa) on a 6 mm lattice in the
//! closed box `[-1, 1] cm³ × [0, 2] cm`, each with a fixed pseudo-random velocity of up to
//! 0.5 m/s per component (`box_csv`): within 300 steps (6 ms) they collide with each other and
//! the walls, load plastically, slide, roll, are damped, separate and (adhesive law) let go.
//! Used with the test crate's `common` and `box_toml` modules.

use crate::box_toml::BoxToml;
use crate::common::box_csv;
use mdr_sim::scene::load_scene;
use mdr_sim::Scene;
use std::path::Path;

/// The `[contact]` keys of each normal law.
pub const LAWS: [(&str, &str); 4] = [
    (
        "mdr",
        "normal = \"mdr\"\ncritical_line_load_n_per_m = 20.0\nhardening_ratio = 0.37",
    ),
    ("hertz", "normal = \"hertz\""),
    (
        "thornton",
        "normal = \"thornton\"\nyield_pressure_pa = 2.0e5",
    ),
    (
        "adhesive_mdr",
        "normal = \"adhesive_mdr\"\ncritical_line_load_n_per_m = 20.0\nhardening_ratio = 0.37\n\
         work_of_adhesion_j_per_m2 = 1.0",
    ),
];

/// The stiffness-viscous dashpot (Tsuji's `η √(m k_n)`, `η` as the shipped drum's) with its
/// tangential dashpot.
pub const STIFFNESS_DAMPING: &str =
    "damping = \"stiffness_viscous\"\ndamping_eta = 0.3\ndamping_tangential_ratio = 0.5";

/// The box scene with the normal law's keys `normal`, the damping law's keys `damping` and
/// extra `[run]` keys `run`, written into `dir` (`scene.toml`, `particles.csv`).
pub fn write_box_scene(dir: &Path, normal: &str, damping: &str, run: &str) -> Scene {
    std::fs::write(dir.join("particles.csv"), box_csv()).unwrap();
    let text = BoxToml {
        name: "box",
        duration_s: 0.006,
        dt_s: 2.0e-5,
        max_speed_m_per_s: 1.0,
        output_interval_s: 0.003,
        run: &format!("energy_interval_s = 0.0005\n{run}"),
        materials: &[("grain", 2.0e6, 0.25, 2500.0, "")],
        contact: &format!(
            "{normal}\ntangential = \"mindlin\"\nfriction = 0.5\nrolling_friction = 0.1\n{damping}"
        ),
        particles: &[("grain", "particles.csv")],
        wall_material: "grain",
        min_m: [-0.01, -0.01, 0.0],
        max_m: [0.01, 0.01, 0.02],
        thickness_m: 0.004,
        open_top: false,
    }
    .text();
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}
