//! Scenes on the neighbour-list path (the default force path): the headlines agree with rapier's
//! path, every wall kind and placement runs, the energy books close with damping and a moving
//! wall, a drum with a mesh paddle keeps its spheres, and results do not depend on the number of
//! threads.

mod common;

use mdr_rapier::neighbour_list::rayon::ThreadPoolBuilder;
use mdr_sim::output::energy::EnergyRow;
use mdr_sim::run::RunSummary;
use mdr_sim::{run_scene, scene::validate::parse_scene, RunOptions};
use std::path::Path;

/// Run `text` (written as `dir/name.toml`) without frames.
fn run(dir: &Path, name: &str, text: &str) -> RunSummary {
    let path = common::write(dir, &format!("{name}.toml"), text);
    let scene = parse_scene(&path, text).unwrap_or_else(|p| panic!("{name}: {p}"));
    run_scene(
        &scene,
        &RunOptions::new(dir.join(name)).quiet(true).no_frames(true),
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// `text` with `force_path = "rapier"` added to `[run]`.
fn on_rapier(text: &str) -> String {
    text.replacen("[run]\n", "[run]\nforce_path = \"rapier\"\n", 1)
}

/// A small hopper: a cylinder (32 mesh slabs) on an orifice plate (prisms), D/d = 4.
fn hopper(count: usize, duration: f64) -> String {
    format!(
        r#"
[run]
name = "hopper"
seed = 3
duration_s = {duration}
dt_s = "auto"
max_speed_m_per_s = 1.0
steps_per_contact = 25
output_interval_s = 0.01
headline = "hopper"
discharge_height_m = -0.01

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
friction = 0.4
damping = "stiffness_viscous"
damping_eta = 0.3

[[particles]]
material = "grain"
count = {count}
radius_m = 0.001
placement = "lattice"
region_min_m = [-0.0055, -0.0055, 0.0002]
region_max_m = [0.0055, 0.0055, 0.07]
gap_fraction = 0.02
jitter_fraction = 0.5

[[walls]]
kind = "cylinder"
material = "grain"
center_m = [0.0, 0.0, 0.04]
axis = [0.0, 0.0, 1.0]
radius_m = 0.009
length_m = 0.08
segments = 32
thickness_m = 0.003

[[walls]]
kind = "orifice_plate"
material = "grain"
center_m = [0.0, 0.0, 0.0]
outer_radius_m = 0.012
orifice_diameter_m = 0.008
thickness_m = 0.002
segments = 32
"#
    )
}

/// Both paths run the same scene; returns (neighbour list, rapier) headline values of `name`.
fn both(dir: &Path, tag: &str, text: &str, name: &str) -> (f64, f64) {
    let fast = run(dir, &format!("{tag}_fast"), text);
    let plain = run(dir, &format!("{tag}_rapier"), &on_rapier(text));
    let (a, b) = (
        fast.headline.get(name).unwrap(),
        plain.headline.get(name).unwrap(),
    );
    eprintln!("{tag}: {name} neighbour list {a:.6}, rapier {b:.6}");
    assert!(a.is_finite() && b.is_finite());
    (a, b)
}

/// The drop scene's e_n matches the law's closed form on the neighbour-list path, and equals
/// rapier's path to round-off (one sphere and a plane: no chaos to amplify round-off).
#[test]
fn drop_headline_is_the_same_on_both_paths() {
    let dir = common::temp_dir("fast-drop");
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/drop.toml"),
    )
    .unwrap()
    .replace("duration_s = 0.2 ", "duration_s = 0.11 ")
    .replace("steps_per_contact = 200", "steps_per_contact = 50");
    let fast = run(&dir, "drop_fast", &text);
    let plain = run(&dir, "drop_rapier", &on_rapier(&text));
    let e = fast.headline.get("restitution").unwrap();
    let reference = fast.headline.get("law_energy_route_restitution").unwrap();
    let e_plain = plain.headline.get("restitution").unwrap();
    eprintln!("drop: e_n {e:.8} (rapier path {e_plain:.8}), closed form {reference:.8}");
    assert!(reference < 0.9, "the impact is plastic: {reference}");
    assert!(
        (e / reference - 1.0).abs() < 0.01,
        "e_n = {e} vs {reference}"
    );
    assert!(
        (e / e_plain - 1.0).abs() < 1e-9,
        "paths differ: {e} vs {e_plain}"
    );
}

/// Column collapse and hopper discharge: the same headline on both paths, and the drum the same
/// wall work, within the scatter of such runs (the paths differ by round-off, which granular flow amplifies).
#[test]
fn column_hopper_and_drum_headlines_agree_on_both_paths() {
    let dir = common::temp_dir("fast-headlines");
    let (a, b) = both(
        &dir,
        "column",
        &common::column(4, 6, 0.08, 0.5, ""),
        "runout_m",
    );
    assert!((a / b - 1.0).abs() < 0.05, "column run-out {a} vs {b}");
    let (a, b) = both(
        &dir,
        "hopper",
        &hopper(250, 0.15),
        "mass_flow_rate_kg_per_s",
    );
    assert!(a > 0.0 && b > 0.0, "the hopper discharged");
    assert!((a / b - 1.0).abs() < 0.15, "hopper rate {a} vs {b}");
    // The small drum is too short for its angle fit (NaN on both paths): compare the work the
    // turning drum did on the spheres instead.
    let text = common::drum(48, 0.3, "");
    let fast = run(&dir, "drum_fast", &text);
    let plain = run(&dir, "drum_rapier", &on_rapier(&text));
    let (a, b) = (
        fast.energy.last().unwrap().wall_work_j,
        plain.energy.last().unwrap().wall_work_j,
    );
    eprintln!("drum: wall work neighbour list {a:.6e} J, rapier {b:.6e} J");
    assert!(
        a > 0.0 && (a / b - 1.0).abs() < 0.1,
        "drum wall work {a} vs {b}"
    );
}

/// A closed cuboid as OBJ text (outward normals).
fn obj_cuboid(lo: [f64; 3], hi: [f64; 3]) -> String {
    let mut s = String::new();
    for k in 0..8 {
        let x = if matches!(k % 4, 1 | 2) { hi[0] } else { lo[0] };
        let y = if matches!(k % 4, 2 | 3) { hi[1] } else { lo[1] };
        let z = if k >= 4 { hi[2] } else { lo[2] };
        s += &format!("v {x} {y} {z}\n");
    }
    for f in [
        [1, 3, 2],
        [1, 4, 3],
        [5, 6, 7],
        [5, 7, 8],
        [1, 2, 6],
        [1, 6, 5],
        [4, 8, 7],
        [4, 7, 3],
        [1, 5, 8],
        [1, 8, 4],
        [2, 3, 7],
        [2, 7, 6],
    ] {
        s += &format!("f {} {} {}\n", f[0], f[1], f[2]);
    }
    s
}

/// A drum (kinematic, rotating) with a mesh paddle turning with it: every sphere stays inside,
/// nothing diverges, the paddle and the drum both touch spheres; the energy books close with
/// damping, friction, rolling resistance and the drum's work booked as wall work.
#[test]
fn drum_with_a_mesh_paddle_keeps_every_sphere_and_closes_its_books() {
    let dir = common::temp_dir("fast-drum-mesh");
    common::write(
        &dir,
        "paddle.obj",
        // Clear of the drum's wall by more than a diameter: a paddle flush with the wall wedges
        // spheres into its corner until one goes through it (the wall guard stops such a run).
        &obj_cuboid([-0.002, -0.005, -0.0165], [0.002, 0.005, -0.0135]),
    );
    let paddle = r#"
[[walls]]
kind = "mesh"
material = "grain"
file = "paddle.obj"
angular_velocity_rad_per_s = [0.0, 3.0, 0.0]
rotation_center_m = [0.0, 0.0, 0.0]
"#;
    // At 25 steps per contact the books drift by several per cent against the rotating mesh
    // (bound below 10 %), beyond the energy guard's default.
    let text = common::drum(48, 0.6, paddle).replace(
        "steps_per_contact = 25",
        "steps_per_contact = 25\nmax_energy_drift = 0.1",
    );
    let summary = run(&dir, "drum_paddle", &text);
    for (i, p) in summary.particles.iter().enumerate() {
        let [x, y, z] = p.translation;
        assert!(
            x.is_finite() && y.is_finite() && z.is_finite(),
            "sphere {i}"
        );
        assert!(
            (x * x + z * z).sqrt() < 0.02,
            "sphere {i} left the drum: {x} {z}"
        );
        assert!(y.abs() < 0.005, "sphere {i} left through a cap: {y}");
    }
    let rows = &summary.energy;
    assert!(rows.iter().all(|r| r.balance_j.is_finite()));
    let last = rows.last().unwrap();
    let dissipated = last.plastic_j + last.friction_j + last.damping_j + last.rolling_j;
    let worst = |left_out: &dyn Fn(&EnergyRow) -> f64| {
        let start = rows[0].balance_j - left_out(&rows[0]);
        rows.iter()
            .map(|r| (r.balance_j - left_out(r) - start).abs())
            .fold(0.0, f64::max)
    };
    let drift = worst(&|_| 0.0);
    let drift_without_wall_work = worst(&|r| -r.wall_work_j);
    eprintln!(
        "drum + paddle: wall work {:.4e} J, dissipated {dissipated:.4e} J (damping {:.3e}, \
         friction {:.3e}, rolling {:.3e}, plastic {:.3e}), drift {drift:.3e} J, without the \
         wall work {drift_without_wall_work:.3e} J",
        last.wall_work_j, last.damping_j, last.friction_j, last.rolling_j, last.plastic_j
    );
    assert!(last.damping_j > 0.0 && last.friction_j > 0.0 && last.rolling_j > 0.0);
    assert!(last.wall_work_j > 0.2 * dissipated, "the drum did work");
    // Measured: 5.9 % of the dissipated work at 25 steps per contact (the books of the
    // incremental springs against a rotating 32-facet mesh); bound 10 %.
    assert!(drift < 0.1 * dissipated, "books drift {drift:.3e} J");
    assert!(drift_without_wall_work > 10.0 * drift);
}

/// Every other wall kind and placement: a box filled by lattice (normal sizes), random fill
/// (uniform sizes, initial velocity), CSV and LAMMPS files; meshes from STL and OBJ files over a
/// plane; the spheres stay inside and touch the walls.
#[test]
fn every_wall_kind_and_placement_runs_on_the_neighbour_list_path() {
    let dir = common::temp_dir("fast-walls");
    common::write(
        &dir,
        "spheres.csv",
        "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n\
         -0.012,-0.012,0.03,0.0015,0.1,0.0,0.0\n0.012,0.012,0.03,0.0012,0.0,-0.1,0.0\n",
    );
    common::write(
        &dir,
        "spheres.data",
        "LAMMPS data file\n\n2 atoms\n1 atom types\n\n-0.02 0.02 xlo xhi\n-0.02 0.02 ylo yhi\n\
         0 0.05 zlo zhi\n\nAtoms # sphere\n\n1 1 0.003 2500 -0.012 0.012 0.035\n\
         2 1 0.0026 2500 0.012 -0.012 0.035\n",
    );
    let head = r#"
[run]
name = "walls"
seed = 9
duration_s = 0.15
dt_s = "auto"
max_speed_m_per_s = 1.0
steps_per_contact = 25
output_interval_s = 0.05

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 1.0e6
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "thornton"
yield_pressure_pa = 2.0e5
tangential = "mindlin"
friction = 0.3
damping = "hertzian_viscous"
damping_gamma_n_per_m_s = 2000.0
"#;
    let box_scene = format!(
        r#"{head}
[[particles]]
material = "grain"
count = 27
size_distribution = "normal"
radius_m = 0.0013
radius_std_m = 0.0001
radius_min_m = 0.0011
radius_max_m = 0.0015
placement = "lattice"
region_min_m = [-0.008, -0.008, 0.0005]
region_max_m = [0.008, 0.008, 0.012]

[[particles]]
material = "grain"
count = 20
size_distribution = "uniform"
radius_min_m = 0.001
radius_max_m = 0.0015
placement = "random"
region_min_m = [-0.018, -0.018, 0.014]
region_max_m = [0.018, 0.018, 0.025]
velocity_m_per_s = [0.2, -0.1, 0.0]

[[particles]]
material = "grain"
placement = "csv"
file = "spheres.csv"

[[particles]]
material = "grain"
placement = "lammps"
file = "spheres.data"

[[walls]]
kind = "box"
material = "grain"
min_m = [-0.02, -0.02, 0.0]
max_m = [0.02, 0.02, 0.05]
thickness_m = 0.004
"#
    );
    let summary = run(&dir, "box", &box_scene);
    assert_eq!(summary.particles.len(), 27 + 20 + 2 + 2);
    for (i, p) in summary.particles.iter().enumerate() {
        let [x, y, z] = p.translation;
        assert!(x.abs() < 0.02 && y.abs() < 0.02, "sphere {i} left the box");
        assert!(z > 0.0 && z < 0.05, "sphere {i} at z = {z}");
    }
    assert!(summary.energy.last().unwrap().contacts > 0);

    // STL floor (x < 0) and OBJ floor (x > 0) at z = 0, a plane 5 mm below as a backstop.
    let mut stl = String::from("solid floor\n");
    for t in [
        [[-0.02, -0.02], [0.0, -0.02], [0.0, 0.02]],
        [[-0.02, -0.02], [0.0, 0.02], [-0.02, 0.02]],
    ] {
        stl += "facet normal 0 0 1\nouter loop\n";
        for v in t {
            stl += &format!("vertex {} {} 0\n", v[0], v[1]);
        }
        stl += "endloop\nendfacet\n";
    }
    stl += "endsolid floor\n";
    common::write(&dir, "floor.stl", &stl);
    common::write(
        &dir,
        "floor.obj",
        "v 0 -0.02 0\nv 0.02 -0.02 0\nv 0.02 0.02 0\nv 0 0.02 0\nf 1 2 3\nf 1 3 4\n",
    );
    let mesh_scene = format!(
        r#"{head}
[[particles]]
material = "grain"
count = 32
radius_m = 0.0015
placement = "lattice"
region_min_m = [-0.016, -0.004, 0.0005]
region_max_m = [0.016, 0.004, 0.02]

[[walls]]
kind = "mesh"
material = "grain"
file = "floor.stl"

[[walls]]
kind = "mesh"
material = "grain"
file = "floor.obj"

[[walls]]
kind = "plane"
material = "grain"
point_m = [0.0, 0.0, -0.005]
normal = [0.0, 0.0, 1.0]
"#
    );
    let summary = run(&dir, "meshes", &mesh_scene);
    let (mut left, mut right) = (0, 0);
    for (i, p) in summary.particles.iter().enumerate() {
        let [x, _, z] = p.translation;
        assert!(z > 0.0, "sphere {i} fell through a mesh: z = {z}");
        if x < 0.0 {
            left += 1;
        } else {
            right += 1;
        }
    }
    assert!(left > 0 && right > 0, "both meshes carry spheres");
}

/// The same scene in a pool of one thread and of two threads: the same bits.
#[test]
fn scene_results_do_not_depend_on_the_number_of_threads() {
    let dir = common::temp_dir("fast-threads");
    let text = common::drum(48, 0.1, "");
    let in_pool = |threads: usize, name: &str| {
        ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run(&dir, name, &text))
    };
    let one = in_pool(1, "one");
    let two = in_pool(2, "two");
    for (a, b) in one.particles.iter().zip(&two.particles) {
        assert_eq!(a, b);
    }
    for (a, b) in one.energy.iter().zip(&two.energy) {
        assert_eq!(a.balance_j.to_bits(), b.balance_j.to_bits());
        assert_eq!(a.wall_work_j.to_bits(), b.wall_work_j.to_bits());
    }
}

/// Two 2 mm spheres in zero gravity in a box periodic over [0, 0.1] m in x and y: A at
/// x = 98.5 mm moving +x at 0.5 m/s, B at rest at x = 6.5 mm, 8 mm apart across the boundary
/// (`extra_run` goes into `[run]`).
fn periodic_pair(extra_run: &str) -> String {
    format!(
        r#"
[run]
name = "periodic"
duration_s = 0.03
dt_s = "auto"
max_speed_m_per_s = 0.5
output_interval_s = 0.01
{extra_run}

[[material]]
name = "grain"
youngs_pa = 1.0e7
poisson_ratio = 0.3
density_kg_per_m3 = 2500.0

[contact]
normal = "hertz"
tangential = "mindlin"
friction = 0.5

[[particles]]
material = "grain"
placement = "csv"
file = "pair.csv"
"#
    )
}

#[test]
fn periodic_box_collides_across_the_boundary_and_wraps() {
    let dir = common::temp_dir("periodic_box");
    common::write(
        &dir,
        "pair.csv",
        "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n\
         0.0985,0.05,0.05,0.002,0.5,0,0\n\
         0.0065,0.05,0.05,0.002,0,0,0\n",
    );
    let periodic = "periodic_x_m = [0.0, 0.1]\nperiodic_y_m = [0.0, 0.1]";
    let summary = run(&dir, "periodic", &periodic_pair(periodic));
    let (a, b) = (&summary.particles[0], &summary.particles[1]);
    // An elastic head-on collision of equal spheres exchanges their velocities (Hertz, no
    // damping: to the integration's error, 1.6e-5 of the speed at 50 steps per contact time),
    // through the boundary.
    assert!(a.linvel[0].abs() < 1e-4 * 0.5, "A: {:?}", a.linvel);
    assert!((b.linvel[0] - 0.5).abs() < 1e-4 * 0.5, "B: {:?}", b.linvel);
    // A crossed the boundary and was wrapped into the box (it stops about 2.5 mm past it, in
    // contact with B's image); B left at 0.5 m/s from about 8 ms on.
    for p in [a, b] {
        let [x, y, _] = p.translation;
        assert!((0.0..0.1).contains(&x) && (0.0..0.1).contains(&y), "{p:?}");
    }
    assert!(a.translation[0] < 0.005, "A at {:?}", a.translation);
    assert!(
        (b.translation[0] - 0.0175).abs() < 1e-3,
        "B at {:?}",
        b.translation
    );
    let row = summary.energy.iter().max_by_key(|r| r.contacts).unwrap();
    assert_eq!(row.contacts, 1, "the pair touched across the boundary");
    // In open space they fly apart and never touch.
    let open = run(&dir, "open", &periodic_pair(""));
    assert!(open.energy.iter().all(|r| r.contacts == 0));
    assert_eq!(open.particles[0].linvel[0], 0.5);
}

#[test]
fn bad_periodic_boxes_are_refused_with_file_line_and_key() {
    let dir = common::temp_dir("periodic_bad");
    common::write(
        &dir,
        "pair.csv",
        "x_m,y_m,z_m,radius_m\n0.003,0.05,0.05,0.002\n",
    );
    for (extra, key, says) in [
        (
            "periodic_x_m = [0.0, 0.1]",
            "periodic_x_m",
            "needs periodic_y_m",
        ),
        (
            "periodic_y_m = [0.0, 0.1]",
            "periodic_y_m",
            "needs periodic_x_m",
        ),
        (
            "periodic_x_m = [0.1, 0.0]\nperiodic_y_m = [0.0, 0.1]",
            "periodic_x_m",
            "lo < hi",
        ),
        (
            "periodic_x_m = [0.0, 0.1]\nperiodic_y_m = [0.0, 0.1]\nforce_path = \"rapier\"",
            "periodic_x_m",
            "neighbour-list path only",
        ),
        (
            "periodic_x_m = [0.0, 0.1]\nperiodic_y_m = [0.0, 0.1]\ndelete_below_m = -1.0",
            "periodic_x_m",
            "delete_below_m",
        ),
    ] {
        let text = periodic_pair(extra);
        let path = common::write(&dir, "bad.toml", &text);
        let problems = parse_scene(&path, &text).expect_err(extra).to_string();
        assert!(
            problems.contains(key) && problems.contains(says) && problems.contains("bad.toml:"),
            "{extra}: {problems}"
        );
    }
    // The overlap allowance of a group is checked too.
    let text = periodic_pair("").replace(
        "file = \"pair.csv\"",
        "file = \"pair.csv\"\nmax_initial_overlap_fraction = 0.7",
    );
    let path = common::write(&dir, "bad.toml", &text);
    let problems = parse_scene(&path, &text).unwrap_err().to_string();
    assert!(
        problems.contains("max_initial_overlap_fraction") && problems.contains("[0, 0.5]"),
        "{problems}"
    );
    // A box narrower than twice the neighbour cut-off is refused before the run.
    let text = periodic_pair("periodic_x_m = [0.0, 0.006]\nperiodic_y_m = [0.0, 0.1]");
    let path = common::write(&dir, "narrow.toml", &text);
    let scene = parse_scene(&path, &text).unwrap();
    let e = run_scene(&scene, &RunOptions::new(dir.join("narrow")).quiet(true))
        .unwrap_err()
        .to_string();
    assert!(e.contains("periodic box length"), "{e}");
}

/// The built-in bed scene (the settled bed of `bench bed`, periodic over 22 × 22), shortened to
/// 100 steps: every sphere stays in the box and above the floor, the bed keeps its contact
/// network (5.09 contacts per sphere in the benchmark), and pairs across the periodic
/// boundary are found (a bed without them loses the contacts of its 4 × 22 boundary columns).
#[test]
fn bed_scene_holds_its_spheres_in_the_periodic_box() {
    let dir = common::temp_dir("bed_scene");
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/bed.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("duration_s = 1.2", "duration_s = 0.01")
        .replace("output_interval_s = 0.2", "output_interval_s = 0.01");
    let run = |name: &str, text: &str| {
        let scene = parse_scene(&path, text).unwrap_or_else(|p| panic!("{p}"));
        run_scene(
            &scene,
            &RunOptions::new(dir.join(name)).quiet(true).no_frames(true),
        )
        .unwrap()
    };
    let summary = run("bed", &text);
    assert_eq!(summary.particles.len(), 10_000);
    for p in &summary.particles {
        let [x, y, z] = p.translation;
        assert!(
            (0.0..22.0).contains(&x) && (0.0..22.0).contains(&y),
            "{p:?}"
        );
        assert!(z > 0.4, "{p:?}");
    }
    let last = summary.energy.last().unwrap();
    // Sphere pairs plus the floor contacts of the bottom layer (about 400).
    let per_sphere = 2.0 * (last.contacts as f64 - 400.0) / 10_000.0;
    assert!(
        (per_sphere - 5.09).abs() < 0.25,
        "{} contacts: {per_sphere} per sphere",
        last.contacts
    );
    // The same bed in open space lacks the pairs across the sides.
    let open = run(
        "open",
        &text
            .replace("periodic_x_m = [0.0, 22.0]", "")
            .replace("periodic_y_m = [0.0, 22.0]", ""),
    );
    let open_contacts = open.energy.last().unwrap().contacts;
    assert!(
        (open_contacts as f64) < last.contacts as f64 - 1000.0,
        "open {open_contacts} vs periodic {}",
        last.contacts
    );
}
