//! Agglomerates: the particles that touch, joined into clusters by union–find across the
//! shearing box's boundaries, and the cluster-size distribution (how many clusters of each
//! size). Two particles touch when the gap between their surfaces is at most
//! [`TOUCH_TOLERANCE`] of the smaller radius: a pair that stuck (restitution `ε = 0`) rests at
//! contact, up to the solver's allowed penetration or gap.

use crate::boundary::{Image, ShearingBox};
use crate::particles::Particles;
use serde::Serialize;
use std::collections::HashMap;

/// Largest gap, as a fraction of the smaller radius, at which two particles count as touching.
pub const TOUCH_TOLERANCE: f64 = 0.01;

/// The clusters of one configuration.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Clusters {
    /// Per particle, its cluster's index (clusters numbered in order of their first particle).
    #[serde(skip)]
    pub label: Vec<u32>,
    /// Per particle, the number of particles of its cluster.
    #[serde(skip)]
    pub size_of: Vec<u32>,
    /// `(size, number of clusters of that size)`, by increasing size.
    pub distribution: Vec<(u32, u32)>,
}

impl Clusters {
    /// The clusters of `particles` in `domain` at `time` (s; the shear offset of the images).
    pub fn of(domain: &ShearingBox, particles: &Particles, time: f64) -> Self {
        let n = particles.len();
        let r_max = particles.max_radius();
        let reach = 2.0 * r_max * (1.0 + TOUCH_TOLERANCE);
        // Particles and their images within `reach` of the box, binned by `reach` in x and y.
        let mut points: Vec<(u32, [f64; 3])> = Vec::with_capacity(n);
        let mut images: Vec<Image> = Vec::new();
        for i in 0..n {
            let (p, v) = (particles.position[i], particles.velocity[i]);
            points.push((i as u32, [p.x, p.y, p.z]));
            images.clear();
            domain.images_near_box(p, v, time, reach, &mut images);
            points.extend(
                images
                    .iter()
                    .map(|im| (i as u32, [im.position.x, im.position.y, im.position.z])),
            );
        }
        let cell = |x: f64| (x / reach).floor() as i64;
        let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (k, (_, p)) in points.iter().enumerate() {
            grid.entry((cell(p[0]), cell(p[1]))).or_default().push(k);
        }
        let mut parent: Vec<u32> = (0..n as u32).collect();
        for i in 0..n {
            let p = particles.position[i];
            let (cx, cy) = (cell(p.x), cell(p.y));
            for dx in -1..=1 {
                for dy in -1..=1 {
                    let Some(bin) = grid.get(&(cx + dx, cy + dy)) else {
                        continue;
                    };
                    for &k in bin {
                        let (j, q) = points[k];
                        let j = j as usize;
                        if j == i {
                            continue;
                        }
                        let (ri, rj) = (particles.radius[i], particles.radius[j]);
                        let d =
                            ((q[0] - p.x).powi(2) + (q[1] - p.y).powi(2) + (q[2] - p.z).powi(2))
                                .sqrt();
                        if d - ri - rj <= TOUCH_TOLERANCE * ri.min(rj) {
                            union(&mut parent, i as u32, j as u32);
                        }
                    }
                }
            }
        }
        let roots: Vec<u32> = (0..n as u32).map(|i| find(&mut parent, i)).collect();
        let mut index: HashMap<u32, u32> = HashMap::new();
        let mut sizes: Vec<u32> = Vec::new();
        let label: Vec<u32> = roots
            .iter()
            .map(|&r| {
                let next = index.len() as u32;
                let l = *index.entry(r).or_insert(next);
                if l as usize == sizes.len() {
                    sizes.push(0);
                }
                sizes[l as usize] += 1;
                l
            })
            .collect();
        let size_of = label.iter().map(|&l| sizes[l as usize]).collect();
        let mut counts: HashMap<u32, u32> = HashMap::new();
        for &s in &sizes {
            *counts.entry(s).or_default() += 1;
        }
        let mut distribution: Vec<(u32, u32)> = counts.into_iter().collect();
        distribution.sort_unstable();
        Self {
            label,
            size_of,
            distribution,
        }
    }

    /// Number of clusters of at least two particles (agglomerates).
    pub fn agglomerates(&self) -> u32 {
        self.distribution
            .iter()
            .filter(|&&(s, _)| s >= 2)
            .map(|&(_, c)| c)
            .sum()
    }

    /// Fraction of the particles that are part of an agglomerate.
    pub fn agglomerated_fraction(&self) -> f64 {
        if self.label.is_empty() {
            return 0.0;
        }
        self.size_of.iter().filter(|&&s| s >= 2).count() as f64 / self.label.len() as f64
    }

    /// Size of the largest cluster.
    pub fn largest(&self) -> u32 {
        self.distribution.last().map_or(0, |&(s, _)| s)
    }
}

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        parent[i as usize] = parent[parent[i as usize] as usize];
        i = parent[i as usize];
    }
    i
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        parent[hi as usize] = lo;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hill::HillFrame;
    use crate::run::REBOUND_OMEGA;
    use rapier3d_f64::math::Vector;

    /// Three touching particles in a row (one across the radial boundary, through its sheared
    /// image), a touching pair, and a loner: sizes 3, 2, 1.
    #[test]
    fn touching_particles_form_clusters_across_the_boundary() {
        let domain = ShearingBox::new(HillFrame::new(REBOUND_OMEGA).unwrap(), 10.0, 10.0).unwrap();
        let mut p = Particles::default();
        let zero = Vector::new(0.0, 0.0, 0.0);
        // Across x = ±5 at t = 0 (no shear offset yet): 4.5 and −4.5 are 1 m apart.
        p.push(Vector::new(4.5, 0.0, 0.0), zero, 0.5, 1.0);
        p.push(Vector::new(-4.5, 0.0, 0.0), zero, 0.5, 1.0);
        p.push(Vector::new(-3.5, 0.0, 0.0), zero, 0.5, 1.0);
        p.push(Vector::new(0.0, 3.0, 0.0), zero, 0.5, 1.0);
        p.push(Vector::new(0.0, 4.0, 0.0), zero, 0.5, 1.0);
        p.push(Vector::new(0.0, -2.0, 0.0), zero, 0.5, 1.0);
        let c = Clusters::of(&domain, &p, 0.0);
        assert_eq!(c.distribution, vec![(1, 1), (2, 1), (3, 1)]);
        assert_eq!(c.size_of, vec![3, 3, 3, 2, 2, 1]);
        assert_eq!(c.agglomerates(), 2);
        assert_eq!(c.largest(), 3);
        // A gap of 2 % of the radius separates them.
        let mut q = p.clone();
        q.position[4].y = 4.01;
        assert_eq!(
            Clusters::of(&domain, &q, 0.0).distribution,
            vec![(1, 3), (3, 1)]
        );
    }
}
