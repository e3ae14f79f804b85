//! The batched force loop: one call per neighbour list. For every pair of the half list it
//! binds the pair's law (cached while consecutive pairs share types, radii and masses), loads the
//! contact's history from the per-neighbour history array, calls mdr-contact's
//! [`ContactLaw::update`](mdr_contact::model::ContactLaw::update) and the rolling law, and adds
//! forces, torques and the energy/virial tallies.
//!
//! Contact kinematics are those of two spheres in mdr-rapier's kernel (`SphereArms`): the contact
//! point sits at mid-overlap, `lever = r − δ/2` from each centre, so the contact-point velocity
//! of `i` relative to `j` is `v_i − v_j − (ℓ_i ω_i + ℓ_j ω_j) × n` and the torques are
//! `−ℓ n × F` on each body (plus the rolling torque).

use crate::coeffs::{CoeffTable, PairModel};
use crate::contact::{add3, respond, vec3};
use crate::error::PluginError;
use crate::history::{self, load, store, HistoryLayout, PairLaw, PluginNormalLaw};
use mdr_contact::material::ContactPair;
use mdr_contact::model::ContactInput;
use mdr_contact::normal::{AdhesiveMdrLaw, MdrLaw};
use mdr_contact::rolling::{EpsdRollingLaw, RollingModel};
use nalgebra::Vector3;

/// Per-atom arrays of LAMMPS (`atom->x[0]` etc.: `3 × nall` contiguous doubles).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct MdrdemAtoms {
    /// Positions, `3 × nall`.
    pub x: *const f64,
    /// Velocities, `3 × nall`.
    pub v: *const f64,
    /// Angular velocities, `3 × nall`.
    pub omega: *const f64,
    /// Forces (accumulated into), `3 × nall`.
    pub f: *mut f64,
    /// Torques (accumulated into), `3 × nall`.
    pub torque: *mut f64,
    /// Radii, `nall`.
    pub radius: *const f64,
    /// Masses, `nall`.
    pub rmass: *const f64,
    /// Atom types (1-based), `nall`.
    pub atom_type: *const i32,
    /// Owned atoms.
    pub nlocal: i32,
    /// Owned + ghost atoms.
    pub nall: i32,
}

/// A half neighbour list and its per-neighbour history (`offset[i] + jj` indexes the history
/// of the `jj`-th neighbour of atom `i`: flag `touch[k]`, values `history[k·dnum ..]`).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct MdrdemNeighbours {
    /// Number of `i` atoms.
    pub inum: i32,
    /// The `i` atoms.
    pub ilist: *const i32,
    /// Neighbour count of each atom.
    pub numneigh: *const i32,
    /// Neighbours of each atom (masked with `neighmask`).
    pub firstneigh: *const *const i32,
    /// The bits of a neighbour entry that hold the atom index (LAMMPS `NEIGHMASK`).
    pub neighmask: i32,
    /// First history slot of each atom's neighbours, `nall`.
    pub offset: *const i64,
    /// Touch flag per neighbour (1 while the contact has a history).
    pub touch: *mut i32,
    /// History values per neighbour, `dnum` each.
    pub history: *mut f64,
    /// Values per contact (must equal the layout's size).
    pub dnum: i32,
    /// 1: advance every contact's history by this call (a step); 0: forces only, leaving
    /// `touch` and `history` untouched (LAMMPS's setup call at the start of every `run`, see
    /// [`compute`]).
    pub history_update: i32,
}

/// Energy and virial tallies (LAMMPS `Pair::ev_tally_xyz` conventions).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct MdrdemTally {
    /// `force->newton_pair`.
    pub newton_pair: i32,
    /// Add to `eng_vdwl` (the normal elastic energy of every contact).
    pub eflag_global: i32,
    /// Add to `virial[6]`.
    pub vflag_global: i32,
    /// Global energy accumulator.
    pub eng_vdwl: *mut f64,
    /// Global virial accumulator, 6 values.
    pub virial: *mut f64,
    /// Per-atom energy, `nall` (null when not requested).
    pub eatom: *mut f64,
    /// Per-atom virial, `6 × nall` (null when not requested).
    pub vatom: *mut f64,
}

/// The law of the last bound pair and what it was bound to: the types, radii and masses of its
/// two atoms (compared bitwise).
struct BoundCache<N> {
    itype: i32,
    jtype: i32,
    ri: u64,
    rj: u64,
    mi: u64,
    mj: u64,
    law: PairLaw<N>,
    rolling: EpsdRollingLaw,
}

impl<N> BoundCache<N> {
    /// Whether the law is bound to atom `i`'s side of a pair (checked once per row of the list).
    #[inline(always)]
    fn binds_i(&self, itype: i32, ri: f64, mi: f64) -> bool {
        self.itype == itype && self.ri == ri.to_bits() && self.mi == mi.to_bits()
    }

    /// Whether the law is bound to atom `j`'s side of a pair (checked per contact).
    #[inline(always)]
    fn binds_j(&self, jtype: i32, rj: f64, mj: f64) -> bool {
        self.jtype == jtype && self.rj == rj.to_bits() && self.mj == mj.to_bits()
    }
}

#[inline(always)]
fn bind<N: PluginNormalLaw>(
    model: &PairModel,
    ri: f64,
    rj: f64,
    mi: f64,
    mj: f64,
) -> Result<(PairLaw<N>, EpsdRollingLaw), mdr_contact::ContactError> {
    // Effective radius and reduced mass of two spheres, as ContactPair::sphere_on_sphere.
    let pair = ContactPair::new(
        model.effective_modulus,
        model.effective_shear_modulus,
        ri * rj / (ri + rj),
        mi * mj / (mi + mj),
    )?;
    Ok((N::bind(model, &pair)?, model.rolling.bind(&pair)?))
}

/// One atom of a pair: index, type, radius and mass.
#[derive(Clone, Copy)]
struct PairAtom {
    index: usize,
    atom_type: i32,
    radius: f64,
    mass: f64,
}

/// Bind the law of a pair whose types, radii or masses differ from the cached pair's (out of the
/// contact loop: a bed of equal spheres binds once per call).
#[cold]
#[inline(never)]
fn rebind<N: PluginNormalLaw>(
    table: &CoeffTable,
    i: PairAtom,
    j: PairAtom,
) -> Result<BoundCache<N>, PluginError> {
    let model = table
        .model(i.atom_type as usize, j.atom_type as usize)
        .ok_or(PluginError::NotSet {
            i: i.atom_type as usize,
            j: j.atom_type as usize,
        })?;
    let (law, rolling) =
        bind::<N>(model, i.radius, j.radius, i.mass, j.mass).map_err(|source| {
            PluginError::Contact {
                i: i.index,
                j: j.index,
                source,
            }
        })?;
    Ok(BoundCache {
        itype: i.atom_type,
        jtype: j.atom_type,
        ri: i.radius.to_bits(),
        rj: j.radius.to_bits(),
        mi: i.mass.to_bits(),
        mj: j.mass.to_bits(),
        law,
        rolling,
    })
}

/// A contact whose spheres separated (and whose neck, for an adhesive law, let go): the law sees
/// the separation (MDR keeps `d_max` for a re-touch, the Mindlin and rolling springs are
/// released) and writes its history; no force. Out of the contact loop: rare in a dense bed.
#[cold]
#[inline(never)]
unsafe fn release<N: PluginNormalLaw, const ROLLING: bool>(
    bound: &BoundCache<N>,
    values: &mut [f64],
    overlap: f64,
    dt: f64,
) {
    let state = load::<N, ROLLING>(values);
    history::release::<N, ROLLING>(&bound.law, &bound.rolling, state, values, overlap, dt);
}

/// The global energy and virial of one call, summed before they are added to LAMMPS's.
#[derive(Default)]
struct EnergyVirial {
    energy: f64,
    virial: [f64; 6],
}

/// One contact's energy and virial (LAMMPS `ev_tally_xyz`: a pair with a ghost `j` under newton
/// off counts half). Out of the contact loop: LAMMPS asks for them on output steps only.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
unsafe fn tally_contact<N: PluginNormalLaw>(
    tally: &MdrdemTally,
    sums: &mut EnergyVirial,
    law: &N,
    state: &N::State,
    (i, j, j_owned): (usize, usize, bool),
    overlap: f64,
    delta: &Vector3<f64>,
    force: &Vector3<f64>,
) {
    let share = if j_owned { 1.0 } else { 0.5 };
    if tally.eflag_global != 0 || !tally.eatom.is_null() {
        let e = law.elastic_energy(state, overlap);
        sums.energy += share * e;
        if !tally.eatom.is_null() {
            *tally.eatom.add(i) += 0.5 * e;
            if j_owned {
                *tally.eatom.add(j) += 0.5 * e;
            }
        }
    }
    if tally.vflag_global != 0 || !tally.vatom.is_null() {
        let v = [
            delta.x * force.x,
            delta.y * force.y,
            delta.z * force.z,
            delta.x * force.y,
            delta.x * force.z,
            delta.y * force.z,
        ];
        for (sum, vc) in sums.virial.iter_mut().zip(v) {
            *sum += share * vc;
        }
        if !tally.vatom.is_null() {
            for (c, vc) in v.iter().enumerate() {
                *tally.vatom.add(6 * i + c) += 0.5 * vc;
                if j_owned {
                    *tally.vatom.add(6 * j + c) += 0.5 * vc;
                }
            }
        }
    }
}

/// One call for a whole neighbour list.
///
/// With `list.history_update == 0` the law updates a copy of each contact's state and neither
/// `touch` nor `history` is written: the shim passes it in LAMMPS's setup call
/// (`Verlet::setup`, `update->setupflag = 1`), made at the start of every `run` at the
/// positions the last step left, whose increments the histories already hold. Otherwise every
/// extra `run` command would add one more increment to every contact's history, and a run split
/// into two `run` commands (or continued from a restart file) would leave the uninterrupted
/// run's trajectory. LAMMPS's own history styles do not update either (`shearupdate = 0` in
/// `pair gran/hooke/history` and `gran/hertz/history`, `history_update = 0` in
/// `pair granular`). The shim gives either the stored histories with `dt = 0` (no tangential
/// displacement or rolling rotation increment: the forces of the stored histories, as those
/// styles compute them), or the histories before the step the last run ended on with that
/// step's velocities and `dt`, which repeats that step's force call
/// (`shim/fix_mdrdem_history.cpp`).
///
/// # Safety
/// Every pointer must be valid for the sizes documented on the structs (LAMMPS's own arrays),
/// `offset[i] + numneigh[i] ≤ len(touch)` for every listed `i`, and `history` must hold
/// `dnum` values per `touch` entry.
pub unsafe fn compute(
    table: &CoeffTable,
    atoms: &MdrdemAtoms,
    list: &MdrdemNeighbours,
    tally: &MdrdemTally,
    dt: f64,
) -> Result<(), PluginError> {
    let layout = HistoryLayout::for_table(table);
    if list.dnum as usize != layout.size() {
        return Err(PluginError::Abi("dnum differs from the history layout"));
    }
    if layout.adhesion {
        compute_law::<AdhesiveMdrLaw>(table, atoms, list, tally, dt, layout.rolling)
    } else {
        compute_law::<MdrLaw>(table, atoms, list, tally, dt, layout.rolling)
    }
}

unsafe fn compute_law<N: PluginNormalLaw>(
    table: &CoeffTable,
    atoms: &MdrdemAtoms,
    list: &MdrdemNeighbours,
    tally: &MdrdemTally,
    dt: f64,
    rolling: bool,
) -> Result<(), PluginError> {
    match (rolling, list.history_update != 0) {
        (true, true) => compute_with::<N, true, true>(table, atoms, list, tally, dt),
        (false, true) => compute_with::<N, false, true>(table, atoms, list, tally, dt),
        (true, false) => compute_with::<N, true, false>(table, atoms, list, tally, dt),
        (false, false) => compute_with::<N, false, false>(table, atoms, list, tally, dt),
    }
}

/// The loop, compiled twice on x86-64: for the CPU the plugin was built for and, chosen at run
/// time when the CPU has it, with AVX2 (its three-operand instructions need about a fifth fewer
/// instructions per contact). Both run the same operations in the same order (Rust never fuses a
/// multiplication and an addition on its own), so they give the same bits.
unsafe fn compute_with<N: PluginNormalLaw, const ROLLING: bool, const UPDATE: bool>(
    table: &CoeffTable,
    atoms: &MdrdemAtoms,
    list: &MdrdemNeighbours,
    tally: &MdrdemTally,
    dt: f64,
) -> Result<(), PluginError> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        return compute_avx2::<N, ROLLING, UPDATE>(table, atoms, list, tally, dt);
    }
    compute_rows::<N, ROLLING, UPDATE>(table, atoms, list, tally, dt)
}

/// [`compute_rows`] with AVX2 (the caller checks that the CPU has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn compute_avx2<N: PluginNormalLaw, const ROLLING: bool, const UPDATE: bool>(
    table: &CoeffTable,
    atoms: &MdrdemAtoms,
    list: &MdrdemNeighbours,
    tally: &MdrdemTally,
    dt: f64,
) -> Result<(), PluginError> {
    compute_rows::<N, ROLLING, UPDATE>(table, atoms, list, tally, dt)
}

/// The loop over the list's rows; `UPDATE = false` writes neither `touch` nor `history`. A
/// contact is evaluated while the spheres overlap and, for an adhesive law, while its neck holds
/// at a separation ([`NormalLaw::holds`](mdr_contact::normal::NormalLaw::holds)); the neighbour
/// cut-off covers the neck's reach ([`PairModel::neck_reach`]).
#[inline(always)]
unsafe fn compute_rows<N: PluginNormalLaw, const ROLLING: bool, const UPDATE: bool>(
    table: &CoeffTable,
    atoms: &MdrdemAtoms,
    list: &MdrdemNeighbours,
    tally: &MdrdemTally,
    dt: f64,
) -> Result<(), PluginError> {
    // Values per contact, a constant of this instance (the caller checked `list.dnum`).
    let dnum = HistoryLayout {
        rolling: ROLLING,
        adhesion: N::ADHESIVE,
    }
    .size();
    let nlocal = atoms.nlocal as usize;
    let newton = tally.newton_pair != 0;
    let mask = list.neighmask;
    let ev = tally.eflag_global != 0
        || !tally.eatom.is_null()
        || tally.vflag_global != 0
        || !tally.vatom.is_null();
    let mut cache: Option<BoundCache<N>> = None;
    let mut sums = EnergyVirial::default();
    for ii in 0..list.inum as usize {
        let i = *list.ilist.add(ii) as usize;
        let jlist = *list.firstneigh.add(i);
        let jnum = *list.numneigh.add(i) as usize;
        let base = *list.offset.add(i) as usize;
        let xi = vec3(atoms.x, i);
        let ri = *atoms.radius.add(i);
        let itype = *atoms.atom_type.add(i);
        let mi = *atoms.rmass.add(i);
        let mut i_bound = cache.as_ref().is_some_and(|c| c.binds_i(itype, ri, mi));
        for jj in 0..jnum {
            let j = (*jlist.add(jj) & mask) as usize;
            let k = base + jj;
            let delta = xi - vec3(atoms.x, j);
            let rsq = delta.norm_squared();
            let rj = *atoms.radius.add(j);
            let radsum = ri + rj;
            let touching = rsq < radsum * radsum;
            let touched = *list.touch.add(k) != 0;
            if !touching && !touched {
                // Apart and without a history.
                continue;
            }
            let jtype = *atoms.atom_type.add(j);
            let mj = *atoms.rmass.add(j);
            let bound = match &cache {
                Some(c) if i_bound && c.binds_j(jtype, rj, mj) => c,
                _ => {
                    let atom_i = PairAtom {
                        index: i,
                        atom_type: itype,
                        radius: ri,
                        mass: mi,
                    };
                    let atom_j = PairAtom {
                        index: j,
                        atom_type: jtype,
                        radius: rj,
                        mass: mj,
                    };
                    i_bound = true;
                    cache.insert(rebind::<N>(table, atom_i, atom_j)?)
                }
            };
            let values = std::slice::from_raw_parts_mut(list.history.add(k * dnum), dnum);
            let (mut state, mut roll_state) = load::<N, ROLLING>(values);
            let r = rsq.sqrt();
            let overlap = radsum - r;
            if !touching && !bound.law.normal.holds(&state.normal) {
                // A setup call has no force to add and no history to write.
                if UPDATE {
                    release::<N, ROLLING>(bound, values, overlap, dt);
                }
                continue;
            }
            if UPDATE {
                *list.touch.add(k) = 1;
            }
            let normal = delta * (1.0 / r);
            let lever_i = ri - 0.5 * overlap;
            let lever_j = rj - 0.5 * overlap;
            let wi = vec3(atoms.omega, i);
            let wj = vec3(atoms.omega, j);
            let relative_velocity = (vec3(atoms.v, i) - vec3(atoms.v, j))
                - (wi * lever_i + wj * lever_j).cross(&normal);
            let response = respond::<N, ROLLING>(
                &bound.law,
                &bound.rolling,
                (&mut state, &mut roll_state),
                &ContactInput {
                    overlap,
                    normal,
                    relative_velocity,
                    dt,
                },
                (wi - wj) * dt,
            );
            let force = response.force;
            let mut torque_on_i = response.moment * -lever_i;
            let mut torque_on_j = response.moment * -lever_j;
            if ROLLING {
                torque_on_i += response.rolling_torque;
                torque_on_j -= response.rolling_torque;
            }
            if UPDATE {
                store::<N, ROLLING>(values, &state, &roll_state);
            }
            add3(atoms.f, i, &force);
            add3(atoms.torque, i, &torque_on_i);
            let j_owned = newton || j < nlocal;
            if j_owned {
                add3(atoms.f, j, &(-force));
                add3(atoms.torque, j, &torque_on_j);
            }
            if ev {
                tally_contact(
                    tally,
                    &mut sums,
                    &bound.law.normal,
                    &state.normal,
                    (i, j, j_owned),
                    overlap,
                    &delta,
                    &force,
                );
            }
        }
    }
    if tally.eflag_global != 0 && !tally.eng_vdwl.is_null() {
        *tally.eng_vdwl += sums.energy;
    }
    if tally.vflag_global != 0 && !tally.virial.is_null() {
        for (c, v) in sums.virial.iter().enumerate() {
            *tally.virial.add(c) += v;
        }
    }
    Ok(())
}

/// Force of one contact from its stored history, without advancing the history (for LAMMPS
/// `single()`, i.e. `compute pair/local`): the law sees `dt = 0` on a copy of the state (no
/// tangential displacement increment), as LAMMPS's `pair granular` `single()` sets
/// `history_update = 0` and `pair gran/hooke/history` reads the stored shear without adding to it.
/// Returns `(force on i, normal force, overlap)`; `values` has the `layout`'s size.
pub fn evaluate_one(
    model: &PairModel,
    sphere_i: (f64, f64),
    sphere_j: (f64, f64),
    kinematics: (&Vector3<f64>, &Vector3<f64>, &Vector3<f64>, &Vector3<f64>),
    values: &[f64],
    layout: HistoryLayout,
) -> Result<(Vector3<f64>, f64, f64), PluginError> {
    if values.len() != layout.size() {
        return Err(PluginError::Abi("history size differs from the layout"));
    }
    match (layout.adhesion, layout.rolling) {
        (true, true) => {
            evaluate_with::<AdhesiveMdrLaw, true>(model, sphere_i, sphere_j, kinematics, values)
        }
        (true, false) => {
            evaluate_with::<AdhesiveMdrLaw, false>(model, sphere_i, sphere_j, kinematics, values)
        }
        (false, true) => {
            evaluate_with::<MdrLaw, true>(model, sphere_i, sphere_j, kinematics, values)
        }
        (false, false) => {
            evaluate_with::<MdrLaw, false>(model, sphere_i, sphere_j, kinematics, values)
        }
    }
}

fn evaluate_with<N: PluginNormalLaw, const ROLLING: bool>(
    model: &PairModel,
    sphere_i: (f64, f64),
    sphere_j: (f64, f64),
    kinematics: (&Vector3<f64>, &Vector3<f64>, &Vector3<f64>, &Vector3<f64>),
    values: &[f64],
) -> Result<(Vector3<f64>, f64, f64), PluginError> {
    let (ri, mi) = sphere_i;
    let (rj, mj) = sphere_j;
    let (delta, vrel_linear, wi, wj) = kinematics;
    let (law, _) = bind::<N>(model, ri, rj, mi, mj).map_err(|source| PluginError::Contact {
        i: 0,
        j: 1,
        source,
    })?;
    let r = delta.norm();
    let overlap = ri + rj - r;
    let (mut state, _) = load::<N, ROLLING>(values);
    if overlap <= 0.0 && !law.normal.holds(&state.normal) {
        return Ok((Vector3::zeros(), 0.0, overlap));
    }
    let normal = delta / r;
    let relative_velocity =
        vrel_linear - (wi * (ri - 0.5 * overlap) + wj * (rj - 0.5 * overlap)).cross(&normal);
    let out = law.update(
        &mut state,
        &ContactInput {
            overlap,
            normal,
            relative_velocity,
            dt: 0.0,
        },
    );
    Ok((out.force, out.normal_force, overlap))
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::coeffs::CoeffLine;
    use mdr_contact::normal::{AdhesiveMdrLaw, MdrLaw};

    /// A jittered cubic cluster of 27 overlapping spheres of two radii and two types (so the law
    /// is bound again and again), moving and spinning, each pair listed once, with every
    /// per-atom and per-contact array the loop writes.
    struct Cluster {
        x: Vec<f64>,
        v: Vec<f64>,
        omega: Vec<f64>,
        f: Vec<f64>,
        torque: Vec<f64>,
        radius: Vec<f64>,
        rmass: Vec<f64>,
        types: Vec<i32>,
        rows: Vec<Vec<i32>>,
        offset: Vec<i64>,
        touch: Vec<i32>,
        history: Vec<f64>,
        eatom: Vec<f64>,
        vatom: Vec<f64>,
        energy: f64,
        virial: [f64; 6],
    }

    impl Cluster {
        fn new(dnum: usize) -> Self {
            // A fixed linear congruential sequence in [-1, 1): the same cluster every run.
            let mut seed = 0x2545_f491_4f6c_dd1d_u64;
            let mut next = move || {
                seed = seed
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            };
            let n = 27;
            let mut c = Cluster {
                x: Vec::new(),
                v: Vec::new(),
                omega: Vec::new(),
                f: vec![0.0; 3 * n],
                torque: vec![0.0; 3 * n],
                radius: Vec::new(),
                rmass: Vec::new(),
                types: Vec::new(),
                rows: vec![Vec::new(); n],
                offset: Vec::new(),
                touch: Vec::new(),
                history: Vec::new(),
                eatom: vec![0.0; n],
                vatom: vec![0.0; 6 * n],
                energy: 0.0,
                virial: [0.0; 6],
            };
            for a in 0..n {
                let cell = [a % 3, (a / 3) % 3, a / 9];
                for axis in cell {
                    c.x.push(0.93 * axis as f64 + 0.02 * next());
                }
                for _ in 0..3 {
                    c.v.push(0.5 * next());
                }
                for _ in 0..3 {
                    c.omega.push(2.0 * next());
                }
                let big = a % 2 == 0;
                let r = if big { 0.5 } else { 0.47 };
                c.radius.push(r);
                c.rmass.push(r * r * r);
                c.types.push(if big { 1 } else { 2 });
            }
            let mut k = 0;
            for a in 0..n {
                c.offset.push(k);
                for b in a + 1..n {
                    c.rows[a].push(b as i32);
                    k += 1;
                }
            }
            c.touch = vec![0; k as usize];
            c.history = vec![0.0; k as usize * dnum];
            c
        }

        /// `steps` calls of the loop (`avx2`: its AVX2 copy), moving the spheres between calls
        /// and pulling sphere 0 out of the cluster half-way (its contacts are released).
        fn run<N: PluginNormalLaw, const ROLLING: bool>(
            &mut self,
            table: &CoeffTable,
            avx2: bool,
            steps: usize,
        ) {
            let dnum = HistoryLayout::for_table(table).size();
            let dt = 2e-3;
            for step in 0..steps {
                if step == steps / 2 {
                    self.x[0] -= 5.0;
                }
                let first: Vec<*const i32> = self.rows.iter().map(|r| r.as_ptr()).collect();
                let numneigh: Vec<i32> = self.rows.iter().map(|r| r.len() as i32).collect();
                let ilist: Vec<i32> = (0..self.rows.len() as i32).collect();
                let n = ilist.len() as i32;
                let atoms = MdrdemAtoms {
                    x: self.x.as_ptr(),
                    v: self.v.as_ptr(),
                    omega: self.omega.as_ptr(),
                    f: self.f.as_mut_ptr(),
                    torque: self.torque.as_mut_ptr(),
                    radius: self.radius.as_ptr(),
                    rmass: self.rmass.as_ptr(),
                    atom_type: self.types.as_ptr(),
                    nlocal: n,
                    nall: n,
                };
                let list = MdrdemNeighbours {
                    inum: n,
                    ilist: ilist.as_ptr(),
                    numneigh: numneigh.as_ptr(),
                    firstneigh: first.as_ptr(),
                    neighmask: 0x1fff_ffff,
                    offset: self.offset.as_ptr(),
                    touch: self.touch.as_mut_ptr(),
                    history: self.history.as_mut_ptr(),
                    dnum: dnum as i32,
                    history_update: 1,
                };
                let tally = MdrdemTally {
                    newton_pair: 1,
                    eflag_global: 1,
                    vflag_global: 1,
                    eng_vdwl: &mut self.energy,
                    virial: self.virial.as_mut_ptr(),
                    eatom: self.eatom.as_mut_ptr(),
                    vatom: self.vatom.as_mut_ptr(),
                };
                // SAFETY: every array has the size the structs document.
                unsafe {
                    if avx2 {
                        compute_avx2::<N, ROLLING, true>(table, &atoms, &list, &tally, dt)
                    } else {
                        compute_rows::<N, ROLLING, true>(table, &atoms, &list, &tally, dt)
                    }
                }
                .expect("the cluster's laws bind");
                for (x, v) in self.x.iter_mut().zip(&self.v) {
                    *x += v * dt;
                }
            }
        }

        /// Every value the loop wrote, as bits.
        fn bits(&self) -> Vec<u64> {
            let floats = [
                &self.f[..],
                &self.torque,
                &self.history,
                &self.eatom,
                &self.vatom,
                &self.virial,
                &[self.energy],
            ];
            floats
                .iter()
                .flat_map(|a| a.iter().map(|v| v.to_bits()))
                .chain(self.touch.iter().map(|&t| t as u64))
                .collect()
        }
    }

    fn table(extra: &str) -> CoeffTable {
        let words: Vec<String> = format!(
            "youngs 2.73e5 poisson 0.3 qc 10.0 theta 0.37 friction 0.5 damping 50.0 \
             tangential_damping 0.5 {extra}"
        )
        .split_whitespace()
        .map(String::from)
        .collect();
        let mut table = CoeffTable::new(2);
        table
            .set(
                (1, 2),
                (1, 2),
                CoeffLine::parse(&words).expect("a valid line"),
            )
            .expect("types 1 and 2");
        for (i, j) in [(1, 1), (1, 2), (2, 2)] {
            table.init_one(i, j).expect("set above");
        }
        table
    }

    /// The loop's AVX2 copy and its copy for the CPU the crate is built for write the same bits:
    /// forces, torques, histories, touch flags, per-atom and global energy and virial, through
    /// loading, unloading, sliding, rebinding and release, for each normal law and history
    /// layout. Fails if either copy reorders or fuses the floating-point operations.
    #[test]
    fn the_avx2_loop_gives_the_same_bits() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("this CPU has no AVX2: the AVX2 copy is never run, nothing to compare");
            return;
        }
        fn compare<N: PluginNormalLaw, const ROLLING: bool>(extra: &str) {
            let table = table(extra);
            let dnum = HistoryLayout::for_table(&table).size();
            let mut portable = Cluster::new(dnum);
            let mut avx2 = Cluster::new(dnum);
            portable.run::<N, ROLLING>(&table, false, 60);
            avx2.run::<N, ROLLING>(&table, true, 60);
            let touched = portable.touch.iter().filter(|&&t| t != 0).count();
            assert!(touched > 20, "{extra}: {touched} contacts");
            assert!(portable.f.iter().all(|f| f.is_finite()), "{extra}");
            assert_eq!(portable.bits(), avx2.bits(), "{extra}");
        }
        compare::<MdrLaw, false>("");
        compare::<MdrLaw, true>("rolling 0.1");
        compare::<AdhesiveMdrLaw, false>("adhesion 5.0");
        compare::<AdhesiveMdrLaw, true>("rolling 0.1 adhesion 5.0");
    }
}
