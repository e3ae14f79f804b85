//! Particle files are bounded before their spheres are held: a CSV file stops being read at the
//! first row past the bound, and a LAMMPS data file whose header declares more atoms than the
//! bound is refused before any memory is set aside for them (a header of 10¹⁴ atoms used to
//! ask for 4 PB at once, and the process aborted).

use mdr_sim::placement::{read_csv, read_lammps};
use mdr_sim::scene::validate::parse_scene;
use std::path::PathBuf;

fn scratch(name: &str, text: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sim_particle_file_bounds");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn lammps(declared: &str, atoms: usize) -> String {
    let mut text = format!(
        "LAMMPS data file\n\n{declared} atoms\n1 atom types\n\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms # sphere\n\n"
    );
    for i in 0..atoms {
        text.push_str(&format!(
            "{} 1 0.002 2500 {} 0.5 0.5 0 0 0\n",
            i + 1,
            0.1 + 0.01 * i as f64
        ));
    }
    text
}

#[test]
fn a_csv_file_is_read_up_to_its_bound() {
    let rows = "x_m,y_m,z_m,radius_m\n0,0,0,0.001\n0.01,0,0,0.001\n0.02,0,0,0.001\n";
    let path = scratch("three.csv", rows);
    assert_eq!(read_csv(&path, 3).unwrap().len(), 3);
    let refused = read_csv(&path, 2).unwrap_err();
    assert!(
        refused.ends_with("three.csv: more than 2 particles, the most a scene holds"),
        "{refused}"
    );
}

#[test]
fn a_lammps_header_beyond_the_bound_is_refused_before_reading() {
    let path = scratch("three.data", &lammps("3", 3));
    assert_eq!(read_lammps(&path, 1.0, 3).unwrap().len(), 3);
    let refused = read_lammps(&path, 1.0, 2).unwrap_err();
    assert!(
        refused.ends_with(
            "three.data: the header declares 3 atoms, more than 2, the most a scene holds"
        ),
        "{refused}"
    );
    // The header alone decides: a file of three atoms that declares 10¹⁴ is refused at once.
    let huge = scratch("huge.data", &lammps("100000000000000", 3));
    let refused = read_lammps(&huge, 1.0, 1_000_000).unwrap_err();
    assert!(
        refused.contains("declares 100000000000000 atoms, more than 1000000"),
        "{refused}"
    );
}

/// Through a scene: the file's error at its `file` key, the scene refused, the process alive.
#[test]
fn a_scene_naming_a_lammps_file_of_too_many_atoms_is_refused_at_its_file() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sim_particle_file_bounds");
    scratch("huge_scene.data", &lammps("100000000000000", 2));
    let text = r#"[run]
name = "huge"
duration_s = 0.01
dt_s = 5e-6
max_speed_m_per_s = 1.0
output_interval_s = 0.005

[[material]]
name = "grain"
youngs_pa = 1.0e7
poisson_ratio = 0.3
density_kg_per_m3 = 2500.0

[contact]
normal = "hertz"

[[particles]]
material = "grain"
placement = "lammps"
file = "huge_scene.data"
"#;
    let problems = parse_scene(&dir.join("huge.toml"), text).unwrap_err();
    let message = problems.to_string();
    assert!(message.contains("particles[0].file"), "{message}");
    assert!(
        message.contains("the header declares 100000000000000 atoms, more than 1000000"),
        "{message}"
    );
}
