//! Binned neighbour lists with a skin (the LAMMPS scheme): particles and their periodic ghosts
//! are sorted into cells of side `2 r_max + skin`; every particle `i` looks at the 27 cells around
//! it for partners `j > i` closer than `r_i + r_j + skin`, reading each row of three cells as one
//! run of a cell-ordered copy of the points. The list is a half list sorted by
//! `(i, j, image)`, with the pair's contact history stored next to it; histories are carried over
//! a rebuild by merging the old and new lists on that key.
//!
//! The build is parallel over blocks of particles: each block searches into its own persistent
//! buffer, then writes its share of the list (whose place follows from the blocks' counts) and
//! merges it with its share of the old list (found by the first particle, on which the old list
//! is sorted) to carry the histories over. The list does not depend on the number of threads;
//! steady-state rebuilds allocate only a few vectors of one entry per block. Binning and the
//! transposed index are serial.

use super::boundary::{Boundary, Image};
use super::workers::map_tasks;
use crate::kernel::PairWrench;
use nalgebra::Vector3;

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
    /// Contact history of each pair, meaningful only while the pair is `active`: a pair that
    /// starts touching starts from the default history (the pair loop resets it then), so
    /// neither a build nor a separation spends a write on the pairs that are apart.
    pub history: Vec<H>,
    /// Wrench of each pair at the last force evaluation that was asked to keep them
    /// (`NeighbourListStepper::compute_forces` with `keep_wrenches`, as for a contact-network
    /// frame), zero where not `active`; empty after any other: the pair loop adds each wrench
    /// to the particles' sums as it goes and stores none.
    pub wrench: Vec<PairWrench>,
    /// `first[i]..first[i + 1]`: the pairs whose first particle is `i`.
    pub first: Vec<u32>,
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
        }
    }

    /// Recompute the per-particle index `first` of a list whose `(i, j, image)` arrays are
    /// sorted, for `n` particles.
    pub(crate) fn reindex(&mut self, n: usize) {
        self.first.clear();
        self.first.resize(n + 1, 0);
        for &i in &self.i {
            self.first[i as usize + 1] += 1;
        }
        for k in 0..n {
            self.first[k + 1] += self.first[k];
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
            + self.first.capacity() * 4
    }
}

/// One search block's buffers, kept between rebuilds.
#[derive(Debug, Default)]
struct BlockBuffers {
    /// The partners found, as `(j << 8) | image code` (one integer, so that sorting a
    /// particle's partners by `(j, image)` compares one word), particle after particle.
    partners: Vec<u64>,
    /// Partners per particle of the block.
    counts: Vec<u32>,
}

impl BlockBuffers {
    fn bytes(&self) -> usize {
        self.partners.capacity() * 8 + self.counts.capacity() * 4
    }
}

/// The cell grid and the search buffers, kept between rebuilds.
///
/// A build is LAMMPS's sequence of neighbour steps, each a function of its own:
/// `NeighbourBuilder::add_ghosts` (periodic images), `CellGrid::over` and
/// `NeighbourBuilder::bin` (NBin: the grid and a counting sort of the points into its cells),
/// `NeighbourBuilder::search` (NStencil and NPair: the 27-cell stencil of every particle, one
/// parallel task per block of particles) and `carry_histories` (FixNeighHistory: the new list
/// written and the histories carried over by key).
#[derive(Debug, Default)]
pub struct NeighbourBuilder {
    /// Ghost images: `(owner, image code)`.
    ghosts: Vec<(u32, u8)>,
    /// Positions of particles then ghosts.
    points: Vec<Vector3<f64>>,
    cell_of: Vec<u32>,
    cell_start: Vec<u32>,
    /// `(x, y, z, r)` of the points in cell order (a cell's points in increasing point index):
    /// the candidate search reads a stencil row's cells as one contiguous run.
    sorted: Vec<[f64; 4]>,
    /// `(particle, image code)` of the points in cell order.
    sorted_owner: Vec<(u32, u8)>,
    /// Fill cursors of the counting sorts.
    fill: Vec<u32>,
    /// Per block: candidates and per-particle counts.
    blocks: Vec<BlockBuffers>,
}

impl NeighbourBuilder {
    /// Bytes held by the builder's buffers (capacity).
    pub fn bytes(&self) -> usize {
        self.ghosts.capacity() * 8
            + self.points.capacity() * 24
            + (self.cell_of.capacity() + self.cell_start.capacity() + self.fill.capacity()) * 4
            + self.sorted.capacity() * 32
            + self.sorted_owner.capacity() * 8
            + self.blocks.iter().map(BlockBuffers::bytes).sum::<usize>()
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
        self.add_ghosts(boundary, x, cutoff);
        let grid = CellGrid::over(&self.points, cutoff);
        self.bin(&grid, r, n);
        let nblocks = n.div_ceil(BLOCK);
        self.search(&grid, Reach { radius: r, skin }, nblocks);
        carry_histories(&self.blocks[..nblocks], n, old, out);
    }

    /// The particles, then their periodic images within one cutoff of the box (the ghosts).
    fn add_ghosts(&mut self, boundary: &Boundary, x: &[Vector3<f64>], cutoff: f64) {
        self.ghosts.clear();
        self.points.clear();
        self.points.extend_from_slice(x);
        if !boundary.is_periodic() {
            return;
        }
        let offsets = boundary.offsets();
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

    /// Counting sort of the points (the first `n` are the particles, radii `r`) into the cells
    /// of `grid`: `cell_start` and the cell-ordered copies `sorted` and `sorted_owner`, a cell's
    /// points in increasing point index.
    fn bin(&mut self, grid: &CellGrid, r: &[f64], n: usize) {
        let ncells = grid.len();
        self.cell_of.clear();
        self.cell_of
            .extend(self.points.iter().map(|p| grid.index(grid.cell(p)) as u32));
        self.cell_start.clear();
        self.cell_start.resize(ncells + 1, 0);
        for &c in &self.cell_of {
            self.cell_start[c as usize + 1] += 1;
        }
        for c in 0..ncells {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        self.sorted.clear();
        self.sorted.resize(self.points.len(), [0.0; 4]);
        self.sorted_owner.clear();
        self.sorted_owner.resize(self.points.len(), (0, 0));
        self.fill.clear();
        self.fill.extend_from_slice(&self.cell_start[..ncells]);
        for (q, (&c, x)) in self.cell_of.iter().zip(&self.points).enumerate() {
            let (owner, code) = if q < n {
                (q as u32, Image::ZERO.code())
            } else {
                self.ghosts[q - n]
            };
            let at = self.fill[c as usize] as usize;
            self.sorted[at] = [x.x, x.y, x.z, r[owner as usize]];
            self.sorted_owner[at] = (owner, code);
            self.fill[c as usize] += 1;
        }
    }

    /// The partners of every particle, in parallel over `nblocks` blocks of particles, each into
    /// its own buffers.
    fn search(&mut self, grid: &CellGrid, reach: Reach<'_>, nblocks: usize) {
        if self.blocks.len() < nblocks {
            self.blocks.resize_with(nblocks, Default::default);
        }
        let bins = Bins {
            grid,
            points: &self.points,
            cell_start: &self.cell_start,
            sorted: &self.sorted,
            sorted_owner: &self.sorted_owner,
        };
        let n = reach.radius.len();
        let tasks: Vec<_> = self.blocks[..nblocks].iter_mut().enumerate().collect();
        map_tasks(tasks, |(b, block)| {
            block.partners.clear();
            block.counts.clear();
            for i in b * BLOCK..((b + 1) * BLOCK).min(n) {
                let start = block.partners.len();
                bins.partners_of(i, &reach, &mut block.partners);
                block.counts.push((block.partners.len() - start) as u32);
            }
        });
    }
}

/// Who is a partner of whom: particles closer than `radius[i] + radius[j] + skin`.
#[derive(Debug, Clone, Copy)]
struct Reach<'a> {
    radius: &'a [f64],
    skin: f64,
}

/// The cell grid of one build over the bounding box of all points: the cell side is at least
/// the cutoff and grows if the box is so sparse that the grid would exceed 8 cells per point (a
/// hopper's particles fill a cylinder inside their square bounding box, and the parked ones a
/// sparse lattice below it: a tighter cap would grow the cells, and with them the candidates of
/// every particle, by half).
#[derive(Debug, Clone, Copy)]
struct CellGrid {
    lo: Vector3<f64>,
    inv_cell: f64,
    dims: [usize; 3],
}

/// The most cells along one axis before the cap on the grid's size is applied (a count that
/// fits a `usize` and an `f64` product of three exactly enough to compare with the cap).
const MAX_CELLS_PER_AXIS: f64 = 1e15;

impl CellGrid {
    fn over(points: &[Vector3<f64>], cutoff: f64) -> Self {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        for p in points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let mut cell = cutoff.max(1e-300);
        // A span that is not a number (a particle at infinity, between the run's checks of the
        // state) gives one cell along that axis: no cell count overflows and the grid can
        // still shrink below its cap; every pair with such a particle is then out of reach.
        let dims_of = |cell: f64| -> [usize; 3] {
            std::array::from_fn(|k| {
                let cells = ((hi[k] - lo[k]) / cell).floor();
                if cells.is_finite() {
                    cells.min(MAX_CELLS_PER_AXIS) as usize + 1
                } else {
                    1
                }
            })
        };
        let mut dims = dims_of(cell);
        while (dims[0] as f64) * (dims[1] as f64) * (dims[2] as f64)
            > 8.0 * points.len() as f64 + 27.0
        {
            cell *= 1.26;
            dims = dims_of(cell);
        }
        Self {
            lo,
            inv_cell: 1.0 / cell,
            dims,
        }
    }

    /// Number of cells.
    fn len(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    /// The cell of a point inside the grid's box.
    #[inline(always)]
    fn cell(&self, p: &Vector3<f64>) -> [usize; 3] {
        std::array::from_fn(|k| {
            (((p[k] - self.lo[k]) * self.inv_cell) as usize).min(self.dims[k] - 1)
        })
    }

    /// The index of cell `c` in cell order (x fastest).
    #[inline(always)]
    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }
}

/// What the search reads of a binned build.
#[derive(Clone, Copy)]
struct Bins<'a> {
    grid: &'a CellGrid,
    points: &'a [Vector3<f64>],
    cell_start: &'a [u32],
    sorted: &'a [[f64; 4]],
    sorted_owner: &'a [(u32, u8)],
}

impl Bins<'_> {
    /// The stencil of cell `c` (NStencil): the runs of the cell-ordered points of its (up to)
    /// nine rows of three cells, which are adjacent in cell order, so each row is one run of
    /// `sorted`. Returns the runs and their number of points.
    #[inline(always)]
    fn stencil(&self, c: [usize; 3]) -> (StencilRuns, usize) {
        let d = self.grid.dims;
        let (x_lo, x_hi) = (c[0].saturating_sub(1), (c[0] + 1).min(d[0] - 1));
        let mut runs = StencilRuns::default();
        let mut total = 0;
        for cz in c[2].saturating_sub(1)..(c[2] + 2).min(d[2]) {
            for cy in c[1].saturating_sub(1)..(c[1] + 2).min(d[1]) {
                let row = self.grid.index([0, cy, cz]);
                let run = (
                    self.cell_start[row + x_lo] as usize,
                    self.cell_start[row + x_hi + 1] as usize,
                );
                total += run.1 - run.0;
                runs.push(run);
            }
        }
        (runs, total)
    }

    /// Append the partners `j > i` of particle `i` (NPair), sorted by `(j, image)`.
    #[inline(always)]
    fn partners_of(&self, i: usize, reach: &Reach<'_>, partners: &mut Vec<u64>) {
        let start = partners.len();
        let xi = &self.points[i];
        let ri = reach.radius[i];
        let (runs, total) = self.stencil(self.grid.cell(xi));
        // Every point of the stencil is written at the cursor, which advances only past a
        // partner: no branch on whether a point is one (a third or so are, at random in a
        // packing, so a branch would mispredict often).
        let mut len = start;
        partners.resize(start + total, 0);
        for &(a, b) in runs.as_slice() {
            for (s, &(j, code)) in self.sorted[a..b].iter().zip(&self.sorted_owner[a..b]) {
                let reach = ri + s[3] + reach.skin;
                let (dx, dy, dz) = (xi.x - s[0], xi.y - s[1], xi.z - s[2]);
                let partner = (j as usize > i) & (dx * dx + dy * dy + dz * dz < reach * reach);
                partners[len] = (u64::from(j) << 8) | u64::from(code);
                len += usize::from(partner);
            }
        }
        partners.truncate(len);
        partners[start..].sort_unstable();
    }
}

/// The `[start, end)` runs of a stencil's rows.
#[derive(Debug, Clone, Copy, Default)]
struct StencilRuns {
    runs: [(usize, usize); 9],
    len: usize,
}

impl StencilRuns {
    #[inline(always)]
    fn push(&mut self, run: (usize, usize)) {
        self.runs[self.len] = run;
        self.len += 1;
    }

    #[inline(always)]
    fn as_slice(&self) -> &[(usize, usize)] {
        &self.runs[..self.len]
    }
}

/// Write the new list of `n` particles into `out` from the blocks' partners, and carry the
/// histories of `old` over (FixNeighHistory), in parallel per block: each block writes its
/// share of the list (whose place follows from the blocks' counts) and merges its new pairs
/// with its share of the old list (both sorted by `(i, j, image)`).
fn carry_histories<H: Clone + Default + Send + Sync>(
    blocks: &[BlockBuffers],
    n: usize,
    old: &mut PairList<H>,
    out: &mut PairList<H>,
) {
    let nblocks = blocks.len();
    // Each block's range in the new list (its candidates, in block order) and in the old
    // one (the old pairs whose first particle is in the block: the old list is sorted by
    // `i`, and may be for another number of particles).
    let mut bounds = Vec::with_capacity(nblocks + 1);
    bounds.push(0);
    for block in blocks {
        bounds.push(bounds[bounds.len() - 1] + block.partners.len());
    }
    let m = bounds[nblocks];
    let old_bounds: Vec<usize> = (0..nblocks)
        .map(|b| old.i.partition_point(|&i| (i as usize) < b * BLOCK))
        // The last block also takes the old pairs of particles past `n` (none match).
        .chain([old.len()])
        .collect();

    // Only the live histories are copied; the other entries keep whatever the buffer held,
    // since a history counts only while its pair is active (`old` is overwritten by the
    // next build; its active entries are what this build dropped). Wrenches are stored only
    // by a force evaluation that keeps them, for the list it runs on.
    out.i.resize(m, 0);
    out.j.resize(m, 0);
    out.image.resize(m, 0);
    out.active.resize(m, false);
    out.history.resize(m, H::default());
    out.wrench.clear();
    out.first.resize(n + 1, 0);
    out.first[0] = 0;

    let PairList {
        i: old_i,
        j: old_j,
        image: old_image,
        active: old_active,
        history: old_history,
        ..
    } = old;
    let old_pairs = OldPairs {
        i: old_i,
        j: old_j,
        image: old_image,
        history: old_history,
    };
    let PairList {
        i,
        j,
        image,
        active,
        history,
        first,
        ..
    } = out;
    let new_pairs = NewPairs {
        i,
        j,
        image,
        active,
        history,
    };
    let mut new_parts = new_pairs.split_at_bounds(&bounds).into_iter();
    let mut old_active = split_at_bounds(old_active, &old_bounds).into_iter();
    let tasks: Vec<BlockTask<'_, H>> = blocks
        .iter()
        .zip(first[1..].chunks_mut(BLOCK))
        .enumerate()
        .filter_map(|(b, (block, first))| {
            Some(BlockTask {
                first_particle: b * BLOCK,
                base: bounds[b],
                old_range: old_bounds[b]..old_bounds[b + 1],
                block,
                new: new_parts.next()?,
                first,
                old_active: old_active.next()?,
            })
        })
        .collect();
    map_tasks(tasks, |task| task.run(&old_pairs));
}

/// `slice` cut at `bounds` (increasing, starting at 0): the parts
/// `bounds[k]..bounds[k + 1]`.
pub(crate) fn split_at_bounds<'a, T>(mut slice: &'a mut [T], bounds: &[usize]) -> Vec<&'a mut [T]> {
    let mut parts = Vec::with_capacity(bounds.len().saturating_sub(1));
    for w in bounds.windows(2) {
        let (head, tail) = std::mem::take(&mut slice).split_at_mut(w[1] - w[0]);
        parts.push(head);
        slice = tail;
    }
    parts
}

/// What a block's carry-over reads of the old list.
struct OldPairs<'a, H> {
    i: &'a [u32],
    j: &'a [u32],
    image: &'a [u8],
    history: &'a [H],
}

/// A share of the new list's pair arrays.
struct NewPairs<'a, H> {
    i: &'a mut [u32],
    j: &'a mut [u32],
    image: &'a mut [u8],
    active: &'a mut [bool],
    history: &'a mut [H],
}

impl<H> NewPairs<'_, H> {
    /// The first `mid` pairs and the rest.
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (i, i_rest) = self.i.split_at_mut(mid);
        let (j, j_rest) = self.j.split_at_mut(mid);
        let (image, image_rest) = self.image.split_at_mut(mid);
        let (active, active_rest) = self.active.split_at_mut(mid);
        let (history, history_rest) = self.history.split_at_mut(mid);
        (
            Self {
                i,
                j,
                image,
                active,
                history,
            },
            Self {
                i: i_rest,
                j: j_rest,
                image: image_rest,
                active: active_rest,
                history: history_rest,
            },
        )
    }

    /// The shares `bounds[k]..bounds[k + 1]` (as [`split_at_bounds`]).
    fn split_at_bounds(self, bounds: &[usize]) -> Vec<Self> {
        let mut parts = Vec::with_capacity(bounds.len().saturating_sub(1));
        let mut rest = self;
        for w in bounds.windows(2) {
            let (head, tail) = rest.split_at(w[1] - w[0]);
            parts.push(head);
            rest = tail;
        }
        parts
    }
}

/// One search block's share of the new list, and its old pairs' `active` flags.
struct BlockTask<'a, H> {
    /// Index of the block's first particle.
    first_particle: usize,
    /// Index of the block's first pair in the new list.
    base: usize,
    /// The block's pairs in the old list.
    old_range: std::ops::Range<usize>,
    block: &'a BlockBuffers,
    new: NewPairs<'a, H>,
    /// `first[i + 1]` of the block's particles.
    first: &'a mut [u32],
    old_active: &'a mut [bool],
}

impl<H: Clone> BlockTask<'_, H> {
    fn run(self, old: &OldPairs<'_, H>) {
        let BlockBuffers { partners, counts } = self.block;
        let new = self.new;
        let mut p = 0;
        for (di, &count) in counts.iter().enumerate() {
            let i = (self.first_particle + di) as u32;
            for &partner in &partners[p..p + count as usize] {
                new.i[p] = i;
                new.j[p] = (partner >> 8) as u32;
                new.image[p] = partner as u8;
                p += 1;
            }
            self.first[di] = (self.base + p) as u32;
        }
        let old_base = self.old_range.start;
        let old_key = |q: usize| (old.i[q], old.j[q], old.image[q]);
        let mut q = self.old_range.start;
        for p in 0..new.i.len() {
            let key = (new.i[p], new.j[p], new.image[p]);
            while q < self.old_range.end && old_key(q) < key {
                q += 1;
            }
            let carried = q < self.old_range.end
                && old_key(q) == key
                && std::mem::take(&mut self.old_active[q - old_base]);
            // Carried over: what stays active in `old` was dropped by this build.
            new.active[p] = carried;
            if carried {
                new.history[p].clone_from(&old.history[q]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Every pair `(i < j, image)` closer than `r_i + r_j + skin`, by testing all of them.
    fn brute_force(
        boundary: &Boundary,
        x: &[Vector3<f64>],
        r: &[f64],
        skin: f64,
    ) -> Vec<(u32, u32, u8)> {
        let offsets = boundary.offsets();
        let codes: Vec<u8> = if boundary.is_periodic() {
            (0..9).collect()
        } else {
            vec![Image::ZERO.code()]
        };
        let mut pairs = Vec::new();
        for i in 0..x.len() {
            for j in i + 1..x.len() {
                for &code in &codes {
                    let reach = r[i] + r[j] + skin;
                    if (x[i] - (x[j] + offsets[code as usize].position)).norm_squared()
                        < reach * reach
                    {
                        pairs.push((i as u32, j as u32, code));
                    }
                }
            }
        }
        pairs
    }

    /// The binned search finds exactly the pairs a test of every pair finds, sorted, with the
    /// per-particle indexes consistent: dense and polydisperse, in open space with a sparse
    /// cloud far away (which makes the grid coarser than the cutoff) and in a periodic box.
    #[test]
    fn binned_search_matches_every_pair_tested() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let skin = 0.1;
        for periodic in [false, true] {
            let boundary = if periodic {
                Boundary::periodic_xy((0.0, 6.0), (0.0, 5.0)).unwrap()
            } else {
                Boundary::Open
            };
            let mut x = Vec::new();
            let mut r = Vec::new();
            for _ in 0..1500 {
                x.push(Vector3::new(
                    rng.random_range(0.0..6.0),
                    rng.random_range(0.0..5.0),
                    rng.random_range(0.0..4.0),
                ));
                r.push(rng.random_range(0.2..0.35));
            }
            if !periodic {
                for _ in 0..300 {
                    x.push(Vector3::new(
                        rng.random_range(-60.0..60.0),
                        rng.random_range(-60.0..60.0),
                        rng.random_range(-60.0..0.0),
                    ));
                    r.push(0.3);
                }
            }
            let mut builder = NeighbourBuilder::default();
            let (mut old, mut list) = (PairList::<u8>::default(), PairList::<u8>::default());
            builder.build(&boundary, &x, &r, skin, &mut old, &mut list);
            let found: Vec<(u32, u32, u8)> = (0..list.len())
                .map(|p| (list.i[p], list.j[p], list.image[p]))
                .collect();
            let expected = brute_force(&boundary, &x, &r, skin);
            assert!(expected.len() > 2 * x.len(), "a dense packing");
            assert_eq!(found, expected, "periodic: {periodic}");
            for i in 0..x.len() {
                let first = list.first[i] as usize..list.first[i + 1] as usize;
                assert!(list.i[first].iter().all(|&k| k as usize == i));
            }
        }
    }

    /// A particle at infinity, at NaN or 10^300 m away (a run going wrong between its checks
    /// of the state) builds a list without overflowing a cell count: the finite particles keep
    /// exactly their pairs, and the particle out of reach has none.
    #[test]
    fn a_particle_at_infinity_or_far_away_builds_a_list() {
        let skin = 0.1;
        let base = vec![
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(0.5, 0.0, 0.0),
            Vector3::new(3.0, 0.0, 0.0),
        ];
        for stray in [
            Vector3::new(0.0, 0.0, f64::NEG_INFINITY),
            Vector3::new(f64::INFINITY, 1.0, 0.0),
            Vector3::new(f64::NAN, 0.0, 0.0),
            Vector3::new(0.0, -1e300, 0.0),
        ] {
            let mut x = base.clone();
            x.push(stray);
            let r = vec![0.3; x.len()];
            let mut builder = NeighbourBuilder::default();
            let (mut old, mut list) = (PairList::<u8>::default(), PairList::<u8>::default());
            builder.build(&Boundary::Open, &x, &r, skin, &mut old, &mut list);
            let found: Vec<(u32, u32)> = (0..list.len()).map(|p| (list.i[p], list.j[p])).collect();
            assert_eq!(found, vec![(0, 1)], "stray particle at {stray:?}");
        }
    }

    /// Over many search blocks, and when particles were removed or added since the last
    /// build, a rebuild carries exactly the live histories whose key it lists again (checked
    /// against a map by key), marks every other pair inactive, and leaves active in the old
    /// list exactly the live pairs it dropped.
    #[test]
    fn rebuild_carries_histories_across_blocks_by_key() {
        use std::collections::HashMap;
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let boundary = Boundary::periodic_xy((0.0, 8.0), (0.0, 8.0)).unwrap();
        let cloud = |rng: &mut ChaCha8Rng, n: usize| -> Vec<Vector3<f64>> {
            (0..n)
                .map(|_| {
                    Vector3::new(
                        rng.random_range(0.0..8.0),
                        rng.random_range(0.0..8.0),
                        rng.random_range(0.0..6.0),
                    )
                })
                .collect()
        };
        let x = cloud(&mut rng, 3000);
        for n_next in [3000, 2100, 3400] {
            let mut builder = NeighbourBuilder::default();
            let (mut old, mut list) = (PairList::<u64>::default(), PairList::<u64>::default());
            builder.build(&boundary, &x, &vec![0.25; 3000], 0.1, &mut old, &mut list);
            let mut live = HashMap::new();
            for p in 0..list.len() {
                list.active[p] = rng.random_bool(0.5);
                list.history[p] = rng.random();
                if list.active[p] {
                    live.insert((list.i[p], list.j[p], list.image[p]), list.history[p]);
                }
            }
            // Keep the first particles (moved a little), drop or add the rest.
            let mut moved: Vec<Vector3<f64>> = x[..n_next.min(3000)]
                .iter()
                .map(|p| {
                    let shift = Vector3::new(
                        rng.random_range(-0.05..0.05),
                        rng.random_range(-0.05..0.05),
                        rng.random_range(-0.05..0.05),
                    );
                    let mut q = p + shift;
                    q.z = q.z.max(0.0);
                    let mut v = Vector3::zeros();
                    boundary.wrap(&mut q, &mut v);
                    q
                })
                .collect();
            moved.extend(cloud(&mut rng, n_next.saturating_sub(3000)));
            let mut next = PairList::default();
            builder.build(
                &boundary,
                &moved,
                &vec![0.25; n_next],
                0.1,
                &mut list,
                &mut next,
            );
            assert!(next.len() > 4 * BLOCK, "pairs of several blocks");
            let mut carried = 0;
            for p in 0..next.len() {
                let key = (next.i[p], next.j[p], next.image[p]);
                match live.remove(&key) {
                    Some(h) => {
                        assert!(next.active[p], "{key:?} carried");
                        assert_eq!(next.history[p], h, "{key:?}");
                        carried += 1;
                    }
                    None => assert!(!next.active[p], "{key:?} starts apart"),
                }
            }
            assert!(carried > 1000, "most live pairs are listed again");
            // What is left in the map was dropped while live: exactly the old list's active.
            let dropped: Vec<_> = (0..list.len())
                .filter(|&p| list.active[p])
                .map(|p| (list.i[p], list.j[p], list.image[p]))
                .collect();
            assert_eq!(dropped.len(), live.len(), "n = {n_next}");
            assert!(dropped.iter().all(|k| live.contains_key(k)));
            assert_eq!(next.first.len(), n_next + 1);
            for i in 0..n_next {
                let own = next.first[i] as usize..next.first[i + 1] as usize;
                assert!(next.i[own].iter().all(|&k| k as usize == i));
            }
        }
    }

    /// A rebuild carries each live pair's history over by `(i, j, image)`, lists new pairs as
    /// inactive, and leaves the pairs it dropped active in the old list.
    #[test]
    fn rebuild_carries_live_histories_by_key() {
        let x = vec![
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(0.9, 0.0, 0.0),
            Vector3::new(0.45, 0.8, 0.0),
        ];
        let r = vec![0.5; 3];
        let mut builder = NeighbourBuilder::default();
        let (mut old, mut list) = (PairList::<u32>::default(), PairList::<u32>::default());
        builder.build(&Boundary::Open, &x, &r, 0.1, &mut old, &mut list);
        assert_eq!(
            (list.i.clone(), list.j.clone()),
            (vec![0, 0, 1], vec![1, 2, 2])
        );
        assert_eq!(
            list.active,
            vec![false; 3],
            "a first build lists every pair as apart"
        );
        // Pairs (0, 1) and (0, 2) touch with a history; (1, 2) is listed but apart.
        list.active = vec![true, true, false];
        list.history = vec![11, 12, 0];
        // Particle 2 leaves: (0, 2) and (1, 2) drop out, (0, 1) stays.
        let moved = vec![x[0], x[1], Vector3::new(0.0, 5.0, 0.0)];
        let mut next = PairList::default();
        builder.build(&Boundary::Open, &moved, &r, 0.1, &mut list, &mut next);
        assert_eq!((next.i.clone(), next.j.clone()), (vec![0], vec![1]));
        assert_eq!(
            (next.history.clone(), next.active.clone()),
            (vec![11], vec![true])
        );
        assert_eq!(
            list.active,
            vec![false, true, false],
            "(0, 2) was dropped while live"
        );
    }
}
