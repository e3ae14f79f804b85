//! `mdr-dem sim ring` contract: `--json` prints one object with the documented keys, `--out`
//! writes the time series, the summary, the plots and VTK frames; bad input is a typed error.

use std::process::Command;

fn mdr_dem() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
}

#[test]
fn sim_ring_json_has_the_documented_keys_and_writes_outputs() {
    let out_guard = tempfile::tempdir().unwrap();
    let out = out_guard.path().to_path_buf();
    let output = mdr_dem()
        .args([
            "sim", "ring", "--box", "40", "--orbits", "0.4", "--seed", "3", "--quiet",
        ])
        .args(["--law", "mdr", "--json", "--frame-orbits", "0.2", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    for key in [
        "c_m_per_s",
        "c_over_mean_r_omega",
        "z_rms_m",
        "filling_factor_z0",
        "collisions_per_particle_per_orbit",
        "wall_s_per_orbit",
        "particles",
    ] {
        assert!(json[key].is_number(), "missing {key}: {json}");
    }
    assert_eq!(json["law"]["name"], "mdr");
    assert!(json["c_m_per_s"].as_f64().unwrap() > 0.0);
    for file in [
        "timeseries.csv",
        "summary.json",
        "equilibration.svg",
        "restitution.svg",
    ] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    assert!(out.join("frames/ring_0000.vtk").is_file());
    assert!(out.join("frames/ring_0002.vtk").is_file());
    for image in [
        "sigma_0000.png",
        "top_0000.png",
        "sigma_0002.png",
        "top_0002.png",
    ] {
        let bytes = std::fs::read(out.join("frames").join(image)).expect(image);
        assert!(bytes.starts_with(b"\x89PNG"), "{image} is not a PNG");
    }
    let csv = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 4, "header + 4 samples");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn sim_ring_rejects_bad_parameters_with_their_names() {
    let output = mdr_dem()
        .args([
            "sim", "ring", "--law", "constant", "--eps", "1.5", "--orbits", "0.1",
        ])
        .output()
        .unwrap();
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("eps"));
    let output = mdr_dem()
        .args(["sim", "ring", "--box", "10", "--orbits", "0.1"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("`box`"));
}
