//! `fix wall/mdrdem`'s Rust side against mdr-contact called directly: a sphere on a wall gets the
//! force of mdr-contact's law for the sphere-on-half-space pair (the wall's material mixed with
//! the sphere type's by eq. 3), the history it writes is the law's new state, LAMMPS's setup call
//! writes nothing, a replayed setup call gives the forces of the step it repeats, curved walls
//! use the Hertz equivalent radius, and bad lines name the keyword.

use mdr_contact::damping::HertzianViscous;
use mdr_contact::material::{effective_modulus, effective_shear_modulus, ContactPair, Material};
use mdr_contact::model::{ContactInput, ContactModel, ContactState, NoBooks};
use mdr_contact::normal::{MdrElastoPlastic, MdrState};
use mdr_contact::tangential::{Mindlin, MindlinState};
use mdr_lammps::compute::MdrdemAtoms;
use mdr_lammps::ffi::mdrdem_wall_new;
use mdr_lammps::wall::{compute_wall, wall_effective_radius, MdrdemWallContacts};
use mdr_lammps::{CoeffLine, CoeffTable, PluginError, WallTable};
use nalgebra::Vector3;
use std::ffi::{CStr, CString};

const SPHERE_LINE: &str =
    "youngs 2.0e11 poisson 0.286 qc 3.8e5 theta 0.37 friction 0.3 damping 20 tangential_damping 0.5";
const WALL_LINE: &str =
    "youngs 1.0e11 poisson 0.3 qc 3.8e5 theta 0.37 friction 0.4 damping 20 tangential_damping 0.5";

fn line(text: &str) -> CoeffLine {
    CoeffLine::parse(&text.split_whitespace().collect::<Vec<_>>()).unwrap()
}

fn wall_for_type_1() -> WallTable {
    let mut table = CoeffTable::new(2);
    table.set((1, 1), (1, 1), line(SPHERE_LINE)).unwrap();
    let mut wall = WallTable::new(line(WALL_LINE));
    wall.init(&table).unwrap();
    wall
}

/// One sphere (type `itype`) above a zplane at 0; its row (touch, 5 values, 5 values before the
/// step) is the caller's.
struct Sphere {
    x: [f64; 3],
    v: [f64; 3],
    omega: [f64; 3],
    radius: f64,
    mass: f64,
    itype: i32,
}

/// Force and torque on the sphere, and the sum of the forces the wall reported.
type WallOutcome = ([f64; 3], [f64; 3], Vector3<f64>);

fn on_plane(
    wall: &WallTable,
    s: &Sphere,
    row: &mut [f64; 11],
    (history_update, replay): (i32, Option<[f64; 6]>),
    dt: f64,
) -> Result<WallOutcome, PluginError> {
    let mut f = [0.0; 3];
    let mut torque = [0.0; 3];
    let atoms = MdrdemAtoms {
        x: s.x.as_ptr(),
        v: s.v.as_ptr(),
        omega: s.omega.as_ptr(),
        f: f.as_mut_ptr(),
        torque: torque.as_mut_ptr(),
        radius: &s.radius,
        rmass: &s.mass,
        atom_type: &s.itype,
        nlocal: 1,
        nall: 1,
    };
    let atom = [0i32];
    let branch = [0.0, 0.0, s.x[2]];
    let vwall = [0.0; 3];
    let radii = [0.0; 2];
    let rows = [row.as_mut_ptr()];
    let replay_velocity = replay.unwrap_or([0.0; 6]);
    let contacts = MdrdemWallContacts {
        n: 1,
        atom: atom.as_ptr(),
        branch: branch.as_ptr(),
        wall_velocity: vwall.as_ptr(),
        wall_radius: radii.as_ptr(),
        row: rows.as_ptr(),
        dnum: 5,
        history_update,
        replay: replay.is_some() as i32,
        replay_velocity: replay_velocity.as_ptr(),
    };
    let total = unsafe { compute_wall(wall, &atoms, &contacts, dt) }?;
    Ok((f, torque, total))
}

fn steel_ball(z: f64) -> Sphere {
    let r = 0.635e-2;
    Sphere {
        x: [0.0, 0.0, z],
        v: [0.3, -0.1, -0.8],
        omega: [5.0, 2.0, -1.0],
        radius: r,
        mass: Material::paper_steel().sphere_mass(r),
        itype: 1,
    }
}

/// mdr-contact's law for the sphere on the wall's half-space (materials mixed by eq. 3 and
/// docs/theory.md §5, the wall line's law parameters), from `state` with `input`.
fn reference(
    s: &Sphere,
    state: &mut ContactState<MdrState, MindlinState, NoBooks>,
    input: &ContactInput,
) -> Vector3<f64> {
    let sphere = Material::new(2.0e11, 0.286, 7800.0).unwrap();
    let wall = Material::new(1.0e11, 0.3, 7800.0).unwrap();
    let pair = ContactPair::new(
        effective_modulus(&sphere, &wall),
        effective_shear_modulus(&sphere, &wall),
        s.radius,
        s.mass,
    )
    .unwrap();
    let model = ContactModel::new(MdrElastoPlastic::new(3.8e5, 0.37).unwrap())
        .with_tangential(Mindlin::new(0.4).unwrap())
        .with_damping(
            HertzianViscous::new(20.0)
                .unwrap()
                .with_tangential_ratio(0.5)
                .unwrap(),
        );
    model.bind(&pair).unwrap().update(state, input).force
}

#[test]
fn a_sphere_on_a_plane_gets_the_law_of_the_sphere_on_the_walls_half_space() {
    let wall = wall_for_type_1();
    let dt = 1e-8;
    for (nominal, d_max, xi) in [
        (2e-6, 0.0, [0.0; 3]),
        (9e-6, 8e-6, [1e-7, -2e-7, 0.0]),
        (4e-6, 9e-6, [0.0, 1e-7, 0.0]),
    ] {
        let s = steel_ball(0.635e-2 - nominal);
        let overlap = s.radius - s.x[2];
        let mut row = [0.0; 11];
        row[0] = 1.0;
        row[1] = d_max;
        row[2..5].copy_from_slice(&xi);
        row[5] = if d_max > 0.0 { 1e-4 } else { 0.0 };
        let before = row;
        let (f, torque, total) = on_plane(&wall, &s, &mut row, (1, None), dt).unwrap();

        let lever = s.radius - 0.5 * overlap;
        let normal = Vector3::z();
        let w = Vector3::from(s.omega);
        let input = ContactInput {
            overlap,
            normal,
            relative_velocity: Vector3::from(s.v) - (w * lever).cross(&normal),
            dt,
        };
        let mut state = ContactState {
            normal: MdrState { max_overlap: d_max },
            tangential: MindlinState {
                displacement: Vector3::from(xi),
                contact_radius: before[5],
            },
            books: NoBooks,
        };
        let force = reference(&s, &mut state, &input);
        let expected_torque = normal.cross(&force) * -lever;
        for c in 0..3 {
            assert!(
                (f[c] - force[c]).abs() <= 1e-12 * force.norm(),
                "{overlap}: {f:?} {force}"
            );
            assert!(
                (torque[c] - expected_torque[c]).abs() <= 1e-12 * expected_torque.norm().max(1e-30)
            );
            assert_eq!(total[c], f[c]);
        }
        assert!(force.z > 0.0, "the wall pushes the sphere away");
        assert_eq!(row[0], 1.0);
        assert_eq!(row[1], state.normal.max_overlap);
        assert_eq!(&row[2..5], state.tangential.displacement.as_slice());
        assert_eq!(row[5], state.tangential.contact_radius);
        assert_eq!(
            &row[6..11],
            &before[6..11],
            "the values before the step are the fix's"
        );
    }
}

#[test]
fn the_setup_call_writes_nothing_and_a_replay_repeats_the_step() {
    let wall = wall_for_type_1();
    let dt = 1e-8;
    let s = steel_ball(0.635e-2 - 7e-6);
    let mut row = [0.0; 11];
    row[0] = 1.0;
    row[1] = 9e-6;
    row[2] = 1e-7;
    row[5] = 1e-4;
    // the step, with the values before it kept in slots 6..11 as the fix keeps them
    row.copy_within(1..6, 6);
    let (step_force, step_torque, _) = on_plane(&wall, &s, &mut row, (1, None), dt).unwrap();
    let after = row;
    // a plain setup call: the stored histories, no increment; nothing written
    let (setup_force, _, _) = on_plane(&wall, &s, &mut row, (0, None), 0.0).unwrap();
    assert_eq!(row, after);
    assert!(setup_force[2] > 0.0);
    // a replayed setup call with other current velocities: the forces of the step, bit for bit
    let mut moved = steel_ball(0.635e-2 - 7e-6);
    moved.v = [9.0, 9.0, 9.0];
    moved.omega = [0.0; 3];
    let mut seen = [0.0; 6];
    seen[..3].copy_from_slice(&s.v);
    seen[3..].copy_from_slice(&s.omega);
    let (replayed, replayed_torque, _) =
        on_plane(&wall, &moved, &mut row, (0, Some(seen)), dt).unwrap();
    assert_eq!(row, after);
    assert_eq!(replayed, step_force);
    assert_eq!(replayed_torque, step_torque);
}

#[test]
fn a_separated_sphere_keeps_d_max_and_releases_its_spring() {
    let wall = wall_for_type_1();
    let s = steel_ball(0.635e-2 + 1e-6);
    let mut row = [0.0; 11];
    row[0] = 1.0;
    row[1] = 9e-6;
    row[2] = 1e-7;
    row[5] = 1e-4;
    let (f, _, _) = on_plane(&wall, &s, &mut row, (1, None), 1e-8).unwrap();
    assert_eq!(f, [0.0; 3]);
    assert_eq!(row[1], 9e-6, "d_max stays");
    assert_eq!(&row[2..5], &[0.0; 3], "the Mindlin spring is released");
    // without a history, a separated sphere is skipped
    let mut fresh = [0.0; 11];
    on_plane(&wall, &s, &mut fresh, (1, None), 1e-8).unwrap();
    assert_eq!(fresh, [0.0; 11]);
}

#[test]
fn a_type_without_a_material_cannot_touch_the_wall() {
    let wall = wall_for_type_1();
    let mut s = steel_ball(0.635e-2 - 1e-6);
    s.itype = 2;
    let mut row = [0.0; 11];
    let err = on_plane(&wall, &s, &mut row, (1, None), 1e-8).unwrap_err();
    assert!(matches!(err, PluginError::WallTypeNotSet(2)), "{err}");
    assert!(err.to_string().contains("pair_coeff 2 2"));
}

#[test]
fn curved_walls_use_the_hertz_equivalent_radius() {
    let (r, big) = (0.5, 15.0);
    assert_eq!(wall_effective_radius(r, [0.0, 0.0]).unwrap(), r);
    // inside a cylinder: R' = r along the axis, 1/R'' = 1/r - 1/R around it
    let inside = wall_effective_radius(r, [-big, 0.0]).unwrap();
    let around = 1.0 / (1.0 / r - 1.0 / big);
    assert!((inside - (r * around).sqrt()).abs() < 1e-15);
    assert!(inside > r);
    // outside a sphere: both directions curved, 1/R = 1/r + 1/R_w
    let outside = wall_effective_radius(r, [big, big]).unwrap();
    assert!((outside - 1.0 / (1.0 / r + 1.0 / big)).abs() < 1e-15);
    // a concave wall tighter than the sphere is refused
    assert!(matches!(
        wall_effective_radius(r, [-0.4, 0.0]),
        Err(PluginError::WallTooCurved { .. })
    ));
}

#[test]
fn bad_wall_lines_are_errors_naming_the_keyword() {
    for (text, keyword) in [
        ("youngs -1 poisson 0.3 qc 1 theta 0.3", "youngs"),
        (
            "youngs 1e5 poisson 0.3 qc 1 theta 0.3 friction -1",
            "friction",
        ),
        ("youngs 1e5 poisson 0.3 qc 1 theta 0.3 colour 3", "colour"),
        ("poisson 0.3 qc 1 theta 0.3", "youngs"),
    ] {
        let words: Vec<CString> = text
            .split_whitespace()
            .map(|w| CString::new(w).unwrap())
            .collect();
        let ptrs: Vec<*const std::ffi::c_char> = words.iter().map(|w| w.as_ptr()).collect();
        let mut err = [0 as std::ffi::c_char; 512];
        let handle = unsafe {
            mdrdem_wall_new(
                ptrs.len() as i32,
                ptrs.as_ptr(),
                err.as_mut_ptr(),
                err.len(),
            )
        };
        assert!(handle.is_null());
        let message = unsafe { CStr::from_ptr(err.as_ptr()) }
            .to_string_lossy()
            .into_owned();
        assert!(
            message.contains(&format!("`{keyword}`")),
            "{text}: {message}"
        );
    }
}
