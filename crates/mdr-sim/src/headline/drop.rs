//! Drop: the coefficient of restitution of a sphere's first bounce, compared with the law's
//! energy route (`MdrLaw::impact`, docs/theory.md §4; with adhesion
//! `mdr_rapier::restitution_law::adhesive_impact`, §9). With the adhesive law a sphere that
//! still holds to the wall at the end of the run stuck: `e_n = 0`.

use super::{up, HeadlineReport, HeadlineSample, HeadlineTracker, ParticleView};
use crate::scene::Scene;
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic, MdrState, NormalModel};
use mdr_contact::params::Declared;
use mdr_contact::ContactPair;
use serde::{Deserialize, Serialize};

/// The first bounce as it happens: the speed before the first contact, whether the sphere has
/// touched, and its rebound speed once it has left again. Updated every step: a contact lasts
/// a few hundred steps, shorter than the sampling interval.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct DropTracker {
    before: f64,
    touched: bool,
    rebound: Option<f64>,
}

impl HeadlineTracker for DropTracker {
    fn series_names(&self) -> &'static [&'static str] {
        &["height_m", "vertical_velocity_m_per_s"]
    }

    fn needs_every_step(&self) -> bool {
        true
    }

    fn on_step(&mut self, scene: &Scene, view: &ParticleView<'_>) {
        let up = up(scene);
        let touching = view.contacts.first().is_some_and(|&c| c > 0);
        let vn = view.velocity.first().map_or(0.0, |v| v.dot(&up));
        if !self.touched {
            if touching {
                self.touched = true;
            } else if vn > 0.0 && self.before > 0.0 {
                // Restitution mode: the impulse reverses the velocity within one step.
                self.touched = true;
                self.rebound = Some(vn);
            } else if vn < 0.0 {
                // Approaching: a sphere that stuck (restitution mode) keeps its approach speed.
                self.before = -vn;
            }
        } else if self.rebound.is_none() && !touching {
            self.rebound = Some(vn);
        }
    }

    fn sample(&self, scene: &Scene, view: &ParticleView<'_>) -> Vec<f64> {
        let up = up(scene);
        vec![
            view.position.first().map_or(f64::NAN, |p| p.dot(&up)),
            view.velocity.first().map_or(f64::NAN, |v| v.dot(&up)),
        ]
    }

    fn report(&self, scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport {
        let mut r = HeadlineReport::default();
        let Self {
            before,
            rebound,
            touched,
        } = *self;
        let law = scene.contact.normal.law;
        // The sphere–floor pair's work of adhesion (its materials' mixed value).
        let work_of_adhesion = match (scene.particles.first(), scene.walls.first()) {
            (Some(p), Some(wall)) => scene
                .contact
                .pair_work_of_adhesion(p.material, wall.material),
            _ => 0.0,
        };
        let mdr = if law == MdrElastoPlastic::DECLARATION.name {
            MdrElastoPlastic::from_values(&scene.contact.normal.values).ok()
        } else if law == AdhesiveMdr::DECLARATION.name {
            AdhesiveMdr::from_values(&scene.contact.normal.values)
                .ok()
                .map(|a| *a.params())
        } else {
            None
        };
        // Restitution mode resolves a stuck impact within a step, with no contact left to see:
        // the sphere is then at rest at the end.
        let at_rest = samples
            .last()
            .and_then(|s| s.values.get(1))
            .is_some_and(|v| v.abs() < 1e-3 * before);
        let stuck = work_of_adhesion > 0.0 && rebound.is_none() && (touched || at_rest);
        let e = rebound.map_or(if stuck { 0.0 } else { f64::NAN }, |v| v / before);
        r.push("impact_speed_m_per_s", before);
        r.push("restitution", e);
        let rebound_text = match rebound {
            Some(v) => format!("{v:.4}"),
            None if stuck => "0 (stuck: the contact holds at the end of the run)".to_owned(),
            None => "(none yet)".to_owned(),
        };
        let mut text =
            format!("drop: impact speed {before:.4} m/s, rebound {rebound_text} m/s, e_n = {e:.5}");
        if let (Some(model), Some(wall)) = (mdr, scene.walls.first()) {
            let p = &scene.particles[0];
            let m = scene.materials[p.material].1;
            let reference =
                ContactPair::sphere_on_half_space(p.radius, &m, &scene.materials[wall.material].1)
                    .ok()
                    .zip(Some(model))
                    .and_then(|(pair, model)| model.bind(&pair).ok().map(|law| (pair, law)))
                    .and_then(|(pair, law)| {
                        mdr_rapier::restitution_law::adhesive_impact(
                            &law,
                            work_of_adhesion,
                            &MdrState::default(),
                            pair.reduced_mass(),
                            before,
                        )
                        .ok()
                        .map(|impact| impact.restitution)
                    });
            if let Some(reference) = reference {
                r.push("law_energy_route_restitution", reference);
                text.push_str(&format!(
                    "\n  law's energy route (closed form, docs/theory.md §{}) at that speed: e_n = {reference:.5} \
                     (difference {:.3} %)",
                    if work_of_adhesion > 0.0 { 9 } else { 4 },
                    100.0 * (e / reference - 1.0)
                ));
            }
        }
        r.text = text;
        r
    }
}
