//! Checkpoint and restart: a run stopped at a checkpoint and resumed gives bit-identical particle
//! states to the uninterrupted run; damaged or foreign checkpoints are refused whole.

mod common;

use mdr_sim::checkpoint::CheckpointError;
use mdr_sim::{run_scene, scene::validate::parse_scene, RunOptions, SimError};

fn scene_text() -> String {
    // Friction and rolling resistance on, so every kind of per-contact history is exercised.
    common::column(3, 3, 0.03, 0.5, "")
        .replace("friction = 0.5", "friction = 0.5\nrolling_friction = 0.05")
}

fn bits(r: &mdr_sim::run::BodyRecord) -> Vec<u64> {
    r.translation
        .iter()
        .chain(&r.rotation)
        .chain(&r.linvel)
        .chain(&r.angvel)
        .map(|v| v.to_bits())
        .collect()
}

#[test]
fn resumed_run_is_bit_identical_to_the_uninterrupted_run() {
    resume_matches(&scene_text(), "resume", true);
}

/// The same on rapier's force path.
#[test]
fn resumed_run_on_the_rapier_path_is_bit_identical_to_the_uninterrupted_run() {
    let text = scene_text().replacen("[run]\n", "[run]\nforce_path = \"rapier\"\n", 1);
    resume_matches(&text, "resume-rapier", true);
}

/// Without rolling resistance the neighbour-list path keeps no rolling history per contact (the
/// checkpoint writes the default one): the restart is bit-identical all the same.
#[test]
fn resumed_run_without_rolling_resistance_is_bit_identical() {
    let text = common::column(3, 3, 0.03, 0.5, "");
    assert!(!text.contains("rolling_friction"));
    resume_matches(&text, "resume-no-rolling", true);
}

/// The Hertz and Thornton laws, each with its own history on the neighbour-list path (Thornton's
/// the longest: the largest overlap, the unloading curve and the residual overlap), written to
/// a checkpoint and read back: bit-identical restarts, with rolling resistance and without.
#[test]
fn resumed_hertz_and_thornton_runs_are_bit_identical() {
    let mdr = "normal = \"mdr\"\ncritical_line_load_n_per_m = 100.0\nhardening_ratio = 0.37";
    for (tag, normal) in [
        ("hertz", "normal = \"hertz\""),
        (
            "thornton",
            "normal = \"thornton\"\nyield_pressure_pa = 5.0e5",
        ),
    ] {
        let sliding = common::column(3, 3, 0.03, 0.5, "");
        assert!(sliding.contains(mdr));
        let sliding = sliding.replace(mdr, normal);
        let rolling = sliding.replace("friction = 0.5", "friction = 0.5\nrolling_friction = 0.05");
        resume_matches(&sliding, &format!("resume-{tag}"), true);
        resume_matches(&rolling, &format!("resume-{tag}-rolling"), true);
    }
}

/// A rotating drum (kinematic mesh container, moving-wall books) on the neighbour-list path,
/// with frames and the contact network written (steps that store every pair's wrench) and
/// periodic checkpoints: stopped between two neighbour-list builds and resumed, bit for bit.
#[test]
fn resumed_drum_on_the_neighbour_list_path_is_bit_identical() {
    let text = common::drum(48, 0.06, "").replace(
        "headline = \"drum\"",
        "headline = \"drum\"\ncontact_network = true\ncheckpoint_interval_s = 0.013",
    );
    resume_matches(&text, "resume-drum", false);
}

fn resume_matches(text: &str, tag: &str, no_frames: bool) {
    let dir = common::temp_dir(tag);
    let text = text.to_owned();
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    let total = scene.total_steps();
    let whole = run_scene(
        &scene,
        &RunOptions::new(dir.join("a"))
            .quiet(true)
            .no_frames(no_frames),
    )
    .expect("uninterrupted run");
    assert_eq!(whole.step, total);

    let stop = total / 2 + 7;
    let first = run_scene(
        &scene,
        &RunOptions::new(dir.join("b"))
            .quiet(true)
            .no_frames(no_frames)
            .stop_at_step(Some(stop)),
    )
    .expect("first half");
    assert!(first.stopped_early);
    assert_eq!(first.step, stop);
    let checkpoint = first.checkpoint.expect("a checkpoint at the stop");
    let resumed = run_scene(
        &scene,
        &RunOptions::new(dir.join("b"))
            .quiet(true)
            .no_frames(no_frames)
            .resume(Some(checkpoint)),
    )
    .expect("second half");
    assert_eq!(resumed.step, total);
    assert_eq!(resumed.particles.len(), whole.particles.len());
    for (i, (a, b)) in whole.particles.iter().zip(&resumed.particles).enumerate() {
        assert_eq!(bits(a), bits(b), "particle {i} differs after the restart");
    }
    // The books continue as well.
    assert_eq!(whole.energy.len(), resumed.energy.len());
    for (a, b) in whole.energy.iter().zip(&resumed.energy) {
        assert_eq!(a.balance_j.to_bits(), b.balance_j.to_bits());
        assert_eq!(a.plastic_j.to_bits(), b.plastic_j.to_bits());
        assert_eq!(a.wall_work_j.to_bits(), b.wall_work_j.to_bits());
        assert_eq!(a.contacts, b.contacts);
    }
    // Contacts happened, so histories mattered.
    assert!(whole.energy.iter().any(|r| r.contacts > 0));
}

/// Restitution mode: rapier resolves the contacts with impulses, and its solver starts from the
/// previous step's impulses (warm start) and its broad phase from the previous tree, so the
/// checkpoint holds rapier's whole world. A 27-sphere column collapsing with friction (resting
/// contacts, so warm starts matter) is stopped half-way, resumed, and compared with the
/// uninterrupted run bit for bit. (Restoring only the bodies and the impact history, as the
/// first checkpoint format did, fails this test: the solver's warm start differs.)
#[test]
fn resumed_restitution_run_is_bit_identical_to_the_uninterrupted_run() {
    let dir = common::temp_dir("resume-restitution");
    let text = common::column(3, 3, 0.06, 0.5, "").replace(
        "dt_s = \"auto\"",
        "dt_s = 2.0e-4\ncoupling = \"restitution\"",
    );
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    let total = scene.total_steps();
    let quiet = |d: &str| RunOptions::new(dir.join(d)).quiet(true).no_frames(true);
    let whole = run_scene(&scene, &quiet("a")).expect("uninterrupted run");
    assert_eq!(whole.step, total);
    let stop = total / 2 + 3;
    let first = run_scene(&scene, &quiet("b").stop_at_step(Some(stop))).expect("first half");
    assert_eq!(first.step, stop);
    let checkpoint = first.checkpoint.expect("a checkpoint at the stop");
    let resumed =
        run_scene(&scene, &quiet("b").resume(Some(checkpoint.clone()))).expect("second half");
    assert_eq!(resumed.step, total);
    for (i, (a, b)) in whole.particles.iter().zip(&resumed.particles).enumerate() {
        assert_eq!(bits(a), bits(b), "particle {i} differs after the restart");
    }
    for (a, b) in whole.energy.iter().zip(&resumed.energy) {
        assert_eq!(a.balance_j.to_bits(), b.balance_j.to_bits());
    }
    // The particles moved in the second half (the comparison is not of a frozen state).
    let moved = first
        .particles
        .iter()
        .zip(&whole.particles)
        .filter(|(a, b)| a.translation != b.translation)
        .count();
    assert!(moved > 0, "nothing moved after the stop");
}

#[test]
fn damaged_and_foreign_checkpoints_are_refused() {
    let dir = common::temp_dir("refuse");
    let text = scene_text().replace("duration_s = 0.03", "duration_s = 0.002");
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    let run = run_scene(
        &scene,
        &RunOptions::new(dir.join("a")).quiet(true).no_frames(true),
    )
    .expect("run");
    let good = run.checkpoint.expect("final checkpoint");
    let bytes = std::fs::read(&good).unwrap();
    let resume = |p: &std::path::Path| {
        run_scene(
            &scene,
            &RunOptions::new(dir.join("r"))
                .quiet(true)
                .no_frames(true)
                .resume(Some(p.into())),
        )
    };

    let mut flipped = bytes.clone();
    let mid = flipped.len() / 2;
    flipped[mid] ^= 1;
    let p = common::write(&dir, "flipped.mdrck", "");
    std::fs::write(&p, &flipped).unwrap();
    let e = resume(&p).unwrap_err();
    assert!(
        matches!(e, SimError::Checkpoint(CheckpointError::Checksum { .. })),
        "{e}"
    );
    assert!(e.to_string().contains("corrupted"));

    std::fs::write(&p, &bytes[..bytes.len() - 5]).unwrap();
    let e = resume(&p).unwrap_err();
    assert!(
        matches!(e, SimError::Checkpoint(CheckpointError::Length { .. })),
        "{e}"
    );

    // Checkpoints of the earlier formats (1: before the rolling books and rapier's world; 2:
    // before the springs' stiffness books; 3: before the neighbour-list state; 4: before the
    // pairs' largest overlaps in the books; 5: before the stiffness energy in each contact's
    // work books; 6: before the scene's fixed keys) are refused with the readable versions
    // named. (7, before the adhesive MDR history and the adhesive work books, is read:
    // sim_checkpoint_format7.rs.)
    for old in [1u8, 2, 3, 4, 5, 6] {
        let mut version = bytes.clone();
        version[8] = old;
        std::fs::write(&p, &version).unwrap();
        let e = resume(&p).unwrap_err();
        assert!(
            matches!(
                e,
                SimError::Checkpoint(CheckpointError::Version { found, expected: 8, oldest: 7, .. })
                    if found == u32::from(old)
            ),
            "{e}"
        );
        assert!(
            e.to_string().contains(&format!("format version {old}")),
            "{e}"
        );
    }

    // A checkpoint of another scene (other seed, so other placement): refused.
    let other_text = text.replace("seed = 5", "seed = 6");
    let other_path = common::write(&dir, "other.toml", &other_text);
    let other = parse_scene(&other_path, &other_text).unwrap();
    let e = run_scene(
        &other,
        &RunOptions::new(dir.join("o"))
            .quiet(true)
            .no_frames(true)
            .resume(Some(good.clone())),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            SimError::Checkpoint(CheckpointError::Incompatible { .. })
        ),
        "{e}"
    );
    // The refusal names what changed.
    assert!(e.to_string().contains("`run.seed` 5 → 6"), "{e}");

    // A longer duration is a legitimate restart.
    let longer_text = text.replace("duration_s = 0.002", "duration_s = 0.003");
    let longer_path = common::write(&dir, "longer.toml", &longer_text);
    let longer = parse_scene(&longer_path, &longer_text).unwrap();
    let cont = run_scene(
        &longer,
        &RunOptions::new(dir.join("l"))
            .quiet(true)
            .no_frames(true)
            .resume(Some(good)),
    )
    .expect("extending a run");
    assert_eq!(cont.step, longer.total_steps());
}

/// Ctrl-C: the CLI's handler sets the run's interrupt flag. Set it from another thread while the
/// run is under way (after its second frame exists): the run stops at the end of a step with a
/// final checkpoint and returns normally, leaving no temporary file and a readable last frame; a
/// restart from that checkpoint, extended by 200 steps, ends bit-identical to an uninterrupted
/// run of the same length.
#[test]
fn an_interrupted_run_writes_a_final_checkpoint_and_resumes_bit_identically() {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;

    let dir = common::temp_dir("interrupt");
    // Long enough that the interrupt always comes first (10 s of simulated time).
    let text = common::column(3, 3, 10.0, 0.5, "");
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    let out = dir.join("i");
    let flag = Arc::new(AtomicBool::new(false));
    let watcher = {
        let flag = Arc::clone(&flag);
        let second = out.join("frames").join("column_000001.vtp");
        std::thread::spawn(move || {
            while !second.exists() {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
            flag.store(true, Ordering::SeqCst);
        })
    };
    let stopped = run_scene(
        &scene,
        &RunOptions::new(&out)
            .quiet(true)
            .interrupt(Arc::clone(&flag)),
    )
    .expect("an interrupted run returns normally");
    watcher.join().unwrap();
    assert!(stopped.stopped_early);
    assert!(stopped.step > 0 && stopped.step < scene.total_steps());
    let checkpoint = stopped.checkpoint.expect("a final checkpoint");
    assert!(checkpoint
        .file_name()
        .unwrap()
        .to_string_lossy()
        .contains(&format!("step{:012}", stopped.step)));
    // Outputs are whole: no temporary files, the collection's last frame reads back.
    for sub in [out.clone(), out.join("frames"), out.join("checkpoints")] {
        for e in std::fs::read_dir(&sub).unwrap() {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            assert!(!name.contains(".tmp"), "{name} left in {}", sub.display());
        }
    }
    let pvd = std::fs::read_to_string(out.join("column.pvd")).unwrap();
    let last = pvd
        .lines()
        .filter_map(|l| l.split("file=\"").nth(1))
        .filter_map(|f| f.split('"').next())
        .rfind(|f| !f.contains("contacts"))
        .expect("frames listed")
        .to_owned();
    let frame = mdr_sim::output::vtk::read_particles(&out.join(last)).expect("whole frame");
    assert_eq!(frame.position.len(), scene.particles.len());

    // Extend to 200 steps past the stop: resumed vs uninterrupted.
    let end = (stopped.step as f64 + 199.5) * scene.dt;
    let short_text = text.replace("duration_s = 10", &format!("duration_s = {end:e}"));
    let short_path = common::write(&dir, "short.toml", &short_text);
    let short = parse_scene(&short_path, &short_text).unwrap();
    assert_eq!(short.total_steps(), stopped.step + 200);
    let quiet = |d: &str| RunOptions::new(dir.join(d)).quiet(true).no_frames(true);
    let resumed = run_scene(&short, &quiet("i").resume(Some(checkpoint))).expect("resume");
    let whole = run_scene(&short, &quiet("w")).expect("uninterrupted");
    assert_eq!(resumed.step, whole.step);
    for (i, (a, b)) in whole.particles.iter().zip(&resumed.particles).enumerate() {
        assert_eq!(bits(a), bits(b), "particle {i} differs after the restart");
    }
}
