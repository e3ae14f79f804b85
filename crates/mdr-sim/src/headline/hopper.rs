//! Hopper discharge: the steady mass flow rate, fitted over the second half of the time after
//! the plug opens, compared with the Beverloo correlation `W = C ρ_b √g (D − k d)^{5/2}`
//! (Beverloo, Leniger & van de Velde, Chem. Eng. Sci. 15, 260 (1961)).

use super::fit::linear_fit;
use super::{mean_diameter, HeadlineReport, HeadlineSample, HeadlineTracker, ParticleView};
use crate::scene::schema::WallKind;
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

pub use crate::scene::validate::JAMMING_RATIO;

/// Beverloo's discharge coefficient `C`.
pub const BEVERLOO_C: f64 = 0.58;
/// Beverloo's empty-annulus coefficient `k`.
pub const BEVERLOO_K: f64 = 1.5;
/// Solid fraction assumed for the bulk density `ρ_b = φ ρ_p`.
pub const BULK_SOLID_FRACTION: f64 = 0.6;

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

/// The orifice plate's height and diameter, and the height below which mass counts as
/// discharged.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HopperTracker {
    plate_z: f64,
    discharge_z: f64,
    orifice: f64,
}

impl HopperTracker {
    /// The hopper of `scene`: its orifice plate, and the discharge height of the scene (two
    /// mean diameters under the plate by default).
    pub fn new(scene: &Scene) -> Self {
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
        Self {
            plate_z,
            discharge_z: scene.discharge_height.unwrap_or(plate_z - 2.0 * d),
            orifice,
        }
    }
}

impl HeadlineTracker for HopperTracker {
    fn series_names(&self) -> &'static [&'static str] {
        &["discharged_mass_kg"]
    }

    fn sample(&self, _scene: &Scene, view: &ParticleView<'_>) -> Vec<f64> {
        let m: f64 = view
            .position
            .iter()
            .zip(view.mass)
            .filter(|(p, _)| p.z < self.discharge_z)
            .map(|(_, m)| m)
            .sum();
        vec![m]
    }

    fn report(&self, scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport {
        let orifice = self.orifice;
        let mut r = HeadlineReport::default();
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
            format!("the second half of the time after the plug opened at {opened_at:.4e} s")
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
        r
    }
}
