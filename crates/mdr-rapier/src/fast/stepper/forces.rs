//! The force passes of a step: particle–surface pairs, then sphere–sphere pairs in two passes
//! per chunk, and the fixed-order per-particle gather.

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
    /// One-thread path: start each particle's sums with its surface wrenches, in the order the
    /// parallel path's gather adds them.
    pub(super) fn surface_sums(&mut self) {
        let sp = &self.surface_pairs;
        let n = self.particles.len();
        self.sums.clear();
        self.sums.extend((0..n).map(|i| {
            let mut force = Vector3::zeros();
            let mut torque = Vector3::zeros();
            for w in &sp.wrench[sp.start[i] as usize..sp.start[i + 1] as usize] {
                force += w.force;
                torque += w.torque1;
            }
            (force, torque)
        }));
    }

    /// Step 3: sphere–sphere pairs. Returns the number of touching pairs. With `serial`, each
    /// wrench is also added to both particles' sums (`self.sums`, started by
    /// [`Self::surface_sums`]) in pair order.
    pub(super) fn sphere_wrenches(&mut self, dt: f64, serial: bool) -> usize {
        let offsets = self.boundary.offsets();
        let p = &self.particles;
        let laws = &self.sphere_laws;
        let ns = self.laws_species;
        let record = self.ended.is_some();
        let PairList {
            i: pi,
            j: pj,
            image,
            active,
            history,
            wrench,
            ..
        } = &mut self.pairs;
        let (pi, pj, image) = (&*pi, &*pj, &*image);
        let chunk = |c: usize,
                     history: &mut [FastHistory<N, T, R, B>],
                     wrench: &mut [PairWrench],
                     active: &mut [bool],
                     mut sums: Option<&mut [(Vector3<f64>, Vector3<f64>)]>|
         -> (usize, Vec<EndedContact>) {
            let mut ended = Vec::new();
            let base = c * CHUNK;
            let len = history.len();
            let (pi, pj, image) = (
                &pi[base..base + len],
                &pj[base..base + len],
                &image[base..base + len],
            );
            // Pass 1, the overlap test alone (the exact test `sphere_sphere` makes): collect
            // the touching pairs of the chunk without a data-dependent branch, and forget the
            // pairs that separated. Pass 2 runs the law on the touching ones only, so the
            // unpredictable touch/apart branch of a mixed list is not taken per pair.
            let mut touching_pairs = [0u16; CHUNK];
            let mut touching = 0usize;
            for k in 0..len {
                let (i, j) = (pi[k] as usize, pj[k] as usize);
                let xj = p.position[j] + offsets[image[k] as usize].position;
                let dist2 = (p.position[i] - xj).norm_squared();
                let reach = p.radius[i] + p.radius[j];
                let touch = !(dist2 >= reach * reach || dist2 == 0.0);
                touching_pairs[touching] = k as u16;
                touching += usize::from(touch);
                if active[k] & !touch {
                    // Separated: the plain path drops the entry; this one marks the pair
                    // inactive and leaves its history as it is (a pair that touches again
                    // starts from the default, below). The wrench of an inactive pair is kept
                    // at zero, so that the per-particle gather need not test `active`.
                    if record {
                        ended.push(EndedContact::of(
                            i as u32,
                            ContactPartner::Sphere(j as u32),
                            &laws[p.species[i] as usize * ns + p.species[j] as usize],
                            &history[k],
                        ));
                    }
                    active[k] = false;
                    if let Some(w) = wrench.get_mut(k) {
                        *w = PairWrench::default();
                    }
                }
            }
            // Pass 2, per block of touching pairs: first the geometry (a square root and a
            // division per pair, independent of each other, so they overlap instead of heading
            // each pair's dependency chain through the law), then the law.
            let mut geometry: Vec<(f64, Vector3<f64>)> = Vec::with_capacity(BLOCK);
            for block in touching_pairs[..touching].chunks(BLOCK) {
                geometry.clear();
                geometry.extend(block.iter().map(|&k| {
                    let k = k as usize;
                    let (i, j) = (pi[k] as usize, pj[k] as usize);
                    let xj = p.position[j] + offsets[image[k] as usize].position;
                    // Always `Some`: pass 1 made the same test.
                    sphere_sphere(&p.position[i], p.radius[i], &xj, p.radius[j])
                        .map_or((0.0, Vector3::zeros()), |c| (c.overlap, c.normal))
                }));
                for (&k, &(overlap, normal)) in block.iter().zip(&geometry) {
                    let k = k as usize;
                    let (i, j) = (pi[k] as usize, pj[k] as usize);
                    let offset = &offsets[image[k] as usize];
                    if !active[k] {
                        // A contact begins: from the default history (an inactive pair's entry
                        // is stale, see `PairList::history`).
                        history[k] = Default::default();
                        active[k] = true;
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
                    let (law, rolling) = &laws[p.species[i] as usize * ns + p.species[j] as usize];
                    let w = evaluate_pair(law, rolling, &mut history[k], &kinematics, dt);
                    if let Some(sums) = sums.as_deref_mut() {
                        sums[i].0 += w.force;
                        sums[i].1 += w.torque1;
                        sums[j].0 += -w.force;
                        sums[j].1 += w.torque2;
                    } else {
                        wrench[k] = w;
                    }
                }
            }
            (touching, ended)
        };
        let results: Vec<(usize, Vec<EndedContact>)> = if serial {
            // The wrenches go straight into the sums: none is stored (72 bytes per touching
            // pair and step less to write; the list's `wrench` stays empty).
            wrench.clear();
            let sums = &mut self.sums[..];
            history
                .chunks_mut(CHUNK)
                .zip(active.chunks_mut(CHUNK))
                .enumerate()
                .map(|(c, (history, active))| chunk(c, history, &mut [], active, Some(&mut *sums)))
                .collect()
        } else {
            if wrench.len() != history.len() {
                // First parallel step after one-thread steps: every pair starts at zero; the
                // touching ones are all evaluated below.
                wrench.clear();
                wrench.resize(history.len(), PairWrench::default());
            }
            history
                .par_chunks_mut(CHUNK)
                .zip(wrench.par_chunks_mut(CHUNK))
                .zip(active.par_chunks_mut(CHUNK))
                .enumerate()
                .map(|(c, ((history, wrench), active))| chunk(c, history, wrench, active, None))
                .collect()
        };
        self.collect_ended(results)
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
        let results: Vec<(usize, Vec<EndedContact>)> = history
            .par_chunks_mut(SURFACE_CHUNK)
            .zip(wrench.par_chunks_mut(SURFACE_CHUNK))
            .zip(active.par_chunks_mut(SURFACE_CHUNK))
            .zip(contacts.par_chunks_mut(SURFACE_CHUNK))
            .enumerate()
            .map(|(c, (((history, wrench), active), contacts))| {
                let base = c * SURFACE_CHUNK;
                let mut touching = 0;
                let mut ended = Vec::new();
                for k in 0..history.len() {
                    let q = base + k;
                    let (i, s) = (particle[q] as usize, surface[q] as usize);
                    let surf = &surfaces[s];
                    let contact = colliders
                        .get(surf.collider)
                        .and_then(|co| surf.sphere_contact(co, &p.position[i], p.radius[i]));
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
                    let (law, rolling) = &laws[p.species[i] as usize * nsurf + s];
                    wrench[k] = evaluate_pair(law, rolling, &mut history[k], &kinematics, dt);
                    contacts[k] = contact;
                }
                (touching, ended)
            })
            .collect();
        self.collect_ended(results)
    }
}

/// The parallel path's per-particle sum: surfaces, then the pairs where `i` is second (in
/// increasing first particle), then the pairs where `i` is first (increasing second particle),
/// i.e. pair order. Inactive pairs hold a zero wrench (see the pair loops): no branch on
/// `active` here.
#[inline]
pub(super) fn gather<H>(
    pairs: &PairList<H>,
    sp: &SurfacePairs<H>,
    i: usize,
) -> (Vector3<f64>, Vector3<f64>) {
    let mut force = Vector3::zeros();
    let mut torque = Vector3::zeros();
    for w in &sp.wrench[sp.start[i] as usize..sp.start[i + 1] as usize] {
        force += w.force;
        torque += w.torque1;
    }
    for &e in &pairs.second[pairs.second_start[i] as usize..pairs.second_start[i + 1] as usize] {
        let w: &PairWrench = &pairs.wrench[e as usize];
        force += -w.force;
        torque += w.torque2;
    }
    for w in &pairs.wrench[pairs.first[i] as usize..pairs.first[i + 1] as usize] {
        force += w.force;
        torque += w.torque1;
    }
    (force, torque)
}
