//! A removed wall stops acting whatever its orientation: a side wall (a plane whose normal is
//! across gravity) removed before a sphere reaches it lets the sphere through on both force
//! paths; kept, it sends the sphere back (the negative control).

mod common;

use common::{temp_dir, write};
use mdr_sim::{load_scene, run_scene, RunOptions};

/// One sphere of radius 2 mm at the origin moving at 0.5 m/s towards the side wall `x = −1 cm`
/// (normal `+x`), no gravity along `x`; the wall removed at `removed` (s) or never.
fn scene(removed: Option<f64>, force_path: &str) -> String {
    let removal = removed.map_or(String::new(), |t| format!("removed_at_s = {t:?}\n"));
    format!(
        r#"
[run]
name = "side"
duration_s = 0.06
dt_s = 1.0e-5
max_speed_m_per_s = 1.0
output_interval_s = 0.06
force_path = "{force_path}"

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, 0.0]

[[material]]
name = "grain"
youngs_pa = 1.0e7
poisson_ratio = 0.3
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 1000.0
hardening_ratio = 0.37

[[particles]]
material = "grain"
placement = "csv"
file = "one.csv"

[[walls]]
kind = "plane"
material = "grain"
point_m = [-0.01, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
{removal}"#
    )
}

/// The sphere's final position and velocity along `x`.
fn run(removed: Option<f64>, force_path: &str) -> (f64, f64) {
    let dir = temp_dir(&format!("wall_removal_{force_path}_{}", removed.is_some()));
    write(
        &dir,
        "one.csv",
        "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n0,0,0,0.002,-0.5,0,0\n",
    );
    let path = write(&dir, "side.toml", &scene(removed, force_path));
    let scene = load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
    let out = dir.join("out");
    let summary = run_scene(&scene, &RunOptions::new(&out).quiet(true).no_frames(true))
        .unwrap_or_else(|e| panic!("{e}"));
    let p = &summary.particles[0];
    (p.translation[0], p.linvel[0])
}

#[test]
fn a_removed_side_wall_lets_the_sphere_through_on_both_paths() {
    for path in ["neighbour_list", "rapier"] {
        // Removed after 1 ms, before the sphere (16 ms from the wall) reaches it: it flies on
        // to x = −0.03 m at its speed.
        let (x, v) = run(Some(0.001), path);
        assert!(
            (x - (-0.03)).abs() < 1e-9 && (v + 0.5).abs() < 1e-12,
            "{path}: x = {x}, v = {v}"
        );
        // Negative control: kept, the wall sends it back.
        let (x, v) = run(None, path);
        assert!(x > -0.01 && v > 0.0, "{path} kept: x = {x}, v = {v}");
    }
}
