//! Helpers shared by the scene tests: small scenes written to a temporary directory.

#![allow(dead_code)]

use std::ops::Deref;
use std::path::{Path, PathBuf};

/// A temporary directory for one test (a [`tempfile::TempDir`]), removed with everything in it
/// when dropped; it dereferences to its path.
pub struct TempDir(tempfile::TempDir);

impl Deref for TempDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        self.0.path()
    }
}

/// A fresh temporary directory for one test; `name` starts its file name.
pub fn temp_dir(name: &str) -> TempDir {
    TempDir(
        tempfile::Builder::new()
            .prefix(&format!("mdr-sim-test-{name}-"))
            .tempdir()
            .unwrap(),
    )
}

/// Write `text` as `dir/name` and return the path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A small column collapse: `n × n × layers` spheres released on a rough floor. MDR normal law,
/// Mindlin friction `mu`, no damping. `extra_run` is appended to `[run]`.
pub fn column(n: usize, layers: usize, duration: f64, mu: f64, extra_run: &str) -> String {
    let r = 0.002;
    let spacing = 2.0 * r * 1.05;
    let half = 0.5 * spacing * n as f64 + 1e-4;
    let top = spacing * layers as f64 + 1e-4;
    let tangential = if mu > 0.0 {
        format!("tangential = \"mindlin\"\nfriction = {mu}")
    } else {
        String::new()
    };
    format!(
        r#"
[run]
name = "column"
seed = 5
duration_s = {duration}
dt_s = "auto"
max_speed_m_per_s = 1.0
steps_per_contact = 50
output_interval_s = 0.005
energy_interval_s = 0.0005
headline = "column"
{extra_run}

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 5.0e7
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 100.0
hardening_ratio = 0.37
{tangential}

[[particles]]
material = "grain"
count = {count}
radius_m = {r}
placement = "lattice"
region_min_m = [{lo}, {lo}, 0.0]
region_max_m = [{half}, {half}, {top}]
gap_fraction = 0.05
jitter_fraction = 0.8

[[walls]]
kind = "plane"
material = "grain"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#,
        count = n * n * layers,
        lo = -half,
    )
}

/// A small rotating drum (a capped cylinder on a kinematic body), with `extra_walls` appended.
pub fn drum(count: usize, duration: f64, extra_walls: &str) -> String {
    format!(
        r#"
[run]
name = "drum"
seed = 11
duration_s = {duration}
dt_s = "auto"
max_speed_m_per_s = 1.0
steps_per_contact = 25
output_interval_s = 0.01
energy_interval_s = 0.002
headline = "drum"

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 1.0e6
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 50.0
hardening_ratio = 0.37
tangential = "mindlin"
friction = 0.5
rolling_friction = 0.1
damping = "stiffness_viscous"
damping_eta = 0.3
damping_tangential_ratio = 0.5

[[particles]]
material = "grain"
count = {count}
radius_m = 0.0015
placement = "lattice"
region_min_m = [-0.011, -0.004, -0.013]
region_max_m = [0.011, 0.004, 0.0]
gap_fraction = 0.05
jitter_fraction = 0.5

[[walls]]
kind = "cylinder"
material = "grain"
center_m = [0.0, 0.0, 0.0]
axis = [0.0, 1.0, 0.0]
radius_m = 0.02
length_m = 0.01
capped = true
segments = 32
thickness_m = 0.004
angular_velocity_rad_per_s = [0.0, 3.0, 0.0]
rotation_center_m = [0.0, 0.0, 0.0]
{extra_walls}
"#
    )
}
