//! What a run does when it goes wrong: mesh walls whatever their winding (an open mesh is
//! two-sided, a closed one must be wound consistently), a sphere driven through a wall, the
//! energy guard, a state that stops being finite, a resumed run's output folder.

mod common;

use common::{column, temp_dir, write};
use mdr_sim::{load_scene, run_scene, RunOptions, SimError};

const PLANE: &str = r#"[[walls]]
kind = "plane"
material = "grain"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#;

/// A flat square floor at z = 0 (two triangles) in ASCII STL, every facet normal +z, wound
/// counter-clockwise seen from above, or clockwise.
fn floor_stl(clockwise: bool) -> String {
    let h = 0.05;
    let mut tris = [[[-h, -h], [h, -h], [h, h]], [[-h, -h], [h, h], [-h, h]]];
    if clockwise {
        for t in &mut tris {
            t.swap(1, 2);
        }
    }
    let mut s = String::from("solid floor\n");
    for t in tris {
        s.push_str("  facet normal 0 0 1\n    outer loop\n");
        for [x, y] in t {
            s.push_str(&format!("      vertex {x} {y} 0\n"));
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid floor\n");
    s
}

/// The small column of the scene tests, standing on `walls` instead of its plane.
fn column_on(walls: &str, duration: f64, extra_run: &str) -> String {
    let text = column(2, 2, duration, 0.5, extra_run);
    assert!(text.contains(PLANE));
    text.replace(PLANE, walls)
}

const MESH_FLOOR: &str = r#"[[walls]]
kind = "mesh"
material = "grain"
file = "floor.stl"
"#;

/// The floor wound clockwise seen from the spheres (its facet normals +z): an open mesh is
/// two-sided, so the spheres land on it and stay above it, as on the counter-clockwise floor;
/// the facet normals that disagree with the winding are reported.
#[test]
fn spheres_stay_above_a_floor_mesh_wound_either_way() {
    for clockwise in [false, true] {
        let dir = temp_dir(&format!("mesh_floor_{clockwise}"));
        write(&dir, "floor.stl", &floor_stl(clockwise));
        let path = write(&dir, "scene.toml", &column_on(MESH_FLOOR, 0.04, ""));
        let scene = load_scene(&path).unwrap();
        let notes: Vec<String> = scene.warnings.iter().map(|w| w.to_string()).collect();
        assert_eq!(
            notes.iter().any(|w| w.contains("facet normals")),
            clockwise,
            "{notes:?}"
        );
        let summary = run_scene(&scene, &RunOptions::new(dir.join("out")).quiet(true))
            .unwrap_or_else(|e| panic!("clockwise {clockwise}: {e}"));
        for (i, p) in summary.particles.iter().enumerate() {
            let r = scene.particles[i].radius;
            assert!(
                p.translation[2] > 0.9 * r,
                "clockwise {clockwise}: sphere {i} at z = {} (r = {r})",
                p.translation[2]
            );
        }
    }
}

/// A closed mesh (a tetrahedron) with one triangle turned round has no consistent outside: it
/// is refused with the triangle named, at the wall's `file` key.
#[test]
fn a_closed_mesh_wound_inconsistently_is_refused_naming_the_triangle() {
    let dir = temp_dir("mesh_closed");
    let corners = [
        [0.0, 0.0, -0.05],
        [0.05, 0.0, -0.1],
        [0.0, 0.05, -0.1],
        [0.0, 0.0, -0.1],
    ];
    // Outward winding of the four faces; the third turned round.
    let faces = [[0, 1, 2], [0, 3, 1], [0, 3, 2], [1, 3, 2]];
    let mut stl = String::from("solid tet\n");
    for f in faces {
        stl.push_str("  facet normal 0 0 0\n    outer loop\n");
        for c in f {
            let [x, y, z] = corners[c];
            stl.push_str(&format!("      vertex {x} {y} {z}\n"));
        }
        stl.push_str("    endloop\n  endfacet\n");
    }
    stl.push_str("endsolid tet\n");
    write(&dir, "tet.stl", &stl);
    let walls = format!("{PLANE}\n{}", MESH_FLOOR.replace("floor.stl", "tet.stl"));
    let path = write(&dir, "scene.toml", &column_on(&walls, 0.01, ""));
    let problems = load_scene(&path).unwrap_err();
    let text = problems.to_string();
    assert!(text.contains("walls[1].file"), "{text}");
    assert!(text.contains("triangle 3 "), "{text}");
}

/// A sphere thrown at the floor at 100 m/s sinks deeper than the contact can hold: the run
/// stops with the sphere and the wall named and a checkpoint of the state.
#[test]
fn a_sphere_going_through_a_wall_stops_the_run_naming_it() {
    let dir = temp_dir("crossing");
    let scene = r#"
[run]
name = "shot"
duration_s = 0.001
dt_s = 4.0e-6
max_speed_m_per_s = 100.0
output_interval_s = 0.0005

[[material]]
name = "grain"
youngs_pa = 5.0e7
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 100.0
hardening_ratio = 0.37

[[particles]]
material = "grain"
placement = "csv"
file = "shot.csv"
velocity_m_per_s = [0.0, 0.0, -100.0]

[[walls]]
kind = "plane"
material = "grain"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#;
    write(&dir, "shot.csv", "x_m,y_m,z_m,radius_m\n0,0,0.0025,0.002\n");
    let path = write(&dir, "shot.toml", scene);
    let scene = load_scene(&path).unwrap();
    let e = run_scene(&scene, &RunOptions::new(dir.join("out")).quiet(true)).unwrap_err();
    let SimError::Stopped {
        reason, checkpoint, ..
    } = &e
    else {
        panic!("{e}");
    };
    assert!(
        reason.contains("sphere 0 ") && reason.contains("wall 0 "),
        "{e}"
    );
    assert!(checkpoint.exists(), "{e}");
    assert!(e.is_guard());
}

/// The energy guard: the same column stops once its books drift beyond `max_energy_drift`
/// (here below its round-off drift), with a checkpoint and the books written; with the default
/// threshold it runs to the end. The checkpoint resumes with a larger threshold (the key may
/// change on a restart).
#[test]
fn the_energy_guard_stops_a_drifting_run_with_a_checkpoint() {
    let dir = temp_dir("drift");
    let tight = write(
        &dir,
        "tight.toml",
        &column(2, 2, 0.02, 0.5, "max_energy_drift = 1e-15"),
    );
    let scene = load_scene(&tight).unwrap();
    let out = dir.join("out");
    let e = run_scene(&scene, &RunOptions::new(&out).quiet(true)).unwrap_err();
    let SimError::Stopped {
        reason,
        checkpoint,
        step,
        ..
    } = &e
    else {
        panic!("{e}");
    };
    assert!(reason.contains("max_energy_drift"), "{reason}");
    assert!(checkpoint.exists());
    assert!(*step < scene.total_steps(), "{e}");
    assert!(out.join("column_energy.csv").exists());
    let relaxed = write(&dir, "relaxed.toml", &column(2, 2, 0.02, 0.5, ""));
    let scene = load_scene(&relaxed).unwrap();
    assert_eq!(
        scene.max_energy_drift,
        Some(mdr_sim::scene::validate::DEFAULT_MAX_ENERGY_DRIFT)
    );
    let resumed = run_scene(
        &scene,
        &RunOptions::new(&out)
            .quiet(true)
            .resume(Some(checkpoint.clone())),
    )
    .unwrap();
    assert_eq!(resumed.step, scene.total_steps());
    assert!(resumed.start_step > 0);
    let fresh = run_scene(&scene, &RunOptions::new(dir.join("fresh")).quiet(true)).unwrap();
    assert_eq!(fresh.start_step, 0);
    let drift = mdr_sim::output::energy::BalanceDrift::of(&fresh.energy).unwrap();
    assert!(drift.fraction.abs() < 1e-3, "{drift:?}");
}

/// A resumed run continues its own collection: frames written after the checkpoint by an
/// earlier continuation are removed, and the collection and the frames agree.
#[test]
fn a_resumed_run_leaves_no_stale_frames() {
    let dir = temp_dir("stale");
    let path = write(
        &dir,
        "scene.toml",
        &column(2, 2, 0.02, 0.5, "checkpoint_interval_s = 0.005"),
    );
    let scene = load_scene(&path).unwrap();
    let out = dir.join("out");
    let full = run_scene(&scene, &RunOptions::new(&out).quiet(true)).unwrap();
    let frames = |out: &std::path::Path| std::fs::read_dir(out.join("frames")).unwrap().count();
    let all = frames(&out);
    // Resume from the oldest checkpoint kept, stopping at three quarters (at once or later).
    let first = std::fs::read_dir(out.join("checkpoints"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .min()
        .unwrap();
    let stop = full.step * 3 / 4;
    let summary = run_scene(
        &scene,
        &RunOptions::new(&out)
            .quiet(true)
            .resume(Some(first))
            .stop_at_step(Some(stop)),
    )
    .unwrap();
    assert!(summary.stopped_early);
    let pvd = std::fs::read_to_string(out.join("column.pvd")).unwrap();
    let entries = pvd.matches("<DataSet").count();
    assert!(entries < all, "{entries} of {all}");
    assert_eq!(frames(&out), entries, "{pvd}");
}

/// Eight spheres over an orifice of 1.5 particle diameters: the check warns at the orifice's
/// key, and the hopper headline says "jammed" with no NaN in its text or values.
#[test]
fn an_orifice_below_four_diameters_is_warned_and_reported_jammed() {
    let dir = temp_dir("jam");
    let text = column_on(
        r#"[[walls]]
kind = "orifice_plate"
material = "grain"
center_m = [0.0, 0.0, 0.0]
outer_radius_m = 0.02
orifice_diameter_m = 0.006
thickness_m = 0.002
"#,
        0.01,
        "",
    )
    .replace("headline = \"column\"", "headline = \"hopper\"");
    let path = write(&dir, "jam.toml", &text);
    let scene = load_scene(&path).unwrap();
    let warning = scene
        .warnings
        .iter()
        .find(|w| w.key == "walls[0].orifice_diameter_m")
        .unwrap_or_else(|| panic!("{:?}", scene.warnings));
    assert!(
        warning.message.contains("1.50 mean particle diameters"),
        "{warning}"
    );
    let summary = run_scene(&scene, &RunOptions::new(dir.join("out")).quiet(true)).unwrap();
    let headline = &summary.headline;
    assert!(headline.text.contains("jammed"), "{}", headline.text);
    assert!(!headline.text.contains("NaN"), "{}", headline.text);
    assert!(
        headline.values.iter().all(|v| v.value.is_finite()),
        "{:?}",
        headline.values
    );
    assert_eq!(headline.get("jammed"), Some(1.0));
}

/// Radii in millimetres written into `radius_m`: a warning at the key, and the lattice's
/// refusal says the spheres do not fit the region at all.
#[test]
fn radii_that_look_like_millimetres_are_pointed_at() {
    let text = column(2, 2, 0.01, 0.5, "").replace("radius_m = 0.002", "radius_m = 2.0");
    let problems =
        mdr_sim::scene::validate::parse_scene(std::path::Path::new("mm.toml"), &text).unwrap_err();
    let hint = problems
        .0
        .iter()
        .find(|p| p.key == "particles[0].radius_m")
        .unwrap_or_else(|| panic!("{problems}"));
    assert!(hint.message.contains("millimetres"), "{hint}");
    assert!(
        problems
            .to_string()
            .contains("does not fit the region at all"),
        "{problems}"
    );
}

/// A misspelt key gets the nearest allowed one; an empty file and a duplicate key or table say
/// so with the key named.
#[test]
fn misspelt_duplicate_and_missing_keys_are_named() {
    let parse = |text: &str| {
        mdr_sim::scene::validate::parse_scene(std::path::Path::new("s.toml"), text)
            .unwrap_err()
            .to_string()
    };
    let good = column(2, 2, 0.01, 0.5, "");
    let typo = parse(&good.replace("seed = 5", "sed = 5"));
    assert!(typo.contains("did you mean `seed`?"), "{typo}");
    let far = parse(&good.replace("seed = 5", "colour = 5"));
    assert!(!far.contains("did you mean"), "{far}");
    let empty = parse("\n  \n");
    assert!(
        empty.contains("s.toml") && empty.contains("empty"),
        "{empty}"
    );
    let twice = parse(&good.replace("seed = 5", "seed = 5\nseed = 6"));
    assert!(twice.contains("`seed` is given a second time"), "{twice}");
    let table = parse(&good.replace("[contact]", "[contact]\nfriction = 0.1\n[contact]"));
    assert!(
        table.contains("[contact] is defined a second time"),
        "{table}"
    );
}

/// One sphere in free fall under a gravity of 10³⁰⁷ m/s², 1 ms steps, a frame every 500 steps.
const NON_FINITE_SCENE: &str = include_str!("data/blowup.toml");

/// One sphere falling freely under a gravity of 10³⁰⁷ m/s² (finite, so the scene is accepted;
/// no contact, so no stability check applies). Symplectic Euler puts it at
/// `z_k = z_0 − g dt² k(k+1)/2`, past the largest double at step 5996, while its speed `g k dt`
/// stays finite until step 17 977: the first non-finite state is a position alone. The check at
/// the frame samples stops the run at step 6000 with the particle and `dt_s` named, and what the
/// samples before it wrote stays: the 12 frames of steps 0 to 5500, the collection listing
/// them, and the energy rows up to the last of them.
#[test]
fn a_non_finite_state_stops_the_run_naming_the_particle_and_dt() {
    let dir = temp_dir("non_finite");
    write(&dir, "one.csv", "x_m,y_m,z_m,radius_m\n0,0,0.0025,0.002\n");
    let path = write(&dir, "blowup.toml", NON_FINITE_SCENE);
    let scene = load_scene(&path).unwrap();
    let (g, dt) = (1.0e307, scene.dt);
    assert_eq!(scene.gravity.z, -g);
    let position_overflow = (1..u64::MAX)
        .find(|&k| (k * (k + 1) / 2) as f64 > f64::MAX / (g * dt * dt))
        .unwrap();
    assert_eq!(position_overflow, 5996);
    assert!(f64::MAX / (g * dt) > 17_000.0);
    let out = dir.join("out");
    let e = run_scene(&scene, &RunOptions::new(&out).quiet(true)).unwrap_err();
    let SimError::Diverged { time, step, reason } = &e else {
        panic!("{e}");
    };
    assert_eq!(*step, 6000, "{e}");
    assert!((time - 6.0).abs() < 1e-9, "{e}");
    assert!(
        reason.contains("particle 0 has a non-finite position or velocity")
            && reason.contains("dt_s"),
        "{e}"
    );
    assert!(e.to_string().contains("step 6000"), "{e}");
    assert!(e.is_guard());
    // The frames of the finite samples, and the collection that lists them.
    let mut names: Vec<String> = std::fs::read_dir(out.join("frames"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let expected: Vec<String> = (0..12).map(|i| format!("blowup_{i:06}.vtp")).collect();
    assert_eq!(names, expected);
    let pvd = std::fs::read_to_string(out.join("blowup.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 12, "{pvd}");
    // The energy rows every 100 steps up to the stop, those after the last finite frame sample
    // (step 5500) included: a row at t = 0 s with every value finite (the sphere at rest), the
    // last at t = 6 s with the height gone to -inf; no checkpoint of the broken state.
    let csv = std::fs::read_to_string(out.join("blowup_energy.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 61, "{csv}");
    assert!(rows[0].iter().all(|v| v.is_finite()), "{csv}");
    assert_eq!(rows[0][0], 0.0);
    assert!((rows[60][0] - 6.0).abs() < 1e-9, "{csv}");
    assert!(rows[60].iter().any(|v| !v.is_finite()), "{csv}");
    assert!(
        !out.join("checkpoints").exists()
            || std::fs::read_dir(out.join("checkpoints"))
                .unwrap()
                .next()
                .is_none()
    );
}
