//! Checkpoints of the previous format version (7: before the adhesive MDR history and the
//! adhesive work books), written by the release that wrote that format (`tests/data/*_v7.mdrck`,
//! next to their scenes): each resumes, and the resumed run ends with every particle bit for bit
//! and every output file byte for byte as the uninterrupted run of this program.

mod common;

use mdr_sim::checkpoint::{self, CheckpointError};
use mdr_sim::run::{BodyRecord, CheckpointData};
use mdr_sim::{run_scene, scene::validate::parse_scene, RunOptions, SimError};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn bits(r: &BodyRecord) -> Vec<u64> {
    r.translation
        .iter()
        .chain(&r.rotation)
        .chain(&r.linvel)
        .chain(&r.angvel)
        .map(|v| v.to_bits())
        .collect()
}

/// Resume `scene`'s format-7 checkpoint and compare with the uninterrupted run.
fn resumes_as_the_uninterrupted_run(scene: &str, fixture: &str) {
    let path = data(scene);
    let text = std::fs::read_to_string(&path).unwrap();
    let scene = parse_scene(&path, &text).expect("valid scene");
    let dir = common::temp_dir(fixture);
    let fixture = data(fixture);
    let head = std::fs::read(&fixture).unwrap();
    assert_eq!(&head[8..12], &7u32.to_le_bytes(), "not a format-7 file");

    let out = |d: &str| RunOptions::new(dir.join(d)).quiet(true);
    let whole = run_scene(&scene, &out("a")).expect("uninterrupted run");
    let resumed = run_scene(&scene, &out("b").resume(Some(fixture))).expect("resumed run");
    assert!(resumed.start_step > 0 && resumed.start_step < whole.step);
    assert_eq!(resumed.step, whole.step);
    assert_eq!(resumed.particles.len(), whole.particles.len());
    for (i, (a, b)) in whole.particles.iter().zip(&resumed.particles).enumerate() {
        assert_eq!(bits(a), bits(b), "particle {i} differs after the restart");
    }
    assert_eq!(whole.headline.text, resumed.headline.text);
    // Every file the resumed run wrote (energy and headline tables and plots, the frames after
    // the checkpoint, the frame collection, its own checkpoints) is the uninterrupted run's.
    assert!(!resumed.files.is_empty());
    for file in &resumed.files {
        let name = file
            .strip_prefix(dir.join("b"))
            .expect("in the output folder");
        let mine = std::fs::read(file).unwrap();
        let theirs = std::fs::read(dir.join("a").join(name)).unwrap();
        assert!(mine == theirs, "{} differs", name.display());
    }
}

/// The drop scene stopped during the impact (rapier's force path would hold the pair in
/// `contacts`, the neighbour-list path in its histories: the one the scene runs on holds it).
#[test]
fn a_drop_stopped_during_the_impact_resumes_bit_identically() {
    let data = CheckpointData::read(&data("drop_v7.mdrck")).expect("format 7 reads");
    let touching = data.contacts.len()
        + data
            .neighbour_list
            .as_ref()
            .map_or(0, |n| n.pair_histories.len() + n.surface_histories.len());
    assert_eq!(touching, 1, "the checkpoint holds the impact");
    resumes_as_the_uninterrupted_run("drop_v7.toml", "drop_v7.mdrck");
}

/// A collapsing column with friction and rolling resistance on the neighbour-list path.
#[test]
fn a_column_on_the_neighbour_list_path_resumes_bit_identically() {
    let data = CheckpointData::read(&data("column_neighbour_list_v7.mdrck")).unwrap();
    let lists = data.neighbour_list.as_ref().expect("neighbour-list state");
    assert!(!lists.pair_histories.is_empty() && !lists.surface_histories.is_empty());
    resumes_as_the_uninterrupted_run(
        "column_neighbour_list.toml",
        "column_neighbour_list_v7.mdrck",
    );
}

/// The same column on rapier's force path (pair histories and each pair's books).
#[test]
fn a_column_on_the_rapier_path_resumes_bit_identically() {
    let data = CheckpointData::read(&data("column_rapier_v7.mdrck")).unwrap();
    assert!(!data.contacts.is_empty() && !data.books.last.is_empty());
    resumes_as_the_uninterrupted_run("column_rapier.toml", "column_rapier_v7.mdrck");
}

/// The format-7 payload is not the present one: decoded with the present types it is refused
/// (the reader of the previous format is what reads it), and the strict reader of the present
/// format refuses the file by its version, naming both.
#[test]
fn the_previous_payload_needs_its_own_reader() {
    let path = data("column_rapier_v7.mdrck");
    let bytes = std::fs::read(&path).unwrap();
    let (version, body) = checkpoint::check(&path, &bytes).unwrap();
    assert_eq!(version, checkpoint::PREVIOUS_FORMAT_VERSION);
    assert!(matches!(
        checkpoint::decode_payload::<CheckpointData>(&path, body),
        Err(CheckpointError::Decode { .. })
    ));
    let e = checkpoint::read::<CheckpointData>(&path).unwrap_err();
    assert!(
        matches!(e, CheckpointError::Version { found: 7, .. }),
        "{e}"
    );
}

/// Versions older than the previous one, and newer than this program's, are refused with both
/// ends of the readable range named.
#[test]
fn other_versions_are_refused() {
    let path = data("column_rapier.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let scene = parse_scene(&path, &text).unwrap();
    let dir = common::temp_dir("v7-refused");
    let bytes = std::fs::read(data("column_rapier_v7.mdrck")).unwrap();
    for version in [1u32, 5, 6, 9] {
        let mut other = bytes.clone();
        other[8..12].copy_from_slice(&version.to_le_bytes());
        let p = common::write(&dir, "other.mdrck", "");
        std::fs::write(&p, &other).unwrap();
        let e = run_scene(
            &scene,
            &RunOptions::new(dir.join("r"))
                .quiet(true)
                .no_frames(true)
                .resume(Some(p)),
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                SimError::Checkpoint(CheckpointError::Version {
                    found,
                    expected: 8,
                    oldest: 7,
                    ..
                }) if found == version
            ),
            "{e}"
        );
        assert!(
            e.to_string().contains(&format!(
                "format version {version}; this program reads versions 7 to 8"
            )),
            "{e}"
        );
    }
}
