//! The C ABI against mdr-contact called directly: the same overlaps and histories must give the
//! same forces, torques and new histories; bad `pair_coeff` lines are errors naming the keyword.

use mdr_contact::damping::HertzianViscous;
use mdr_contact::material::{effective_modulus, ContactPair, Material};
use mdr_contact::model::{ContactInput, ContactModel, ContactState, NoBooks};
use mdr_contact::normal::{MdrElastoPlastic, MdrState};
use mdr_contact::tangential::{Mindlin, MindlinState};
use mdr_lammps::compute::{MdrdemAtoms, MdrdemNeighbours, MdrdemTally};
use mdr_lammps::ffi::*;
use nalgebra::Vector3;
use std::ffi::{c_void, CStr, CString};

const STEEL_LINE: &str =
    "youngs 2.0e11 poisson 0.286 qc 3.8e5 theta 0.37 friction 0.3 damping 20 tangential_damping 0.5";

fn coeff(handle: *mut c_void, types: (i32, i32), line: &str) -> Result<i32, String> {
    let words: Vec<CString> = line
        .split_whitespace()
        .map(|w| CString::new(w).unwrap())
        .collect();
    let ptrs: Vec<*const i8> = words.iter().map(|w| w.as_ptr()).collect();
    let mut err = [0i8; 512];
    let n = unsafe {
        mdrdem_coeff(
            handle,
            types.0,
            types.0,
            types.1,
            types.1,
            ptrs.len() as i32,
            ptrs.as_ptr(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    if n < 0 {
        Err(unsafe { CStr::from_ptr(err.as_ptr()) }
            .to_string_lossy()
            .into_owned())
    } else {
        Ok(n)
    }
}

fn init(handle: *mut c_void, i: i32, j: i32) -> Result<(), String> {
    let mut err = [0i8; 512];
    if unsafe { mdrdem_init_one(handle, i, j, err.as_mut_ptr(), err.len()) } != 0 {
        return Err(unsafe { CStr::from_ptr(err.as_ptr()) }
            .to_string_lossy()
            .into_owned());
    }
    Ok(())
}

/// Two spheres (`i` = 0 owned, `j` = 1 owned or ghost), one neighbour-list entry.
struct TwoSpheres {
    x: [f64; 6],
    v: [f64; 6],
    omega: [f64; 6],
    radius: [f64; 2],
    rmass: [f64; 2],
    types: [i32; 2],
}

struct Outcome {
    f: [f64; 6],
    torque: [f64; 6],
    history: Vec<f64>,
    touch: i32,
    virial: [f64; 6],
    energy: f64,
}

fn run(
    handle: *mut c_void,
    s: &TwoSpheres,
    history: &[f64],
    touch: i32,
    nlocal: i32,
    newton: i32,
    dt: f64,
) -> Outcome {
    run_with(handle, s, history, (touch, 1), nlocal, newton, dt)
}

/// As [`run`], with the history flag `(touch, history_update)`: `history_update = 0` is LAMMPS's
/// setup call.
fn run_with(
    handle: *mut c_void,
    s: &TwoSpheres,
    history: &[f64],
    (touch, history_update): (i32, i32),
    nlocal: i32,
    newton: i32,
    dt: f64,
) -> Outcome {
    let mut f = [0.0; 6];
    let mut torque = [0.0; 6];
    let mut hist = history.to_vec();
    let mut touch = [touch];
    let ilist = [0i32];
    let numneigh = [1i32, 0];
    let jlist = [1i32];
    let firstneigh = [jlist.as_ptr(), std::ptr::null()];
    let offset = [0i64, 1];
    let mut energy = 0.0;
    let mut virial = [0.0; 6];
    let atoms = MdrdemAtoms {
        x: s.x.as_ptr(),
        v: s.v.as_ptr(),
        omega: s.omega.as_ptr(),
        f: f.as_mut_ptr(),
        torque: torque.as_mut_ptr(),
        radius: s.radius.as_ptr(),
        rmass: s.rmass.as_ptr(),
        atom_type: s.types.as_ptr(),
        nlocal,
        nall: 2,
    };
    let list = MdrdemNeighbours {
        inum: 1,
        ilist: ilist.as_ptr(),
        numneigh: numneigh.as_ptr(),
        firstneigh: firstneigh.as_ptr(),
        neighmask: 0x1FFF_FFFF,
        offset: offset.as_ptr(),
        touch: touch.as_mut_ptr(),
        history: hist.as_mut_ptr(),
        dnum: history.len() as i32,
        history_update,
    };
    let tally = MdrdemTally {
        newton_pair: newton,
        eflag_global: 1,
        vflag_global: 1,
        eng_vdwl: &mut energy,
        virial: virial.as_mut_ptr(),
        eatom: std::ptr::null_mut(),
        vatom: std::ptr::null_mut(),
    };
    let mut err = [0i8; 512];
    let rc = unsafe { mdrdem_compute(handle, &atoms, &list, &tally, dt, err.as_mut_ptr(), 512) };
    assert_eq!(rc, 0, "{:?}", unsafe { CStr::from_ptr(err.as_ptr()) });
    Outcome {
        f,
        torque,
        history: hist,
        touch: touch[0],
        virial,
        energy,
    }
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-12 * scale
}

/// Cases: (overlap, unit normal direction, v_i − v_j, ω_i, ω_j, prior d_max, prior ξ, prior a).
type Case = (
    f64,
    [f64; 3],
    [f64; 3],
    [f64; 3],
    [f64; 3],
    f64,
    [f64; 3],
    f64,
);

#[test]
fn forces_equal_mdr_contact_for_the_same_overlaps_and_histories() {
    let (r1, r2) = (0.635e-2, 0.5e-2);
    let steel = Material::paper_steel();
    let (m1, m2) = (steel.sphere_mass(r1), steel.sphere_mass(r2));
    let cases: [Case; 6] = [
        // first touch, elastic, head-on approach
        (
            2e-6,
            [1.0, 0.0, 0.0],
            [-0.5, 0.0, 0.0],
            [0.0; 3],
            [0.0; 3],
            0.0,
            [0.0; 3],
            0.0,
        ),
        // plastic loading past u_c, oblique, sliding
        (
            9e-6,
            [0.6, 0.8, 0.0],
            [-0.3, 0.4, 0.2],
            [10.0, 0.0, -5.0],
            [0.0, 3.0, 0.0],
            8e-6,
            [0.0, 0.0, 1e-7],
            1.5e-4,
        ),
        // unloading from a larger d_max (plastic memory), separating
        (
            6e-6,
            [0.0, 0.0, 1.0],
            [0.0, 0.1, 0.3],
            [0.0; 3],
            [1.0, 1.0, 1.0],
            1.2e-5,
            [2e-8, -1e-8, 0.0],
            2.0e-4,
        ),
        // below the residual depth of d_max: touching, no force
        (
            1e-7,
            [0.0, 1.0, 0.0],
            [0.0, 0.2, 0.0],
            [0.0; 3],
            [0.0; 3],
            1.5e-5,
            [0.0; 3],
            2.0e-4,
        ),
        // stuck tangential spring with a turned contact plane
        (
            4e-6,
            [0.0, 0.6, 0.8],
            [0.01, 0.0, 0.0],
            [0.0; 3],
            [0.0; 3],
            4e-6,
            [1e-9, 2e-9, -1.5e-9],
            1.0e-4,
        ),
        // deep plastic
        (
            3e-5,
            [-1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0; 3],
            [0.0; 3],
            2.9e-5,
            [0.0; 3],
            3.0e-4,
        ),
    ];
    let handle = mdrdem_new(1);
    assert_eq!(coeff(handle, (1, 1), STEEL_LINE), Ok(1));
    init(handle, 1, 1).unwrap();
    let model = ContactModel::new(MdrElastoPlastic::new(3.8e5, 0.37).unwrap())
        .with_tangential(Mindlin::new(0.3).unwrap())
        .with_damping(
            HertzianViscous::new(20.0)
                .unwrap()
                .with_tangential_ratio(0.5)
                .unwrap(),
        );
    let law = model
        .bind(&ContactPair::sphere_on_sphere(r1, &steel, r2, &steel).unwrap())
        .unwrap();
    let dt = 1e-8;
    for (k, (overlap, dir, vrel, w1, w2, dmax, xi, a)) in cases.iter().enumerate() {
        let n = Vector3::from(*dir).normalize();
        let dist = r1 + r2 - overlap;
        let s = TwoSpheres {
            x: [n.x * dist, n.y * dist, n.z * dist, 0.0, 0.0, 0.0],
            v: [vrel[0], vrel[1], vrel[2], 0.0, 0.0, 0.0],
            omega: [w1[0], w1[1], w1[2], w2[0], w2[1], w2[2]],
            radius: [r1, r2],
            rmass: [m1, m2],
            types: [1, 1],
        };
        let history = [*dmax, xi[0], xi[1], xi[2], *a];
        let out = run(handle, &s, &history, 1, 2, 1, dt);

        // The same step through mdr-contact directly.
        let mut state: ContactState<MdrState, MindlinState, NoBooks> = ContactState {
            normal: MdrState { max_overlap: *dmax },
            tangential: MindlinState {
                displacement: Vector3::from(*xi),
                contact_radius: *a,
            },
            books: NoBooks,
        };
        // the kinematics as LAMMPS positions give them (the overlap up to rounding)
        let del = Vector3::new(s.x[0], s.x[1], s.x[2]);
        let overlap = &(r1 + r2 - del.norm());
        let n = del * (1.0 / del.norm());
        let (l1, l2) = (r1 - 0.5 * overlap, r2 - 0.5 * overlap);
        let w1 = Vector3::from(*w1);
        let w2 = Vector3::from(*w2);
        let relative_velocity = Vector3::from(*vrel) - (w1 * l1 + w2 * l2).cross(&n);
        let expected = law.update(
            &mut state,
            &ContactInput {
                overlap: *overlap,
                normal: n,
                relative_velocity,
                dt,
            },
        );
        let scale = expected.force.norm().max(1e-30);
        let moment = n.cross(&expected.force);
        for c in 0..3 {
            assert!(
                close(out.f[c], expected.force[c], scale),
                "case {k}: f {:?} vs {:?}",
                out.f,
                expected.force
            );
            assert!(
                close(out.f[3 + c], -expected.force[c], scale),
                "case {k}: reaction"
            );
            assert!(
                close(out.torque[c], -l1 * moment[c], scale * r1),
                "case {k}: torque i"
            );
            assert!(
                close(out.torque[3 + c], -l2 * moment[c], scale * r1),
                "case {k}: torque j"
            );
        }
        assert_eq!(out.history[0], state.normal.max_overlap, "case {k}: d_max");
        for c in 0..3 {
            let d = state.tangential.displacement;
            assert!(
                close(out.history[1 + c], d[c], d.norm().max(1e-30)),
                "case {k}: xi"
            );
        }
        assert_eq!(
            out.history[4], state.tangential.contact_radius,
            "case {k}: a"
        );
        assert_eq!(out.touch, 1);
        // virial of a pair with both atoms owned: Σ del·F
        assert!(close(out.virial[0], del.x * expected.force.x, scale * dist));
        assert!(close(out.virial[5], del.y * expected.force.z, scale * dist));
        let e =
            mdr_contact::normal::NormalLaw::elastic_energy(&law.normal, &state.normal, *overlap);
        assert!(close(out.energy, e, e.abs().max(1e-30)));
    }
    unsafe { mdrdem_free(handle) };
}

#[test]
fn the_partner_sees_the_opposite_force_with_the_partner_signs() {
    let handle = mdrdem_new(1);
    coeff(handle, (1, 1), STEEL_LINE).unwrap();
    init(handle, 1, 1).unwrap();
    let steel = Material::paper_steel();
    let (r, m) = (0.5e-2, steel.sphere_mass(0.5e-2));
    let n = Vector3::new(0.36, 0.48, 0.8);
    let dist = 2.0 * r - 7e-6;
    let history = [8e-6, 3e-8, -1e-8, 2e-8, 1.2e-4];
    let mut signs = [0.0; 5];
    assert_eq!(unsafe { mdrdem_partner_signs(5, signs.as_mut_ptr()) }, 0);
    let forward = TwoSpheres {
        x: [n.x * dist, n.y * dist, n.z * dist, 0.0, 0.0, 0.0],
        v: [0.1, -0.2, 0.05, 0.0, 0.0, 0.0],
        omega: [1.0, 2.0, 3.0, -1.0, 0.5, 0.0],
        radius: [r, r],
        rmass: [m, m],
        types: [1, 1],
    };
    let backward = TwoSpheres {
        x: [0.0, 0.0, 0.0, n.x * dist, n.y * dist, n.z * dist],
        v: [0.0, 0.0, 0.0, 0.1, -0.2, 0.05],
        omega: [-1.0, 0.5, 0.0, 1.0, 2.0, 3.0],
        ..forward
    };
    let seen: Vec<f64> = history.iter().zip(signs).map(|(v, s)| v * s).collect();
    let a = run(handle, &forward, &history, 1, 2, 1, 1e-8);
    let b = run(handle, &backward, &seen, 1, 2, 1, 1e-8);
    let scale = a.f[0].abs() + a.f[1].abs() + a.f[2].abs();
    assert!(scale > 0.0);
    for c in 0..3 {
        assert!(close(a.f[c], b.f[3 + c], scale), "{:?} {:?}", a.f, b.f);
        assert!(close(a.torque[c], b.torque[3 + c], scale * r));
    }
    for (k, (x, y)) in a.history.iter().zip(&b.history).enumerate() {
        assert!(close(*x, signs[k] * y, x.abs().max(1e-30)), "slot {k}");
    }
    unsafe { mdrdem_free(handle) };
}

#[test]
fn newton_off_with_a_ghost_partner_leaves_the_ghost_and_halves_the_virial() {
    let handle = mdrdem_new(1);
    coeff(handle, (1, 1), STEEL_LINE).unwrap();
    init(handle, 1, 1).unwrap();
    let steel = Material::paper_steel();
    let (r, m) = (0.5e-2, steel.sphere_mass(0.5e-2));
    let s = TwoSpheres {
        x: [2.0 * r - 5e-6, 0.0, 0.0, 0.0, 0.0, 0.0],
        v: [-0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
        omega: [0.0; 6],
        radius: [r, r],
        rmass: [m, m],
        types: [1, 1],
    };
    let owned = run(handle, &s, &[0.0; 5], 0, 2, 0, 1e-8);
    let ghost = run(handle, &s, &[0.0; 5], 0, 1, 0, 1e-8);
    assert_eq!(owned.f[0], ghost.f[0]);
    assert_eq!(ghost.f[3], 0.0);
    assert!(close(
        ghost.virial[0],
        0.5 * owned.virial[0],
        owned.virial[0].abs()
    ));
    unsafe { mdrdem_free(handle) };
}

#[test]
fn apart_pairs_without_history_are_skipped_and_with_history_keep_d_max() {
    let handle = mdrdem_new(1);
    coeff(handle, (1, 1), STEEL_LINE).unwrap();
    init(handle, 1, 1).unwrap();
    let (r, m) = (0.5e-2, Material::paper_steel().sphere_mass(0.5e-2));
    let s = TwoSpheres {
        x: [2.0 * r + 1e-6, 0.0, 0.0, 0.0, 0.0, 0.0],
        v: [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
        omega: [0.0; 6],
        radius: [r, r],
        rmass: [m, m],
        types: [1, 1],
    };
    let fresh = run(handle, &s, &[0.0; 5], 0, 2, 1, 1e-8);
    assert_eq!((fresh.touch, fresh.f), (0, [0.0; 6]));
    let old = run(handle, &s, &[9e-6, 1e-8, 0.0, 0.0, 1e-4], 1, 2, 1, 1e-8);
    assert_eq!(old.f, [0.0; 6]);
    assert_eq!(old.history, vec![9e-6, 0.0, 0.0, 0.0, 0.0]);
    unsafe { mdrdem_free(handle) };
}

#[test]
fn unset_cross_pairs_mix_materials_by_eq_3() {
    let handle = mdrdem_new(2);
    coeff(
        handle,
        (1, 1),
        "youngs 2.0e11 poisson 0.286 qc 3.8e5 theta 0.37",
    )
    .unwrap();
    coeff(
        handle,
        (2, 2),
        "youngs 7.0e10 poisson 0.33 qc 3.8e5 theta 0.37",
    )
    .unwrap();
    init(handle, 1, 2).unwrap();
    let (r, m) = (0.5e-2, 1e-3);
    let overlap = 1e-6; // elastic: F = (4/3) E* √R δ^{3/2}
    let s = TwoSpheres {
        x: [2.0 * r - overlap, 0.0, 0.0, 0.0, 0.0, 0.0],
        v: [0.0; 6],
        omega: [0.0; 6],
        radius: [r, r],
        rmass: [m, m],
        types: [1, 2],
    };
    let out = run(handle, &s, &[0.0; 5], 0, 2, 1, 1e-8);
    let estar = effective_modulus(
        &Material::new(2.0e11, 0.286, 1.0).unwrap(),
        &Material::new(7.0e10, 0.33, 1.0).unwrap(),
    );
    let hertz = 4.0 / 3.0 * estar * (0.5 * r).sqrt() * overlap.powf(1.5);
    assert!(
        (out.f[0] - hertz).abs() < 1e-9 * hertz,
        "{} vs {hertz}",
        out.f[0]
    );
    // different law parameters cannot be mixed: an explicit line is required
    coeff(
        handle,
        (2, 2),
        "youngs 7.0e10 poisson 0.33 qc 1.0e5 theta 0.37",
    )
    .unwrap();
    let err = init(handle, 1, 2).unwrap_err();
    assert!(
        err.contains("`qc`") && err.contains("pair_coeff 1 2"),
        "{err}"
    );
    coeff(
        handle,
        (1, 2),
        "youngs 1.0e11 poisson 0.3 qc 2.0e5 theta 0.37",
    )
    .unwrap();
    init(handle, 1, 2).unwrap();
    unsafe { mdrdem_free(handle) };
}

#[test]
fn bad_pair_coeff_lines_are_errors_naming_the_keyword() {
    let handle = mdrdem_new(1);
    let bad = [
        (
            "youngs 2e11 poisson 0.286 qc 3.8e5 theta 0.37 colour 3",
            "`colour`",
        ),
        ("youngs -2e11 poisson 0.286 qc 3.8e5 theta 0.37", "`youngs`"),
        ("youngs 2e11 poisson 0.7 qc 3.8e5 theta 0.37", "`poisson`"),
        ("youngs 2e11 poisson 0.286 qc -1 theta 0.37", "`qc`"),
        ("youngs 2e11 poisson 0.286 qc 3.8e5 theta 1.5", "`theta`"),
        (
            "youngs 2e11 poisson 0.286 qc 3.8e5 theta 0.37 friction -0.1",
            "`friction`",
        ),
        (
            "youngs 2e11 poisson 0.286 qc 3.8e5 theta 0.37 damping nan",
            "`damping`",
        ),
        (
            "youngs 2e11 poisson 0.286 qc 3.8e5 theta 0.37 rolling abc",
            "`rolling`",
        ),
        (
            "youngs 2e11 poisson 0.286 qc 3.8e5 theta 0.37 estar 0",
            "`estar`",
        ),
        ("poisson 0.286 qc 3.8e5 theta 0.37", "`youngs`"),
        ("youngs 2e11 poisson 0.286 qc 3.8e5 theta", "`theta`"),
        (
            "youngs 2e11 youngs 2e11 poisson 0.286 qc 3.8e5 theta 0.37",
            "`youngs`",
        ),
    ];
    for (line, keyword) in bad {
        let err = coeff(handle, (1, 1), line).unwrap_err();
        assert!(err.contains(keyword), "{line}: {err}");
    }
    // nothing was set, so the pair cannot be initialised
    assert!(init(handle, 1, 1).unwrap_err().contains("no pair_coeff"));
    assert_eq!(mdrdem_is_set(handle, 1, 1), 0);
    unsafe { mdrdem_free(handle) };
}

#[test]
fn rolling_resistance_widens_the_history_to_ten_values() {
    let handle = mdrdem_new(1);
    coeff(handle, (1, 1), &format!("{STEEL_LINE} rolling 0.1")).unwrap();
    init(handle, 1, 1).unwrap();
    assert_eq!(mdrdem_history_size(handle), 10);
    let (r, m) = (0.5e-2, Material::paper_steel().sphere_mass(0.5e-2));
    let s = TwoSpheres {
        x: [2.0 * r - 5e-6, 0.0, 0.0, 0.0, 0.0, 0.0],
        v: [0.0; 6],
        omega: [0.0, 0.0, 50.0, 0.0, 0.0, 0.0],
        radius: [r, r],
        rmass: [m, m],
        types: [1, 1],
    };
    let out = run(handle, &s, &[0.0; 10], 0, 2, 1, 1e-6);
    // the rolling spring resists ω_z: a torque against it, equal and opposite on j
    assert!(out.history[7] < 0.0, "{:?}", out.history);
    assert!(close(
        out.torque[2] - out.torque[5],
        2.0 * out.history[7],
        out.history[7].abs()
    ));
    unsafe { mdrdem_free(handle) };
}

/// LAMMPS's setup call (`history_update = 0`): with `dt = 0` the forces of the stored histories,
/// with the histories before a step and its `dt` the forces of that step; never a write.
#[test]
fn the_setup_call_writes_no_history() {
    let handle = mdrdem_new(1);
    coeff(handle, (1, 1), &format!("{STEEL_LINE} rolling 0.1")).unwrap();
    init(handle, 1, 1).unwrap();
    let (r, m) = (0.5e-2, Material::paper_steel().sphere_mass(0.5e-2));
    let n = Vector3::new(0.36, 0.48, 0.8);
    let dist = 2.0 * r - 7e-6;
    // a plastically loaded, sliding and rolling contact: every slot of the history in use
    let s = TwoSpheres {
        x: [n.x * dist, n.y * dist, n.z * dist, 0.0, 0.0, 0.0],
        v: [0.1, -0.2, 0.05, 0.0, 0.0, 0.0],
        omega: [1.0, 2.0, 3.0, -1.0, 0.5, 0.0],
        radius: [r, r],
        rmass: [m, m],
        types: [1, 1],
    };
    // ξ and the rolling torque in the contact plane (n·ξ = 0.36·3 − 0.48·1 − 0.8·0.75 = 0)
    let history = [
        8e-6, 3e-8, -1e-8, -7.5e-9, 1.2e-4, 2e-3, 1e-3, -1.5e-3, 5e3, 1e-7,
    ];
    let dt = 1e-6;
    // the stored histories (dt = 0): the forces of a step with no increment, nothing written
    let setup = run_with(handle, &s, &history, (1, 0), 2, 1, 0.0);
    assert_eq!(
        setup.history,
        history.to_vec(),
        "the setup call wrote a history"
    );
    assert_eq!(setup.touch, 1);
    let still = run_with(handle, &s, &history, (1, 1), 2, 1, 0.0);
    assert_eq!((setup.f, setup.torque), (still.f, still.torque));
    assert!(setup.f.iter().any(|f| *f != 0.0) && setup.torque.iter().any(|t| *t != 0.0));
    // a step's increment moves ξ and the rolling spring, and the forces
    let step = run_with(handle, &s, &history, (1, 1), 2, 1, dt);
    assert_ne!(step.history, history.to_vec());
    assert!((0..3).any(|c| step.f[c] != setup.f[c]));
    assert!((0..3).any(|c| step.torque[c] != setup.torque[c]));
    // the histories before that step with its dt: that step's forces, bit for bit, nothing written
    let replay = run_with(handle, &s, &history, (1, 0), 2, 1, dt);
    assert_eq!((replay.f, replay.torque), (step.f, step.torque));
    assert_eq!(replay.history, history.to_vec());
    // a setup call followed by a step is that step alone: nothing of the setup call remains
    for before in [&setup, &replay] {
        let after = run_with(handle, &s, &before.history, (before.touch, 1), 2, 1, dt);
        assert_eq!((after.f, &after.history), (step.f, &step.history));
    }

    // a new contact (touch 0) gets its normal force but no history and no touch flag
    let fresh = run_with(handle, &s, &[0.0; 10], (0, 0), 2, 1, 0.0);
    assert_eq!((fresh.touch, fresh.history), (0, vec![0.0; 10]));
    assert!(fresh.f[0] != 0.0);
    // an opened contact keeps its history (not released as a step would) and has no force
    let apart = TwoSpheres {
        x: [n.x * 2.1 * r, n.y * 2.1 * r, n.z * 2.1 * r, 0.0, 0.0, 0.0],
        ..s
    };
    let opened = run_with(handle, &apart, &history, (1, 0), 2, 1, dt);
    assert_eq!((opened.touch, opened.f), (1, [0.0; 6]));
    assert_eq!(opened.history, history.to_vec());
    let released = run_with(handle, &apart, &history, (1, 1), 2, 1, dt);
    assert_ne!(released.history, history.to_vec());

    // single() (compute pair/local) reports the force of the stored history
    let del = [s.x[0], s.x[1], s.x[2]];
    let (ri_rj_mi_mj, vrel) = ([r, r, m, m], [s.v[0], s.v[1], s.v[2]]);
    let mut out = [0.0; 5];
    let mut err = [0i8; 512];
    let rc = unsafe {
        mdrdem_single(
            handle,
            1,
            1,
            ri_rj_mi_mj.as_ptr(),
            del.as_ptr(),
            vrel.as_ptr(),
            s.omega.as_ptr(),
            s.omega[3..].as_ptr(),
            history.as_ptr(),
            out.as_mut_ptr(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    assert_eq!(rc, 0);
    let scale = setup.f[0].abs() + setup.f[1].abs() + setup.f[2].abs();
    for c in 0..3 {
        assert!(close(out[c], setup.f[c], scale), "{out:?} {:?}", setup.f);
    }
    assert!(close(out[4], 7e-6, 7e-6));
    unsafe { mdrdem_free(handle) };
}
