//! Neighbour-list builds: the pair laws bound per species, the sphere–sphere lists and the
//! particle–surface candidates.

use super::*;

impl<N, T, D, R, B> FastForceStepper<N, T, D, R, B>
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
    /// Bind the sphere–sphere laws (species pairs) and the particle–surface laws.
    pub(super) fn bind_laws(&mut self, bodies: &RigidBodySet) -> Result<()> {
        let table = &self.particles.species_table;
        let ns = table.len();
        let nm = self.materials.len();
        let species_changed = self.laws_species != ns;
        if species_changed {
            self.sphere_laws.clear();
            for a in table {
                for b in table {
                    let (e, g) = self.moduli[a.material.0 as usize * nm + b.material.0 as usize];
                    // The plain path's pair quantities: R = r1 r2/(r1 + r2), m = m1 m2/(m1 + m2).
                    let pair = ContactPair::new(
                        e,
                        g,
                        a.radius * b.radius / (a.radius + b.radius),
                        a.mass * b.mass / (a.mass + b.mass),
                    )?;
                    self.sphere_laws
                        .push((self.model.bind(&pair)?, self.rolling.bind(&pair)?));
                }
            }
            self.laws_species = ns;
        }
        // Surface laws again when a dynamic body's mass changed (or the species or surfaces).
        let masses: Vec<f64> = self
            .surfaces
            .iter()
            .map(|s| {
                s.body
                    .and_then(|h| bodies.get(h))
                    .filter(|b| b.is_dynamic())
                    .map_or(f64::INFINITY, |b| b.mass())
            })
            .collect();
        if !species_changed
            && self.surface_laws.len() == ns * self.surfaces.len()
            && masses == self.surface_masses
        {
            return Ok(());
        }
        self.surface_masses = masses;
        self.surface_laws.clear();
        for a in table {
            for (s, &m2) in self.surfaces.iter().zip(&self.surface_masses) {
                let (e, g) = self.moduli[a.material.0 as usize * nm + s.material.0 as usize];
                let mass = if m2.is_finite() {
                    a.mass * m2 / (a.mass + m2)
                } else {
                    a.mass
                };
                let pair = ContactPair::new(e, g, a.radius, mass)?;
                self.surface_laws
                    .push((self.model.bind(&pair)?, self.rolling.bind(&pair)?));
            }
        }
        Ok(())
    }

    /// Record the touching pairs the last build dropped (still active in the old lists; none
    /// while every particle moved less than half the skin, but a particle moved by hand may
    /// leave its contacts behind).
    fn record_dropped(&mut self) {
        let Some(ended) = &mut self.ended else {
            return;
        };
        let species = &self.particles.species;
        let (ns, nsurf) = (self.laws_species, self.surfaces.len());
        let old = &self.old_surface_pairs;
        for q in (0..old.len()).filter(|&q| old.active[q]) {
            let (i, s) = (old.particle[q], old.surface[q]);
            let (law, rolling) =
                &self.surface_laws[species[i as usize] as usize * nsurf + s as usize];
            ended.push(EndedContact {
                particle: i,
                partner: ContactPartner::Surface(s),
                works: ContactWorks::of(law, rolling, &old.history[q]),
            });
        }
        let old = &self.old_pairs;
        for q in (0..old.len()).filter(|&q| old.active[q]) {
            let (i, j) = (old.i[q], old.j[q]);
            let (law, rolling) =
                &self.sphere_laws[species[i as usize] as usize * ns + species[j as usize] as usize];
            ended.push(EndedContact {
                particle: i,
                partner: ContactPartner::Sphere(j),
                works: ContactWorks::of(law, rolling, &old.history[q]),
            });
        }
    }

    pub(super) fn surfaces_moved(&self, colliders: &ColliderSet) -> f64 {
        self.surfaces
            .iter()
            .map(|s| {
                colliders
                    .get(s.collider)
                    .map_or(0.0, |co| surface_displacement(s, co.position()))
            })
            .fold(0.0, f64::max)
    }

    /// Wrap the particles into the box and rebuild both neighbour lists.
    pub(super) fn rebuild(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet) -> Result<()> {
        let n = self.particles.len();
        let r_max = self.particles.radius.iter().cloned().fold(0.0, f64::max);
        self.boundary.check_cutoff(2.0 * r_max + self.skin)?;
        self.bind_laws(bodies)?;
        let p = &mut self.particles;
        for (x, v) in p.position.iter_mut().zip(p.linvel.iter_mut()) {
            self.boundary.wrap(x, v);
        }
        self.built_at.clear();
        self.built_at.extend_from_slice(&p.position);

        std::mem::swap(&mut self.pairs, &mut self.old_pairs);
        self.builder.build(
            &self.boundary,
            &p.position,
            &p.radius,
            self.skin,
            &mut self.old_pairs,
            &mut self.pairs,
        );

        // Particle–surface candidates: within r + skin of the collider (parry distance query),
        // after a cheap test against its loosened AABB.
        self.surface_candidates.clear();
        for s in &mut self.surfaces {
            if let Some(co) = colliders.get(s.collider) {
                s.pose_at_build = *co.position();
            }
        }
        let skin = self.skin;
        // Each surface's world AABB once per build (not once per particle).
        let aabbs: Vec<_> = self
            .surfaces
            .iter()
            .map(|s| colliders.get(s.collider).map(|co| (co, co.compute_aabb())))
            .collect();
        // In parallel over fixed blocks of particles, joined in block order: the candidates
        // come out in particle order whatever the number of threads.
        const SEARCH_BLOCK: usize = 1024;
        let (position, radius, surfaces) = (&p.position, &p.radius, &self.surfaces);
        let found: Vec<Vec<(u32, u32)>> = (0..n.div_ceil(SEARCH_BLOCK))
            .into_par_iter()
            .map(|b| {
                let mut found = Vec::new();
                for i in b * SEARCH_BLOCK..((b + 1) * SEARCH_BLOCK).min(n) {
                    let x = to_glam(&position[i]);
                    let reach = radius[i] + skin;
                    for (k, entry) in aabbs.iter().enumerate() {
                        let Some((co, aabb)) = entry else {
                            continue;
                        };
                        let inside = (0..3)
                            .all(|d| x[d] >= aabb.mins[d] - reach && x[d] <= aabb.maxs[d] + reach);
                        if inside && surfaces[k].within(co, &position[i], reach) {
                            found.push((i as u32, k as u32));
                        }
                    }
                }
                found
            })
            .collect();
        for block in &found {
            self.surface_candidates.extend_from_slice(block);
        }
        std::mem::swap(&mut self.surface_pairs, &mut self.old_surface_pairs);
        self.surface_pairs
            .rebuild_from(&self.surface_candidates, n, &mut self.old_surface_pairs);
        self.record_dropped();
        self.max_displacement = 0.0;
        self.needs_build = false;
        self.rebuilds += 1;
        Ok(())
    }
}
