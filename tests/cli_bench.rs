//! `mdr-dem bench make-bed` and `mdr-dem bench bed`: the JSON contract, trajectories
//! that do not depend on the number of threads, and bad values named by their flag.

mod common;

use common::mdr_dem;

use std::path::{Path, PathBuf};

use std::sync::OnceLock;

/// A small settled bed written by the generator, once for all tests: 150 spheres of diameter 1
/// and density 1 poured from a 38-layer lattice (its top at z ≈ 41, a fall of ≈ 9 time units)
/// and settled for 15 time units.
fn small_bed() -> &'static PathBuf {
    static BED: OnceLock<PathBuf> = OnceLock::new();
    BED.get_or_init(make_small_bed)
}

fn make_small_bed() -> PathBuf {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_bench_bed.data");
    let output = mdr_dem(&[
        "bench",
        "make-bed",
        "--count",
        "150",
        "--settle-steps",
        "150000",
        "--threads",
        "1",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert!(
        output.status.success(),
        "make-bed failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    path
}

fn bench_json(bed: &Path, law: &str, threads: usize, extra: &[&str]) -> serde_json::Value {
    let threads = threads.to_string();
    let mut args = vec![
        "bench",
        "bed",
        "--data",
        bed.to_str().unwrap(),
        "--law",
        law,
        "--threads",
        &threads,
        "--warmup",
        "200",
        "--steps",
        "100",
        "--json",
    ];
    args.extend_from_slice(extra);
    let output = mdr_dem(&args);
    assert!(
        output.status.success(),
        "bench bed failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("one JSON object on stdout")
}

#[test]
fn bench_bed_json_contract_and_same_trajectories_for_one_and_two_threads() {
    let bed = small_bed();
    for law in ["hertz", "mdr"] {
        let mut checksums = Vec::new();
        for threads in [1, 2] {
            let d = bench_json(bed, law, threads, &[]);
            // The contract's keys.
            for key in [
                "particle_steps_per_s",
                "ms_per_step",
                "contacts_per_particle",
                "peak_rss_mb",
                "particle_steps_per_cpu_s",
                "cpu_seconds",
                "stepper_bytes_per_particle",
            ] {
                let v = d[key]
                    .as_f64()
                    .unwrap_or_else(|| panic!("{key} is not a number: {}", d[key]));
                assert!(
                    v.is_finite() && v > 0.0,
                    "{key} = {v} ({law}, {threads} threads)"
                );
            }
            assert_eq!(d["threads"].as_u64(), Some(threads as u64));
            assert_eq!(d["particles"].as_u64(), Some(150));
            assert_eq!(d["steps"].as_u64(), Some(100));
            assert_eq!(d["law"].as_str(), Some(law));
            assert_eq!(d["work_books"].as_bool(), Some(true));
            assert_eq!(d["orientation"].as_bool(), Some(true));
            // A settled bed: every sphere rests on others or on the floor (2.7 × 2.7 of it).
            let contacts = d["contacts_per_particle"].as_f64().unwrap();
            assert!(contacts > 4.0, "{contacts} contacts per particle");
            assert!(d["floor_contacts"].as_u64().unwrap() >= 3);
            let ms = d["ms_per_step"].as_f64().unwrap();
            let rate = d["particle_steps_per_s"].as_f64().unwrap();
            assert!(
                (rate * ms / 1e3 / 150.0 - 1.0).abs() < 1e-9,
                "rate and ms/step disagree"
            );
            let checksum = d["state_checksum"].as_str().unwrap().to_string();
            assert_eq!(checksum.len(), 16);
            assert!(checksum.chars().all(|c| c.is_ascii_hexdigit()));
            checksums.push(checksum);
        }
        assert_eq!(
            checksums[0], checksums[1],
            "{law}: 1 and 2 threads must give the same final state"
        );
        // Without work books (diagnostics only): the same trajectory, reported as such.
        let d = bench_json(bed, law, 1, &["--no-work-books"]);
        assert_eq!(d["work_books"].as_bool(), Some(false));
        assert_eq!(d["state_checksum"].as_str(), Some(checksums[0].as_str()));
    }
}

/// Thornton, the adhesive law and rolling resistance on the CPU bench: each gives the same final
/// state on 1 and 2 threads, reports its own name, and ends elsewhere than the MDR law alone
/// (the law or sub-model is applied, not silently replaced by another).
#[test]
fn bench_bed_runs_thornton_adhesion_and_rolling_on_the_cpu_independent_of_threads() {
    let bed = small_bed();
    let mdr = bench_json(bed, "mdr", 1, &[]);
    let mdr_checksum = mdr["state_checksum"].as_str().unwrap();
    for (law, extra, name) in [
        ("adhesive-mdr", &[][..], "adhesive-mdr"),
        ("thornton", &[][..], "thornton"),
        ("mdr", &["--rolling", "0.1"][..], "mdr"),
    ] {
        let one = bench_json(bed, law, 1, extra);
        let two = bench_json(bed, law, 2, extra);
        assert_eq!(one["law"].as_str(), Some(name), "{one}");
        assert_eq!(one["device"].as_str(), Some("cpu"), "{one}");
        let checksum = one["state_checksum"].as_str().unwrap();
        assert_eq!(
            Some(checksum),
            two["state_checksum"].as_str(),
            "{law} {extra:?}: 1 and 2 threads must give the same final state"
        );
        assert_ne!(
            checksum, mdr_checksum,
            "{law} {extra:?} ends where the MDR law alone does"
        );
        let contacts = one["contacts_per_particle"].as_f64().unwrap();
        assert!(contacts > 4.0, "{law}: {contacts} contacts per particle");
    }
}

#[test]
fn bench_bed_refuses_bad_values_by_name() {
    let data = small_bed().to_str().unwrap();
    for (flag, value, law) in [
        ("--threads", "0", "hertz"),
        ("--tile", "0", "hertz"),
        // tile² × spheres beyond MAX_BED_SPHERES, and a tile whose square overflows.
        ("--tile", "100000", "hertz"),
        ("--tile", "18446744073709551615", "hertz"),
        ("--skin", "-0.1", "hertz"),
        ("--skin", "0", "hertz"),
        ("--steps", "0", "hertz"),
        ("--qc", "-1", "mdr"),
        ("--qc", "nan", "adhesive-mdr"),
        ("--work-of-adhesion", "-1", "adhesive-mdr"),
        ("--work-of-adhesion", "nan", "adhesive-mdr"),
        ("--yield-stress", "-1", "thornton"),
        ("--yield-stress", "nan", "thornton"),
        ("--rolling", "-1", "mdr"),
        ("--rolling", "nan", "hertz"),
    ] {
        let setting = format!("{flag}={value}");
        let output = mdr_dem(&[
            "bench", "bed", "--data", data, "--warmup", "1", "--law", law, &setting,
        ]);
        assert!(!output.status.success(), "{flag} {value} was accepted");
        let stderr = String::from_utf8_lossy(&output.stderr);
        let name = flag.trim_start_matches("--");
        assert!(
            stderr.contains(name),
            "{flag} {value}: the error does not name it: {stderr}"
        );
    }
    let output = mdr_dem(&["bench", "bed", "--data", "/nonexistent/bed.data"]);
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("/nonexistent/bed.data"));
}

/// `bench scene` on a small column: the JSON contract (keys present, figures positive) on both
/// force paths, and bad values refused by their flag.
#[test]
fn bench_scene_json_contract_and_bad_values() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_bench_scene");
    std::fs::create_dir_all(&dir).unwrap();
    let column =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/column.toml"))
            .unwrap();
    let path = dir.join("column.toml");
    std::fs::write(&path, &column).unwrap();
    let scene = path.to_str().unwrap();
    for threads in ["1", "2"] {
        let out = mdr_dem(&[
            "bench",
            "scene",
            scene,
            "--steps",
            "20",
            "--warmup",
            "5",
            "--threads",
            threads,
            "--json",
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let d: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        for key in [
            "particle_steps_per_s",
            "cpu_particle_steps_per_s",
            "ms_per_step",
            "peak_rss_mb",
        ] {
            assert!(d[key].as_f64().unwrap() > 0.0, "{key}: {d}");
        }
        let contacts = d["contacts_per_particle"].as_f64().unwrap();
        assert!(contacts >= 0.0);
        // The column's first steps: spheres on a lattice with gaps, hardly touching.
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            stderr.contains("free flight"),
            contacts < 0.5,
            "{contacts}: {stderr}"
        );
        assert_eq!(d["threads"].as_u64().unwrap().to_string(), threads);
        assert!(d["particles"].as_u64().unwrap() > 100);
        assert_eq!(d["path"], "neighbour_list");
        // The timing breakdown: every part, and with the rest they make up the whole step.
        let b = &d["breakdown_ns_per_particle_step"];
        let parts = [
            "pairs",
            "builds",
            "surfaces",
            "integration",
            "rapier",
            "rest",
        ];
        let sum: f64 = parts
            .iter()
            .map(|k| {
                let v = b[k].as_f64().unwrap_or_else(|| panic!("{k}: {d}"));
                assert!(v >= 0.0, "{k}: {d}");
                v
            })
            .sum();
        assert!(b["pairs"].as_f64().unwrap() > 0.0, "{d}");
        let per_step = 1e6 * d["ms_per_step"].as_f64().unwrap() / d["particles"].as_f64().unwrap();
        assert!(
            (sum / per_step - 1.0).abs() < 1e-9,
            "{sum} against {per_step}: {d}"
        );
    }
    for (flag, value) in [("--steps", "0"), ("--threads", "0")] {
        let out = mdr_dem(&["bench", "scene", scene, flag, value]);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(flag), "{flag}: {err}");
    }
}
