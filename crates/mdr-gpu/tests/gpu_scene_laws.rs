//! The GPU path picks its kernel's tangential, damping and rolling laws by the scene's declared
//! laws' registered names: every other law of each kind is refused by its own name, with the
//! names the GPU has, before a device is needed; the shipped scenes' laws (Mindlin, Hertzian
//! and stiffness-viscous damping, the elastic–plastic rolling spring, and each kind's `none`)
//! are accepted, with the coefficients their declared keys give.

use mdr_contact::params::{LawDeclaration, LawKind, Param, Range};
use mdr_gpu::{gpu_scene_support, DeviceSubModels};
use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::{load_scene, SubModelSpec, FRICTION_KEY, ROLLING_FRICTION_KEY};
use mdr_sim::Scene;
use std::path::{Path, PathBuf};

fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name)
}

/// The shipped scene `name`.
fn shipped(name: &str) -> Scene {
    load_scene(&scene_path(name)).unwrap_or_else(|p| panic!("{p}"))
}

/// The shipped scene `name` with `from` replaced by `to` in its text (`from` must be there).
fn scene_edited(name: &str, from: &str, to: &str) -> Scene {
    let path = scene_path(name);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(from), "{name}: {from}");
    parse_scene(&path, &text.replace(from, to)).unwrap_or_else(|p| panic!("{p}"))
}

/// The refusal of `scene` by the GPU path (which must refuse it).
fn refusal(scene: &Scene) -> String {
    gpu_scene_support(scene).expect_err("refused").to_string()
}

/// A law of `kind` no registry line names, declaring `params` (the keys of a built-in law's
/// coefficient among them).
fn unregistered(name: &'static str, kind: LawKind, params: &'static [Param]) -> LawDeclaration {
    LawDeclaration {
        name,
        kind,
        summary: "",
        params,
    }
}

/// The bed scene's damping block (Hertzian viscous).
const BED_DAMPING: &str = "damping = \"hertzian_viscous\"\ndamping_gamma_n_per_m_s = 50.0\n\
                           damping_tangential_ratio = 0.5\n";

/// The demo damping law: registered by one line, run by the CPU paths, not by the kernel.
#[test]
fn a_damping_law_without_a_kernel_is_refused_by_its_registered_name() {
    let scene = scene_edited(
        "bed.toml",
        BED_DAMPING,
        "damping = \"linear_dashpot\"\ndamping_coefficient_n_s_per_m = 0.1\n",
    );
    assert_eq!(
        scene.contact.sub_models.damping.declaration.name,
        "linear_dashpot"
    );
    let err = refusal(&scene);
    assert!(
        err.contains(
            "`damping = \"linear_dashpot\"` has no GPU kernel (the GPU has `none`, \
             `hertzian_viscous` and `stiffness_viscous`)"
        ),
        "{err}"
    );
}

/// A tangential law declaring Mindlin's `friction` key is still not Mindlin's: the GPU refuses
/// it by its name rather than running Mindlin's spring with its `μ`.
#[test]
fn a_tangential_law_without_a_kernel_is_refused_by_its_name() {
    static PARAMS: &[Param] = &[
        Param::new(
            "tangential_stiffness_n_per_m",
            "k_t",
            "N/m",
            Range::POSITIVE,
            "",
        ),
        Param::new(FRICTION_KEY, "μ", "1", Range::NON_NEGATIVE, ""),
    ];
    let mut scene = shipped("bed.toml");
    scene.contact.sub_models.tangential = SubModelSpec {
        declaration: unregistered("linear_history", LawKind::Tangential, PARAMS),
        values: vec![1e4, 0.5],
    };
    assert_eq!(scene.contact.friction(), 0.5);
    let err = refusal(&scene);
    assert!(
        err.contains(
            "`tangential = \"linear_history\"` has no GPU kernel (the GPU has `none` and `mindlin`)"
        ),
        "{err}"
    );
}

/// A rolling law declaring the spring's `rolling_friction` key is refused by its name rather
/// than run as the elastic–plastic spring.
#[test]
fn a_rolling_law_without_a_kernel_is_refused_by_its_name() {
    static PARAMS: &[Param] = &[
        Param::new("rolling_stiffness_n_m", "k_r", "N·m", Range::POSITIVE, ""),
        Param::new(ROLLING_FRICTION_KEY, "μ_r", "1", Range::NON_NEGATIVE, ""),
    ];
    let mut scene = shipped("column.toml");
    scene.contact.sub_models.rolling = SubModelSpec {
        declaration: unregistered("sds", LawKind::Rolling, PARAMS),
        values: vec![1e-3, 0.1],
    };
    assert_eq!(scene.contact.rolling_friction(), 0.1);
    let err = refusal(&scene);
    assert!(
        err.contains("`rolling = \"sds\"` has no GPU kernel (the GPU has `none` and `epsd`)"),
        "{err}"
    );
}

/// A law of another kind in a kind's place is refused, even where its name is one the GPU has
/// for that kind (`none`).
#[test]
fn a_law_of_another_kind_is_refused() {
    let mut scene = shipped("drop.toml");
    let damping_none = scene.contact.sub_models.damping.clone();
    assert_eq!(damping_none.declaration.name, "none");
    scene.contact.sub_models.tangential = damping_none;
    let err = refusal(&scene);
    assert!(
        err.contains("`tangential = \"none\"` has no GPU kernel"),
        "{err}"
    );
}

/// Negative control: the shipped scenes' laws are accepted, and the kernel takes the
/// coefficients their declared keys give (rolling state only where `μ_r > 0`).
#[test]
fn the_laws_the_kernel_has_are_accepted_with_their_declared_coefficients() {
    let of = |scene: &Scene| {
        gpu_scene_support(scene).unwrap_or_else(|e| panic!("{}: {e}", scene.name));
        DeviceSubModels::of(&scene.contact).unwrap()
    };
    // Mindlin, Hertzian viscous damping, rolling law left at its default (the spring, off).
    let bed = of(&shipped("bed.toml"));
    assert_eq!(
        (bed.friction, bed.rolling_friction, bed.rolling()),
        (0.5, 0.0, false)
    );
    assert_eq!(bed.stiffness_eta, None);
    // The stiffness-viscous dashpot with its `η` (the drum), and with the tangential ratio.
    let drum = of(&shipped("drum.toml"));
    assert_eq!(
        (drum.friction, drum.rolling_friction, drum.stiffness_eta),
        (0.5, 0.1, Some(0.3))
    );
    let tangential = of(&scene_edited(
        "bed.toml",
        BED_DAMPING,
        "damping = \"stiffness_viscous\"\ndamping_eta = 0.25\ndamping_tangential_ratio = 0.5\n",
    ));
    assert_eq!(tangential.stiffness_eta, Some(0.25));
    // Mindlin and the rolling spring with μ_r = 0.1.
    let column = of(&shipped("column.toml"));
    assert_eq!(
        (column.friction, column.rolling_friction, column.rolling()),
        (0.5, 0.1, true)
    );
    // Each kind's `none`, named.
    let none = of(&scene_edited(
        "column.toml",
        "tangential = \"mindlin\"\nfriction = 0.5\nrolling_friction = 0.1",
        "tangential = \"none\"\ndamping = \"none\"\nrolling = \"none\"",
    ));
    assert_eq!((none.friction, none.rolling()), (0.0, false));
    // The drop scene: every sub-model at its default.
    let drop = of(&shipped("drop.toml"));
    assert_eq!((drop.friction, drop.rolling()), (0.0, false));
}
