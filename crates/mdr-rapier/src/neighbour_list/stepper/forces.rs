//! The force passes of a step: particle–surface pairs, then sphere–sphere pairs in two passes
//! per chunk, summed per particle block in an order fixed by the particle count alone.

use super::*;
use crate::neighbour_list::boundary::ImageOffset;
use crate::neighbour_list::neighbours::split_at_bounds;

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
    /// Step 3: sphere–sphere pairs, one parallel task per block of particles ([`particle_block`]),
    /// with the per-particle sums of forces and torques, LAMMPS's scatter made parallel without
    /// atomics: a block's pairs (those whose first particle is in it) add each wrench to both
    /// particles as they are met, in pair order, into the block's window, its own particles'
    /// sums and the next block's. Windows of blocks of one colour (even or odd index) do not
    /// overlap, so all blocks of one colour run in parallel, then those of the other; an even
    /// block first starts its window's sums with their surface wrenches. A share for a particle
    /// beyond the next block is deferred and added after both colours, in block and pair order.
    /// Every sum so has one order, fixed by the particle count and the list, whatever the number
    /// of threads. With `keep`, every pair's wrench is also stored in [`PairList::wrench`] (zero
    /// where the pair does not touch). Returns the number of touching pairs.
    pub(super) fn sphere_wrenches(&mut self, dt: f64, keep: bool) -> usize {
        let n = self.particles.len();
        let PairList {
            i,
            j,
            image,
            active,
            history,
            wrench,
            first,
        } = &mut self.pairs;
        let block_len = particle_block(n);
        let nblocks = n.div_ceil(block_len);
        let bounds: Vec<usize> = (0..=nblocks)
            .map(|b| first[(b * block_len).min(n)] as usize)
            .collect();
        wrench.clear();
        if keep {
            wrench.resize(history.len(), PairWrench::default());
        }
        self.sums.resize(n, (Vector3::zeros(), Vector3::zeros()));
        self.deferred.resize_with(nblocks, Vec::new);
        let pass = PairPass::<N, T, D, R> {
            particles: &self.particles,
            offsets: self.boundary.offsets(),
            laws: &self.sphere_laws,
            species: self.laws_species,
            record: self.ended.is_some(),
            surface_start: &self.surface_pairs.start,
            surface_wrench: &self.surface_pairs.wrench,
            i,
            j,
            image,
            bounds: &bounds,
            block_len,
            dt,
            adhesive: self.adhesive,
        };
        // Blocks of one colour have disjoint windows: all of one colour in parallel, then all
        // of the other.
        let mut wrench_parts: Vec<Option<&mut [PairWrench]>> = if keep {
            split_at_bounds(wrench, &bounds)
                .into_iter()
                .map(Some)
                .collect()
        } else {
            (0..nblocks).map(|_| None).collect()
        };
        let mut active_parts = split_at_bounds(active, &bounds).into_iter();
        let tasks: Vec<BlockPairs<'_, NeighbourListHistory<N, T, R, B>>> =
            split_at_bounds(history, &bounds)
                .into_iter()
                .zip(self.deferred.iter_mut())
                .enumerate()
                .filter_map(|(b, (history, deferred))| {
                    Some(BlockPairs {
                        index: b,
                        history,
                        active: active_parts.next()?,
                        wrench: wrench_parts.get_mut(b)?.take(),
                        deferred,
                    })
                })
                .collect();
        let (even, odd): (Vec<_>, Vec<_>) = tasks.into_iter().partition(|t| t.index % 2 == 0);
        // An even block's window starts at its own first particle, and so does an odd one's.
        let mut results = Vec::with_capacity(nblocks);
        for (colour, start) in [(even, 0), (odd, block_len.min(n))] {
            let tasks: Vec<_> = colour
                .into_iter()
                .zip(self.sums[start..].chunks_mut(2 * block_len))
                .collect();
            results.extend(map_tasks(tasks, |(block, sums)| pass.block(block, sums)));
        }
        // The shares for particles beyond the next block, in block and pair order.
        for deferred in &self.deferred {
            for c in deferred {
                let sum = &mut self.sums[c.particle as usize];
                sum.0 += c.force;
                sum.1 += c.torque;
            }
        }
        // Ended contacts in block order.
        results.sort_unstable_by_key(|r| r.block);
        self.collect_ended(results.into_iter().map(|r| (r.touching, r.ended)).collect())
    }

    /// Sum the chunks' touching counts and append their ended contacts in chunk order.
    fn collect_ended(&mut self, results: Vec<(usize, Vec<EndedContact>)>) -> usize {
        let mut touching = 0;
        for (count, mut ended) in results {
            touching += count;
            if let Some(all) = &mut self.ended {
                all.append(&mut ended);
            }
        }
        touching
    }

    /// Step 2: particle–surface pairs. Returns the number of touching pairs.
    pub(super) fn surface_wrenches(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        dt: f64,
    ) -> usize {
        let p = &self.particles;
        let laws = &self.surface_laws;
        let surfaces = &self.surfaces;
        let nsurf = surfaces.len();
        let record = self.ended.is_some();
        let adhesive = self.surface_adhesive;
        let SurfacePairs {
            particle,
            surface,
            active,
            history,
            wrench,
            contact: contacts,
            ..
        } = &mut self.surface_pairs;
        let (particle, surface) = (&*particle, &*surface);
        // Smaller chunks than the sphere pairs': a scene's wall contacts are few (a floor
        // under a column, a hopper's rim), and one or two chunks would leave a thread idle.
        let chunks: Vec<_> = history
            .chunks_mut(SURFACE_CHUNK)
            .zip(wrench.chunks_mut(SURFACE_CHUNK))
            .zip(active.chunks_mut(SURFACE_CHUNK))
            .zip(contacts.chunks_mut(SURFACE_CHUNK))
            .enumerate()
            .collect();
        let results: Vec<(usize, Vec<EndedContact>)> =
            map_tasks(chunks, |(c, (((history, wrench), active), contacts))| {
                let base = c * SURFACE_CHUNK;
                let mut touching = 0;
                let mut ended = Vec::new();
                for k in 0..history.len() {
                    let q = base + k;
                    let (i, s) = (particle[q] as usize, surface[q] as usize);
                    let surf = &surfaces[s];
                    let (law, rolling) = &laws[p.species[i] as usize * nsurf + s];
                    let contact = colliders.get(surf.collider).and_then(|co| {
                        surf.sphere_contact(co, &p.position[i], p.radius[i])
                            .or_else(|| {
                                // A held adhesive contact goes on at its negative overlap.
                                let held = adhesive
                                    && active[k]
                                    && law.normal.holds(&history[k].contact.normal);
                                held.then(|| {
                                    surf.sphere_contact_signed(co, &p.position[i], p.radius[i])
                                })
                                .flatten()
                            })
                    });
                    let Some(contact) = contact else {
                        if active[k] {
                            if record {
                                ended.push(EndedContact::of(
                                    i as u32,
                                    ContactPartner::Surface(s as u32),
                                    &laws[p.species[i] as usize * nsurf + s],
                                    &history[k],
                                ));
                            }
                            active[k] = false;
                            history[k] = Default::default();
                            wrench[k] = PairWrench::default();
                        }
                        continue;
                    };
                    active[k] = true;
                    touching += 1;
                    let (linvel2, angvel2, arm2) = match surf.body.and_then(|h| bodies.get(h)) {
                        Some(b2) => (
                            to_na(b2.linvel()),
                            to_na(b2.angvel()),
                            contact.point - to_na(b2.center_of_mass()),
                        ),
                        None => (Vector3::zeros(), Vector3::zeros(), Vector3::zeros()),
                    };
                    let kinematics = ContactKinematics {
                        overlap: contact.overlap,
                        normal: contact.normal,
                        arms: Arms {
                            arm1: contact.point - p.position[i],
                            arm2,
                        },
                        linvel1: p.linvel[i],
                        angvel1: p.angvel[i],
                        linvel2,
                        angvel2,
                    };
                    wrench[k] = evaluate_pair(law, rolling, &mut history[k], &kinematics, dt);
                    contacts[k] = contact;
                }
                (touching, ended)
            });
        self.collect_ended(results)
    }
}

/// Particles per block of the sphere pair loop: from the particle count alone (about 40
/// blocks; never from the number of threads, so that every sum has the same order for any
/// number of threads). At least 512 from 4,096 particles on, so that a window of two blocks
/// spans the index distance of most pairs of a lattice-ordered bed (a layer of a 10⁴-sphere bed
/// is about 500 spheres) and few shares are deferred; below that, eight blocks (of at least 64),
/// so that a small system still splits between threads; at most 4,096, so that a window's sums
/// (48 bytes each) stay in the core's cache.
pub(super) fn particle_block(n: usize) -> usize {
    (n / 40).clamp((n / 8).clamp(64, 512), 4096)
}

/// What a touching pair gives its second particle when that particle lies beyond the next
/// block.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct DeferredShare {
    particle: u32,
    force: Vector3<f64>,
    torque: Vector3<f64>,
}

/// The composed and rolling laws bound to one species pair.
type BoundLaws<N, T, D, R> = (Law<N, T, D>, <R as RollingModel>::Law);

/// Per-particle force and torque sums.
type Sums = (Vector3<f64>, Vector3<f64>);

/// What every block of the sphere pair pass reads: the particles, the list's pairs, the bound
/// laws and the surface wrenches that start the sums.
struct PairPass<'a, N: NormalModel, T: TangentialModel, D: DampingModel, R: RollingModel> {
    particles: &'a NeighbourListParticles,
    offsets: [ImageOffset; 9],
    /// Sphere–sphere laws by species pair `(a, b)` at `a * species + b`.
    laws: &'a [BoundLaws<N, T, D, R>],
    species: usize,
    /// Whether ended contacts are recorded.
    record: bool,
    surface_start: &'a [u32],
    surface_wrench: &'a [PairWrench],
    i: &'a [u32],
    j: &'a [u32],
    image: &'a [u8],
    /// `bounds[b]..bounds[b + 1]`: the pairs of block `b`.
    bounds: &'a [usize],
    block_len: usize,
    dt: f64,
    /// Whether a law is adhesive: a contact may hold apart.
    adhesive: bool,
}

/// One block's share of the pair list, and its deferred shares.
struct BlockPairs<'a, H> {
    index: usize,
    history: &'a mut [H],
    active: &'a mut [bool],
    wrench: Option<&'a mut [PairWrench]>,
    deferred: &'a mut Vec<DeferredShare>,
}

/// One chunk of a block's pairs: its particles, images, histories, flags and wrenches, all
/// sliced to the chunk's length (so that indexing them by a pair of the chunk needs no bounds
/// check once the slices are made).
struct ChunkPairs<'a, H> {
    i: &'a [u32],
    j: &'a [u32],
    image: &'a [u8],
    history: &'a mut [H],
    active: &'a mut [bool],
    wrench: Option<&'a mut [PairWrench]>,
}

/// Where a block adds its wrenches: the sums of its particles and the next block's, from
/// particle `first` on, and the shares deferred for particles beyond them.
struct Window<'a> {
    sums: &'a mut [Sums],
    first: usize,
    deferred: &'a mut Vec<DeferredShare>,
}

impl Window<'_> {
    /// Add the wrench of the pair `(i, j)` to both particles' sums (`i` is in the window and
    /// `j ≥ i`: only a partner further on is deferred, rare once a block is thicker than the
    /// reach of a pair in index).
    #[inline(always)]
    fn add(&mut self, i: usize, j: usize, w: &PairWrench) {
        let first = &mut self.sums[i - self.first];
        first.0 += w.force;
        first.1 += w.torque1;
        match self.sums.get_mut(j.wrapping_sub(self.first)) {
            Some(second) => {
                second.0 += -w.force;
                second.1 += w.torque2;
            }
            None => self.deferred.push(DeferredShare {
                particle: j as u32,
                force: -w.force,
                torque: w.torque2,
            }),
        }
    }
}

/// The touching pairs of a chunk, by index in the chunk.
struct Touching {
    pairs: [u16; CHUNK],
    len: usize,
}

/// The overlap and normal of a group of touching pairs (pass 2): made once per block, not once
/// per chunk, so that a chunk does not spend a store per entry setting it up.
type Geometry = [(f64, Vector3<f64>); BLOCK];

/// What one block of the pair pass found.
struct BlockOutcome {
    block: usize,
    touching: usize,
    ended: Vec<EndedContact>,
}

impl<N, T, D, R> PairPass<'_, N, T, D, R>
where
    N: NormalModel,
    T: TangentialModel,
    D: DampingModel,
    R: RollingModel,
{
    /// One block's pairs: its window is the block's sums and the next block's. A block of the
    /// first colour (even index) first starts both blocks' sums with their surface wrenches.
    fn block<B: WorkBooks>(
        &self,
        block: BlockPairs<'_, NeighbourListHistory<N, T, R, B>>,
        sums: &mut [Sums],
    ) -> BlockOutcome {
        let BlockPairs {
            index: b,
            history,
            active,
            mut wrench,
            deferred,
        } = block;
        let mut ended = Vec::new();
        deferred.clear();
        let mut window = Window {
            sums,
            first: b * self.block_len,
            deferred,
        };
        if b % 2 == 0 {
            self.start_sums(&mut window);
        }
        let mut geometry: Geometry = [(0.0, Vector3::zeros()); BLOCK];
        let mut touching = 0;
        for sub in (0..history.len()).step_by(CHUNK) {
            let len = (history.len() - sub).min(CHUNK);
            let base = self.bounds[b] + sub;
            let chunk = ChunkPairs {
                i: &self.i[base..base + len],
                j: &self.j[base..base + len],
                image: &self.image[base..base + len],
                history: &mut history[sub..sub + len],
                active: &mut active[sub..sub + len],
                wrench: wrench.as_deref_mut().map(|w| &mut w[sub..sub + len]),
            };
            // The adhesive test once per chunk: each instance of `chunk` compiles its own
            // overlap test and geometry.
            touching += if self.adhesive {
                self.chunk::<true, B>(chunk, &mut geometry, &mut window, &mut ended)
            } else {
                self.chunk::<false, B>(chunk, &mut geometry, &mut window, &mut ended)
            };
        }
        BlockOutcome {
            block: b,
            touching,
            ended,
        }
    }

    /// Start the window's sums with each particle's surface wrenches.
    fn start_sums(&self, window: &mut Window<'_>) {
        for (sum, i) in window.sums.iter_mut().zip(window.first..) {
            let mut force = Vector3::zeros();
            let mut torque = Vector3::zeros();
            let own = self.surface_start[i] as usize..self.surface_start[i + 1] as usize;
            for w in &self.surface_wrench[own] {
                force += w.force;
                torque += w.torque1;
            }
            *sum = (force, torque);
        }
    }

    /// One chunk: the touching pairs (pass 1), then per group of them their geometry and law
    /// (pass 2). `HOLDS`: whether a law is adhesive (see [`PairPass::touching`]). Returns the
    /// number of touching pairs.
    #[inline(always)]
    fn chunk<const HOLDS: bool, B: WorkBooks>(
        &self,
        mut chunk: ChunkPairs<'_, NeighbourListHistory<N, T, R, B>>,
        geometry: &mut Geometry,
        window: &mut Window<'_>,
        ended: &mut Vec<EndedContact>,
    ) -> usize {
        let touching = self.touching::<HOLDS, B>(&mut chunk, ended);
        // Per group of touching pairs: first the geometry (a square root and a division per
        // pair, independent of each other, so they overlap instead of heading each pair's
        // dependency chain through the law), then the law.
        for group in touching.pairs[..touching.len].chunks(BLOCK) {
            self.geometry::<HOLDS, B>(&chunk, group, geometry);
            for (&k, contact) in group.iter().zip(geometry.iter()) {
                self.evaluate(&mut chunk, k as usize, contact, window);
            }
        }
        touching.len
    }

    /// The particles and image offset of the chunk's pair `k`.
    #[inline(always)]
    fn pair<H>(&self, chunk: &ChunkPairs<'_, H>, k: usize) -> (usize, usize, &ImageOffset) {
        (
            chunk.i[k] as usize,
            chunk.j[k] as usize,
            &self.offsets[chunk.image[k] as usize],
        )
    }

    /// The bound laws of particles `i` and `j`.
    #[inline(always)]
    fn laws(&self, i: usize, j: usize) -> &BoundLaws<N, T, D, R> {
        let s = &self.particles.species;
        &self.laws[s[i] as usize * self.species + s[j] as usize]
    }

    /// Pass 1, the overlap test alone (the exact test `sphere_sphere` makes): collect the
    /// touching pairs of the chunk without a data-dependent branch, and forget the pairs that
    /// separated. Pass 2 runs the law on the touching ones only, so the unpredictable
    /// touch/apart branch of a mixed list is not taken per pair. With `HOLDS` (adhesive laws)
    /// a live pair that no longer overlaps but whose contact still holds
    /// ([`mdr_contact::normal::NormalLaw::holds`]) counts as touching and is evaluated at its
    /// negative overlap until its law lets go; the hold test sits in the rare branch of a live
    /// pair that no longer overlaps (the one that separates pairs), so the other listed pairs
    /// (most of the longer list that the necks' reach needs) pay nothing for it; without
    /// `HOLDS` it is compiled away. Not inlined: the loop then keeps its slices and counters in
    /// registers instead of sharing them with the law's.
    #[inline(never)]
    fn touching<const HOLDS: bool, B: WorkBooks>(
        &self,
        chunk: &mut ChunkPairs<'_, NeighbourListHistory<N, T, R, B>>,
        ended: &mut Vec<EndedContact>,
    ) -> Touching {
        let (position, radius) = (&self.particles.position[..], &self.particles.radius[..]);
        let offsets = &self.offsets;
        let (pi, pj, image) = (chunk.i, chunk.j, chunk.image);
        let mut touching = Touching {
            pairs: [0u16; CHUNK],
            len: 0,
        };
        for (k, ((&i, &j), &image)) in pi.iter().zip(pj).zip(image).enumerate() {
            let (i, j) = (i as usize, j as usize);
            let xj = position[j] + offsets[image as usize].position;
            let dist2 = (position[i] - xj).norm_squared();
            let reach = radius[i] + radius[j];
            let touch = !(dist2 >= reach * reach || dist2 == 0.0);
            touching.pairs[touching.len] = k as u16;
            let mut live = touch;
            if chunk.active[k] & !touch {
                // A live pair that no longer overlaps: it goes on while its contact holds, and
                // separates otherwise. Only here are the pair's law and history read.
                live = HOLDS
                    && dist2 != 0.0
                    && self
                        .laws(i, j)
                        .0
                        .normal
                        .holds(&chunk.history[k].contact.normal);
                if !live {
                    self.separate(chunk, k, ended);
                }
            }
            touching.len += usize::from(live);
        }
        touching
    }

    /// The chunk's live pair `k` separated: the rapier pipeline path drops the entry; this one
    /// marks the pair inactive and leaves its history as it is (a pair that touches again
    /// starts from the default, in `evaluate`).
    #[inline(always)]
    fn separate<B: WorkBooks>(
        &self,
        chunk: &mut ChunkPairs<'_, NeighbourListHistory<N, T, R, B>>,
        k: usize,
        ended: &mut Vec<EndedContact>,
    ) {
        if self.record {
            let (i, j, _) = self.pair(chunk, k);
            ended.push(EndedContact::of(
                i as u32,
                ContactPartner::Sphere(j as u32),
                self.laws(i, j),
                &chunk.history[k],
            ));
        }
        chunk.active[k] = false;
    }

    /// Overlap and normal of the touching pairs `group` of the chunk (`HOLDS`: at any distance,
    /// as a held pair may be apart), into the first `group.len()` entries of `out` (a local
    /// array, so that its stores cannot alias the particles' data and force reloads).
    #[inline(always)]
    fn geometry<const HOLDS: bool, B: WorkBooks>(
        &self,
        chunk: &ChunkPairs<'_, NeighbourListHistory<N, T, R, B>>,
        group: &[u16],
        out: &mut [(f64, Vector3<f64>); BLOCK],
    ) {
        let (position, radius) = (&self.particles.position[..], &self.particles.radius[..]);
        for (slot, &k) in out.iter_mut().zip(group) {
            let (i, j, offset) = self.pair(chunk, k as usize);
            let xj = position[j] + offset.position;
            // Always `Some`: pass 1 made the same test (and a held pair's centres differ).
            let contact = if HOLDS {
                sphere_sphere_signed(&position[i], radius[i], &xj, radius[j])
            } else {
                sphere_sphere(&position[i], radius[i], &xj, radius[j])
            };
            *slot = contact.map_or((0.0, Vector3::zeros()), |c| (c.overlap, c.normal));
        }
    }

    /// The law on the chunk's touching pair `k` with overlap and normal `contact`, its wrench
    /// added to the window.
    #[inline(always)]
    fn evaluate<B: WorkBooks>(
        &self,
        chunk: &mut ChunkPairs<'_, NeighbourListHistory<N, T, R, B>>,
        k: usize,
        &(overlap, normal): &(f64, Vector3<f64>),
        window: &mut Window<'_>,
    ) {
        let p = self.particles;
        let (i, j, offset) = self.pair(chunk, k);
        if !chunk.active[k] {
            // A contact begins: from the default history (an inactive pair's entry is stale,
            // see `PairList::history`).
            chunk.history[k] = Default::default();
            chunk.active[k] = true;
        }
        let kinematics = ContactKinematics {
            overlap,
            normal,
            arms: SphereArms {
                lever1: p.radius[i] - 0.5 * overlap,
                lever2: p.radius[j] - 0.5 * overlap,
            },
            linvel1: p.linvel[i],
            angvel1: p.angvel[i],
            linvel2: p.linvel[j] + offset.velocity,
            angvel2: p.angvel[j],
        };
        let (law, rolling) = self.laws(i, j);
        let w = evaluate_pair(law, rolling, &mut chunk.history[k], &kinematics, self.dt);
        if let Some(wrench) = chunk.wrench.as_deref_mut() {
            wrench[k] = w;
        }
        window.add(i, j, &w);
    }
}
