//! Each built-in scene's headline quantity, measured from the particle states:
//!
//! - column collapse: run-out distance and final height (compared with the axisymmetric
//!   run-out scaling of Lube, Huppert, Sparks & Hallworth, J. Fluid Mech. 508, 175 (2004));
//! - hopper: steady mass flow rate, fitted over the second half of the time after the plug opens (compared with the Beverloo correlation
//!   `W = C ρ_b √g (D − k d)^{5/2}`, Beverloo, Leniger & van de Velde, Chem. Eng. Sci. 15, 260
//!   (1961), with `C = 0.58`, `k = 1.5`, `ρ_b = 0.6 ρ_p`);
//! - rotating drum: dynamic angle of repose of the free surface;
//! - drop: coefficient of restitution of the first bounce (compared with the law's energy route,
//!   `MdrLaw::impact`, docs/theory.md §4);
//! - funnel: spheres left in the funnel against time (the discharge curve), written as a CSV;
//! - hopper orifice sweep ([`run_orifice_sweep`]): the flow rate at several orifice diameters and
//!   Beverloo's `C` and `k` fitted to them ([`fit_beverloo`]).

use crate::scene::schema::WallKind;
use crate::scene::{Headline, NormalSpec, Scene};
use mdr_contact::normal::{MdrElastoPlastic, MdrState, NormalModel};
use mdr_contact::ContactPair;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Orifices narrower than this many mean particle diameters jam: arches form over them and
/// stop the flow for good (in 3D silos the mean avalanche between jams grows without bound
/// only as `D/d` approaches about 5; Zuriguel, Garcimartín, Maza, Pugnaloni & Pastor, Phys.
/// Rev. E 71, 051303, 2005). The scene check warns below it, and the hopper headline reports
/// "jammed" instead of a flow rate.
pub const JAMMING_RATIO: f64 = 4.0;

/// The time (s) the first removable wall (a plug) is removed, 0 when there is none: the
/// discharge starts then.
pub fn plug_opened_at(scene: &Scene) -> f64 {
    scene
        .walls
        .iter()
        .filter_map(|w| w.removed_at)
        .reduce(f64::min)
        .map_or(0.0, |t| t.clamp(0.0, scene.duration))
}

/// The literature's prediction drawn next to a headline's time series, as labelled lines in the
/// series' units: the column's run-out of Lube et al. (2004) (and its final height, `H = H0`
/// below `a = 0.74`), the hopper's discharged mass at Beverloo's rate from the start of the
/// fitted window. Other headlines have none.
pub fn reference_lines(
    report: &HeadlineReport,
    samples: &[HeadlineSample],
) -> Vec<(String, Vec<(f64, f64)>)> {
    let (Some(first), Some(last)) = (samples.first(), samples.last()) else {
        return Vec::new();
    };
    let span = |v: f64| vec![(first.time, v), (last.time, v)];
    let mut lines = Vec::new();
    if let (Some(r0), Some(lube)) = (
        report.get("initial_radius_m"),
        report.get("lube_2004_normalised_runout"),
    ) {
        lines.push((
            format!("Lube et al. 2004 run-out R0 (1 + {lube:.3})"),
            span(r0 * (1.0 + lube)),
        ));
        if let Some(h) = report
            .get("lube_2004_final_height_m")
            .filter(|h| h.is_finite())
        {
            lines.push(("Lube et al. 2004 height H = H0".to_owned(), span(h)));
        }
    }
    if let (Some(w), Some(start)) = (
        report.get("beverloo_kg_per_s").filter(|w| *w > 0.0),
        report.get("fit_window_start_s"),
    ) {
        if let Some(s0) = samples.iter().find(|s| s.time >= start) {
            let m0 = s0.values[0];
            lines.push((
                format!("Beverloo et al. 1961: W = {w:.3e} kg/s"),
                vec![(s0.time, m0), (last.time, m0 + w * (last.time - s0.time))],
            ));
        }
    }
    lines
}

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
    Funnel {
        /// Height (along `up`) below which a sphere has left the funnel.
        discharge_z: f64,
        /// Height below which a sphere is removed (`−∞` without a sink).
        delete_z: f64,
        /// Time the plug opens (s): the earliest `removed_at_s` of the walls (0 without one).
        opened_at: f64,
    },
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
            Headline::Funnel => {
                let up = up(scene);
                let lowest = scene
                    .particles
                    .iter()
                    .map(|p| p.position.dot(&up) - p.radius)
                    .fold(f64::INFINITY, f64::min);
                TrackerKind::Funnel {
                    discharge_z: scene.discharge_height.unwrap_or(lowest),
                    delete_z: scene.source.run.delete_below_m.unwrap_or(f64::NEG_INFINITY),
                    opened_at: scene
                        .walls
                        .iter()
                        .filter_map(|w| w.removed_at)
                        .fold(f64::INFINITY, f64::min)
                        .min(scene.duration)
                        .max(0.0),
                }
            }
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
            TrackerKind::Funnel { .. } => &["spheres_in_funnel", "spheres_remaining"],
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
            TrackerKind::Funnel {
                discharge_z,
                delete_z,
                ..
            } => {
                let up = up(scene);
                let (mut inside, mut remaining) = (0usize, 0usize);
                for p in view.position {
                    let h = p.dot(&up);
                    inside += usize::from(h >= discharge_z);
                    remaining += usize::from(h >= delete_z);
                }
                vec![inside as f64, remaining as f64]
            }
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
                // 1.6 a^{1/2} (a > 1.7); for a < 0.74 the failure surface does not reach the
                // top of the column, which keeps its height: H∞ = H0.
                let lube = if a < 1.7 { 1.24 * a } else { 1.6 * a.sqrt() };
                let lube_height = if a < 0.74 { h0 } else { f64::NAN };
                r.push("initial_radius_m", r0);
                r.push("initial_height_m", h0);
                r.push("aspect_ratio", a);
                r.push("runout_m", runout);
                r.push("final_height_m", height);
                r.push("normalised_runout", spread);
                r.push("lube_2004_normalised_runout", lube);
                r.push("lube_2004_final_height_m", lube_height);
                r.text = format!(
                    "column collapse: aspect ratio a = H0/R0 = {a:.3} (R0 = {r0:.4e} m, H0 = {h0:.4e} m)\n  \
                     run-out R = {runout:.4e} m, (R − R0)/R0 = {spread:.3} (Lube et al. 2004: {lube:.3})\n  \
                     final height at the axis H = {height:.4e} m, H/R0 = {:.3} ({})",
                    height / r0,
                    if a < 0.74 {
                        format!("Lube et al. 2004 for a < 0.74: H = H0 = {h0:.4e} m, ratio {:.3}", height / h0)
                    } else {
                        "no height correlation for a ≥ 0.74 here".to_owned()
                    }
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
                // `+ 0.0` turns a negative zero into 0 (no "−0.0 %").
                let final_mass = samples.last().map_or(0.0, |s| s.values[0]) + 0.0;
                // Steady discharge: the second half of the time after the plug opens (the whole
                // run without a plug), once the flow has started and while the hopper is not yet
                // nearly empty.
                let t_end = samples.last().map_or(0.0, |s| s.time);
                let opened_at = plug_opened_at(scene);
                let window_start = opened_at + 0.5 * (t_end - opened_at);
                let window: Vec<(f64, f64)> = samples
                    .iter()
                    .map(|s| (s.time, s.values[0]))
                    .filter(|(t, m)| *t >= window_start && *m > 0.0 && *m <= 0.9 * total)
                    .collect();
                let rate = linear_fit(&window).map_or(f64::NAN, |(_, slope)| slope);
                r.push("orifice_diameter_m", orifice);
                r.push("mean_particle_diameter_m", d);
                r.push("discharged_fraction", final_mass / total);
                let jammed = orifice < JAMMING_RATIO * d;
                if jammed {
                    r.push("jammed", 1.0);
                    r.push(
                        "mass_flow_rate_kg_per_s",
                        if rate.is_finite() { rate } else { 0.0 },
                    );
                    r.text = format!(
                        "hopper discharge: D = {orifice:.4e} m, d = {d:.4e} m (D/d = {:.2}): jammed: an \
                         orifice narrower than {JAMMING_RATIO} particle diameters arches over and \
                         stops the flow (Zuriguel et al. 2005), so no steady rate and no Beverloo \
                         ratio are reported; discharged {:.1} % of the mass",
                        orifice / d,
                        100.0 * final_mass / total,
                    );
                    return r;
                }
                r.push("mass_flow_rate_kg_per_s", rate);
                r.push("beverloo_kg_per_s", beverloo);
                r.push("ratio_to_beverloo", rate / beverloo);
                r.push("fit_window_start_s", window_start);
                let after = if opened_at > 0.0 {
                    format!(
                        "the second half of the time after the plug opened at {opened_at:.4e} s"
                    )
                } else {
                    "the second half of the run".to_owned()
                };
                let rate_text = if rate.is_finite() {
                    format!(
                        "W = {rate:.4e} kg/s (fit over {after}, {} samples)",
                        window.len()
                    )
                } else {
                    format!(
                        "W not measured: {} samples of the discharged mass in {after} \
                         (between none and 90 % of the mass), a fit needs 3 (run longer, \
                         or write rows more often with output_interval_s)",
                        window.len()
                    )
                };
                r.text = format!(
                    "hopper discharge: D = {orifice:.4e} m, d = {d:.4e} m (D/d = {:.2}), discharged {:.1} % of the mass\n  \
                     steady mass flow rate {rate_text}\n  \
                     Beverloo W = C ρ_b √g (D − k d)^{{5/2}} = {beverloo:.4e} kg/s (C = {BEVERLOO_C}, k = {BEVERLOO_K}, \
                     ρ_b = {BULK_SOLID_FRACTION} ρ_p); ratio {:.3}",
                    orifice / d,
                    100.0 * final_mass / total,
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
            TrackerKind::Funnel { opened_at, .. } => {
                let n0 = scene.particles.len() as f64;
                let curve: Vec<(f64, f64)> =
                    samples.iter().map(|s| (s.time, s.values[0])).collect();
                let summary = discharge_summary(&curve, opened_at, n0);
                let last = samples
                    .last()
                    .map_or([n0, n0], |s| [s.values[0], s.values[1]]);
                r.push("spheres", n0);
                r.push("opened_at_s", opened_at);
                r.push("spheres_in_funnel_at_opening", summary.at_opening);
                r.push("spheres_in_funnel_at_end", last[0]);
                r.push("spheres_remaining_at_end", last[1]);
                r.push("discharge_rate_spheres_per_s", summary.rate);
                r.push("half_discharge_time_s", summary.half_time);
                r.text = format!(
                    "funnel discharge: {n0} spheres, plug removed at t = {opened_at:.4} s with {:.0} in the funnel\n  \
                     steady discharge rate {:.4} spheres/s (fit while 90 % to 30 % of them remain), half emptied \
                     {:.4} s after opening\n  at the end (t = {:.4} s): {:.0} in the funnel, {:.0} not removed",
                    summary.at_opening,
                    summary.rate,
                    summary.half_time,
                    samples.last().map_or(0.0, |s| s.time),
                    last[0],
                    last[1]
                );
            }
        }
        r
    }

    /// Write the headline time series as CSV (`time_s` and one column per series name), e.g.
    /// the funnel's discharge curve; nothing for a scene without series.
    pub fn write_csv(
        &self,
        path: &std::path::Path,
        samples: &[HeadlineSample],
    ) -> std::io::Result<()> {
        let names = self.series_names();
        if names.is_empty() {
            return Ok(());
        }
        let mut text = format!("time_s,{}\n", names.join(","));
        for s in samples {
            text.push_str(&format!("{:.9e}", s.time));
            for v in &s.values {
                text.push_str(&format!(",{v}"));
            }
            text.push('\n');
        }
        crate::output::atomic::write_atomic(path, text.as_bytes())
    }
}

/// Figures of a discharge curve (spheres in the funnel against time).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DischargeSummary {
    /// Spheres in the funnel when it opens (the sample nearest after the opening).
    pub at_opening: f64,
    /// Steady discharge rate (spheres/s): minus the slope of a least-squares line through the
    /// samples after the opening while between 90 % and 30 % of `at_opening` remain (NaN with
    /// fewer than three such samples).
    pub rate: f64,
    /// Time after the opening until half of `at_opening` have left, interpolated linearly
    /// between samples (NaN if it does not happen within the curve).
    pub half_time: f64,
}

/// Summarise a discharge curve `(time, spheres in the funnel)` of a funnel opened at `opened_at`
/// that held `n0` spheres in all.
pub fn discharge_summary(curve: &[(f64, f64)], opened_at: f64, n0: f64) -> DischargeSummary {
    let after: Vec<(f64, f64)> = curve
        .iter()
        .copied()
        .filter(|(t, _)| *t >= opened_at)
        .collect();
    let at_opening = after.first().map_or(n0, |p| p.1);
    let window: Vec<(f64, f64)> = after
        .iter()
        .copied()
        .filter(|(_, n)| *n <= 0.9 * at_opening && *n >= 0.3 * at_opening)
        .collect();
    let rate = linear_fit(&window).map_or(f64::NAN, |(_, b)| -b);
    let half = 0.5 * at_opening;
    let half_time = after
        .windows(2)
        .find(|w| w[0].1 > half && w[1].1 <= half)
        .map_or(f64::NAN, |w| {
            let f = (w[0].1 - half) / (w[0].1 - w[1].1);
            w[0].0 + f * (w[1].0 - w[0].0) - opened_at
        });
    DischargeSummary {
        at_opening,
        rate,
        half_time,
    }
}

/// Beverloo's `C` and `k` fitted to measured flow rates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeverlooFit {
    /// Discharge coefficient `C`.
    pub c: f64,
    /// Empty-annulus coefficient `k`.
    pub k: f64,
    /// Intercept `a` and slope `b` of the line `W^{2/5} = a + b D`.
    pub line: (f64, f64),
}

/// Fit Beverloo's correlation `W = C ρ_b √g (D − k d)^{5/2}` to `(D, W)` points (m, kg/s) of
/// particles of diameter `d` (m), bulk density `ρ_b` (kg/m³) and gravity `g` (m/s²).
/// Raising both sides to the power 2/5 makes it linear in `D`:
/// `W^{2/5} = (C ρ_b √g)^{2/5} (D − k d) = a + b D` with `b = (C ρ_b √g)^{2/5}` and
/// `a = −b k d`, so a least-squares line gives `C = b^{5/2} / (ρ_b √g)` and `k = −a / (b d)`.
/// `None` with fewer than three points, a non-positive rate or slope, or non-finite input.
pub fn fit_beverloo(
    points: &[(f64, f64)],
    d: f64,
    bulk_density: f64,
    g: f64,
) -> Option<BeverlooFit> {
    if points
        .iter()
        .any(|(dd, w)| !(dd.is_finite() && w.is_finite() && *w > 0.0))
        || !(d > 0.0 && bulk_density > 0.0 && g > 0.0)
    {
        return None;
    }
    let line: Vec<(f64, f64)> = points.iter().map(|(dd, w)| (*dd, w.powf(0.4))).collect();
    let (a, b) = linear_fit(&line)?;
    if b <= 0.0 {
        return None;
    }
    Some(BeverlooFit {
        c: b.powf(2.5) / (bulk_density * g.sqrt()),
        k: -a / (b * d),
        line: (a, b),
    })
}

/// The result of an orifice sweep.
#[derive(Debug, Clone)]
pub struct SweepSummary {
    /// `(orifice diameter (m), measured mass flow rate (kg/s), Beverloo with C = 0.58, k = 1.5)`.
    pub points: Vec<(f64, f64, f64)>,
    /// The fit to the measured rates (`None` if a rate could not be measured).
    pub fit: Option<BeverlooFit>,
    /// Each run's summary, in sweep order.
    pub runs: Vec<crate::run::RunSummary>,
    /// Human-readable summary.
    pub text: String,
    /// Files written by the sweep itself (the CSV of the points).
    pub files: Vec<std::path::PathBuf>,
}

/// Run a hopper scene once per diameter of its `orifice_sweep_m` (each run in
/// `out_dir/<name>_D<i>`, the orifice plate's diameter replaced, everything else as written),
/// then fit Beverloo's `C` and `k` to the measured flow rates ([`fit_beverloo`]) and write
/// `<name>_beverloo.csv`. Resuming is per run: resume a run by writing its diameter into the
/// scene and running it alone.
pub fn run_orifice_sweep(
    scene: &Scene,
    options: &crate::run::RunOptions,
) -> Result<SweepSummary, crate::SimError> {
    let sweep = scene.source.run.orifice_sweep_m.clone().unwrap_or_default();
    let mut points = Vec::new();
    let mut runs = Vec::new();
    for (i, diameter) in sweep.iter().enumerate() {
        let mut file = scene.source.clone();
        file.run.orifice_sweep_m = None;
        file.run.name = format!("{}_D{i}", scene.source.run.name);
        for w in file
            .walls
            .iter_mut()
            .filter(|w| w.kind == WallKind::OrificePlate)
        {
            w.orifice_diameter_m = Some(*diameter);
        }
        let text = toml::to_string(&file)
            .map_err(|e| crate::SimError::Build(format!("orifice sweep: {e}")))?;
        let one = crate::scene::validate::parse_scene(&scene.file, &text)?;
        let mut opts = options.clone();
        opts.out_dir = options.out_dir.join(&one.name);
        opts.resume = None;
        let summary = crate::run::run_scene(&one, &opts)?;
        let rate = summary
            .headline
            .get("mass_flow_rate_kg_per_s")
            .unwrap_or(f64::NAN);
        let beverloo = summary
            .headline
            .get("beverloo_kg_per_s")
            .unwrap_or(f64::NAN);
        points.push((*diameter, rate, beverloo));
        let stopped = summary.stopped_early;
        runs.push(summary);
        if stopped {
            break;
        }
    }
    let d = mean_diameter(scene);
    let rho_p = scene.materials[scene.particles[0].material].1.density();
    let bulk = BULK_SOLID_FRACTION * rho_p;
    let g = scene.gravity.norm();
    let fit = fit_beverloo(
        &points.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>(),
        d,
        bulk,
        g,
    );
    let mut text =
        String::from("orifice sweep:\n  D (m)        D/d    W (kg/s)     Beverloo (kg/s)  ratio\n");
    for (dd, w, b) in &points {
        text.push_str(&format!(
            "  {dd:.4e}  {:>5.2}  {w:.4e}   {b:.4e}       {:.3}\n",
            dd / d,
            w / b
        ));
    }
    match fit {
        Some(f) => text.push_str(&format!(
            "  fitted W = C ρ_b √g (D − k d)^{{5/2}} (least squares of W^{{2/5}} against D): C = {:.4}, k = {:.4} \
             (Beverloo et al. 1961: C = {BEVERLOO_C}, k = {BEVERLOO_K}; ρ_b = {BULK_SOLID_FRACTION} ρ_p, d = {d:.4e} m)",
            f.c, f.k
        )),
        None => text.push_str("  fit: not possible (fewer than three measured flow rates)"),
    }
    let csv_path = options
        .out_dir
        .join(format!("{}_beverloo.csv", scene.source.run.name));
    let mut csv = String::from("orifice_diameter_m,mass_flow_rate_kg_per_s,beverloo_kg_per_s\n");
    for (dd, w, b) in &points {
        csv.push_str(&format!("{dd},{w},{b}\n"));
    }
    std::fs::create_dir_all(&options.out_dir).map_err(crate::error::output(&options.out_dir))?;
    crate::output::atomic::write_atomic(&csv_path, csv.as_bytes())
        .map_err(crate::error::output(&csv_path))?;
    Ok(SweepSummary {
        points,
        fit,
        runs,
        text,
        files: vec![csv_path],
    })
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

    /// Rates from Beverloo's law with known `C`, `k` (exact, then with ±2 % scatter) give back
    /// `C` and `k`: exactly, then within what the scatter allows.
    #[test]
    fn beverloo_fit_recovers_c_and_k_from_synthetic_rates() {
        let (c, k, d, rho_b, g): (f64, f64, f64, f64, f64) = (0.58, 1.5, 0.003, 1500.0, 9.81);
        let law = |dd: f64| c * rho_b * g.sqrt() * (dd - k * d).powf(2.5);
        let diameters = [0.018, 0.024, 0.03, 0.036];
        let exact: Vec<(f64, f64)> = diameters.iter().map(|&dd| (dd, law(dd))).collect();
        let fit = fit_beverloo(&exact, d, rho_b, g).unwrap();
        assert!((fit.c / c - 1.0).abs() < 1e-10, "{fit:?}");
        assert!((fit.k - k).abs() < 1e-8, "{fit:?}");
        let noisy: Vec<(f64, f64)> = exact
            .iter()
            .zip([1.02, 0.98, 1.01, 0.99])
            .map(|((dd, w), f)| (*dd, w * f))
            .collect();
        let fit = fit_beverloo(&noisy, d, rho_b, g).unwrap();
        assert!((fit.c / c - 1.0).abs() < 0.08, "{fit:?}");
        assert!((fit.k - k).abs() < 0.4, "{fit:?}");
        // A wrong law is not recovered: W ∝ D² gives a different k.
        let square: Vec<(f64, f64)> = diameters.iter().map(|&dd| (dd, dd * dd)).collect();
        let fit = fit_beverloo(&square, d, rho_b, g).unwrap();
        assert!((fit.k - k).abs() > 1.0, "{fit:?}");
        assert!(fit_beverloo(&exact[..2], d, rho_b, g).is_none());
        assert!(fit_beverloo(&[(0.02, 1.0), (0.03, -1.0), (0.04, 2.0)], d, rho_b, g).is_none());
    }

    /// A plugged funnel of 100 spheres opened at t = 2 s and emptying at 10 spheres/s.
    #[test]
    fn discharge_summary_of_a_linear_curve() {
        let curve: Vec<(f64, f64)> = (0..80)
            .map(|i| {
                let t = 0.1 * i as f64;
                (t, (100.0 - 10.0 * (t - 2.0).max(0.0)).max(0.0))
            })
            .collect();
        let s = discharge_summary(&curve, 2.0, 100.0);
        assert!((s.at_opening - 100.0).abs() < 1e-9, "{s:?}");
        assert!((s.rate - 10.0).abs() < 1e-9, "{s:?}");
        assert!((s.half_time - 5.0).abs() < 1e-9, "{s:?}");
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
