//! The built-in scenes (`scenes/*.toml`) as the GPU tests load them, unchanged.

use mdr_sim::scene::load_scene;
use mdr_sim::Scene;
use std::path::Path;

/// The built-in scene `name`, loaded from disk.
pub fn scene_file(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name);
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}
