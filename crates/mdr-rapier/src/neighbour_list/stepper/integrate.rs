//! Integration of the particles (rapier's symplectic Euler with one solver iteration, written
//! out) and the reactions on dynamic rapier bodies.

use super::*;
use rapier3d_f64::math::Rotation;

impl<N, T, D, R, B> NeighbourListStepper<N, T, D, R, B>
where
    N: NormalModel,
    T: TangentialModel,
    D: DampingModel,
    R: RollingModel,
    B: WorkBooks,
    N::Law: Clone,
    T::Law: Clone,
    D::Law: Clone,
    R::Law: Clone,
{
    /// Step 4: sum each particle's wrenches in a fixed order and integrate it. Returns the
    /// largest squared displacement since the last build.
    pub(super) fn integrate(&mut self, gravity: &Vector3<f64>, dt: f64) -> f64 {
        let sums = &self.sums;
        let orientation = self.orientation;
        let built_at = &self.built_at;
        let NeighbourListParticles {
            position,
            linvel,
            angvel,
            rotation,
            species,
            species_table,
            ..
        } = &mut self.particles;
        let (species, table) = (&*species, &*species_table);
        const PCHUNK: usize = 1024;
        let chunks: Vec<_> = position
            .chunks_mut(PCHUNK)
            .zip(linvel.chunks_mut(PCHUNK))
            .zip(angvel.chunks_mut(PCHUNK))
            .zip(rotation.chunks_mut(PCHUNK))
            .enumerate()
            .collect();
        map_tasks(chunks, |(c, (((x, v), w), q))| {
            let mut max2: f64 = 0.0;
            for k in 0..x.len() {
                let i = c * PCHUNK + k;
                let (force, torque) = sums[i];
                let s = &table[species[i] as usize];
                // rapier: force = user_force + g · m; Δv = force · (1/m) · dt.
                let total = force + gravity * s.mass;
                v[k] += total * s.inv_mass * dt;
                w[k] += torque * s.inv_inertia * dt;
                x[k] += v[k] * dt;
                // rapier's linearised rotation update.
                if orientation {
                    let half = w[k] * (dt * 0.5);
                    let id_plus_half = Rotation::from_xyzw(half.x, half.y, half.z, 1.0);
                    q[k] = renormalize(id_plus_half * q[k]);
                }
                max2 = max2.max((x[k] - built_at[i]).norm_squared());
            }
            max2
        })
        .into_iter()
        .fold(0.0, f64::max)
    }

    /// Step 5: reaction wrenches on the surfaces' dynamic bodies, in key order, added to the
    /// forces the user put on them (given back after rapier's step).
    pub(super) fn apply_reactions(&mut self, bodies: &mut RigidBodySet) {
        self.reactions.clear();
        for s in &self.surfaces {
            if let Some(h) = s.body {
                if bodies.get(h).is_some_and(|b| b.is_dynamic())
                    && !self.reactions.iter().any(|r| r.0 == h)
                {
                    self.reactions.push((h, Vector3::zeros(), Vector3::zeros()));
                }
            }
        }
        if self.reactions.is_empty() {
            return;
        }
        let sp = &self.surface_pairs;
        for q in 0..sp.len() {
            if !sp.active[q] {
                continue;
            }
            let Some(h) = self.surfaces[sp.surface[q] as usize].body else {
                continue;
            };
            if let Some(r) = self.reactions.iter_mut().find(|r| r.0 == h) {
                r.1 += -sp.wrench[q].force;
                r.2 += sp.wrench[q].torque2;
            }
        }
        for (h, f, t) in &self.reactions {
            self.added.add(*h, &mut bodies[*h], to_glam(f), to_glam(t));
        }
    }
}

/// `q / |q|` for the product of a unit quaternion and rapier's linearised increment `1 + h`,
/// whose squared norm is `1 + ε` with `ε = |h|²` up to rounding. For `|ε| < 10⁻⁶` (a rotation
/// increment below 2·10⁻³ rad per step) the series `(1 + ε)^{-1/2} = 1 − ε/2 + 3ε²/8 − 5ε³/16 …`
/// truncated after `ε²` is exact to `5ε³/16 < 4·10⁻¹⁹`, below the rounding of a double, and saves
/// the square root and the division of a normalisation per particle and step; larger steps take
/// the exact normalisation.
#[inline(always)]
fn renormalize(q: Rotation) -> Rotation {
    let eps = q.length_squared() - 1.0;
    if eps.abs() < 1e-6 {
        q * (1.0 - 0.5 * eps + 0.375 * eps * eps)
    } else {
        q.normalize()
    }
}
