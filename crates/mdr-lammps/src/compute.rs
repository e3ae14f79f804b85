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
use crate::error::PluginError;
use crate::history::{load, store, HistoryLayout, PairLaw, PluginNormalLaw};
use mdr_contact::material::ContactPair;
use mdr_contact::model::ContactInput;
use mdr_contact::normal::{AdhesiveMdrLaw, MdrLaw};
use mdr_contact::rolling::{EpsdRollingLaw, RollingInput, RollingLaw, RollingModel};
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

/// What a pair's law is bound to: types, radii and masses (bitwise).
type BindKey = [u64; 6];

/// Whether two keys are equal, without branches or a call: a `[u64; 6]` comparison compiles to a
/// `memcmp` call, once per contact.
#[inline(always)]
fn same_key(a: &BindKey, b: &BindKey) -> bool {
    a.iter().zip(b).fold(0, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// The law of the last bound pair and what it was bound to.
struct BoundCache<N> {
    key: BindKey,
    law: PairLaw<N>,
    rolling: EpsdRollingLaw,
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

#[inline(always)]
unsafe fn vec3(p: *const f64, i: usize) -> Vector3<f64> {
    Vector3::new(*p.add(3 * i), *p.add(3 * i + 1), *p.add(3 * i + 2))
}

#[inline(always)]
unsafe fn add3(p: *mut f64, i: usize, v: &Vector3<f64>) {
    *p.add(3 * i) += v.x;
    *p.add(3 * i + 1) += v.y;
    *p.add(3 * i + 2) += v.z;
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

/// The loop; `UPDATE = false` writes neither `touch` nor `history`. A contact is evaluated while
/// the spheres overlap and, for an adhesive law, while its neck holds at a separation
/// ([`NormalLaw::holds`](mdr_contact::normal::NormalLaw::holds)); the neighbour cut-off covers the neck's reach
/// ([`PairModel::neck_reach`]).
unsafe fn compute_with<N: PluginNormalLaw, const ROLLING: bool, const UPDATE: bool>(
    table: &CoeffTable,
    atoms: &MdrdemAtoms,
    list: &MdrdemNeighbours,
    tally: &MdrdemTally,
    dt: f64,
) -> Result<(), PluginError> {
    let dnum = list.dnum as usize;
    let nlocal = atoms.nlocal as usize;
    let newton = tally.newton_pair != 0;
    let mask = list.neighmask;
    let eflag = tally.eflag_global != 0 || !tally.eatom.is_null();
    let vflag = tally.vflag_global != 0 || !tally.vatom.is_null();
    let mut cache: Option<BoundCache<N>> = None;
    let mut energy = 0.0;
    let mut virial = [0.0; 6];
    for ii in 0..list.inum as usize {
        let i = *list.ilist.add(ii) as usize;
        let jlist = *list.firstneigh.add(i);
        let jnum = *list.numneigh.add(i) as usize;
        let base = *list.offset.add(i) as usize;
        let xi = vec3(atoms.x, i);
        let ri = *atoms.radius.add(i);
        let itype = *atoms.atom_type.add(i);
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
            let mi = *atoms.rmass.add(i);
            let mj = *atoms.rmass.add(j);
            let key = [
                itype as u64,
                jtype as u64,
                ri.to_bits(),
                rj.to_bits(),
                mi.to_bits(),
                mj.to_bits(),
            ];
            if cache.as_ref().is_none_or(|c| !same_key(&c.key, &key)) {
                let model =
                    table
                        .model(itype as usize, jtype as usize)
                        .ok_or(PluginError::NotSet {
                            i: itype as usize,
                            j: jtype as usize,
                        })?;
                let (law, rolling) = bind::<N>(model, ri, rj, mi, mj)
                    .map_err(|source| PluginError::Contact { i, j, source })?;
                cache = Some(BoundCache { key, law, rolling });
            }
            let bound = cache.as_ref().expect("bound above");
            let values = list.history.add(k * dnum);
            let (mut state, mut roll_state) =
                load::<N, ROLLING>(std::slice::from_raw_parts(values, dnum));
            let r = rsq.sqrt();
            let overlap = radsum - r;
            if !touching && !bound.law.normal.holds(&state.normal) {
                if !UPDATE {
                    // A setup call has no force to add and no history to write.
                    continue;
                }
                // Apart after a contact: the law sees the separation (MDR keeps d_max for a
                // re-touch, Mindlin and rolling springs are released); no force.
                bound.law.update(
                    &mut state,
                    &ContactInput {
                        overlap,
                        normal: Vector3::z(),
                        relative_velocity: Vector3::zeros(),
                        dt,
                    },
                );
                if ROLLING {
                    bound.rolling.update(
                        &mut roll_state,
                        &RollingInput {
                            normal: Vector3::z(),
                            rotation_increment: Vector3::zeros(),
                            normal_force: 0.0,
                            normal_stiffness: 0.0,
                        },
                    );
                }
                store::<N, ROLLING>(
                    std::slice::from_raw_parts_mut(values, dnum),
                    &state,
                    &roll_state,
                );
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
            let out = bound.law.update(
                &mut state,
                &ContactInput {
                    overlap,
                    normal,
                    relative_velocity,
                    dt,
                },
            );
            let force = out.force;
            let moment = normal.cross(&force);
            let mut torque_i = moment * -lever_i;
            let mut torque_j = moment * -lever_j;
            if ROLLING {
                let roll = bound.rolling.update(
                    &mut roll_state,
                    &RollingInput {
                        normal,
                        rotation_increment: (wi - wj) * dt,
                        normal_force: out.normal_force,
                        normal_stiffness: out.normal.stiffness,
                    },
                );
                torque_i += roll.torque;
                torque_j -= roll.torque;
            }
            if UPDATE {
                store::<N, ROLLING>(
                    std::slice::from_raw_parts_mut(values, dnum),
                    &state,
                    &roll_state,
                );
            }
            add3(atoms.f, i, &force);
            add3(atoms.torque, i, &torque_i);
            let j_owned = newton || j < nlocal;
            if j_owned {
                add3(atoms.f, j, &(-force));
                add3(atoms.torque, j, &torque_j);
            }
            if eflag || vflag {
                // ev_tally_xyz: a pair with a ghost j under newton off counts half.
                let share = if j_owned { 1.0 } else { 0.5 };
                if eflag {
                    let e = bound.law.normal.elastic_energy(&state.normal, overlap);
                    energy += share * e;
                    if !tally.eatom.is_null() {
                        *tally.eatom.add(i) += 0.5 * e;
                        if j_owned {
                            *tally.eatom.add(j) += 0.5 * e;
                        }
                    }
                }
                if vflag {
                    let v = [
                        delta.x * force.x,
                        delta.y * force.y,
                        delta.z * force.z,
                        delta.x * force.y,
                        delta.x * force.z,
                        delta.y * force.z,
                    ];
                    for (sum, vc) in virial.iter_mut().zip(v) {
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
        }
    }
    if tally.eflag_global != 0 && !tally.eng_vdwl.is_null() {
        *tally.eng_vdwl += energy;
    }
    if tally.vflag_global != 0 && !tally.virial.is_null() {
        for (c, v) in virial.iter().enumerate() {
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
