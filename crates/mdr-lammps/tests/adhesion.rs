//! The `adhesion` keyword: parsing, mixing between types, the history layout, the neck's reach
//! against JKR's snap-off, and a held contact at a separation driven through the batched loop
//! against mdr-contact's adhesive law.

use mdr_contact::material::ContactPair;
use mdr_contact::normal::{
    AdhesiveMdr, AdhesiveMdrState, MdrElastoPlastic, NormalLaw, NormalModel,
};
use mdr_lammps::compute::{compute, MdrdemAtoms, MdrdemNeighbours, MdrdemTally};
use mdr_lammps::history::HistoryLayout;
use mdr_lammps::{CoeffLine, CoeffTable, PluginError};

const SOFT: &str = "youngs 1.0e9 poisson 0.3 qc 20 theta 0.1";

fn line(extra: &str) -> Result<CoeffLine, PluginError> {
    let words: Vec<String> = format!("{SOFT} {extra}")
        .split_whitespace()
        .map(str::to_string)
        .collect();
    CoeffLine::parse(&words)
}

#[test]
fn bad_adhesion_values_name_the_keyword() {
    for bad in [
        "adhesion -0.1",
        "adhesion nan",
        "adhesion inf",
        "adhesion -inf",
        "adhesion",
    ] {
        let e = line(bad).expect_err(bad).to_string();
        assert!(e.contains("`adhesion`"), "{bad}: {e}");
    }
    assert_eq!(line("adhesion 0.25").unwrap().adhesion, 0.25);
    assert_eq!(line("").unwrap().adhesion, 0.0);
}

/// Types with different works of adhesion mix by the geometric mean (the other law parameters
/// must still agree); the moduli mix as without adhesion.
#[test]
fn work_of_adhesion_mixes_by_the_geometric_mean() {
    let mut table = CoeffTable::new(2);
    table
        .set((1, 1), (1, 1), line("adhesion 0.1").unwrap())
        .unwrap();
    table
        .set((2, 2), (2, 2), line("adhesion 0.4").unwrap())
        .unwrap();
    let mixed = table.init_one(1, 2).unwrap();
    assert!((mixed.adhesion - 0.2).abs() <= 1e-16);
    assert_eq!(table.init_one(1, 1).unwrap().adhesion, 0.1);
    let mut dry = CoeffTable::new(2);
    dry.set((1, 1), (1, 1), line("").unwrap()).unwrap();
    dry.set((2, 2), (2, 2), line("adhesion 0.4").unwrap())
        .unwrap();
    assert_eq!(dry.init_one(1, 2).unwrap().adhesion, 0.0);
    assert_eq!(
        dry.init_one(1, 2).unwrap().effective_modulus,
        mixed.effective_modulus
    );
}

/// The adhesive slot is one more value after the base or rolling slots, seen with the same sign
/// from the partner; the layouts without adhesion keep their sizes (old restart files).
#[test]
fn history_layouts() {
    for (rolling, adhesion, size) in [
        (false, false, 5),
        (false, true, 6),
        (true, false, 10),
        (true, true, 11),
    ] {
        let layout = HistoryLayout { rolling, adhesion };
        assert_eq!(layout.size(), size);
        assert_eq!(HistoryLayout::of_size(size).unwrap(), layout);
        let signs = layout.partner_signs();
        assert_eq!(signs.len(), size);
        if adhesion {
            assert_eq!(signs[size - 1], 1.0);
        }
        assert_eq!(&signs[1..4], &[-1.0; 3]);
    }
    assert!(HistoryLayout::of_size(7).is_err());
}

/// The neck's reach is the smallest overlap of the JKR unloading branch
/// `δ(a) = a²/R − √(2π a Δγ / E*)` (docs/theory.md eq. A8), found here by scanning `a`.
#[test]
fn neck_reach_is_the_jkr_snap_off() {
    let mut table = CoeffTable::new(1);
    table
        .set((1, 1), (1, 1), line("adhesion 0.1").unwrap())
        .unwrap();
    let model = table.init_one(1, 1).unwrap();
    let (r, e) = (5e-6, model.effective_modulus);
    let delta = |a: f64| a * a / r - (2.0 * std::f64::consts::PI * a * 0.1 / e).sqrt();
    let lowest = (0..=200_000)
        .map(|k| delta(10f64.powf(-9.0 + 4.0 * k as f64 / 200_000.0)))
        .fold(f64::INFINITY, f64::min);
    let reach = model.neck_reach(r);
    assert!((reach + lowest).abs() <= 1e-6 * reach, "{reach} {lowest}");
    let mut dry = CoeffTable::new(1);
    dry.set((1, 1), (1, 1), line("").unwrap()).unwrap();
    assert_eq!(dry.init_one(1, 1).unwrap().neck_reach(r), 0.0);
}

/// Two spheres pressed to 30 nm and pulled apart step by step to a separation of 12 nm: each
/// step's force from the batched loop equals mdr-contact's adhesive law driven along the same
/// overlaps; the force is tensile at positive separations while the neck holds, and the contact
/// lets go where the law does (after which the loop applies no force).
#[test]
fn a_held_neck_pulls_across_a_separation() {
    let mut table = CoeffTable::new(1);
    table
        .set((1, 1), (1, 1), line("adhesion 0.1").unwrap())
        .unwrap();
    let model = table.init_one(1, 1).unwrap();
    let (radius, mass) = (1e-5, 4.0e-12);
    let pair = ContactPair::new(
        model.effective_modulus,
        model.effective_shear_modulus,
        radius / 2.0,
        mass / 2.0,
    )
    .unwrap();
    let law = AdhesiveMdr::new(MdrElastoPlastic::new(20.0, 0.1).unwrap(), 0.1)
        .unwrap()
        .bind(&pair)
        .unwrap();
    let layout = HistoryLayout::for_table(&table);
    assert_eq!(layout.size(), 6);
    let mut history = vec![0.0; layout.size()];
    let mut touch = [0i32];
    let mut reference = AdhesiveMdrState::default();
    let (mut tensile_apart, mut let_go) = (0, false);
    let overlaps = (0..=300)
        .map(|k| 30e-9 * (k as f64 / 300.0))
        .chain((0..=420).map(|k| 30e-9 - 1e-10 * k as f64));
    for overlap in overlaps {
        let x = [0.0, 0.0, 0.0, 2.0 * radius - overlap, 0.0, 0.0];
        let zeros = [0.0; 6];
        let mut f = [0.0; 6];
        let mut torque = [0.0; 6];
        let (radii, masses, types) = ([radius; 2], [mass; 2], [1i32; 2]);
        let atoms = MdrdemAtoms {
            x: x.as_ptr(),
            v: zeros.as_ptr(),
            omega: zeros.as_ptr(),
            f: f.as_mut_ptr(),
            torque: torque.as_mut_ptr(),
            radius: radii.as_ptr(),
            rmass: masses.as_ptr(),
            atom_type: types.as_ptr(),
            nlocal: 2,
            nall: 2,
        };
        let (ilist, numneigh, jlist, offset) = ([0i32], [1i32, 0], [1i32], [0i64, 1]);
        let firstneigh = [jlist.as_ptr(), std::ptr::null()];
        let list = MdrdemNeighbours {
            inum: 1,
            ilist: ilist.as_ptr(),
            numneigh: numneigh.as_ptr(),
            firstneigh: firstneigh.as_ptr(),
            neighmask: 0x1FFF_FFFF,
            offset: offset.as_ptr(),
            touch: touch.as_mut_ptr(),
            history: history.as_mut_ptr(),
            dnum: history.len() as i32,
            history_update: 1,
        };
        let tally = MdrdemTally {
            newton_pair: 1,
            eflag_global: 0,
            vflag_global: 0,
            eng_vdwl: std::ptr::null_mut(),
            virial: std::ptr::null_mut(),
            eatom: std::ptr::null_mut(),
            vatom: std::ptr::null_mut(),
        };
        unsafe { compute(&table, &atoms, &list, &tally, 1e-9) }.unwrap();
        // the overlap the loop sees (the position rounds it)
        let seen = 2.0 * radius - x[3];
        let expected = law.update(&mut reference, seen).force;
        // force on sphere 1 (at the origin) along x: −F_n (sphere 2 sits at +x)
        let applied = -f[0];
        assert!(
            (applied - expected).abs() <= 1e-12 * expected.abs().max(1e-9),
            "overlap {overlap:e}: {applied:e} vs {expected:e}"
        );
        if overlap < 0.0 && applied < 0.0 {
            tensile_apart += 1;
        }
        if overlap < 0.0 && reference.contact_radius == 0.0 {
            let_go = true;
            assert_eq!(applied, 0.0);
        }
    }
    assert!(
        tensile_apart > 10,
        "{tensile_apart} tensile steps at a separation"
    );
    assert!(let_go);
}

/// A sphere pressed onto an adhesive `fix wall/mdrdem` plane and lifted off step by step: each
/// step's force from the wall kernel equals mdr-contact's adhesive law for the sphere on the
/// wall's half-space (`E*` of the two materials by eq. 3, `R = r`), tensile above the plane
/// while the neck holds, none after it lets go; the wall's reach coefficient is the neck's.
#[test]
fn a_wall_holds_a_neck_above_the_plane() {
    use mdr_contact::material::{effective_modulus, effective_shear_modulus, Material};
    use mdr_lammps::wall::{compute_wall, MdrdemWallContacts};
    use mdr_lammps::WallTable;
    let mut table = CoeffTable::new(1);
    table.set((1, 1), (1, 1), line("").unwrap()).unwrap();
    let mut wall = WallTable::new(line("adhesion 0.1").unwrap());
    wall.init(&table).unwrap();
    let layout = wall.layout();
    assert_eq!(layout.size(), 6);
    let (radius, mass) = (1e-5, 4.0e-12);
    let soft = Material::new(1.0e9, 0.3, 1000.0).unwrap();
    let pair = ContactPair::new(
        effective_modulus(&soft, &soft),
        effective_shear_modulus(&soft, &soft),
        radius,
        mass,
    )
    .unwrap();
    let law = AdhesiveMdr::new(MdrElastoPlastic::new(20.0, 0.1).unwrap(), 0.1)
        .unwrap()
        .bind(&pair)
        .unwrap();
    let reach = 0.75
        * (std::f64::consts::PI.powi(2) * 0.01 * radius / pair.effective_modulus().powi(2)).cbrt();
    assert!((wall.neck_coefficient(1) * radius.cbrt() - reach).abs() <= 1e-12 * reach);
    let mut row = vec![0.0; 1 + 2 * layout.size()];
    let mut reference = AdhesiveMdrState::default();
    let (mut tensile_apart, mut let_go) = (0, false);
    let overlaps = (0..=100)
        .map(|k| 20e-9 * (k as f64 / 100.0))
        .chain((0..=400).map(|k| 20e-9 - 1e-10 * k as f64));
    for overlap in overlaps {
        let x = [0.0, 0.0, radius - overlap];
        let zeros = [0.0; 3];
        let mut f = [0.0; 3];
        let mut torque = [0.0; 3];
        let itype = 1i32;
        let atoms = MdrdemAtoms {
            x: x.as_ptr(),
            v: zeros.as_ptr(),
            omega: zeros.as_ptr(),
            f: f.as_mut_ptr(),
            torque: torque.as_mut_ptr(),
            radius: &radius,
            rmass: &mass,
            atom_type: &itype,
            nlocal: 1,
            nall: 1,
        };
        let atom = [0i32];
        let branch = [0.0, 0.0, x[2]];
        let (vwall, radii) = ([0.0; 3], [0.0; 2]);
        let rows = [row.as_mut_ptr()];
        let contacts = MdrdemWallContacts {
            n: 1,
            atom: atom.as_ptr(),
            branch: branch.as_ptr(),
            wall_velocity: vwall.as_ptr(),
            wall_radius: radii.as_ptr(),
            row: rows.as_ptr(),
            dnum: layout.size() as i32,
            history_update: 1,
            replay: 0,
            replay_velocity: std::ptr::null(),
        };
        unsafe { compute_wall(&wall, &atoms, &contacts, 1e-9) }.unwrap();
        let seen = radius - x[2];
        let expected = if seen > 0.0 || row[0] != 0.0 {
            law.update(&mut reference, seen).force
        } else {
            0.0
        };
        assert!(
            (f[2] - expected).abs() <= 1e-12 * expected.abs().max(1e-9),
            "overlap {seen:e}: {} vs {expected:e}",
            f[2]
        );
        if seen < 0.0 && f[2] < 0.0 {
            tensile_apart += 1;
        }
        if seen < 0.0 && row[0] != 0.0 && reference.contact_radius == 0.0 {
            let_go = true;
            assert_eq!(f[2], 0.0);
        }
    }
    assert!(
        tensile_apart > 10,
        "{tensile_apart} tensile steps above the plane"
    );
    assert!(let_go);
}
