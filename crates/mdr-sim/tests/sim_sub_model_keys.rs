//! The tangential, damping and rolling keys of `[contact]` read from the laws' declarations:
//! each law chosen by its registered name, each parameter defaulted and range-checked as
//! declared, errors naming the key, its range and its equation; and the scene written back in
//! the fixed key order a checkpoint's fingerprint hashes.

mod common;

use mdr_contact::damping::{HertzianViscous, StiffnessViscous};
use mdr_contact::params::Declared;
use mdr_contact::tangential::Mindlin;
use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::{DampingSpec, Problems, Scene};
use std::path::Path;

/// The column scene with `μ = 0.3` and `extra` appended to its `[contact]` table.
fn scene_with(extra: &str) -> Result<Scene, Problems> {
    let text = common::column(2, 2, 0.01, 0.3, "")
        .replace("friction = 0.3", &format!("friction = 0.3\n{extra}"));
    assert!(text.contains(extra), "{text}");
    parse_scene(Path::new("scene.toml"), &text)
}

/// The one error of a refused scene about `key`.
fn error(extra: &str, key: &str) -> String {
    let problems = scene_with(extra).expect_err("refused");
    let errors: Vec<_> = problems.errors().filter(|e| e.key.ends_with(key)).collect();
    assert_eq!(errors.len(), 1, "one error about `{key}`: {problems}");
    errors[0].message.clone()
}

#[test]
fn sub_model_values_and_defaults_come_from_the_declarations() {
    let scene = scene_with("damping = \"hertzian_viscous\"\ndamping_gamma_n_per_m_s = 50.0")
        .expect("valid");
    let c = &scene.contact;
    assert_eq!(c.friction(), 0.3);
    assert_eq!(c.damping(), DampingSpec::HertzianViscous(50.0));
    // The declared defaults of the keys left out.
    let ratio = HertzianViscous::DECLARATION.params[1];
    assert_eq!(
        (ratio.key, ratio.default),
        ("damping_tangential_ratio", Some(0.0))
    );
    assert_eq!(c.tangential_damping_ratio(), 0.0);
    assert_eq!(c.rolling_friction(), 0.0);
    let scene = scene_with(
        "damping = \"stiffness_viscous\"\ndamping_eta = 0.3\ndamping_tangential_ratio = 0.5\n\
         rolling = \"epsd\"\nrolling_friction = 0.1",
    )
    .expect("valid");
    let c = &scene.contact;
    assert_eq!(c.damping(), DampingSpec::StiffnessViscous(0.3));
    assert_eq!(
        (c.tangential_damping_ratio(), c.rolling_friction()),
        (0.5, 0.1)
    );
}

#[test]
fn range_errors_name_the_key_the_range_and_the_equation() {
    let scene = common::column(2, 2, 0.01, 0.3, "").replace("friction = 0.3", "friction = -1.0");
    let problems = parse_scene(Path::new("scene.toml"), &scene).expect_err("refused");
    let e = problems
        .errors()
        .find(|e| e.key == "contact.friction")
        .unwrap_or_else(|| panic!("{problems}"));
    let help = Mindlin::DECLARATION.params[0].help();
    assert!(
        e.message.contains("[0, inf)") && e.message.contains(&help),
        "{e}"
    );
    let m = error(
        "damping = \"stiffness_viscous\"\ndamping_eta = -0.5",
        "damping_eta",
    );
    let help = StiffnessViscous::DECLARATION.params[0].help();
    assert!(
        m.contains("`damping_eta` = -0.5") && m.contains(&help),
        "{m}"
    );
    let m = error("rolling_friction = nan", "rolling_friction");
    assert!(m.contains("rolling_friction"), "{m}");
    let m = error("damping = \"hertzian_viscous\"", "contact");
    assert!(
        m.contains("missing key `damping_gamma_n_per_m_s`")
            && m.contains("required by damping = \"hertzian_viscous\"")
            && m.contains("1/(m·s)"),
        "{m}"
    );
    let m = error(
        "damping_eta = \"much\"\ndamping = \"stiffness_viscous\"",
        "damping_eta",
    );
    assert!(m.contains("expected a number"), "{m}");
}

#[test]
fn laws_are_chosen_by_registered_name_and_other_laws_keys_refused() {
    let m = error("damping = \"hertzian_viscos\"", "damping");
    assert!(
        m.contains("`none`, `hertzian_viscous`, `stiffness_viscous`")
            && m.contains("did you mean `hertzian_viscous`?"),
        "{m}"
    );
    let m = error("rolling = \"spring\"", "rolling");
    assert!(m.contains("`none`, `epsd`"), "{m}");
    let m = error(
        "damping = \"hertzian_viscous\"\ndamping_gamma_n_per_m_s = 50.0\ndamping_eta = 0.3",
        "damping_eta",
    );
    assert!(
        m.contains(
            "not used by damping = \"hertzian_viscous\" (a parameter of `stiffness_viscous`)"
        ),
        "{m}"
    );
    let m = error("damping_tangential_ratio = 0.5", "damping_tangential_ratio");
    assert!(m.contains("not used by damping = \"none\""), "{m}");
    let m = error(
        "rolling = \"none\"\nrolling_friction = 0.1",
        "rolling_friction",
    );
    assert!(
        m.contains("not used by rolling = \"none\" (a parameter of `epsd`)"),
        "{m}"
    );
    // A zero coefficient of a law that is not chosen is that law off: accepted.
    let scene = scene_with("rolling = \"none\"\nrolling_friction = 0.0").expect("valid");
    assert_eq!(scene.contact.rolling_friction(), 0.0);
    // An unknown key lists the sub-models' keys among the allowed ones.
    let m = error("rolling_frction = 0.1", "rolling_frction");
    assert!(
        m.contains("`rolling`, `rolling_friction`")
            && m.contains("did you mean `rolling_friction`?"),
        "{m}"
    );
}

#[test]
fn a_frictionless_scene_refuses_a_friction_coefficient() {
    let text = common::column(2, 2, 0.01, 0.3, "").replace("tangential = \"mindlin\"\n", "");
    let problems = parse_scene(Path::new("scene.toml"), &text).expect_err("refused");
    let e = problems
        .errors()
        .find(|e| e.key == "contact.friction")
        .unwrap_or_else(|| panic!("{problems}"));
    assert!(
        e.message
            .contains("not used by tangential = \"none\" (a parameter of `mindlin`)"),
        "{e}"
    );
    let text = text.replace("friction = 0.3", "friction = 0.0");
    let scene = parse_scene(Path::new("scene.toml"), &text).expect("valid");
    assert_eq!(scene.contact.friction(), 0.0);
}

/// The `[contact]` table is written back (the text a checkpoint's fingerprint hashes) in one
/// order whatever the file's: `normal`, the normal law's keys, `tangential`, `friction`,
/// `damping` (always), the damping keys (shared `damping_tangential_ratio` last), the rolling
/// keys: the order of the scene files whose checkpoints exist.
#[test]
fn the_contact_table_is_written_in_its_fixed_order() {
    let text = common::column(2, 2, 0.01, 0.3, "").replace(
        "[contact]\nnormal = \"mdr\"\ncritical_line_load_n_per_m = 100.0\nhardening_ratio = 0.37\ntangential = \"mindlin\"\nfriction = 0.3",
        "[contact]\nrolling_friction = 0.1\ndamping_tangential_ratio = 0.5\nfriction = 0.3\n\
         hardening_ratio = 0.37\ndamping_eta = 0.3\ndamping = \"stiffness_viscous\"\n\
         tangential = \"mindlin\"\ncritical_line_load_n_per_m = 100.0\nnormal = \"mdr\"",
    );
    assert!(text.contains("rolling_friction = 0.1"), "{text}");
    let scene = parse_scene(Path::new("scene.toml"), &text).expect("valid");
    let written = toml::to_string(&scene.source.contact).unwrap();
    assert_eq!(
        written,
        "normal = \"mdr\"\ncritical_line_load_n_per_m = 100.0\nhardening_ratio = 0.37\n\
         tangential = \"mindlin\"\nfriction = 0.3\ndamping = \"stiffness_viscous\"\n\
         damping_eta = 0.3\ndamping_tangential_ratio = 0.5\nrolling_friction = 0.1\n"
    );
    // `damping` is written when left out, as `none`; `rolling` only when given.
    let scene = parse_scene(
        Path::new("scene.toml"),
        &common::column(2, 2, 0.01, 0.3, ""),
    )
    .expect("valid");
    let written = toml::to_string(&scene.source.contact).unwrap();
    assert!(
        written.ends_with("friction = 0.3\ndamping = \"none\"\n"),
        "{written}"
    );
}

/// Each registered sub-model is built by its name from its validated values (the variant of
/// its kind's enum the steppers run), the coefficients `ContactSpec` gives are read from them
/// by their declared keys, a rolling law that cannot act is compiled out, and a name no entry
/// registers is refused by name.
#[test]
fn sub_models_are_built_by_their_registered_names() {
    use mdr_contact::damping::NoDamping;
    use mdr_contact::params::{LawDeclaration, LawKind, Param, Range};
    use mdr_contact::rolling::EpsdRolling;
    use mdr_contact::tangential::Frictionless;
    use mdr_sim::laws::registry::{contact_spec, SceneParts};
    use mdr_sim::laws::{AnyDamping, AnyRolling, AnyTangential};
    use mdr_sim::scene::SubModelSpec;
    static PARAMS: &[Param] = &[Param::new(
        "damping_c_n_s_per_m",
        "c",
        "N·s/m",
        Range::NON_NEGATIVE,
        "F_d = c dδ/dt",
    )];
    let unregistered = SubModelSpec {
        declaration: LawDeclaration {
            name: "constant_viscous",
            kind: LawKind::Damping,
            summary: "",
            params: PARAMS,
        },
        values: vec![1.0],
    };
    let spec = |declaration: LawDeclaration, values: Vec<f64>| SubModelSpec {
        declaration,
        values,
    };
    let normal = scene_with("").expect("valid").contact.normal;
    let frictionless = spec(Frictionless::DECLARATION, vec![]);
    let rolling = spec(EpsdRolling::DECLARATION, vec![0.2]);
    let viscous = spec(StiffnessViscous::DECLARATION, vec![0.3, 0.5]);
    let c = contact_spec(
        normal.clone(),
        frictionless.clone(),
        viscous,
        rolling.clone(),
    );
    assert_eq!(c.damping(), DampingSpec::StiffnessViscous(0.3));
    assert_eq!(
        (
            c.friction(),
            c.tangential_damping_ratio(),
            c.rolling_friction()
        ),
        (0.0, 0.5, 0.2)
    );
    let parts = SceneParts::of(&c).unwrap();
    assert_eq!(parts.tangential, AnyTangential::Frictionless(Frictionless));
    let eta = StiffnessViscous::new(0.3).unwrap();
    assert_eq!(
        parts.damping,
        AnyDamping::StiffnessViscous(eta.with_tangential_ratio(0.5).unwrap())
    );
    assert_eq!(
        parts.rolling,
        Some(AnyRolling::EpsdRolling(EpsdRolling::new(0.2).unwrap()))
    );
    let friction = spec(Mindlin::DECLARATION, vec![0.4]);
    let none = spec(NoDamping::DECLARATION, vec![]);
    let off = spec(EpsdRolling::DECLARATION, vec![0.0]);
    let c = contact_spec(normal.clone(), friction, none, off);
    assert_eq!(c.friction(), 0.4);
    let parts = SceneParts::of(&c).unwrap();
    assert_eq!(
        parts.tangential,
        AnyTangential::Mindlin(Mindlin::new(0.4).unwrap())
    );
    assert_eq!(parts.rolling, None);
    let c = contact_spec(normal, frictionless, unregistered, rolling);
    assert_eq!(c.damping(), DampingSpec::Other("constant_viscous"));
    let e = SceneParts::of(&c).unwrap_err().to_string();
    assert!(
        e.contains("no registered damping law is named `constant_viscous`"),
        "{e}"
    );
}

/// `ContactSpec`'s coefficients are its declared sub-models' values found by key through each
/// law's declaration: the keys are the built-in laws' own, and a law declaring its `friction`
/// or `rolling_friction` second gives that value (a lookup by position would give the first).
/// The sub-models are the one copy: replacing one changes every coefficient read from it.
#[test]
fn coefficients_are_read_from_the_declared_sub_models_by_key() {
    use mdr_contact::params::{LawDeclaration, LawKind, Param, Range};
    use mdr_contact::rolling::EpsdRolling;
    use mdr_sim::scene::{
        SubModelSpec, DAMPING_TANGENTIAL_RATIO_KEY, FRICTION_KEY, HERTZIAN_GAMMA_KEY,
        ROLLING_FRICTION_KEY, STIFFNESS_ETA_KEY,
    };
    assert!(Mindlin::DECLARATION.param(FRICTION_KEY).is_some());
    assert!(EpsdRolling::DECLARATION
        .param(ROLLING_FRICTION_KEY)
        .is_some());
    for (law, key) in [
        (HertzianViscous::DECLARATION, HERTZIAN_GAMMA_KEY),
        (StiffnessViscous::DECLARATION, STIFFNESS_ETA_KEY),
    ] {
        assert!(law.param(key).is_some(), "{}: {key}", law.name);
        assert!(
            law.param(DAMPING_TANGENTIAL_RATIO_KEY).is_some(),
            "{}",
            law.name
        );
    }
    static TANGENTIAL: &[Param] = &[
        Param::new(
            "tangential_stiffness_n_per_m",
            "k_t",
            "N/m",
            Range::POSITIVE,
            "",
        ),
        Param::new(FRICTION_KEY, "μ", "1", Range::NON_NEGATIVE, ""),
    ];
    static ROLLING: &[Param] = &[
        Param::new("rolling_stiffness_n_m", "k_r", "N·m", Range::POSITIVE, ""),
        Param::new(ROLLING_FRICTION_KEY, "μ_r", "1", Range::NON_NEGATIVE, ""),
    ];
    let declared = |name, kind, params| LawDeclaration {
        name,
        kind,
        summary: "",
        params,
    };
    let mut c = scene_with("").expect("valid").contact;
    assert_eq!((c.friction(), c.rolling_friction()), (0.3, 0.0));
    c.sub_models.tangential = SubModelSpec {
        declaration: declared("linear_history", LawKind::Tangential, TANGENTIAL),
        values: vec![1e4, 0.25],
    };
    c.sub_models.damping = SubModelSpec {
        declaration: StiffnessViscous::DECLARATION,
        values: vec![0.2, 0.4],
    };
    c.sub_models.rolling = SubModelSpec {
        declaration: declared("sds", LawKind::Rolling, ROLLING),
        values: vec![2.0, 0.05],
    };
    assert_eq!(c.friction(), 0.25);
    assert_eq!(c.damping(), DampingSpec::StiffnessViscous(0.2));
    assert_eq!(c.tangential_damping_ratio(), 0.4);
    assert_eq!(c.rolling_friction(), 0.05);
}
