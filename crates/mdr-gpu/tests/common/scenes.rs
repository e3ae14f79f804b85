//! The built-in scenes (`scenes/*.toml`) as the GPU tests load them: unchanged, or with their
//! text edited.

use mdr_sim::scene::load_scene;
use mdr_sim::Scene;
use std::path::{Path, PathBuf};

/// The built-in scene `name`, loaded from disk.
pub fn scene_file(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name);
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}

/// The built-in scene `name` with `replace` applied to its text, written into the folder
/// `folder` of the tests' scratch directory.
pub fn edited_scene(folder: &str, name: &str, replace: &[(&str, &str)]) -> Scene {
    let from = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name);
    let mut text = std::fs::read_to_string(&from).unwrap();
    for (old, new) in replace {
        assert!(text.contains(old), "{name}: {old}");
        text = text.replace(old, new);
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(folder);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}

/// The damping of the built-in drum and hopper, swapped for one the GPU has: their walls alone
/// are then judged.
pub const HERTZIAN_DAMPING: [(&str, &str); 2] = [
    (
        "damping = \"stiffness_viscous\"",
        "damping = \"hertzian_viscous\"\ndamping_gamma_n_per_m_s = 1.0e4\n#",
    ),
    ("damping_eta = 0.3", ""),
];
