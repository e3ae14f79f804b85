//! What a ring run measures, computed as REBOUND's `ring.py` does (docs/rings.md §5): velocity
//! dispersion with the Keplerian shear removed, vertical thickness, mid-plane filling factor.

use crate::boundary::ShearingBox;
use crate::particles::Particles;
use serde::{Deserialize, Serialize};

/// One sample of the ring's state.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Sample {
    /// Time in orbits.
    pub t_orbits: f64,
    /// Mass-weighted radial velocity dispersion `σ_x` (m/s).
    pub sigma_x: f64,
    /// Mass-weighted azimuthal velocity dispersion `σ_y` (m/s), shear removed.
    pub sigma_y: f64,
    /// Mass-weighted vertical velocity dispersion `σ_z` (m/s).
    pub sigma_z: f64,
    /// Mass-weighted 1D dispersion `c = √((σ_x² + σ_y² + σ_z²)/3)` (m/s).
    pub c: f64,
    /// Number-weighted `c` (m/s).
    pub c_number: f64,
    /// Mass-weighted rms height about the mass-weighted mid-plane (m).
    pub z_rms: f64,
    /// Number-weighted rms height (m).
    pub z_rms_number: f64,
    /// Volume filling factor at the mid-plane: `π Σ max(r² − z², 0) / (L_x L_y)`.
    pub filling_factor_z0: f64,
    /// Collisions resolved since the start.
    pub collisions: u64,
    /// Wall-clock time since the start (s).
    pub wall_s: f64,
}

/// Measure `particles` at time `t_orbits` (the collision count and wall time are filled in by the
/// caller).
pub fn sample(domain: &ShearingBox, particles: &Particles, t_orbits: f64) -> Sample {
    let n = particles.len();
    if n == 0 {
        return Sample {
            t_orbits,
            ..Sample::default()
        };
    }
    let frame = domain.frame();
    let total_mass = particles.total_mass();
    // Peculiar velocities: shear removed, then the mass-weighted mean removed.
    let peculiar: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let v = particles.velocity[i];
            let x = particles.position[i].x;
            [v.x, v.y - frame.shear_velocity(x), v.z]
        })
        .collect();
    let mut mean = [0.0; 3];
    let mut z_mean = 0.0;
    for (i, v) in peculiar.iter().enumerate() {
        let m = particles.mass[i];
        for (mk, vk) in mean.iter_mut().zip(v) {
            *mk += m * vk;
        }
        z_mean += m * particles.position[i].z;
    }
    mean.iter_mut().for_each(|v| *v /= total_mass);
    z_mean /= total_mass;
    let (mut s2, mut s2_number) = ([0.0; 3], 0.0);
    let (mut z2, mut z2_number, mut filled) = (0.0, 0.0, 0.0);
    for (i, v) in peculiar.iter().enumerate() {
        let m = particles.mass[i];
        for k in 0..3 {
            let d = v[k] - mean[k];
            s2[k] += m * d * d;
            s2_number += d * d;
        }
        let z = particles.position[i].z - z_mean;
        z2 += m * z * z;
        z2_number += z * z;
        filled += (particles.radius[i].powi(2) - z * z).max(0.0);
    }
    let s2 = s2.map(|v| v / total_mass);
    Sample {
        t_orbits,
        sigma_x: s2[0].sqrt(),
        sigma_y: s2[1].sqrt(),
        sigma_z: s2[2].sqrt(),
        c: ((s2[0] + s2[1] + s2[2]) / 3.0).sqrt(),
        c_number: (s2_number / (3.0 * n as f64)).sqrt(),
        z_rms: (z2 / total_mass).sqrt(),
        z_rms_number: (z2_number / n as f64).sqrt(),
        filling_factor_z0: std::f64::consts::PI * filled / domain.area(),
        collisions: 0,
        wall_s: 0.0,
    }
}

/// Averages over the second half of a run, the figures REBOUND's `ring.py` reports.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Summary {
    /// Number of particles.
    pub particles: usize,
    /// Mass-weighted `c` (m/s).
    pub c_m_per_s: f64,
    /// Number-weighted `c` (m/s).
    pub c_number_m_per_s: f64,
    /// `σ_x` (m/s).
    pub sigma_x_m_per_s: f64,
    /// `σ_y` (m/s).
    pub sigma_y_m_per_s: f64,
    /// `σ_z` (m/s).
    pub sigma_z_m_per_s: f64,
    /// `c / (r̄ Ω)` with `r̄` the mean radius.
    pub c_over_mean_r_omega: f64,
    /// Mass-weighted rms thickness (m).
    pub z_rms_m: f64,
    /// Number-weighted rms thickness (m).
    pub z_rms_number_m: f64,
    /// Mid-plane volume filling factor.
    pub filling_factor_z0: f64,
    /// Collisions per particle per orbit.
    pub collisions_per_particle_per_orbit: f64,
    /// Wall time per orbit over the whole run (s).
    pub wall_s_per_orbit: f64,
    /// Dynamical optical depth `π Σ r² / (L_x L_y)`.
    pub optical_depth: f64,
    /// Toomre's `Q = σ_x Ω / (3.36 G Σ)` with REBOUND's G ([`crate::wakes::toomre_q`]), whether
    /// or not self-gravity is on.
    pub toomre_q: f64,
}

/// Average the samples with `t ≥ t_end/2` (at least the last one).
pub fn summarize(
    samples: &[Sample],
    particles: &Particles,
    domain: &ShearingBox,
    orbits: f64,
) -> Summary {
    let half = 0.5 * orbits - 1e-9;
    let second: Vec<&Sample> = samples.iter().filter(|s| s.t_orbits >= half).collect();
    let before = samples.iter().rev().find(|s| s.t_orbits < half);
    let mean = |f: fn(&Sample) -> f64| -> f64 {
        if second.is_empty() {
            return f64::NAN;
        }
        second.iter().map(|s| f(s)).sum::<f64>() / second.len() as f64
    };
    let (last, first) = (second.last(), before.or(samples.first()));
    let collision_rate = match (first, last) {
        (Some(a), Some(b)) if b.t_orbits > a.t_orbits => {
            (b.collisions - a.collisions) as f64
                / particles.len() as f64
                / (b.t_orbits - a.t_orbits)
        }
        _ => f64::NAN,
    };
    let c = mean(|s| s.c);
    let omega = domain.frame().omega();
    Summary {
        particles: particles.len(),
        c_m_per_s: c,
        c_number_m_per_s: mean(|s| s.c_number),
        sigma_x_m_per_s: mean(|s| s.sigma_x),
        sigma_y_m_per_s: mean(|s| s.sigma_y),
        sigma_z_m_per_s: mean(|s| s.sigma_z),
        c_over_mean_r_omega: c / (particles.mean_radius() * omega),
        z_rms_m: mean(|s| s.z_rms),
        z_rms_number_m: mean(|s| s.z_rms_number),
        filling_factor_z0: mean(|s| s.filling_factor_z0),
        collisions_per_particle_per_orbit: collision_rate,
        wall_s_per_orbit: samples.last().map_or(f64::NAN, |s| s.wall_s / orbits),
        toomre_q: crate::wakes::toomre_q(
            mean(|s| s.sigma_x),
            omega,
            crate::gravity::GRAVITATIONAL_CONSTANT,
            particles.total_mass() / domain.area(),
        ),
        optical_depth: std::f64::consts::PI * particles.radius.iter().map(|r| r * r).sum::<f64>()
            / domain.area(),
    }
}
