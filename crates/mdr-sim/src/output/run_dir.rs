//! What a run leaves in its output folder, by file name: which runs a folder holds, and the
//! removal of one run's files (replacing it) or of the files a resumed run replaces. Only files
//! named as a run names them are touched; anything else in the folder stays.

use std::path::Path;

/// The names of the runs whose files are in `dir` (sorted, each once): a `NAME.pvd`
/// collection, a `NAME_energy.csv` or a `checkpoints/NAME_stepNNNNNNNNNNNN.mdrck`. An absent
/// folder holds none.
pub fn runs_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = file_names(dir)
        .into_iter()
        .filter_map(|f| {
            f.strip_suffix(".pvd")
                .or_else(|| f.strip_suffix("_energy.csv"))
                .map(str::to_owned)
        })
        .chain(
            file_names(&dir.join("checkpoints"))
                .iter()
                .filter_map(|f| checkpoint_step(f).map(|(name, _)| name.to_owned())),
        )
        .filter(|n| !n.is_empty())
        .collect();
    names.sort();
    names.dedup();
    names
}

/// Remove every file of run `name` from `dir`: its collection, frames, checkpoints, energy
/// books, headline series and plots.
pub fn remove_run(dir: &Path, name: &str) -> std::io::Result<()> {
    for suffix in [
        ".pvd",
        "_energy.csv",
        "_energy.svg",
        "_headline.csv",
        "_headline.svg",
        "_headline.toml",
    ] {
        remove_if_present(&dir.join(format!("{name}{suffix}")))?;
    }
    remove_stale(dir, name, 0, 0, 0)?;
    remove_if_present(&dir.join("checkpoints").join(checkpoint_name(name, 0)))
}

/// Remove the files of run `name` that a run resumed at step `step` with `frames` particle
/// frames and `contact_frames` contact-network frames in its collection replaces: frames
/// numbered from those counts on, and checkpoints after `step`.
pub fn remove_stale(
    dir: &Path,
    name: &str,
    frames: usize,
    contact_frames: usize,
    step: u64,
) -> std::io::Result<()> {
    let frames_dir = dir.join("frames");
    for f in file_names(&frames_dir) {
        let Some(stem) = f.strip_suffix(".vtp") else {
            continue;
        };
        let stale = match frame_index(stem, &format!("{name}_contacts_")) {
            Some(i) => i >= contact_frames,
            None => frame_index(stem, &format!("{name}_")).is_some_and(|i| i >= frames),
        };
        if stale {
            remove_if_present(&frames_dir.join(&f))?;
        }
    }
    let checkpoints = dir.join("checkpoints");
    for f in file_names(&checkpoints) {
        if checkpoint_step(&f).is_some_and(|(n, s)| n == name && s > step) {
            remove_if_present(&checkpoints.join(&f))?;
        }
    }
    Ok(())
}

/// A checkpoint's file name (`NAME_stepNNNNNNNNNNNN.mdrck`).
pub fn checkpoint_name(name: &str, step: u64) -> String {
    format!("{name}_step{step:012}.mdrck")
}

/// The run name and step of a checkpoint's file name.
fn checkpoint_step(file: &str) -> Option<(&str, u64)> {
    let stem = file.strip_suffix(".mdrck")?;
    let (name, digits) = stem.rsplit_once("_step")?;
    (digits.len() == 12 && digits.bytes().all(|b| b.is_ascii_digit()))
        .then(|| digits.parse().ok().map(|s| (name, s)))
        .flatten()
}

/// The number of a frame `PREFIXNNNNNN` (exactly six digits after the prefix).
fn frame_index(stem: &str, prefix: &str) -> Option<usize> {
    let digits = stem.strip_prefix(prefix)?;
    (digits.len() == 6 && digits.bytes().all(|b| b.is_ascii_digit()))
        .then(|| digits.parse().ok())
        .flatten()
}

/// The names of the plain files in `dir` (none when it does not exist).
fn file_names(dir: &Path) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    entries
        .filter_map(Result::ok)
        .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
        .filter_map(|e| e.file_name().into_string().ok())
        .collect()
}

fn remove_if_present(path: &Path) -> std::io::Result<()> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(e),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A resumed run's stale files go, its own earlier files and other runs' files stay.
    #[test]
    fn stale_frames_and_checkpoints_of_the_run_only_are_removed() {
        let dir_guard = tempfile::tempdir().unwrap();
        let dir = dir_guard.path().to_path_buf();
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("frames")).unwrap();
        std::fs::create_dir_all(dir.join("checkpoints")).unwrap();
        let touch = |p: &str| std::fs::write(dir.join(p), b"x").unwrap();
        for i in 0..4 {
            touch(&format!("frames/silo_{i:06}.vtp"));
            touch(&format!("frames/silo_contacts_{i:06}.vtp"));
            touch(&format!("frames/other_{i:06}.vtp"));
        }
        for s in [100, 200, 300] {
            touch(&format!("checkpoints/{}", checkpoint_name("silo", s)));
        }
        touch("silo.pvd");
        touch("notes.txt");
        assert_eq!(runs_in(&dir), vec!["silo".to_owned()]);
        remove_stale(&dir, "silo", 2, 1, 200).unwrap();
        let mut left = file_names(&dir.join("frames"));
        left.sort();
        assert_eq!(
            left,
            [
                "other_000000.vtp",
                "other_000001.vtp",
                "other_000002.vtp",
                "other_000003.vtp",
                "silo_000000.vtp",
                "silo_000001.vtp",
                "silo_contacts_000000.vtp"
            ]
        );
        let mut ck = file_names(&dir.join("checkpoints"));
        ck.sort();
        assert_eq!(
            ck,
            [checkpoint_name("silo", 100), checkpoint_name("silo", 200)]
        );
        remove_run(&dir, "silo").unwrap();
        assert!(runs_in(&dir).is_empty());
        assert!(dir.join("notes.txt").exists());
        assert_eq!(file_names(&dir.join("frames")).len(), 4);
        std::fs::remove_dir_all(&dir).ok();
    }
}
