//! Binned neighbour lists with a skin (the LAMMPS scheme): particles and their periodic ghosts
//! are sorted into cells of side `2 r_max + skin`; every particle `i` looks at the 27 cells around
//! it for partners `j > i` closer than `r_i + r_j + skin`. The list is a half list sorted by
//! `(i, j, image)`, with the pair's contact history stored next to it; histories are carried over
//! a rebuild by merging the old and new lists on that key.
//!
//! The build is parallel over blocks of particles; each block writes into its own persistent
//! buffer and the buffers are concatenated in block order, so the list does not depend on the
//! number of threads and steady-state rebuilds do not allocate.

use super::boundary::{Boundary, Image};
use crate::kernel::PairWrench;
use nalgebra::Vector3;
use rayon::prelude::*;

/// Particles per block of the parallel neighbour search.
const BLOCK: usize = 512;

/// A half neighbour list in structure-of-arrays form, sorted by `(i, j, image)`.
#[derive(Debug, Clone, Default)]
pub struct PairList<H> {
    /// First particle of each pair (the smaller index).
    pub i: Vec<u32>,
    /// Second particle of each pair.
    pub j: Vec<u32>,
    /// [`Image::code`] of `j` as seen from `i`.
    pub image: Vec<u8>,
    /// Whether the pair touched at the last force evaluation (its history is live).
    pub active: Vec<bool>,
    /// Contact history of each pair (default while apart).
    pub history: Vec<H>,
    /// Wrench of each pair at the last force evaluation of the parallel path (several threads),
    /// which gathers them per particle; zero where not `active` (the pair loop keeps it so, and
    /// the gather relies on it). Empty after a one-thread step: that path adds each wrench to
    /// the particles' sums as it goes and stores none.
    pub wrench: Vec<PairWrench>,
    /// `first[i]..first[i + 1]`: the pairs whose first particle is `i`.
    pub first: Vec<u32>,
    /// `second_start[j]..second_start[j + 1]` indexes `second`: the pairs whose second particle
    /// is `j`, in increasing `i`.
    pub second_start: Vec<u32>,
    /// Pair indices grouped by second particle.
    pub second: Vec<u32>,
}

impl<H> PairList<H> {
    /// Number of pairs in the list.
    pub fn len(&self) -> usize {
        self.i.len()
    }

    /// Whether the list is empty.
    pub fn is_empty(&self) -> bool {
        self.i.is_empty()
    }

    /// Number of touching pairs.
    pub fn touching(&self) -> usize {
        self.active.iter().filter(|&&a| a).count()
    }

    /// The same list with every history mapped by `f` (e.g. to other work books).
    pub fn map_history<H2>(self, f: impl FnMut(H) -> H2) -> PairList<H2> {
        PairList {
            i: self.i,
            j: self.j,
            image: self.image,
            active: self.active,
            history: self.history.into_iter().map(f).collect(),
            wrench: self.wrench,
            first: self.first,
            second_start: self.second_start,
            second: self.second,
        }
    }

    /// Recompute the per-particle indexes (`first`, `second_start`, `second`) of a list whose
    /// `(i, j, image)` arrays are sorted, for `n` particles.
    pub(crate) fn reindex(&mut self, n: usize) {
        let m = self.i.len();
        self.first.clear();
        self.first.resize(n + 1, 0);
        for &i in &self.i {
            self.first[i as usize + 1] += 1;
        }
        self.second_start.clear();
        self.second_start.resize(n + 1, 0);
        for &j in &self.j {
            self.second_start[j as usize + 1] += 1;
        }
        for k in 0..n {
            self.first[k + 1] += self.first[k];
            self.second_start[k + 1] += self.second_start[k];
        }
        let mut fill: Vec<u32> = self.second_start[..n].to_vec();
        self.second.clear();
        self.second.resize(m, 0);
        for p in 0..m {
            let j = self.j[p] as usize;
            self.second[fill[j] as usize] = p as u32;
            fill[j] += 1;
        }
    }

    /// Bytes held by the list's buffers (capacity).
    pub fn bytes(&self) -> usize {
        self.i.capacity() * 4
            + self.j.capacity() * 4
            + self.image.capacity()
            + self.active.capacity()
            + self.history.capacity() * std::mem::size_of::<H>()
            + self.wrench.capacity() * std::mem::size_of::<PairWrench>()
            + (self.first.capacity() + self.second_start.capacity() + self.second.capacity()) * 4
    }
}

/// One search block's buffers: `(j, image)` candidates and per-particle counts.
type BlockBuffers = (Vec<(u32, u8)>, Vec<u32>);

/// The cell grid and the search buffers, kept between rebuilds.
#[derive(Debug, Default)]
pub struct NeighbourBuilder {
    /// Ghost images: `(owner, image code)`.
    ghosts: Vec<(u32, u8)>,
    /// Positions of particles then ghosts.
    points: Vec<Vector3<f64>>,
    cell_of: Vec<u32>,
    cell_start: Vec<u32>,
    cell_items: Vec<u32>,
    /// Fill cursors of the counting sorts.
    fill: Vec<u32>,
    /// Per block: `(j, image)` candidates and per-particle counts.
    blocks: Vec<BlockBuffers>,
}

impl NeighbourBuilder {
    /// Bytes held by the builder's buffers (capacity).
    pub fn bytes(&self) -> usize {
        self.ghosts.capacity() * 8
            + self.points.capacity() * 24
            + (self.cell_of.capacity()
                + self.cell_start.capacity()
                + self.cell_items.capacity()
                + self.fill.capacity())
                * 4
            + self
                .blocks
                .iter()
                .map(|(a, b)| a.capacity() * 8 + b.capacity() * 4)
                .sum::<usize>()
    }

    /// Build the new list into `out` (its histories defaulted) from the positions `x` (inside
    /// the box) and radii `r`, then carry the histories of `old` over by key.
    pub fn build<H: Clone + Default + Send + Sync>(
        &mut self,
        boundary: &Boundary,
        x: &[Vector3<f64>],
        r: &[f64],
        skin: f64,
        old: &mut PairList<H>,
        out: &mut PairList<H>,
    ) {
        let n = x.len();
        let r_max = r.iter().cloned().fold(0.0, f64::max);
        let cutoff = 2.0 * r_max + skin;
        let offsets = boundary.offsets();

        // Ghosts: periodic images within one cutoff of the box.
        self.ghosts.clear();
        self.points.clear();
        self.points.extend_from_slice(x);
        if boundary.is_periodic() {
            for (i, xi) in x.iter().enumerate() {
                for image in Image::shifted() {
                    let code = image.code();
                    let p = xi + offsets[code as usize].position;
                    if boundary.near_box(&p, cutoff) {
                        self.ghosts.push((i as u32, code));
                        self.points.push(p);
                    }
                }
            }
        }

        // Cell grid over the bounding box of all points; the cell side is at least the cutoff
        // and grows if the box is so sparse that the grid would exceed ~2 cells per point.
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        for p in &self.points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let mut cell = cutoff.max(1e-300);
        let dims = |cell: f64| -> [usize; 3] {
            std::array::from_fn(|k| (((hi[k] - lo[k]) / cell).floor() as usize + 1).max(1))
        };
        let mut d = dims(cell);
        while (d[0] as f64) * (d[1] as f64) * (d[2] as f64) > 2.0 * self.points.len() as f64 + 27.0
        {
            cell *= 1.26;
            d = dims(cell);
        }
        let inv_cell = 1.0 / cell;
        let cell_index = |p: &Vector3<f64>| -> [usize; 3] {
            std::array::from_fn(|k| (((p[k] - lo[k]) * inv_cell) as usize).min(d[k] - 1))
        };
        let ncells = d[0] * d[1] * d[2];
        self.cell_of.clear();
        self.cell_of.extend(self.points.iter().map(|p| {
            let c = cell_index(p);
            ((c[2] * d[1] + c[1]) * d[0] + c[0]) as u32
        }));
        self.cell_start.clear();
        self.cell_start.resize(ncells + 1, 0);
        for &c in &self.cell_of {
            self.cell_start[c as usize + 1] += 1;
        }
        for c in 0..ncells {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        self.cell_items.clear();
        self.cell_items.resize(self.points.len(), 0);
        // Fill in point order: items of a cell are in increasing point index.
        self.fill.clear();
        self.fill.extend_from_slice(&self.cell_start[..ncells]);
        for (p, &c) in self.cell_of.iter().enumerate() {
            self.cell_items[self.fill[c as usize] as usize] = p as u32;
            self.fill[c as usize] += 1;
        }

        // Parallel search, one buffer per block of particles.
        let nblocks = n.div_ceil(BLOCK);
        if self.blocks.len() < nblocks {
            self.blocks.resize_with(nblocks, Default::default);
        }
        let points = &self.points;
        let ghosts = &self.ghosts;
        let cell_start = &self.cell_start;
        let cell_items = &self.cell_items;
        self.blocks[..nblocks]
            .par_iter_mut()
            .enumerate()
            .for_each(|(b, (cands, counts))| {
                cands.clear();
                counts.clear();
                for i in b * BLOCK..((b + 1) * BLOCK).min(n) {
                    let start = cands.len();
                    let xi = &points[i];
                    let c = cell_index(xi);
                    for cz in c[2].saturating_sub(1)..(c[2] + 2).min(d[2]) {
                        for cy in c[1].saturating_sub(1)..(c[1] + 2).min(d[1]) {
                            for cx in c[0].saturating_sub(1)..(c[0] + 2).min(d[0]) {
                                let cell = (cz * d[1] + cy) * d[0] + cx;
                                for &q in &cell_items
                                    [cell_start[cell] as usize..cell_start[cell + 1] as usize]
                                {
                                    let q = q as usize;
                                    let (j, code) = if q < n {
                                        (q as u32, Image::ZERO.code())
                                    } else {
                                        ghosts[q - n]
                                    };
                                    if (j as usize) <= i {
                                        continue;
                                    }
                                    let reach = r[i] + r[j as usize] + skin;
                                    if (xi - points[q]).norm_squared() < reach * reach {
                                        cands.push((j, code));
                                    }
                                }
                            }
                        }
                    }
                    cands[start..].sort_unstable();
                    counts.push((cands.len() - start) as u32);
                }
            });

        // Concatenate in block order.
        out.i.clear();
        out.j.clear();
        out.image.clear();
        out.first.clear();
        out.first.push(0);
        for (b, (cands, counts)) in self.blocks[..nblocks].iter().enumerate() {
            let mut k = 0;
            for (di, &count) in counts.iter().enumerate() {
                let i = (b * BLOCK + di) as u32;
                for &(j, code) in &cands[k..k + count as usize] {
                    out.i.push(i);
                    out.j.push(j);
                    out.image.push(code);
                }
                k += count as usize;
                out.first.push(out.i.len() as u32);
            }
        }
        if n == 0 {
            out.first.clear();
            out.first.push(0);
        }
        let m = out.i.len();

        // Carry histories over: both lists are sorted by (i, j, image).
        out.history.clear();
        out.active.clear();
        // Wrenches are kept only while the parallel path runs (it gathers them per particle);
        // the one-thread path leaves the list's `wrench` empty.
        let keep_wrenches = old.wrench.len() == old.len() && !old.is_empty();
        out.wrench.clear();
        if keep_wrenches {
            out.wrench.resize(m, PairWrench::default());
        }
        let key = |l: &PairList<H>, p: usize| (l.i[p], l.j[p], l.image[p]);
        let mut q = 0;
        for p in 0..m {
            let k = key(out, p);
            while q < old.len() && key(old, q) < k {
                q += 1;
            }
            if q < old.len() && key(old, q) == k {
                out.history.push(std::mem::take(&mut old.history[q]));
                out.active.push(old.active[q]);
                // Carried over: what stays active in `old` was dropped by this build.
                old.active[q] = false;
                if keep_wrenches {
                    out.wrench[p] = old.wrench[q];
                }
                q += 1;
            } else {
                out.history.push(H::default());
                out.active.push(false);
            }
        }

        // Transposed index: pairs by second particle, in increasing first particle.
        out.second_start.clear();
        out.second_start.resize(n + 1, 0);
        for &j in &out.j {
            out.second_start[j as usize + 1] += 1;
        }
        for j in 0..n {
            out.second_start[j + 1] += out.second_start[j];
        }
        out.second.clear();
        out.second.resize(m, 0);
        self.fill.clear();
        self.fill.extend_from_slice(&out.second_start[..n]);
        for p in 0..m {
            let j = out.j[p] as usize;
            out.second[self.fill[j] as usize] = p as u32;
            self.fill[j] += 1;
        }
    }
}
