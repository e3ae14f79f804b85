//! The tangential, damping and rolling laws on the command line: `mdr-dem sim laws` lists them
//! with their declared parameters after the normal laws, and the flags that set their
//! parameters (`--mu`, `bench bed --rolling`) take their help and their range check from the
//! declarations.

mod common;

use common::{mdr_dem, stdout};

use mdr_contact::params::Declared;
use mdr_contact::rolling::EpsdRolling;
use mdr_contact::tangential::Mindlin;

#[test]
fn sim_laws_lists_the_sub_models_after_the_normal_laws() {
    let text = stdout(&mdr_dem(&["sim", "laws"]));
    for line in [
        "tangential = \"none\" (default): frictionless",
        "tangential = \"mindlin\": incremental Mindlin",
        "    friction = …  μ (1, in [0, inf)): Coulomb friction coefficient",
        "damping = \"none\" (default): no damping",
        "damping = \"hertzian_viscous\": ",
        "    damping_gamma_n_per_m_s = …  γ_n (1/(m·s), in [0, inf))",
        "    damping_tangential_ratio = …  η_t/η_n (1, in [0, inf), default 0)",
        "damping = \"stiffness_viscous\": ",
        "rolling = \"epsd\" (default): ",
        "    rolling_friction = …  μ_r (1, in [0, inf), default 0)",
    ] {
        assert!(text.contains(line), "missing `{line}` in\n{text}");
    }
    let normal = text.find("normal = \"mdr\"").unwrap();
    assert!(normal < text.find("tangential = ").unwrap(), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&stdout(&mdr_dem(&["sim", "laws", "--json"]))).unwrap();
    let laws = json.as_array().unwrap();
    assert_eq!(laws[0]["name"], "mdr");
    let kinds: Vec<&str> = laws.iter().map(|l| l["kind"].as_str().unwrap()).collect();
    let first = |k: &str| kinds.iter().position(|x| *x == k).unwrap();
    let last = |k: &str| kinds.iter().rposition(|x| *x == k).unwrap();
    assert!(
        last("normal") < first("tangential")
            && last("tangential") < first("damping")
            && last("damping") < first("rolling"),
        "{kinds:?}"
    );
    let mindlin = laws
        .iter()
        .find(|l| l["kind"] == "tangential" && l["name"] == "mindlin")
        .unwrap();
    let mu = &mindlin["parameters"][0];
    assert_eq!(
        (&mu["key"], &mu["flag"], &mu["python"], &mu["lammps"]),
        (
            &"friction".into(),
            &"--mu".into(),
            &"mu".into(),
            &"friction".into()
        )
    );
}

#[test]
fn sub_model_flags_are_the_declared_ones() {
    let mu = &Mindlin::DECLARATION.params[0];
    assert_eq!(mu.flag_name(), "mu");
    let help = stdout(&mdr_dem(&["impact", "oblique", "--help"]));
    assert!(help.contains("--mu <VALUE>"), "{help}");
    assert!(
        help.contains("Coulomb friction coefficient: |F_t| ≤ μ F_n"),
        "{help}"
    );
    let out = mdr_dem(&["impact", "oblique", "--speed", "1", "--mu", "-0.1"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("invalid value for --mu: -0.1 (must be a finite number in [0, inf)")
            && err.contains(&mu.help()),
        "{err}"
    );
    let rolling = &EpsdRolling::DECLARATION.params[0];
    assert_eq!(rolling.flag_name(), "rolling");
    let help = stdout(&mdr_dem(&["bench", "bed", "--help"]));
    assert!(help.contains("--rolling <VALUE>"), "{help}");
    assert!(
        help.contains("rolling-resistance coefficient: |M_r| ≤ μ_r R F_N"),
        "{help}"
    );
}
