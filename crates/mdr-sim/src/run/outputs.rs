//! What a run writes: energy-book rows, VTK frames (spheres and the contact network), the
//! CSV and plot series, and checkpoints.

use super::coupling::NeighbourListSceneStepper;
use super::records::{NeighbourListPairHistory, SceneLaw};
use super::*;
use crate::laws::{SceneNormal, SceneRolling};
use mdr_contact::tangential::TangentialLaw;

impl Sim<'_> {
    pub(super) fn energy_row(&self) -> EnergyRow {
        let g = self.scene.gravity;
        let mut row = EnergyRow {
            time_s: self.time(),
            ..EnergyRow::default()
        };
        let bodies = &self.built.world.bodies;
        let mut kinetic = |m: f64, r: f64, x: &Vector3<f64>, v: &Vector3<f64>, w: &Vector3<f64>| {
            row.kinetic_translational_j += 0.5 * m * v.norm_squared();
            // Solid sphere: I = (2/5) m r².
            row.kinetic_rotational_j += 0.5 * 0.4 * m * r * r * w.norm_squared();
            row.gravitational_j -= m * g.dot(x);
        };
        if let Coupling::NeighbourList(stepper) = &self.built.coupling {
            let p = stepper.particles();
            for i in 0..p.len() {
                let m = p.species_table[p.species[i] as usize].mass;
                kinetic(m, p.radius[i], &p.position[i], &p.linvel[i], &p.angvel[i]);
            }
        }
        for (h, p) in self.built.particle_bodies.iter().zip(&self.scene.particles) {
            let b = &bodies[*h];
            let (x, v, w) = (to_na(b.translation()), to_na(b.linvel()), to_na(b.angvel()));
            kinetic(b.mass(), p.radius, &x, &v, &w);
        }
        if let Coupling::RapierPipeline(stepper) = &self.built.coupling {
            stepper.add_elastic_energies(&mut row);
        }
        if let Coupling::NeighbourList(stepper) = &self.built.coupling {
            stepper.add_elastic_energies(&mut row);
        }
        // The neighbour-list path's totals hold the contacts that ended; add the live ones.
        let live = match &self.built.coupling {
            Coupling::NeighbourList(stepper) => stepper.live_works(None),
            _ => ContactWorks::default(),
        };
        row.plastic_j = self.books.plastic + live.plastic - self.books.adhesive;
        row.adhesive_j = self.books.adhesive;
        row.friction_j = self.books.friction + live.friction;
        row.damping_j = self.books.damping + live.damping;
        row.rolling_j = self.books.rolling + live.rolling;
        row.stiffness_tangential_j = self.books.stiffness_tangential - live.tangential_stiffness;
        row.stiffness_rolling_j = self.books.stiffness_rolling - live.rolling_stiffness;
        row.wall_work_j = self.books.wall_work;
        row.removed_j = self.books.removed;
        row.with_balance()
    }

    pub(super) fn write_frame(&mut self, out: &Path) -> Result<(), SimError> {
        let scene = self.scene;
        let index = self.collection.iter().filter(|e| e.part == 0).count();
        let name = PathBuf::from("frames").join(format!("{}_{index:06}.vtp", scene.name));
        let bodies = &self.built.world.bodies;
        let mut frame = ParticleFrame::default();
        if let Coupling::NeighbourList(stepper) = &self.built.coupling {
            let p = stepper.particles();
            let mut plastic = self.books.particle_plastic.clone();
            stepper.live_works(Some(&mut plastic));
            for (i, &plastic_work) in plastic.iter().enumerate().take(p.len()) {
                frame.position.push(p.position[i].into());
                frame.radius.push(p.radius[i]);
                frame.velocity.push(p.linvel[i].into());
                frame.angular_velocity.push(p.angvel[i].into());
                frame.contacts.push(self.view.contacts[i]);
                frame.plastic_work.push(plastic_work);
                frame.id.push(i as u32);
            }
        }
        for (i, h) in self.built.particle_bodies.iter().enumerate() {
            let b = &bodies[*h];
            frame.position.push(to_na(b.translation()).into());
            frame.radius.push(scene.particles[i].radius);
            frame.velocity.push(to_na(b.linvel()).into());
            frame.angular_velocity.push(to_na(b.angvel()).into());
            frame.contacts.push(self.view.contacts[i]);
            frame.plastic_work.push(self.books.particle_plastic[i]);
            frame.id.push(i as u32);
        }
        let path = out.join(&name);
        vtk::write_particles(&path, &frame).map_err(output(&path))?;
        self.collection.push(CollectionEntry {
            time: self.time(),
            file: name,
            part: 0,
        });
        if scene.contact_network {
            let mut net = ContactFrame::default();
            if let Coupling::NeighbourList(stepper) = &self.built.coupling {
                stepper.add_contact_network(&mut net);
            }
            if let Coupling::RapierPipeline(stepper) = &self.built.coupling {
                let residual = stepper.residual_overlaps();
                let mut k = 0;
                stepper.for_each_contact(&mut |e| {
                    let c1 = to_na(bodies[e.body1].translation());
                    let to = match self
                        .built
                        .particle_of_collider
                        .get(e.collider2.into_raw_parts().0 as usize)
                    {
                        Some(&j) if j != usize::MAX => {
                            to_na(bodies[self.built.particle_bodies[j]].translation())
                        }
                        _ => e.contact.point,
                    };
                    net.from.push(c1.into());
                    net.to.push(to.into());
                    net.force.push(e.wrench.force.into());
                    net.normal_force.push(e.wrench.force.dot(&e.contact.normal));
                    net.overlap.push(e.contact.overlap);
                    net.plastic_indentation.push(residual[k]);
                    k += 1;
                });
            }
            if !matches!(self.built.coupling, Coupling::Restitution(_)) {
                let cname =
                    PathBuf::from("frames").join(format!("{}_contacts_{index:06}.vtp", scene.name));
                let cpath = out.join(&cname);
                vtk::write_contacts(&cpath, &net).map_err(output(&cpath))?;
                self.collection.push(CollectionEntry {
                    time: self.time(),
                    file: cname,
                    part: 1,
                });
            }
        }
        let pvd = out.join(format!("{}.pvd", scene.name));
        vtk::write_collection(&pvd, &self.collection).map_err(output(&pvd))
    }

    /// Energy CSV at every frame; plots at the end.
    pub(super) fn write_series(
        &self,
        out: &Path,
        files: &mut Vec<PathBuf>,
        plots: bool,
    ) -> Result<(), SimError> {
        let name = &self.scene.name;
        let csv = out.join(format!("{name}_energy.csv"));
        energy::write_csv(&csv, &self.energy).map_err(output(&csv))?;
        if !plots {
            return Ok(());
        }
        files.push(csv);
        let series_csv = out.join(format!("{name}_headline.csv"));
        if !self.tracker.series_names().is_empty() {
            self.tracker
                .write_csv(&series_csv, &self.samples)
                .map_err(output(&series_csv))?;
            files.push(series_csv);
        }
        let svg = out.join(format!("{name}_energy.svg"));
        plot::write_energy_plot(&svg, &format!("{name}: energy books"), &self.energy)
            .map_err(output(&svg))?;
        files.push(svg);
        if let Some(path) = self
            .tracker
            .write_chart(self.scene, &self.samples, out)
            .map_err(|(path, e)| output(&path)(e))?
        {
            files.push(path);
        }
        Ok(())
    }

    pub(super) fn write_checkpoint(&mut self, out: &Path) -> Result<(), SimError> {
        let path = out
            .join("checkpoints")
            .join(crate::output::run_dir::checkpoint_name(
                &self.scene.name,
                self.step,
            ));
        let data = CheckpointData::capture(self).map_err(|reason| CheckpointError::Encode {
            path: path.clone(),
            reason,
        })?;
        checkpoint::write(&path, &data)?;
        self.checkpoints.push(path);
        // Keep the last three.
        while self.checkpoints.len() > 3 {
            let old = self.checkpoints.remove(0);
            let _ = std::fs::remove_file(old);
        }
        Ok(())
    }
}

/// Add the elastic energies of the contacts alive on the neighbour-list path to `row`, and
/// count them.
pub(super) fn live_elastic_energies<N: SceneNormal, R: SceneRolling>(
    stepper: &NeighbourListSceneStepper<N, R>,
    row: &mut EnergyRow,
) {
    let mut add = |(law, rolling): &(SceneLaw<N>, R::Law),
                   h: &NeighbourListPairHistory<N, R>,
                   overlap: f64| {
        row.elastic_normal_j += law.normal.elastic_energy(&h.contact.normal, overlap);
        row.elastic_tangential_j += law.tangential.elastic_energy(&h.contact.tangential);
        row.elastic_rolling_j += rolling.elastic_energy(&h.rolling);
        row.contacts += 1;
    };
    let p = stepper.particles();
    let sp = stepper.surface_pairs();
    for q in (0..sp.len()).filter(|&q| sp.active[q]) {
        let (i, s) = (sp.particle[q] as usize, sp.surface[q] as usize);
        add(
            stepper.surface_pair_laws(i, s),
            &sp.history[q],
            sp.contact[q].overlap,
        );
    }
    let pairs = stepper.pairs();
    let offsets = stepper.boundary().offsets();
    for q in (0..pairs.len()).filter(|&q| pairs.active[q]) {
        let (i, j) = (pairs.i[q] as usize, pairs.j[q] as usize);
        // Partner `j` as the pair sees it (its periodic image in a periodic box).
        let xj = p.position[j] + offsets[pairs.image[q] as usize].position;
        let overlap =
            sphere_sphere(&p.position[i], p.radius[i], &xj, p.radius[j]).map_or(0.0, |c| c.overlap);
        add(stepper.sphere_pair_laws(i, j), &pairs.history[q], overlap);
    }
}

/// Add the contacts alive on the neighbour-list path to a contact-network frame.
pub(super) fn live_contact_network<N: SceneNormal, R: SceneRolling>(
    stepper: &NeighbourListSceneStepper<N, R>,
    net: &mut ContactFrame,
) {
    let p = stepper.particles();
    let sp = stepper.surface_pairs();
    for q in (0..sp.len()).filter(|&q| sp.active[q]) {
        let (i, s) = (sp.particle[q] as usize, sp.surface[q] as usize);
        let (law, _) = stepper.surface_pair_laws(i, s);
        let (c, w) = (&sp.contact[q], &sp.wrench[q]);
        net.from.push(p.position[i].into());
        net.to.push(c.point.into());
        net.force.push(w.force.into());
        net.normal_force.push(w.force.dot(&c.normal));
        net.overlap.push(c.overlap);
        net.plastic_indentation
            .push(law.normal.residual_overlap(&sp.history[q].contact.normal));
    }
    let pairs = stepper.pairs();
    let offsets = stepper.boundary().offsets();
    for q in (0..pairs.len()).filter(|&q| pairs.active[q]) {
        let (i, j) = (pairs.i[q] as usize, pairs.j[q] as usize);
        let (law, _) = stepper.sphere_pair_laws(i, j);
        // In a periodic box the line goes to the partner's image next to `i`.
        let xj = p.position[j] + offsets[pairs.image[q] as usize].position;
        let Some(c) = sphere_sphere(&p.position[i], p.radius[i], &xj, p.radius[j]) else {
            continue;
        };
        // Stored for every pair when a network frame is due (`compute_forces`).
        let force = pairs.wrench.get(q).map_or(Vector3::zeros(), |w| w.force);
        net.from.push(p.position[i].into());
        net.to.push(xj.into());
        net.force.push(force.into());
        net.normal_force.push(force.dot(&c.normal));
        net.overlap.push(c.overlap);
        net.plastic_indentation.push(
            law.normal
                .residual_overlap(&pairs.history[q].contact.normal),
        );
    }
}
