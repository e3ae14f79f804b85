//! Outputs of a real run: a VTK frame read back (positions equal the final particle states), the
//! ParaView collection lists every frame, the energy CSV reads back, plots exist.

mod common;

use mdr_sim::output::{energy, vtk};
use mdr_sim::{run_scene, scene::validate::parse_scene, RunOptions};

#[test]
fn frames_collection_csv_and_plots_are_written_and_read_back() {
    let dir = common::temp_dir("outputs");
    let text = common::column(2, 2, 0.01, 0.3, "contact_network = true");
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    let out = dir.join("out");
    let summary = run_scene(&scene, &RunOptions::new(&out).quiet(true)).expect("run");

    // 0.01 s every 0.005 s: frames near 0, 0.005 and 0.01 s, and always one at the last step.
    let pvd = std::fs::read_to_string(out.join("column.pvd")).unwrap();
    let frames = pvd.matches("part=\"0\"").count();
    assert!((3..=4).contains(&frames), "{pvd}");
    assert_eq!(pvd.matches("part=\"1\"").count(), frames, "{pvd}");
    let last_name = format!("frames/column_{:06}.vtp", frames - 1);
    assert!(pvd.contains(&last_name), "{pvd}");
    let last = vtk::read_particles(&out.join(&last_name)).expect("read back");
    assert_eq!(last.position.len(), scene.particles.len());
    for (i, p) in summary.particles.iter().enumerate() {
        assert_eq!(last.position[i], p.translation, "particle {i}");
        assert_eq!(last.velocity[i], p.linvel, "particle {i}");
        assert_eq!(last.radius[i], scene.particles[i].radius);
        assert_eq!(last.id[i], i as u32);
    }
    assert!(
        last.contacts.iter().any(|&c| c > 0),
        "the bed touches the floor"
    );
    let rows = energy::read_csv(&out.join("column_energy.csv")).unwrap();
    assert_eq!(rows, summary.energy);
    for f in [
        "column_energy.svg",
        "column_headline.svg",
        "column_headline.toml",
    ] {
        let s = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(s.len() > 100, "{f}");
    }
    // No temporary files are left behind.
    let leftovers = std::fs::read_dir(out.join("frames"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .contains(".tmp")
        })
        .count();
    assert_eq!(leftovers, 0);
}

/// The long run: the column scene at reduced size (4 × 4 × 5 = 80 spheres instead
/// of 8 × 8 × 10, with `scenes/column.toml`'s contact model: μ = 0.5, rolling resistance
/// μ_r = 0.1) for 10⁶ steps (3.9 s of simulated time at 50 steps per contact) stays free of NaN
/// and no particle escapes what energy allows: nothing passes through the floor, no particle
/// rises above the height at which it would hold the whole initial energy `E₀`, none moves
/// further horizontally than `R₀ + v_max T` with `v_max = √(2 E₀/m)`; the energy books stay
/// within 1 % of `E₀`. Run with `cargo test --release -p mdr-sim --test sim_scene_outputs --
/// --ignored` (minutes: see docs/user-guide.md, "Reliability").
#[test]
#[ignore]
fn long_column_run_stays_finite_and_bounded() {
    let dir = common::temp_dir("long");
    let column = |duration: f64| {
        common::column(4, 5, duration, 0.5, "")
            .replace("friction = 0.5", "friction = 0.5\nrolling_friction = 0.1")
    };
    let probe_scene = parse_scene(&dir.join("p.toml"), &column(1.0)).unwrap();
    // Just under 10⁶ steps of the auto step, so that the ceiling gives exactly 10⁶.
    let duration = (1.0e6 - 0.5) * probe_scene.dt;
    let text = column(duration)
        .replace(
            "output_interval_s = 0.005",
            &format!("output_interval_s = {}", duration / 20.0),
        )
        .replace(
            "energy_interval_s = 0.0005",
            &format!("energy_interval_s = {}", duration / 2000.0),
        );
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    assert_eq!(scene.total_steps(), 1_000_000);
    let started = std::time::Instant::now();
    let summary = run_scene(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("long run (a NaN would stop it with an error)");
    let wall = started.elapsed().as_secs_f64();
    assert_eq!(summary.step, 1_000_000);
    let rows = &summary.energy;
    // At rest at the start: E₀ is the potential energy above the floor, Σ m g z.
    let e0 = rows[0].balance_j;
    assert_eq!(rows[0].kinetic(), 0.0);
    let sum_z: f64 = scene.particles.iter().map(|p| p.position[2]).sum();
    let mg = rows[0].gravitational_j / sum_z; // equal spheres
    let g = scene.gravity.norm();
    let z_max = e0 / mg;
    let v_max = (2.0 * g * z_max).sqrt();
    let r0 = scene
        .particles
        .iter()
        .map(|p| p.position[0].hypot(p.position[1]))
        .fold(0.0, f64::max);
    let reach = r0 + v_max * summary.time;
    let radius = scene.particles[0].radius;
    let (mut spread, mut lowest, mut highest) = (0.0f64, f64::INFINITY, 0.0f64);
    for (i, p) in summary.particles.iter().enumerate() {
        assert!(
            p.translation
                .iter()
                .chain(&p.linvel)
                .chain(&p.angvel)
                .chain(&p.rotation)
                .all(|v| v.is_finite()),
            "particle {i} is not finite: {p:?}"
        );
        let [x, y, z] = p.translation;
        let horizontal = x.hypot(y);
        assert!(
            z > 0.5 * radius && z < z_max && horizontal < reach,
            "particle {i} escaped: {:?} (floor contact at z = {radius}, energy allows z < {z_max:.3e}, \
             horizontal < {reach:.3e})",
            p.translation
        );
        spread = spread.max(horizontal);
        lowest = lowest.min(z);
        highest = highest.max(z);
    }
    let worst = rows
        .iter()
        .map(|r| (r.balance_j - e0).abs())
        .fold(0.0, f64::max);
    let last = rows.last().unwrap();
    eprintln!(
        "long run: {} spheres, {} steps (t = {:.3} s, dt = {:.3e} s) in {wall:.0} s wall; \
         E0 = {e0:.4e} J, worst balance drift {worst:.3e} J ({:.3} %), final kinetic {:.3e} J, \
         plastic {:.3e} J, friction {:.3e} J, rolling {:.3e} J; spread {spread:.4} m (R0 = {r0:.4} m, \
         energy bound {reach:.2} m), z in [{lowest:.4e}, {highest:.4e}] m",
        scene.particles.len(),
        summary.step,
        summary.time,
        scene.dt,
        100.0 * worst / e0,
        last.kinetic(),
        last.plastic_j,
        last.friction_j,
        last.rolling_j,
    );
    assert!(
        worst < 0.01 * e0,
        "energy drift {worst:.3e} J of {e0:.3e} J"
    );
}
