//! A small hopper orifice sweep both devices run: 166 soft spheres (d = 2 mm, Hertz,
//! Mindlin, the stiffness-viscous dashpot) poured for 0.06 s from a cylinder 12.5 d wide
//! (`exact_surface`) through an orifice plate (`exact_surface`), once per diameter of
//! `orifice_sweep_m` (three: 5, 6 and 7 d, above the jamming ratio).

#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// The sweep's orifice diameters (m).
pub const DIAMETERS: [f64; 3] = [0.010, 0.012, 0.014];

/// The scene's run name: its runs are `hopper_D0`, `hopper_D1`, `hopper_D2`.
pub const NAME: &str = "hopper";

/// The scene's text with the orifice diameters `sweep` (m).
pub fn hopper_sweep_text(sweep: &[f64]) -> String {
    let sweep: Vec<String> = sweep.iter().map(|d| format!("{d:?}")).collect();
    format!(
        r#"
[run]
name = "{NAME}"
seed = 3
duration_s = 0.06
dt_s = "auto"
max_speed_m_per_s = 1.5
output_interval_s = 0.005
headline = "hopper"
discharge_height_m = -0.006
delete_below_m = -0.02
orifice_sweep_m = [{}]

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 1.0e5
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "hertz"
tangential = "mindlin"
friction = 0.4
damping = "stiffness_viscous"
damping_eta = 0.3

[[particles]]
material = "grain"
count = 200
radius_m = 0.001
placement = "lattice"
region_min_m = [-0.011, -0.011, 0.0002]
region_max_m = [0.011, 0.011, 0.06]
region_radius_m = 0.0105
gap_fraction = 0.02
jitter_fraction = 0.5

[[walls]]
kind = "cylinder"
material = "grain"
center_m = [0.0, 0.0, 0.04]
axis = [0.0, 0.0, 1.0]
radius_m = 0.0125
length_m = 0.08
segments = 32
exact_surface = true
thickness_m = 0.003

[[walls]]
kind = "orifice_plate"
material = "grain"
center_m = [0.0, 0.0, 0.0]
outer_radius_m = 0.016
orifice_diameter_m = {:?}
thickness_m = 0.002
segments = 32
exact_surface = true
"#,
        sweep.join(", "),
        DIAMETERS[0]
    )
}

/// The scene with the orifice diameters `sweep` written to `dir/hopper.toml`; its path.
pub fn write_hopper_sweep(dir: &Path, sweep: &[f64]) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join("hopper.toml");
    std::fs::write(&path, hopper_sweep_text(sweep)).unwrap();
    path
}
