//! Each built-in scene's headline quantity, measured from the particle states:
//!
//! - column collapse: run-out distance and final height (compared with the axisymmetric
//!   run-out scaling of Lube, Huppert, Sparks & Hallworth, J. Fluid Mech. 508, 175 (2004));
//! - hopper: steady mass flow rate, fitted over the second half of the run (compared with the Beverloo correlation
//!   `W = C ρ_b √g (D − k d)^{5/2}`, Beverloo, Leniger & van de Velde, Chem. Eng. Sci. 15, 260
//!   (1961), with `C = 0.58`, `k = 1.5`, `ρ_b = 0.6 ρ_p`);
//! - rotating drum: dynamic angle of repose of the free surface;
//! - drop: coefficient of restitution of the first bounce (compared with the law's energy route,
//!   `MdrLaw::impact`, docs/theory.md §4).

use crate::scene::schema::WallKind;
use crate::scene::{Headline, NormalSpec, Scene};
use mdr_contact::normal::{MdrElastoPlastic, MdrState, NormalModel};
use mdr_contact::ContactPair;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Beverloo's discharge coefficient `C`.
pub const BEVERLOO_C: f64 = 0.58;
/// Beverloo's empty-annulus coefficient `k`.
pub const BEVERLOO_K: f64 = 1.5;
/// Solid fraction assumed for the bulk density `ρ_b = φ ρ_p`.
pub const BULK_SOLID_FRACTION: f64 = 0.6;

/// One sample of the headline time series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeadlineSample {
    /// Simulated time (s).
    pub time: f64,
    /// The scene's quantities at that time (see [`Tracker::series_names`]).
    pub values: Vec<f64>,
}

/// One reported number.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeadlineValue {
    /// Name with its unit, e.g. `runout_m`.
    pub name: String,
    /// Value.
    pub value: f64,
}

/// The headline result of a run.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct HeadlineReport {
    /// Named numbers.
    pub values: Vec<HeadlineValue>,
    /// A human-readable summary.
    pub text: String,
}

impl HeadlineReport {
    /// The value named `name`.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|v| v.name == name).map(|v| v.value)
    }

    fn push(&mut self, name: &str, value: f64) {
        self.values.push(HeadlineValue {
            name: name.to_owned(),
            value,
        });
    }
}

/// The state of the particles that the trackers read.
pub struct ParticleView<'a> {
    /// Centres (m).
    pub position: &'a [Vector3<f64>],
    /// Velocities (m/s).
    pub velocity: &'a [Vector3<f64>],
    /// Radii (m).
    pub radius: &'a [f64],
    /// Masses (kg).
    pub mass: &'a [f64],
    /// Touching contacts per particle.
    pub contacts: &'a [u32],
}

/// Measures a scene's headline quantity along the run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tracker {
    kind: TrackerKind,
    /// Per-step state of the drop tracker: (speed before the first contact, touched, rebound).
    drop: (f64, bool, Option<f64>),
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
enum TrackerKind {
    None,
    Column {
        axis: [f64; 2],
        floor: f64,
        r0: f64,
        h0: f64,
    },
    Hopper {
        plate_z: f64,
        discharge_z: f64,
        orifice: f64,
    },
    Drum {
        center: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    },
    Drop,
}

fn up(scene: &Scene) -> Vector3<f64> {
    let g = scene.gravity.norm();
    if g > 0.0 {
        -scene.gravity / g
    } else {
        Vector3::z()
    }
}

fn percentile(mut v: Vec<f64>, q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let i = ((v.len() - 1) as f64 * q).round() as usize;
    v[i]
}

impl Tracker {
    /// A tracker for `scene`'s headline, set up from the initial placement.
    pub fn new(scene: &Scene) -> Self {
        let kind = match scene.headline {
            Headline::None => TrackerKind::None,
            Headline::Column => {
                let n = scene.particles.len() as f64;
                let cx = scene.particles.iter().map(|p| p.position.x).sum::<f64>() / n;
                let cy = scene.particles.iter().map(|p| p.position.y).sum::<f64>() / n;
                let floor = scene
                    .particles
                    .iter()
                    .map(|p| p.position.z - p.radius)
                    .fold(f64::INFINITY, f64::min);
                let r0 = scene
                    .particles
                    .iter()
                    .map(|p| ((p.position.x - cx).hypot(p.position.y - cy)) + p.radius)
                    .fold(0.0, f64::max);
                let h0 = scene
                    .particles
                    .iter()
                    .map(|p| p.position.z + p.radius - floor)
                    .fold(0.0, f64::max);
                TrackerKind::Column {
                    axis: [cx, cy],
                    floor,
                    r0,
                    h0,
                }
            }
            Headline::Hopper => {
                let plate = scene
                    .source
                    .walls
                    .iter()
                    .find(|w| w.kind == WallKind::OrificePlate);
                let (plate_z, orifice) = plate
                    .map(|w| {
                        (
                            w.center_m.map_or(0.0, |c| c[2]),
                            w.orifice_diameter_m.unwrap_or(f64::NAN),
                        )
                    })
                    .unwrap_or((0.0, f64::NAN));
                let d = mean_diameter(scene);
                TrackerKind::Hopper {
                    plate_z,
                    discharge_z: scene.discharge_height.unwrap_or(plate_z - 2.0 * d),
                    orifice,
                }
            }
            Headline::Drum => {
                let drum = scene
                    .source
                    .walls
                    .iter()
                    .find(|w| w.kind == WallKind::Cylinder);
                let (center, axis, radius) = drum
                    .map(|w| {
                        (
                            w.center_m.unwrap_or([0.0; 3]),
                            w.axis.unwrap_or([0.0, 0.0, 1.0]),
                            w.radius_m.unwrap_or(f64::NAN),
                        )
                    })
                    .unwrap_or(([0.0; 3], [0.0, 1.0, 0.0], f64::NAN));
                let a = Vector3::from(axis).normalize();
                TrackerKind::Drum {
                    center,
                    axis: [a.x, a.y, a.z],
                    radius,
                }
            }
            Headline::Drop => TrackerKind::Drop,
        };
        Self {
            kind,
            drop: (0.0, false, None),
        }
    }

    /// Names (with units) of the sampled series.
    pub fn series_names(&self) -> &'static [&'static str] {
        match self.kind {
            TrackerKind::None => &[],
            TrackerKind::Column { .. } => &["runout_m", "height_m"],
            TrackerKind::Hopper { .. } => &["discharged_mass_kg"],
            TrackerKind::Drum { .. } => &["surface_angle_deg"],
            TrackerKind::Drop => &["height_m", "vertical_velocity_m_per_s"],
        }
    }

    /// Whether [`Tracker::on_step`] must see every step.
    pub fn needs_every_step(&self) -> bool {
        matches!(self.kind, TrackerKind::Drop)
    }

    /// Per-step update (only the drop needs every step: contacts last a few hundred steps).
    pub fn on_step(&mut self, scene: &Scene, view: &ParticleView<'_>) {
        if let TrackerKind::Drop = self.kind {
            let up = up(scene);
            let touching = view.contacts.first().is_some_and(|&c| c > 0);
            let vn = view.velocity.first().map_or(0.0, |v| v.dot(&up));
            let (before, touched, rebound) = &mut self.drop;
            if !*touched {
                if touching {
                    *touched = true;
                } else if vn > 0.0 && *before > 0.0 {
                    // Restitution mode: the impulse reverses the velocity within one step.
                    *touched = true;
                    *rebound = Some(vn);
                } else {
                    *before = -vn;
                }
            } else if rebound.is_none() && !touching {
                *rebound = Some(vn);
            }
        }
    }

    /// A sample for the time series.
    pub fn sample(&self, scene: &Scene, time: f64, view: &ParticleView<'_>) -> HeadlineSample {
        let values = match self.kind {
            TrackerKind::None => Vec::new(),
            TrackerKind::Column {
                axis, floor, r0, ..
            } => {
                let runout = percentile(
                    view.position
                        .iter()
                        .zip(view.radius)
                        .map(|(p, r)| (p.x - axis[0]).hypot(p.y - axis[1]) + r)
                        .collect(),
                    0.99,
                );
                let near_axis: Vec<f64> = view
                    .position
                    .iter()
                    .zip(view.radius)
                    .filter(|(p, _)| (p.x - axis[0]).hypot(p.y - axis[1]) < 0.5 * r0)
                    .map(|(p, r)| p.z + r - floor)
                    .collect();
                let height = near_axis.iter().copied().fold(0.0, f64::max);
                vec![runout, height]
            }
            TrackerKind::Hopper { discharge_z, .. } => {
                let m: f64 = view
                    .position
                    .iter()
                    .zip(view.mass)
                    .filter(|(p, _)| p.z < discharge_z)
                    .map(|(_, m)| m)
                    .sum();
                vec![m]
            }
            TrackerKind::Drum {
                center,
                axis,
                radius,
            } => vec![surface_angle(
                &Vector3::from(center),
                &Vector3::from(axis),
                radius,
                &up(scene),
                view,
            )],
            TrackerKind::Drop => {
                let up = up(scene);
                vec![
                    view.position.first().map_or(f64::NAN, |p| p.dot(&up)),
                    view.velocity.first().map_or(f64::NAN, |v| v.dot(&up)),
                ]
            }
        };
        HeadlineSample { time, values }
    }

    /// The final report from the samples and the scene.
    pub fn report(&self, scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport {
        let mut r = HeadlineReport::default();
        match self.kind {
            TrackerKind::None => {}
            TrackerKind::Column { r0, h0, .. } => {
                let Some(last) = samples.last() else {
                    return r;
                };
                let (runout, height) = (last.values[0], last.values[1]);
                let a = h0 / r0;
                let spread = (runout - r0) / r0;
                // Lube et al. (2004), axisymmetric collapse: ΔR/R0 = 1.24 a (a < 1.7),
                // 1.6 a^{1/2} (a > 1.7).
                let lube = if a < 1.7 { 1.24 * a } else { 1.6 * a.sqrt() };
                r.push("initial_radius_m", r0);
                r.push("initial_height_m", h0);
                r.push("aspect_ratio", a);
                r.push("runout_m", runout);
                r.push("final_height_m", height);
                r.push("normalised_runout", spread);
                r.push("lube_2004_normalised_runout", lube);
                r.text = format!(
                    "column collapse: aspect ratio a = H0/R0 = {a:.3} (R0 = {r0:.4e} m, H0 = {h0:.4e} m)\n  \
                     run-out R = {runout:.4e} m, (R − R0)/R0 = {spread:.3} (Lube et al. 2004: {lube:.3})\n  \
                     final height at the axis H = {height:.4e} m, H/R0 = {:.3}",
                    height / r0
                );
            }
            TrackerKind::Hopper { orifice, .. } => {
                let d = mean_diameter(scene);
                let rho_p = scene.materials[scene.particles[0].material].1.density();
                let g = scene.gravity.norm();
                let bulk = BULK_SOLID_FRACTION * rho_p;
                let beverloo = if orifice > BEVERLOO_K * d {
                    BEVERLOO_C * bulk * g.sqrt() * (orifice - BEVERLOO_K * d).powf(2.5)
                } else {
                    0.0
                };
                let total: f64 = scene
                    .particles
                    .iter()
                    .map(|p| scene.materials[p.material].1.sphere_mass(p.radius))
                    .sum();
                let final_mass = samples.last().map_or(0.0, |s| s.values[0]);
                // Steady discharge: the second half of the run, once the flow has started and
                // while the hopper is not yet nearly empty.
                let t_end = samples.last().map_or(0.0, |s| s.time);
                let window: Vec<(f64, f64)> = samples
                    .iter()
                    .map(|s| (s.time, s.values[0]))
                    .filter(|(t, m)| *t >= 0.5 * t_end && *m > 0.0 && *m <= 0.9 * total)
                    .collect();
                let rate = linear_fit(&window).map_or(f64::NAN, |(_, slope)| slope);
                r.push("orifice_diameter_m", orifice);
                r.push("mean_particle_diameter_m", d);
                r.push("discharged_fraction", final_mass / total);
                r.push("mass_flow_rate_kg_per_s", rate);
                r.push("beverloo_kg_per_s", beverloo);
                r.push("ratio_to_beverloo", rate / beverloo);
                r.text = format!(
                    "hopper discharge: D = {orifice:.4e} m, d = {d:.4e} m (D/d = {:.2}), discharged {:.1} % of the mass\n  \
                     steady mass flow rate W = {rate:.4e} kg/s (fit over the second half of the run, {} samples)\n  \
                     Beverloo W = C ρ_b √g (D − k d)^{{5/2}} = {beverloo:.4e} kg/s (C = {BEVERLOO_C}, k = {BEVERLOO_K}, \
                     ρ_b = {BULK_SOLID_FRACTION} ρ_p); ratio {:.3}",
                    orifice / d,
                    100.0 * final_mass / total,
                    window.len(),
                    rate / beverloo
                );
            }
            TrackerKind::Drum { .. } => {
                let t_end = samples.last().map_or(0.0, |s| s.time);
                let late: Vec<f64> = samples
                    .iter()
                    .filter(|s| s.time >= 0.5 * t_end && s.values[0].is_finite())
                    .map(|s| s.values[0])
                    .collect();
                let n = late.len() as f64;
                let mean = late.iter().sum::<f64>() / n;
                let std = (late.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / n).sqrt();
                r.push("dynamic_angle_of_repose_deg", mean);
                r.push("angle_std_deg", std);
                r.text = format!(
                    "rotating drum: dynamic angle of repose {mean:.2}° ± {std:.2}° (mean ± s.d. over {} frames of the second half)",
                    late.len()
                );
            }
            TrackerKind::Drop => {
                let (before, _, rebound) = self.drop;
                let e = rebound.map_or(f64::NAN, |v| v / before);
                r.push("impact_speed_m_per_s", before);
                r.push("restitution", e);
                let mut text = format!(
                    "drop: impact speed {before:.4} m/s, rebound {} m/s, e_n = {e:.5}",
                    rebound.map_or("(none yet)".to_owned(), |v| format!("{v:.4}"))
                );
                if let (
                    NormalSpec::Mdr {
                        critical_line_load,
                        hardening_ratio,
                    },
                    Some(wall),
                ) = (scene.contact.normal, scene.walls.first())
                {
                    let p = &scene.particles[0];
                    let m = scene.materials[p.material].1;
                    let reference = ContactPair::sphere_on_half_space(
                        p.radius,
                        &m,
                        &scene.materials[wall.material].1,
                    )
                    .ok()
                    .zip(MdrElastoPlastic::new(critical_line_load, hardening_ratio).ok())
                    .and_then(|(pair, model)| model.bind(&pair).ok().map(|law| (pair, law)))
                    .map(|(pair, law)| {
                        law.impact(&MdrState::default(), pair.reduced_mass(), before)
                            .restitution
                    });
                    if let Some(reference) = reference {
                        r.push("law_energy_route_restitution", reference);
                        text.push_str(&format!(
                            "\n  law's energy route (closed form, docs/theory.md §4) at that speed: e_n = {reference:.5} \
                             (difference {:.3} %)",
                            100.0 * (e / reference - 1.0)
                        ));
                    }
                }
                r.text = text;
            }
        }
        r
    }
}

fn mean_diameter(scene: &Scene) -> f64 {
    2.0 * scene.particles.iter().map(|p| p.radius).sum::<f64>() / scene.particles.len() as f64
}

/// Least-squares line `y = a + b x`: `(a, b)`; `None` with fewer than 3 points.
pub fn linear_fit(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let b = sxy / sxx;
    Some((my - b * mx, b))
}

/// Angle (degrees) of the free surface in the drum's cross-section: the top particle of each
/// bin across the middle 60 % of the drum, fitted by a line.
fn surface_angle(
    center: &Vector3<f64>,
    axis: &Vector3<f64>,
    radius: f64,
    up: &Vector3<f64>,
    view: &ParticleView<'_>,
) -> f64 {
    let across = axis.cross(up);
    let n = across.norm();
    if n == 0.0 || view.radius.is_empty() {
        return f64::NAN;
    }
    let across = across / n;
    let vertical = across.cross(axis);
    let d = 2.0 * view.radius.iter().sum::<f64>() / view.radius.len() as f64;
    let half = 0.6 * radius;
    let bins = ((2.0 * half / (2.0 * d)).floor() as usize).max(1);
    let mut top = vec![f64::NEG_INFINITY; bins];
    for p in view.position {
        let rel = p - center;
        let u = rel.dot(&across);
        if u.abs() >= half {
            continue;
        }
        let i = (((u + half) / (2.0 * half)) * bins as f64) as usize;
        let w = rel.dot(&vertical);
        top[i.min(bins - 1)] = top[i.min(bins - 1)].max(w);
    }
    let points: Vec<(f64, f64)> = top
        .iter()
        .enumerate()
        .filter(|(_, w)| w.is_finite())
        .map(|(i, w)| (-half + (i as f64 + 0.5) * 2.0 * half / bins as f64, *w))
        .collect();
    if points.len() < 4 {
        return f64::NAN;
    }
    linear_fit(&points).map_or(f64::NAN, |(_, b)| b.atan().abs().to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_fit_recovers_slope() {
        let pts: Vec<(f64, f64)> = (0..10).map(|i| (i as f64, 2.0 + 0.5 * i as f64)).collect();
        let (a, b) = linear_fit(&pts).unwrap();
        assert!((a - 2.0).abs() < 1e-12 && (b - 0.5).abs() < 1e-12);
    }

    #[test]
    fn surface_angle_of_a_tilted_layer() {
        // Particles on a 30° slope in the x-z plane of a drum with axis y.
        let mut pos = Vec::new();
        for i in -40..=40 {
            let x = i as f64 * 0.002;
            for k in 0..3 {
                pos.push(Vector3::new(
                    x,
                    0.0,
                    x * 30f64.to_radians().tan() - k as f64 * 0.002,
                ));
            }
        }
        let n = pos.len();
        let zero = vec![Vector3::zeros(); n];
        let view = ParticleView {
            position: &pos,
            velocity: &zero,
            radius: &vec![0.001; n],
            mass: &vec![1.0; n],
            contacts: &vec![0; n],
        };
        let a = surface_angle(&Vector3::zeros(), &Vector3::y(), 0.1, &Vector3::z(), &view);
        assert!((a - 30.0).abs() < 0.5, "{a}");
    }
}
