//! Self-gravity of the shearing box with Plummer softening (docs/rings.md §9), by one of two
//! solvers over the same shear-periodic images:
//!
//! - [`GravitySolver::Tree`]: a Barnes–Hut tree (Barnes & Hut 1986) over the particles of the box,
//!   walked once for every ghost box, O(N log N) per step — the method of REBOUND's shearing sheet
//!   (Rein & Liu 2012, A&A 537, A128, §3.3–3.4) — by groups of nearby targets that share one
//!   interaction list (Barnes 1990, J. Comput. Phys. 87, 161);
//! - [`GravitySolver::Direct`]: the direct sum, O(N²) per ghost box — the exact reference for the
//!   tree, and with `ghost_boxes = 0` the nearest-image sum.
//!
//! **Images.** Ghost box `(i, j)` (`|i|, |j| ≤ g`) is the box shifted by
//! `(i L_x, j L_y + w(−i S(t)))`, where `S(t)` is the shear offset and `w(u) = u − L_y round(u/L_y)`
//! brings the sliding offset back into `[−L_y/2, L_y/2]`: the image of particle `b` in it is the
//! boundary's image labelled `(i, j + round(i S / L_y))` ([`ghost_box_label`],
//! [`crate::boundary::ShearingBox::images_near_box`]). The shifts of `(i, j)` and `(−i, −j)` are
//! opposite, so the direct sum conserves momentum exactly (REBOUND's `reb_boundary_get_ghostbox`
//! places its ghost boxes the same way).

use crate::boundary::{ImageLabel, ShearingBox};
use crate::error::{in_range, positive, Result, RingError};
use crate::particles::Particles;
use rapier3d_f64::math::Vector;
use rayon::prelude::*;

/// Newton's constant (m³ kg⁻¹ s⁻²), REBOUND's value.
pub const GRAVITATIONAL_CONSTANT: f64 = 6.67428e-11;

/// REBOUND's ring setup opens tree nodes with `opening_angle2 = 0.5`: `θ = √0.5`.
pub const DEFAULT_OPENING_ANGLE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// REBOUND's ring setup sums over two ghost boxes on each side (`N_ghost_x = N_ghost_y = 2`).
pub const DEFAULT_GHOST_BOXES: usize = 2;

/// Most particles in a leaf of the tree: their forces are summed directly when the leaf is opened.
const LEAF_SIZE: usize = 8;

/// Most targets that share a walk (a node of at most this many particles, or a leaf).
const GROUP_SIZE: usize = 32;

/// Targets evaluated together in the force loop.
const LANES: usize = 2;

/// How the accelerations are computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GravitySolver {
    /// Direct summation over every image in the ghost boxes (`ghost_boxes = 0`: over the nearest
    /// image of every other particle only).
    Direct {
        /// Ghost boxes on each side, radially and azimuthally (0: nearest image).
        ghost_boxes: usize,
    },
    /// Barnes–Hut tree with monopole nodes, walked once per ghost box for each group of targets.
    Tree {
        /// Opening angle `θ`: a node of side `w` at distance `d` from the target (to its centre of
        /// mass) is taken whole when `w < θ d` and the target lies outside it.
        opening_angle: f64,
        /// Ghost boxes on each side (≥ 1).
        ghost_boxes: usize,
    },
}

impl GravitySolver {
    /// The tree with REBOUND's settings (`θ = √0.5`, two ghost boxes each side).
    pub fn tree() -> Self {
        GravitySolver::Tree {
            opening_angle: DEFAULT_OPENING_ANGLE,
            ghost_boxes: DEFAULT_GHOST_BOXES,
        }
    }

    /// `tree` or `direct`.
    pub fn name(&self) -> &'static str {
        match self {
            GravitySolver::Direct { .. } => "direct",
            GravitySolver::Tree { .. } => "tree",
        }
    }

    /// Ghost boxes on each side.
    pub fn ghost_boxes(&self) -> usize {
        match *self {
            GravitySolver::Direct { ghost_boxes } | GravitySolver::Tree { ghost_boxes, .. } => {
                ghost_boxes
            }
        }
    }
}

/// Self-gravity: constant, softening and solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfGravity {
    /// Gravitational constant (m³ kg⁻¹ s⁻²).
    pub constant: f64,
    /// Plummer softening length (m).
    pub softening: f64,
    /// The solver.
    pub solver: GravitySolver,
}

impl Default for SelfGravity {
    /// The nearest-image direct sum, the cheapest self-gravity; [`SelfGravity::tree`] is
    /// what `mdr-dem sim ring --gravity` uses.
    fn default() -> Self {
        Self {
            constant: GRAVITATIONAL_CONSTANT,
            softening: 0.1,
            solver: GravitySolver::Direct { ghost_boxes: 0 },
        }
    }
}

/// `u − L round(u/L)`: `u` brought into `[−L/2, L/2]`.
fn centred(u: f64, l: f64) -> f64 {
    u - l * (u / l).round()
}

/// Shift `(Δx, Δy)` of ghost box `(i, j)` at `time` (module documentation).
pub fn ghost_box_shift(domain: &ShearingBox, i: i64, j: i64, time: f64) -> (f64, f64) {
    let sliding = centred(-(i as f64) * domain.shear_offset(time), domain.ly());
    (i as f64 * domain.lx(), j as f64 * domain.ly() + sliding)
}

/// The boundary's label of the image in ghost box `(i, j)` at `time`
/// (`(i, j + round(i S / L_y))`, module documentation).
pub fn ghost_box_label(domain: &ShearingBox, i: i64, j: i64, time: f64) -> ImageLabel {
    let whole = (-(i as f64) * domain.shear_offset(time) / domain.ly()).round() as i64;
    ImageLabel {
        radial: i as i8,
        azimuthal: j - whole,
    }
}

fn ghost_shifts(domain: &ShearingBox, g: usize, time: f64) -> Vec<(f64, f64)> {
    let g = g as i64;
    let mut shifts = Vec::with_capacity(((2 * g + 1) * (2 * g + 1)) as usize);
    for i in -g..=g {
        for j in -g..=g {
            shifts.push(ghost_box_shift(domain, i, j, time));
        }
    }
    shifts
}

impl SelfGravity {
    /// The Barnes–Hut tree with REBOUND's settings, G and softening 0.1 m as REBOUND's ring.
    pub fn tree() -> Self {
        Self {
            solver: GravitySolver::tree(),
            ..Self::default()
        }
    }

    /// Check the settings (names the offending parameter).
    pub fn validate(&self) -> Result<()> {
        positive("gravitational_constant", self.constant)?;
        positive("softening", self.softening)?;
        match self.solver {
            GravitySolver::Direct { ghost_boxes } => {
                in_range("ghost_boxes", ghost_boxes as f64, 0.0, 8.0, "[0, 8]")?;
            }
            GravitySolver::Tree {
                opening_angle,
                ghost_boxes,
            } => {
                in_range("opening_angle", opening_angle, 0.0, 1.5, "[0, 1.5]")?;
                if !(1..=8).contains(&ghost_boxes) {
                    return Err(RingError::OutOfRange {
                        name: "ghost_boxes",
                        value: ghost_boxes as f64,
                        range: "[1, 8] for the tree",
                    });
                }
            }
        }
        Ok(())
    }

    /// Separation from `a` to the nearest image of `b` at `time`: the radial box offset is chosen
    /// first (it carries the shear offset along y), then the azimuthal one.
    pub fn nearest_image(domain: &ShearingBox, a: Vector, b: Vector, time: f64) -> Vector {
        let mut d = b - a;
        let i = (d.x / domain.lx()).round();
        d.x -= i * domain.lx();
        // The image of b in box −i sits at y_b + i S(t).
        d.y += i * domain.shear_offset(time);
        d.y -= domain.ly() * (d.y / domain.ly()).round();
        d
    }

    /// Accelerations of all particles (m/s²) at `time`, by the configured solver. Parallel over
    /// particles (the tree: over groups of particles); each particle's sum runs in a fixed order,
    /// so the result does not depend on the number of threads.
    pub fn accelerations(
        &self,
        domain: &ShearingBox,
        particles: &Particles,
        time: f64,
    ) -> Vec<Vector> {
        match self.solver {
            GravitySolver::Direct { ghost_boxes: 0 } => {
                self.nearest_image_sum(domain, particles, time)
            }
            GravitySolver::Direct { ghost_boxes } => {
                self.ghost_box_sum(domain, particles, time, ghost_boxes)
            }
            GravitySolver::Tree {
                opening_angle,
                ghost_boxes,
            } => {
                let tree = Tree::build(particles);
                let shifts = ghost_shifts(domain, ghost_boxes, time);
                let walk = Walk {
                    theta2: opening_angle * opening_angle,
                    eps2: self.softening * self.softening,
                };
                let groups = tree.groups();
                // Each group's accelerations in tree order, then scattered to particle order.
                let per_group: Vec<Vec<Vector>> = groups
                    .par_iter()
                    .map_init(Interactions::default, |list, &group| {
                        let node = &tree.nodes[group as usize];
                        let mut acc = vec![Vector::ZERO; (node.end - node.start) as usize];
                        let bounds = tree.group_box(node);
                        for &shift in &shifts {
                            tree.interactions(bounds, shift, walk, list);
                            tree.apply(node, shift, walk, list, &mut acc);
                        }
                        acc
                    })
                    .collect();
                let mut out = vec![Vector::ZERO; particles.len()];
                for (&group, acc) in groups.iter().zip(&per_group) {
                    let start = tree.nodes[group as usize].start as usize;
                    for (k, a) in acc.iter().enumerate() {
                        out[tree.order[start + k] as usize] = *a * self.constant;
                    }
                }
                out
            }
        }
    }

    fn nearest_image_sum(
        &self,
        domain: &ShearingBox,
        particles: &Particles,
        time: f64,
    ) -> Vec<Vector> {
        let eps2 = self.softening * self.softening;
        (0..particles.len())
            .into_par_iter()
            .map(|i| {
                let mut acc = Vector::ZERO;
                for j in 0..particles.len() {
                    if j == i {
                        continue;
                    }
                    let d = Self::nearest_image(
                        domain,
                        particles.position[i],
                        particles.position[j],
                        time,
                    );
                    let r2 = d.length_squared() + eps2;
                    acc += d * (self.constant * particles.mass[j] / (r2 * r2.sqrt()));
                }
                acc
            })
            .collect()
    }

    fn ghost_box_sum(
        &self,
        domain: &ShearingBox,
        particles: &Particles,
        time: f64,
        ghost_boxes: usize,
    ) -> Vec<Vector> {
        let eps2 = self.softening * self.softening;
        let shifts = ghost_shifts(domain, ghost_boxes, time);
        (0..particles.len())
            .into_par_iter()
            .map(|i| {
                let a = particles.position[i];
                let mut acc = Vector::ZERO;
                for &(sx, sy) in &shifts {
                    let central = sx == 0.0 && sy == 0.0;
                    for j in 0..particles.len() {
                        if central && j == i {
                            continue;
                        }
                        let b = particles.position[j];
                        let d = Vector::new(b.x + sx - a.x, b.y + sy - a.y, b.z - a.z);
                        let r2 = d.length_squared() + eps2;
                        acc += d * (particles.mass[j] / (r2 * r2.sqrt()));
                    }
                }
                acc * self.constant
            })
            .collect()
    }
}

/// A node of the quadtree (x, y; the thin ring needs no split in z): a square cell, its mass and
/// centre of mass (3-D), and either four children or a range of particles.
#[derive(Debug, Clone, Copy)]
struct Node {
    centre_x: f64,
    centre_y: f64,
    half: f64,
    mass: f64,
    com: Vector,
    /// Index of the first of four consecutive children (0: a leaf; the root is never a child).
    children: u32,
    start: u32,
    end: u32,
}

/// A Barnes–Hut quadtree over the particles (Barnes & Hut 1986, Nature 324, 446), with the
/// particles' positions and masses stored in tree order.
struct Tree {
    nodes: Vec<Node>,
    /// Particle index of each position in tree order.
    order: Vec<u32>,
    position: Vec<Vector>,
    mass: Vec<f64>,
}

impl Tree {
    fn build(particles: &Particles) -> Self {
        let n = particles.len();
        let (mut lo_x, mut lo_y, mut hi_x, mut hi_y) = (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for p in &particles.position {
            lo_x = lo_x.min(p.x);
            lo_y = lo_y.min(p.y);
            hi_x = hi_x.max(p.x);
            hi_y = hi_y.max(p.y);
        }
        let half = 0.5 * (hi_x - lo_x).max(hi_y - lo_y).max(1e-9) * (1.0 + 1e-9);
        let mut tree = Tree {
            nodes: Vec::with_capacity(2 * n / LEAF_SIZE + 8),
            order: (0..n as u32).collect(),
            position: Vec::new(),
            mass: Vec::new(),
        };
        tree.nodes.push(Node {
            centre_x: 0.5 * (lo_x + hi_x),
            centre_y: 0.5 * (lo_y + hi_y),
            half,
            mass: 0.0,
            com: Vector::ZERO,
            children: 0,
            start: 0,
            end: n as u32,
        });
        let mut scratch = Vec::with_capacity(n);
        tree.split(0, particles, &mut scratch, 0);
        tree.position = tree
            .order
            .iter()
            .map(|&k| particles.position[k as usize])
            .collect();
        tree.mass = tree
            .order
            .iter()
            .map(|&k| particles.mass[k as usize])
            .collect();
        tree
    }

    /// Fill in node `index` (mass, centre of mass) and split it if it holds more than a leaf.
    fn split(&mut self, index: usize, particles: &Particles, scratch: &mut Vec<u32>, depth: u32) {
        let node = self.nodes[index];
        let (start, end) = (node.start as usize, node.end as usize);
        let (mut mass, mut moment) = (0.0, Vector::ZERO);
        for &k in &self.order[start..end] {
            let m = particles.mass[k as usize];
            mass += m;
            moment += particles.position[k as usize] * m;
        }
        self.nodes[index].mass = mass;
        self.nodes[index].com = if mass > 0.0 {
            moment / mass
        } else {
            Vector::new(node.centre_x, node.centre_y, 0.0)
        };
        // Depth cap: coincident particles would otherwise split forever.
        if end - start <= LEAF_SIZE || depth >= 48 {
            return;
        }
        // Stable partition into the quadrants (x-, y-), (x+, y-), (x-, y+), (x+, y+).
        let quadrant = |k: u32| {
            let p = particles.position[k as usize];
            usize::from(p.x >= node.centre_x) + 2 * usize::from(p.y >= node.centre_y)
        };
        let mut bounds = [start; 5];
        scratch.clear();
        for (q, bound) in bounds.iter_mut().take(4).enumerate() {
            *bound = start + scratch.len();
            scratch.extend(
                self.order[start..end]
                    .iter()
                    .copied()
                    .filter(|&k| quadrant(k) == q),
            );
        }
        bounds[4] = end;
        self.order[start..end].copy_from_slice(scratch);
        let first = self.nodes.len();
        self.nodes[index].children = first as u32;
        let h = 0.5 * node.half;
        for q in 0..4 {
            self.nodes.push(Node {
                centre_x: node.centre_x + if q & 1 == 1 { h } else { -h },
                centre_y: node.centre_y + if q & 2 == 2 { h } else { -h },
                half: h,
                mass: 0.0,
                com: Vector::ZERO,
                children: 0,
                start: bounds[q] as u32,
                end: bounds[q + 1] as u32,
            });
        }
        for q in 0..4 {
            if bounds[q + 1] > bounds[q] {
                self.split(first + q, particles, scratch, depth + 1);
            }
        }
    }

    /// The leaves, in tree order: the groups of targets that share one walk per ghost box.
    fn groups(&self) -> Vec<u32> {
        let mut groups = Vec::new();
        let mut stack = vec![0u32];
        while let Some(index) = stack.pop() {
            let node = &self.nodes[index as usize];
            if node.children == 0 || node.end - node.start <= GROUP_SIZE as u32 {
                if node.end > node.start {
                    groups.push(index);
                }
            } else {
                // Reversed, so that the leaves come out in tree order.
                stack.extend((0..4).rev().map(|c| node.children + c));
            }
        }
        groups
    }

    /// The bounding box of the group's particles.
    fn group_box(&self, group: &Node) -> [Vector; 2] {
        let (mut lo, mut hi) = (
            Vector::splat(f64::INFINITY),
            Vector::splat(f64::NEG_INFINITY),
        );
        for p in &self.position[group.start as usize..group.end as usize] {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        [lo, hi]
    }

    /// The interaction list of the group with bounding box `[lo, hi]` and the tree shifted by
    /// `(sx, sy)`, as sources in the unshifted tree's frame: the centres of mass of the nodes
    /// taken whole, then the particles of the leaves that are opened. A node is taken whole only when the opening criterion
    /// `w < θ d` holds for the point of the group's bounding box nearest to its centre of mass
    /// and the box lies outside the node, so every target of the group would take it whole on
    /// its own walk too (the group walk is at least as accurate as one walk per target; Barnes
    /// 1990, J. Comput. Phys. 87, 161).
    fn interactions(
        &self,
        [lo, hi]: [Vector; 2],
        (sx, sy): (f64, f64),
        walk: Walk,
        list: &mut Interactions,
    ) {
        // The group's bounding box seen from the unshifted tree.
        let shift = Vector::new(sx, sy, 0.0);
        let (lo, hi) = (lo - shift, hi - shift);
        list.clear();
        list.stack.push(0);
        while let Some(index) = list.stack.pop() {
            let node = &self.nodes[index as usize];
            if node.mass == 0.0 {
                continue;
            }
            if node.children == 0 {
                for k in node.start as usize..node.end as usize {
                    list.push(self.position[k], self.mass[k]);
                }
                continue;
            }
            let gap = (lo - node.com).max(node.com - hi).max(Vector::ZERO);
            let width = 2.0 * node.half;
            let overlaps = lo.x <= node.centre_x + node.half
                && hi.x >= node.centre_x - node.half
                && lo.y <= node.centre_y + node.half
                && hi.y >= node.centre_y - node.half;
            if !overlaps && width * width < walk.theta2 * gap.length_squared() {
                list.push(node.com, node.mass);
            } else {
                list.stack.extend((0..4).map(|c| node.children + c));
            }
        }
    }

    /// Add `Σ m_j d / (|d|² + ε²)^{3/2}` (without G) of the interaction list to the group's
    /// targets (`acc` in tree order). Targets go in blocks of [`LANES`] lanes, the inner loop
    /// over the lanes, so that the compiler vectorises it while every target still sums its
    /// sources in list order. A target's own term (central box) is exactly zero: `d = 0` and the
    /// softening keeps the denominator positive.
    fn apply(
        &self,
        group: &Node,
        (sx, sy): (f64, f64),
        walk: Walk,
        list: &Interactions,
        acc: &mut [Vector],
    ) {
        let targets = &self.position[group.start as usize..group.end as usize];
        for (block, acc) in targets.chunks(LANES).zip(acc.chunks_mut(LANES)) {
            let last = block[block.len() - 1];
            let lane = |t: usize| block.get(t).copied().unwrap_or(last);
            let tx: [f64; LANES] = std::array::from_fn(|t| lane(t).x - sx);
            let ty: [f64; LANES] = std::array::from_fn(|t| lane(t).y - sy);
            let tz: [f64; LANES] = std::array::from_fn(|t| lane(t).z);
            let (mut ax, mut ay, mut az) = ([0.0; LANES], [0.0; LANES], [0.0; LANES]);
            for j in 0..list.mass.len() {
                let (x, y, z, m) = (list.x[j], list.y[j], list.z[j], list.mass[j]);
                for t in 0..LANES {
                    let (dx, dy, dz) = (x - tx[t], y - ty[t], z - tz[t]);
                    let r2 = dx * dx + dy * dy + dz * dz + walk.eps2;
                    let f = m / (r2 * r2.sqrt());
                    ax[t] += dx * f;
                    ay[t] += dy * f;
                    az[t] += dz * f;
                }
            }
            for (t, a) in acc.iter_mut().enumerate() {
                *a += Vector::new(ax[t], ay[t], az[t]);
            }
        }
    }
}

/// The tree walk's accuracy parameters.
#[derive(Debug, Clone, Copy)]
struct Walk {
    /// Opening angle squared.
    theta2: f64,
    /// Softening length squared.
    eps2: f64,
}

/// A group's interaction list with one ghost box (sources by coordinate, so that the force loop
/// reads them in order), reused across groups and boxes.
#[derive(Debug, Default)]
struct Interactions {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    mass: Vec<f64>,
    /// The walk's stack.
    stack: Vec<u32>,
}

impl Interactions {
    fn clear(&mut self) {
        self.x.clear();
        self.y.clear();
        self.z.clear();
        self.mass.clear();
        self.stack.clear();
    }

    fn push(&mut self, at: Vector, mass: f64) {
        self.x.push(at.x);
        self.y.push(at.y);
        self.z.push(at.z);
        self.mass.push(mass);
    }
}
