//! Scene keys that docs/user-guide.md documents, each run once with an outcome that depends on
//! it: a box's `open_top`, a mesh's `scale` and `offset_m`, a LAMMPS placement's
//! `length_scale_m`, and the three checkpoints a run keeps.

mod common;

use mdr_sim::{run_scene, scene::validate::parse_scene, RunOptions, RunSummary};
use std::path::Path;

const HEAD: &str = r#"
[run]
name = "keys"
seed = 3
duration_s = DURATION
dt_s = "auto"
max_speed_m_per_s = 2.5
steps_per_contact = 25
output_interval_s = 0.05

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 1.0e6
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 50.0
hardening_ratio = 0.37
damping = "hertzian_viscous"
damping_gamma_n_per_m_s = 2000.0
"#;

fn run(dir: &Path, name: &str, text: &str, options: RunOptions) -> RunSummary {
    let path = common::write(dir, &format!("{name}.toml"), text);
    let scene = parse_scene(&path, text).unwrap_or_else(|p| panic!("{name}: {p}"));
    run_scene(&scene, &options).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn quiet(dir: &Path, name: &str) -> RunOptions {
    RunOptions::new(dir.join(name)).quiet(true).no_frames(true)
}

/// A sphere launched upward at 2 m/s inside a 20 mm box: it would rise 0.2 m; with
/// `open_top = false` the lid keeps it in, by default it leaves through the open top.
#[test]
fn box_open_top_decides_whether_a_sphere_can_leave() {
    let dir = common::temp_dir("keys-box");
    common::write(
        &dir,
        "up.csv",
        "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n0,0,0.01,0.002,0,0,2.0\n",
    );
    let scene = |open_top: &str| {
        format!(
            "{}\n[[particles]]\nmaterial = \"grain\"\nplacement = \"csv\"\nfile = \"up.csv\"\n\n\
             [[walls]]\nkind = \"box\"\nmaterial = \"grain\"\nmin_m = [-0.01, -0.01, 0.0]\n\
             max_m = [0.01, 0.01, 0.02]\nthickness_m = 0.004\n{open_top}\n",
            HEAD.replace("DURATION", "0.05")
        )
    };
    let open = run(&dir, "open", &scene(""), quiet(&dir, "open"));
    let z_open = open.particles[0].translation[2];
    // Free flight for 0.05 s: 0.01 + 2 · 0.05 − 9.81 · 0.05² / 2 = 0.0977 m.
    assert!((z_open - 0.0977).abs() < 1e-3, "open top: z = {z_open}");
    let closed = run(
        &dir,
        "closed",
        &scene("open_top = false"),
        quiet(&dir, "closed"),
    );
    let z_closed = closed.particles[0].translation[2];
    assert!(z_closed < 0.02 - 0.002 + 1e-4, "closed top: z = {z_closed}");
}

/// A unit square (OBJ, normal +z) scaled by 0.02 and moved down by `offset_m`: a sphere above
/// the scaled square is held by it 5 mm down and falls freely past 0.15 s when it is 0.5 m down;
/// one 30 mm off-centre, outside the scaled square (but inside the unscaled one), falls past it.
#[test]
fn mesh_scale_and_offset_place_the_mesh() {
    let dir = common::temp_dir("keys-mesh");
    common::write(
        &dir,
        "square.obj",
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n",
    );
    common::write(
        &dir,
        "two.csv",
        "x_m,y_m,z_m,radius_m\n0.01,0.01,-0.002,0.002\n0.03,0.0,-0.002,0.002\n",
    );
    let sphere_over_mesh_z = |offset: &str| {
        let text = format!(
            "{}\n[[particles]]\nmaterial = \"grain\"\nplacement = \"csv\"\nfile = \"two.csv\"\n\n\
             [[walls]]\nkind = \"mesh\"\nmaterial = \"grain\"\nfile = \"square.obj\"\nscale = 0.02\n\
             offset_m = [0.0, 0.0, {offset}]\n",
            HEAD.replace("DURATION", "0.15")
        );
        let name = format!("mesh{offset}");
        let summary = run(&dir, &name, &text, quiet(&dir, &name));
        let on_mesh = &summary.particles[0];
        let past = summary.particles[1].translation;
        // Free fall from −2 mm for 0.15 s: −0.1124 m.
        assert!(
            (past[2] - (-0.1124)).abs() < 1e-3,
            "sphere past the mesh at {past:?}"
        );
        on_mesh.translation[2]
    };
    // Held by the mesh 5 mm down: its centre stays above −5 mm + r (less a small overlap).
    let held = sphere_over_mesh_z("-0.005");
    assert!(held > -0.005 + 0.002 - 1e-4, "z = {held}");
    // The mesh 0.5 m down: the same sphere falls freely all the way.
    let free = sphere_over_mesh_z("-0.5");
    assert!((free - (-0.1124)).abs() < 1e-3, "z = {free}");
}

/// A LAMMPS data file in millimetres with `length_scale_m = 0.001`: the spheres start at the
/// positions in metres.
#[test]
fn lammps_placement_length_scale_converts_the_units() {
    let dir = common::temp_dir("keys-lammps");
    common::write(
        &dir,
        "mm.data",
        "LAMMPS data file\n\n2 atoms\n1 atom types\n\n-20 20 xlo xhi\n-20 20 ylo yhi\n\
         0 50 zlo zhi\n\nAtoms # sphere\n\n1 1 4 2500 5 -6 10\n2 1 4 2500 -7 8 10\n",
    );
    let text = format!(
        "{}\n[[particles]]\nmaterial = \"grain\"\nplacement = \"lammps\"\nfile = \"mm.data\"\n\
         length_scale_m = 0.001\n\n[[walls]]\nkind = \"plane\"\nmaterial = \"grain\"\n\
         point_m = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n",
        HEAD.replace("DURATION", "0.001")
    );
    let summary = run(&dir, "lammps", &text, quiet(&dir, "lammps"));
    // 1 ms of free fall moves z by 4.9 µm; x and y do not move.
    for (p, expected) in summary
        .particles
        .iter()
        .zip([[0.005, -0.006, 0.01], [-0.007, 0.008, 0.01]])
    {
        for k in 0..3 {
            assert!(
                (p.translation[k] - expected[k]).abs() < 1e-5,
                "{:?} vs {expected:?}",
                p.translation
            );
        }
    }
}

/// Checkpoints every 2 ms over 20 ms: the run writes about ten and keeps the last three, the
/// newest being the one the summary names.
#[test]
fn a_run_keeps_its_last_three_checkpoints() {
    let dir = common::temp_dir("keys-checkpoints");
    let text = common::column(2, 2, 0.02, 0.3, "checkpoint_interval_s = 0.002");
    let summary = run(&dir, "column", &text, quiet(&dir, "out"));
    let mut kept: Vec<_> = std::fs::read_dir(dir.join("out").join("checkpoints"))
        .expect("checkpoint folder")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "mdrck"))
        .collect();
    kept.sort();
    assert_eq!(kept.len(), 3, "{kept:?}");
    assert_eq!(Some(kept.last().unwrap()), summary.checkpoint.as_ref());
    // The three are the last ones: step numbers in the names increase and the last is the
    // run's last step.
    let step = |p: &Path| -> u64 {
        let stem = p.file_stem().unwrap().to_str().unwrap();
        stem.rsplit("_step").next().unwrap().parse().unwrap()
    };
    assert_eq!(step(kept.last().unwrap()), summary.step);
    assert!(step(&kept[0]) < step(&kept[1]) && step(&kept[1]) < step(&kept[2]));
}

/// The unit as the tables write it (`–` for a dimensionless one).
fn documented_unit(unit: &str) -> &str {
    if unit == "1" {
        "–"
    } else {
        unit
    }
}

/// docs/user-guide.md's `[contact]` table states every registered law's parameters as their
/// declarations do: unit, the laws declaring it, required or its default, allowed range. A
/// declaration changed without the table (or the reverse) fails here.
#[test]
fn contact_table_is_the_declarations() {
    use mdr_sim::laws::registry::{
        DAMPING_LAWS, NORMAL_LAWS, ROLLING_LAWS, SUB_MODEL_KINDS, TANGENTIAL_LAWS,
    };
    let guide = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/user-guide.md"),
    )
    .unwrap();
    let section = guide
        .split("### `[contact]`")
        .nth(1)
        .and_then(|s| s.split("\n### ").next())
        .expect("a [contact] section");
    let row = |key: &str| -> Vec<String> {
        section
            .lines()
            .find(|l| l.starts_with(&format!("| `{key}` |")))
            .unwrap_or_else(|| panic!("no row for `{key}`"))
            .split('|')
            .map(|c| c.trim().to_owned())
            .collect()
    };
    let declarations = NORMAL_LAWS
        .iter()
        .map(|e| e.declaration)
        .chain(TANGENTIAL_LAWS.iter().map(|e| e.declaration))
        .chain(DAMPING_LAWS.iter().map(|e| e.declaration))
        .chain(ROLLING_LAWS.iter().map(|e| e.declaration));
    let mut checked = 0;
    for law in declarations {
        for p in law.params {
            let cells = row(p.key);
            // cells: "", key, unit, used with, allowed, meaning, "".
            assert_eq!(cells[2], documented_unit(p.unit), "unit of `{}`", p.key);
            assert!(
                cells[3].contains(&format!("`{}`", law.name)),
                "`{}` is declared by `{}`: {cells:?}",
                p.key,
                law.name
            );
            match p.default {
                None => assert!(cells[3].contains("(required"), "`{}` is required", p.key),
                Some(d) => assert!(
                    cells[3].contains(&format!("(default {d})")),
                    "`{}` defaults to {d}: {cells:?}",
                    p.key
                ),
            }
            assert_eq!(cells[4], p.range.notation, "range of `{}`", p.key);
            checked += 1;
        }
    }
    assert!(checked >= 8, "{checked} parameters checked");
    // The `normal` row names every registered normal law but the demo one.
    let normal = row("normal");
    for entry in NORMAL_LAWS
        .iter()
        .filter(|e| e.declaration.name != "linear_spring")
    {
        assert!(normal[4].contains(&format!("`{}`", entry.declaration.name)));
    }
    // The `tangential`, `damping` and `rolling` rows name every registered law of their kind.
    for kind in &SUB_MODEL_KINDS {
        let cells = row(kind.key);
        let key = kind.key;
        for entry in kind.laws {
            assert!(
                cells[4].contains(&format!("`{}`", entry.declaration.name)),
                "{key}: {cells:?}"
            );
        }
    }
}
