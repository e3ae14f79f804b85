//! The law between spheres and a wall (`fix wall/mdrdem`): the wall is a half-space of its own
//! material, fixed or moving (`wiggle`, `shear`, a moving region), of infinite mass.
//!
//! The wall's line has the keywords of `pair_coeff` ([`CoeffLine`]). Its law parameters (`qc`,
//! `theta`, `friction`, `damping`, `tangential_damping`, `rolling`) are those of every
//! sphere–wall contact; `E*` and `G*` of a contact mix the wall's material with the material of
//! the sphere's type (its `pair_coeff T T` line of `pair_style mdrdem`) by eq. (3) and
//! docs/theory.md §5, as the pair style mixes two types (`estar`/`gstar` on the wall's line give
//! them directly). The reduced mass is the sphere's mass; the effective radius is the sphere's
//! radius on a flat wall and, on a curved one, the Hertz equivalent radius `R = √(R′ R″)` of the
//! two principal relative radii `1/R′ = 1/r + 1/R_a`, `1/R″ = 1/r + 1/R_b` (the wall's radii of
//! curvature in its two principal directions, 0 for a flat direction, negative where the wall is
//! concave; Johnson, *Contact Mechanics*, 1985, §4.2): a cylinder has one curved direction, a
//! sphere two.
//!
//! The C++ fix finds each sphere's point on the wall (the geometry of LAMMPS's `fix wall/gran`
//! and of its regions) and passes one batch per step: the branch from that point to the
//! sphere's centre, the wall's velocity there and its curvature. Every force comes from the same
//! kernel as the pair's: [`ContactLaw::update`](mdr_contact::model::ContactLaw::update) and the EPSD rolling law.

use crate::coeffs::{CoeffLine, CoeffTable, PairModel};
use crate::compute::MdrdemAtoms;
use crate::contact::{add3, respond, vec3};
use crate::error::PluginError;
use crate::history::{load, release, store, HistoryLayout, PairLaw, PluginNormalLaw};
use mdr_contact::material::{effective_modulus, effective_shear_modulus, ContactPair};
use mdr_contact::model::ContactInput;
use mdr_contact::normal::{AdhesiveMdrLaw, MdrLaw};
use mdr_contact::rolling::{EpsdRollingLaw, RollingModel};
use nalgebra::Vector3;

/// One wall: its line and, per sphere type, the model of a contact with it.
#[derive(Debug, Clone, PartialEq)]
pub struct WallTable {
    line: CoeffLine,
    models: Vec<Option<PairModel>>,
}

impl WallTable {
    /// A wall of the given line; [`WallTable::init`] mixes it with the sphere types.
    pub fn new(line: CoeffLine) -> Self {
        Self {
            line,
            models: Vec::new(),
        }
    }

    /// The wall's line.
    pub fn line(&self) -> &CoeffLine {
        &self.line
    }

    /// The model of a contact with each sphere type that has a `pair_coeff T T` line in the
    /// pair style's table (types without one may not touch the wall).
    pub fn init(&mut self, particles: &CoeffTable) -> Result<(), PluginError> {
        let wall = self.line.material()?;
        let model = self.line.model()?;
        let rolling = self.line.rolling_model()?;
        let n = particles.ntypes();
        let mut models = vec![None; n + 1];
        for (t, slot) in models.iter_mut().enumerate().skip(1) {
            if let Some(own) = particles.line(t, t) {
                let m = own.material()?;
                *slot = Some(PairModel {
                    model,
                    rolling,
                    adhesion: self.line.adhesion,
                    effective_modulus: self
                        .line
                        .estar
                        .unwrap_or_else(|| effective_modulus(&wall, &m)),
                    effective_shear_modulus: self
                        .line
                        .gstar
                        .unwrap_or_else(|| effective_shear_modulus(&wall, &m)),
                });
            }
        }
        self.models = models;
        Ok(())
    }

    /// The model of a contact between the wall and a sphere of type `t` (after `init`).
    pub fn model(&self, t: usize) -> Option<&PairModel> {
        self.models.get(t).and_then(|m| m.as_ref())
    }

    /// The history layout of the wall's contacts: rolling slots when the wall has `rolling`, the
    /// adhesive slot when it has `adhesion`.
    pub fn layout(&self) -> HistoryLayout {
        HistoryLayout {
            rolling: self.line.rolling > 0.0,
            adhesion: self.line.adhesion > 0.0,
        }
    }

    /// `c` of the neck reach `c R^{1/3}` of a contact with a sphere of type `t` (effective radius
    /// `R`): `c = (3/4) (π Δγ / E*)^{2/3}`, docs/theory.md eq. (A11) ([`PairModel::neck_reach`]).
    /// Zero without adhesion or for a type the wall has no model for.
    pub fn neck_coefficient(&self, t: usize) -> f64 {
        self.model(t).map_or(0.0, |m| m.neck_reach(1.0))
    }
}

/// Effective radius of a sphere of radius `radius` on a wall whose radii of curvature in its two
/// principal directions are `wall_radii` (0: flat, negative: concave): the Hertz equivalent
/// radius `√(R′ R″)`, `1/R′ = 1/r + 1/R_a`, `1/R″ = 1/r + 1/R_b` (module docs); `r` on a plane.
pub fn wall_effective_radius(radius: f64, wall_radii: [f64; 2]) -> Result<f64, PluginError> {
    let mut product = 1.0;
    for wall_radius in wall_radii {
        let curvature = if wall_radius == 0.0 {
            1.0 / radius
        } else {
            1.0 / radius + 1.0 / wall_radius
        };
        if curvature <= 0.0 {
            return Err(PluginError::WallTooCurved {
                radius,
                wall_radius,
            });
        }
        product /= curvature;
    }
    Ok(product.sqrt())
}

/// The sphere–wall contacts of one wall in one step (spheres within the neighbour skin of the
/// wall). Each contact's state is a row of `1 + 2 dnum` doubles at `row[c]`: a touch flag
/// (1 while the contact has a history), the contact's history (`dnum` values,
/// [`crate::history`]'s layout), and the history before the step a run ended on (`dnum` values,
/// for the setup call of the next run).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct MdrdemWallContacts {
    /// Number of spheres in this batch.
    pub n: i32,
    /// Local index of each sphere, `n`.
    pub atom: *const i32,
    /// From the sphere's point on the wall to its centre, `3 × n`.
    pub branch: *const f64,
    /// The wall's velocity at that point, `3 × n`.
    pub wall_velocity: *const f64,
    /// The wall's radii of curvature there in its two principal directions, `2 × n` (0 flat,
    /// negative concave).
    pub wall_radius: *const f64,
    /// Each contact's row (see the struct's docs), `n`.
    pub row: *const *mut f64,
    /// History values per contact (must equal the wall's layout).
    pub dnum: i32,
    /// 1: a step (histories advance); 0: LAMMPS's setup call (forces only, nothing written).
    pub history_update: i32,
    /// With `history_update = 0`: 1 repeats the force call of the step the last run ended on,
    /// from the histories before it and the velocities it saw (`replay_velocity`).
    pub replay: i32,
    /// `v` and `ω` the replayed step's force call saw, 6 per local atom (with `replay`).
    pub replay_velocity: *const f64,
}

/// Forces and torques of one wall on the spheres of `contacts`, added to `atoms.f` and
/// `atoms.torque`; returns the sum of the forces on the spheres.
///
/// # Safety
/// The pointers of `atoms` are LAMMPS's arrays (see [`MdrdemAtoms`]); `contacts` holds `n`
/// entries in each array, each `atom` below `atoms.nlocal`, and a row of `1 + 2 dnum` doubles at
/// each `row`; `replay_velocity` holds 6 doubles per local atom when `replay` is set.
pub unsafe fn compute_wall(
    wall: &WallTable,
    atoms: &MdrdemAtoms,
    contacts: &MdrdemWallContacts,
    dt: f64,
) -> Result<Vector3<f64>, PluginError> {
    let layout = wall.layout();
    let dnum = contacts.dnum as usize;
    if dnum != layout.size() {
        return Err(PluginError::Abi("dnum differs from the wall's layout"));
    }
    if layout.adhesion {
        wall_law::<AdhesiveMdrLaw>(wall, atoms, contacts, dt, layout.rolling)
    } else {
        wall_law::<MdrLaw>(wall, atoms, contacts, dt, layout.rolling)
    }
}

unsafe fn wall_law<N: PluginNormalLaw>(
    wall: &WallTable,
    atoms: &MdrdemAtoms,
    contacts: &MdrdemWallContacts,
    dt: f64,
    rolling: bool,
) -> Result<Vector3<f64>, PluginError> {
    match (rolling, contacts.history_update != 0) {
        (true, true) => wall_with::<N, true, true>(wall, atoms, contacts, dt),
        (false, true) => wall_with::<N, false, true>(wall, atoms, contacts, dt),
        (true, false) => wall_with::<N, true, false>(wall, atoms, contacts, dt),
        (false, false) => wall_with::<N, false, false>(wall, atoms, contacts, dt),
    }
}

/// Whether two keys are equal, without a call (a `[u64; 5]` comparison compiles to `memcmp`).
#[inline(always)]
fn same_key(a: &[u64; 5], b: &[u64; 5]) -> bool {
    a.iter().zip(b).fold(0, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// The loop; `UPDATE = false` writes no state. A contact is evaluated while the sphere overlaps
/// the wall and, for an adhesive law, while its neck holds at a separation.
unsafe fn wall_with<N: PluginNormalLaw, const ROLLING: bool, const UPDATE: bool>(
    wall: &WallTable,
    atoms: &MdrdemAtoms,
    contacts: &MdrdemWallContacts,
    dt: f64,
) -> Result<Vector3<f64>, PluginError> {
    let dnum = contacts.dnum as usize;
    let replay = !UPDATE && contacts.replay != 0 && !contacts.replay_velocity.is_null();
    let mut cache: Option<([u64; 5], PairLaw<N>, EpsdRollingLaw)> = None;
    let mut total = Vector3::zeros();
    for c in 0..contacts.n.max(0) as usize {
        let i = *contacts.atom.add(c) as usize;
        let row = *contacts.row.add(c);
        let branch = vec3(contacts.branch, c);
        let distance = branch.norm();
        let radius = *atoms.radius.add(i);
        let overlap = radius - distance;
        let touched = *row != 0.0;
        if overlap <= 0.0 && !touched {
            continue;
        }
        let values = std::slice::from_raw_parts_mut(row.add(1), dnum);
        let itype = *atoms.atom_type.add(i) as usize;
        let mass = *atoms.rmass.add(i);
        let wall_radii = [
            *contacts.wall_radius.add(2 * c),
            *contacts.wall_radius.add(2 * c + 1),
        ];
        let key = [
            itype as u64,
            radius.to_bits(),
            mass.to_bits(),
            wall_radii[0].to_bits(),
            wall_radii[1].to_bits(),
        ];
        if cache.as_ref().is_none_or(|(k, _, _)| !same_key(k, &key)) {
            let model = wall
                .model(itype)
                .ok_or(PluginError::WallTypeNotSet(itype))?;
            let contact = |source| PluginError::Contact { i, j: i, source };
            let pair = ContactPair::new(
                model.effective_modulus,
                model.effective_shear_modulus,
                wall_effective_radius(radius, wall_radii)?,
                mass,
            )
            .map_err(contact)?;
            let law = N::bind(model, &pair).map_err(contact)?;
            let rolling = model.rolling.bind(&pair).map_err(contact)?;
            cache = Some((key, law, rolling));
        }
        let (_, law, rolling) = cache.as_ref().expect("bound above");
        let source: &[f64] = if replay {
            std::slice::from_raw_parts(row.add(1 + dnum), dnum)
        } else {
            values
        };
        let (mut state, mut roll_state) = load::<N, ROLLING>(source);
        if overlap <= 0.0 && !law.normal.holds(&state.normal) {
            if !UPDATE {
                continue;
            }
            // Separated, near the wall: no force.
            release::<N, ROLLING>(law, rolling, (state, roll_state), values, overlap, dt);
            continue;
        }
        let (v, w) = if replay {
            let p = contacts.replay_velocity.add(6 * i);
            (
                Vector3::new(*p, *p.add(1), *p.add(2)),
                Vector3::new(*p.add(3), *p.add(4), *p.add(5)),
            )
        } else {
            (vec3(atoms.v, i), vec3(atoms.omega, i))
        };
        let normal = branch * (1.0 / distance);
        let lever = radius - 0.5 * overlap;
        let relative_velocity = v - vec3(contacts.wall_velocity, c) - (w * lever).cross(&normal);
        let response = respond::<N, ROLLING>(
            law,
            rolling,
            (&mut state, &mut roll_state),
            &ContactInput {
                overlap,
                normal,
                relative_velocity,
                dt,
            },
            w * dt,
        );
        let mut torque = response.moment * -lever;
        if ROLLING {
            torque += response.rolling_torque;
        }
        if UPDATE {
            *row = 1.0;
            store::<N, ROLLING>(values, &state, &roll_state);
        }
        add3(atoms.f, i, &response.force);
        add3(atoms.torque, i, &torque);
        total += response.force;
    }
    Ok(total)
}
