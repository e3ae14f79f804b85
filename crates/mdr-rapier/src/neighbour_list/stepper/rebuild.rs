//! Neighbour-list builds: the pair laws bound per species, the sphere–sphere lists and the
//! particle–surface candidates.

use super::*;

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
    /// Bind the sphere–sphere laws (species pairs) and the particle–surface laws.
    pub(super) fn bind_laws(&mut self, bodies: &RigidBodySet) -> Result<()> {
        let table = &self.particles.species_table;
        let ns = table.len();
        let nm = self.materials.len();
        let species_changed = self.laws_species != ns;
        if species_changed {
            self.sphere_laws.clear();
            let (mut neck, mut adhesive) = (0.0_f64, false);
            for a in table {
                for b in table {
                    let (e, g) = self.moduli[a.material.0 as usize * nm + b.material.0 as usize];
                    // The rapier pipeline path's pair quantities: R = r1 r2/(r1 + r2), m = m1 m2/(m1 + m2).
                    let pair = ContactPair::new(
                        e,
                        g,
                        a.radius * b.radius / (a.radius + b.radius),
                        a.mass * b.mass / (a.mass + b.mass),
                    )?;
                    let law = self
                        .pair_normals
                        .bind(&self.model, a.material, b.material, &pair)?;
                    let pull_off = law.normal.pull_off_force();
                    adhesive |= pull_off > 0.0;
                    neck = neck.max(neck_reach(pull_off, &pair));
                    self.sphere_laws.push((law, self.rolling.bind(&pair)?));
                }
            }
            self.laws_species = ns;
            self.sphere_neck = if self.neck_rule { neck } else { 0.0 };
            self.adhesive = adhesive;
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
        let (mut neck, mut adhesive) = (0.0_f64, false);
        for a in table {
            for (s, &m2) in self.surfaces.iter().zip(&self.surface_masses) {
                let (e, g) = self.moduli[a.material.0 as usize * nm + s.material.0 as usize];
                let mass = if m2.is_finite() {
                    a.mass * m2 / (a.mass + m2)
                } else {
                    a.mass
                };
                let pair = ContactPair::new(e, g, a.radius, mass)?;
                let law = self
                    .pair_normals
                    .bind(&self.model, a.material, s.material, &pair)?;
                let pull_off = law.normal.pull_off_force();
                adhesive |= pull_off > 0.0;
                neck = neck.max(neck_reach(pull_off, &pair));
                self.surface_laws.push((law, self.rolling.bind(&pair)?));
            }
        }
        self.surface_neck = if self.neck_rule { neck } else { 0.0 };
        self.surface_adhesive = adhesive;
        Ok(())
    }

    /// Record the touching pairs the last build dropped (still active in the old lists; none
    /// while every particle moved less than half the skin, but a particle moved by hand may
    /// leave its contacts behind).
    fn record_dropped(&mut self) {
        let Some(mut ended) = self.ended.take() else {
            return;
        };
        let old = &self.old_surface_pairs;
        for q in (0..old.len()).filter(|&q| old.active[q]) {
            let (i, s) = (old.particle[q], old.surface[q]);
            let laws = self.surface_pair_laws(i as usize, s as usize);
            ended.push(EndedContact::of(
                i,
                ContactPartner::Surface(s),
                laws,
                &old.history[q],
            ));
        }
        let old = &self.old_pairs;
        for q in (0..old.len()).filter(|&q| old.active[q]) {
            let (i, j) = (old.i[q], old.j[q]);
            let laws = self.sphere_pair_laws(i as usize, j as usize);
            ended.push(EndedContact::of(
                i,
                ContactPartner::Sphere(j),
                laws,
                &old.history[q],
            ));
        }
        self.ended = Some(ended);
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
        // The laws first: their necks widen the cut-off.
        self.bind_laws(bodies)?;
        // A held pair is at most `neck` apart, and both particles moved less than half the
        // skin since the last build: listing pairs within `skin + neck` keeps every held pair.
        let reach = self.skin + self.sphere_neck;
        self.boundary.check_cutoff(2.0 * r_max + reach)?;
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
            reach,
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
        let skin = self.skin + self.surface_neck;
        // Each surface's world AABB once per build (not once per particle).
        let aabbs: Vec<_> = self
            .surfaces
            .iter()
            .map(|s| colliders.get(s.collider).map(|co| (co, co.compute_aabb())))
            .collect();
        // A coarse grid over the particles: each surface is listed in the cells its AABB,
        // loosened by the largest reach, overlaps, so a particle tests only the surfaces of its
        // own cell (a hopper wall of a hundred convex pieces costs a particle two or three
        // tests, not a hundred). Cells are listed in increasing surface index, so the
        // candidates come out sorted.
        let grid = SurfaceGrid::new(&p.position, r_max + skin, &aabbs);
        // In parallel over fixed blocks of particles, joined in block order: the candidates
        // come out in particle order whatever the number of threads.
        const SEARCH_BLOCK: usize = 1024;
        let (position, radius, surfaces) = (&p.position, &p.radius, &self.surfaces);
        let found: Vec<Vec<(u32, u32)>> = map_tasks((0..n.div_ceil(SEARCH_BLOCK)).collect(), |b| {
            let mut found = Vec::new();
            for i in b * SEARCH_BLOCK..((b + 1) * SEARCH_BLOCK).min(n) {
                let x = to_glam(&position[i]);
                let reach = radius[i] + skin;
                for &k in grid.surfaces_near(&position[i]) {
                    let k = k as usize;
                    let Some((co, aabb)) = &aabbs[k] else {
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
        });
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

/// Surfaces listed per cell of a uniform grid over the particles' bounding box (see
/// [`NeighbourListStepper::rebuild`]).
struct SurfaceGrid {
    lo: Vector3<f64>,
    inv_cell: f64,
    dims: [usize; 3],
    /// Surfaces of cell `c`: `items[start[c]..start[c + 1]]`, in increasing index.
    start: Vec<u32>,
    items: Vec<u32>,
}

impl SurfaceGrid {
    /// The grid over `points` with cells of side at least `reach` (and at most about as many
    /// cells as points), each surface listed in every cell its AABB grown by `reach` overlaps.
    fn new(
        points: &[Vector3<f64>],
        reach: f64,
        aabbs: &[Option<(&Collider, rapier3d_f64::parry::bounding_volume::Aabb)>],
    ) -> Self {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        for p in points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        if points.is_empty() {
            lo = Vector3::zeros();
            hi = Vector3::zeros();
        }
        let mut cell = reach.max(1e-300);
        let dims_of = |cell: f64| -> [usize; 3] {
            std::array::from_fn(|k| (((hi[k] - lo[k]) / cell).floor() as usize + 1).max(1))
        };
        let mut dims = dims_of(cell);
        while (dims[0] * dims[1] * dims[2]) as f64 > points.len() as f64 + 27.0 {
            cell *= 1.26;
            dims = dims_of(cell);
        }
        let inv_cell = 1.0 / cell;
        // The cell range a surface's grown AABB covers, clamped to the grid (a plane's infinite
        // AABB covers every cell; one wholly outside the grid none).
        let range =
            |aabb: &rapier3d_f64::parry::bounding_volume::Aabb| -> Option<[(usize, usize); 3]> {
                let mut r = [(0, 0); 3];
                for k in 0..3 {
                    let a = ((aabb.mins[k] - reach - lo[k]) * inv_cell).floor();
                    let b = ((aabb.maxs[k] + reach - lo[k]) * inv_cell).floor();
                    if b < 0.0 || a > (dims[k] - 1) as f64 || a.is_nan() || b.is_nan() {
                        return None;
                    }
                    r[k] = (a.max(0.0) as usize, (b.min((dims[k] - 1) as f64)) as usize);
                }
                Some(r)
            };
        let ncells = dims[0] * dims[1] * dims[2];
        let mut start = vec![0u32; ncells + 1];
        let cells = |r: [(usize, usize); 3]| {
            (r[2].0..=r[2].1).flat_map(move |z| {
                (r[1].0..=r[1].1).flat_map(move |y| {
                    (r[0].0..=r[0].1).map(move |x| (z * dims[1] + y) * dims[0] + x)
                })
            })
        };
        let ranges: Vec<Option<[(usize, usize); 3]>> = aabbs
            .iter()
            .map(|e| e.as_ref().and_then(|(_, aabb)| range(aabb)))
            .collect();
        for r in ranges.iter().flatten() {
            for c in cells(*r) {
                start[c + 1] += 1;
            }
        }
        for c in 0..ncells {
            start[c + 1] += start[c];
        }
        let mut fill: Vec<u32> = start[..ncells].to_vec();
        let mut items = vec![0u32; start[ncells] as usize];
        for (k, r) in ranges.iter().enumerate() {
            if let Some(r) = r {
                for c in cells(*r) {
                    items[fill[c] as usize] = k as u32;
                    fill[c] += 1;
                }
            }
        }
        Self {
            lo,
            inv_cell,
            dims,
            start,
            items,
        }
    }

    /// The surfaces listed in the cell of `x` (a point inside the grid's box).
    fn surfaces_near(&self, x: &Vector3<f64>) -> &[u32] {
        let c: [usize; 3] = std::array::from_fn(|k| {
            (((x[k] - self.lo[k]) * self.inv_cell).max(0.0) as usize).min(self.dims[k] - 1)
        });
        let cell = (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0];
        &self.items[self.start[cell] as usize..self.start[cell + 1] as usize]
    }
}
