//! Gravitational wakes: the surface density of the patch on a grid, its 2-D autocorrelation under
//! the shear-periodic boundaries, and from it the wakes' pitch angle and wavelength by the method
//! of Salo et al. (2004, Icarus 170, 70, §2.3): the orientation of the autocorrelation's central
//! ellipse gives the pitch angle, the distance from the centre to the first side maximum
//! perpendicular to it the wavelength (docs/rings.md §10). Also the Toomre parameter of a particle
//! disk.

use crate::boundary::ShearingBox;
use crate::particles::Particles;
use serde::Serialize;

/// Toomre's stability parameter of a particle disk, `Q = σ_x Ω / (3.36 G Σ)` (Toomre 1964,
/// ApJ 139, 1217, eq. 67; Salo 1995, Icarus 117, 287): `σ_x` the radial velocity dispersion (m/s),
/// `Ω` (1/s), `G` (m³ kg⁻¹ s⁻²), `Σ` the surface density (kg/m²).
pub fn toomre_q(sigma_x: f64, omega: f64, constant: f64, surface_density: f64) -> f64 {
    sigma_x * omega / (3.36 * constant * surface_density)
}

/// Toomre's critical wavelength `λ_cr = 4π² G Σ / Ω²` (m), the scale of the wakes.
pub fn critical_wavelength(omega: f64, constant: f64, surface_density: f64) -> f64 {
    4.0 * std::f64::consts::PI.powi(2) * constant * surface_density / (omega * omega)
}

/// Surface density on a regular grid over the box, cells `(ix, iy)` row-major in y.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceDensity {
    /// Cells along x (radial).
    pub nx: usize,
    /// Cells along y (azimuthal).
    pub ny: usize,
    /// Cell side along x (m).
    pub dx: f64,
    /// Cell side along y (m).
    pub dy: f64,
    /// Shear offset of the radially neighbouring boxes, modulo `L_y` (m): the grid is periodic in
    /// y, and in x with this slide.
    pub slide: f64,
    /// `Σ` of each cell (kg/m²), index `iy * nx + ix`.
    pub sigma: Vec<f64>,
    /// Variance of `Σ` per cell that the discreteness of the particles alone contributes,
    /// `Σ_i (m_i / A_cell)² / cells` (kg²/m⁴): Poisson shot noise, uncorrelated between cells, so
    /// it is removed from the zero lag of the autocorrelation only.
    pub shot_noise: f64,
}

impl SurfaceDensity {
    /// Mass of each particle deposited into the cell holding its centre, on a grid of cells of
    /// about `cell` m (at least 8 per side), at `time`.
    pub fn of(domain: &ShearingBox, particles: &Particles, time: f64, cell: f64) -> Self {
        let nx = ((domain.lx() / cell).round() as usize).max(8);
        let ny = ((domain.ly() / cell).round() as usize).max(8);
        let (dx, dy) = (domain.lx() / nx as f64, domain.ly() / ny as f64);
        let mut sigma = vec![0.0; nx * ny];
        let area = dx * dy;
        let shot_noise = particles
            .mass
            .iter()
            .map(|m| (m / area).powi(2))
            .sum::<f64>()
            / (nx * ny) as f64;
        for (p, m) in particles.position.iter().zip(&particles.mass) {
            let ix = (((p.x / domain.lx() + 0.5) * nx as f64).floor() as isize)
                .rem_euclid(nx as isize) as usize;
            let iy = (((p.y / domain.ly() + 0.5) * ny as f64).floor() as isize)
                .rem_euclid(ny as isize) as usize;
            sigma[iy * nx + ix] += m / area;
        }
        Self {
            nx,
            ny,
            dx,
            dy,
            slide: domain.shear_offset(time).rem_euclid(domain.ly()),
            sigma,
            shot_noise,
        }
    }

    /// Mean `Σ` (kg/m²).
    pub fn mean(&self) -> f64 {
        self.sigma.iter().sum::<f64>() / self.sigma.len() as f64
    }

    /// `Σ` at cell `(ix, iy)` for any integers: periodic in y, and across x the neighbouring box,
    /// slid by the shear offset (rounded to a cell).
    fn at(&self, ix: isize, iy: isize) -> f64 {
        let (nx, ny) = (self.nx as isize, self.ny as isize);
        let boxes = ix.div_euclid(nx);
        // The box at +1 in x is slid by −S along y: its cell iy shows our cell iy + S/dy.
        let slide_cells = (self.slide / self.dy).round() as isize;
        let x = ix.rem_euclid(nx);
        let y = (iy + boxes * slide_cells).rem_euclid(ny);
        self.sigma[(y * nx + x) as usize]
    }

    /// The normalised autocorrelation `C(Δx, Δy) = ⟨δΣ(r) δΣ(r + Δ)⟩ / (⟨δΣ²⟩ − shot noise)` for
    /// lags up to half the box each way (direct sum, O(cells × lags)); `C(0)` is set to 1.
    pub fn autocorrelation(&self) -> Autocorrelation {
        let mean = self.mean();
        let (hx, hy) = (self.nx as isize / 2, self.ny as isize / 2);
        let (wx, wy) = ((2 * hx + 1) as usize, (2 * hy + 1) as usize);
        let delta: Vec<f64> = self.sigma.iter().map(|s| s - mean).collect();
        let raw = delta.iter().map(|d| d * d).sum::<f64>() / delta.len() as f64;
        // Structured variance: the shot noise removed (kept raw if the noise is all there is).
        let variance = if raw - self.shot_noise > 0.2 * raw {
            raw - self.shot_noise
        } else {
            raw
        };
        let mut values = vec![0.0; wx * wy];
        for ly in -hy..=hy {
            for lx in -hx..=hx {
                let mut sum = 0.0;
                for iy in 0..self.ny as isize {
                    for ix in 0..self.nx as isize {
                        let d0 = delta[(iy as usize) * self.nx + ix as usize];
                        sum += d0 * (self.at(ix + lx, iy + ly) - mean);
                    }
                }
                values[((ly + hy) as usize) * wx + (lx + hx) as usize] = if lx == 0 && ly == 0 {
                    1.0
                } else {
                    sum / delta.len() as f64 / variance.max(f64::MIN_POSITIVE)
                };
            }
        }
        Autocorrelation {
            half_x: hx as usize,
            half_y: hy as usize,
            dx: self.dx,
            dy: self.dy,
            values,
        }
    }
}

/// A normalised 2-D autocorrelation on lags `(−half_x..=half_x) × (−half_y..=half_y)` cells.
#[derive(Debug, Clone, PartialEq)]
pub struct Autocorrelation {
    /// Largest lag along x (cells).
    pub half_x: usize,
    /// Largest lag along y (cells).
    pub half_y: usize,
    /// Lag step along x (m).
    pub dx: f64,
    /// Lag step along y (m).
    pub dy: f64,
    /// Values, index `(ly + half_y) * (2 half_x + 1) + (lx + half_x)`.
    pub values: Vec<f64>,
}

/// What the autocorrelation says about the wakes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WakeMeasure {
    /// Angle between the long axis of the central ellipse and the azimuthal (y) direction
    /// (degrees, in (−90, 90]); positive for trailing wakes, tilted as the Keplerian shear tilts
    /// a radial line (`y` decreasing with `x`).
    pub pitch_deg: f64,
    /// Distance from the centre to the first side maximum perpendicular to the long axis (m);
    /// None when there is no side maximum within half the box.
    pub wavelength_m: Option<f64>,
    /// Ratio of the long to the short axis of the central ellipse (1: isotropic).
    pub anisotropy: f64,
}

impl Autocorrelation {
    /// Mean of several autocorrelations of the same shape (None when empty or shapes differ).
    pub fn average(all: &[Autocorrelation]) -> Option<Autocorrelation> {
        let first = all.first()?;
        if all.iter().any(|a| a.values.len() != first.values.len()) {
            return None;
        }
        let mut mean = first.clone();
        for (k, v) in mean.values.iter_mut().enumerate() {
            *v = all.iter().map(|a| a.values[k]).sum::<f64>() / all.len() as f64;
        }
        Some(mean)
    }

    fn width(&self) -> usize {
        2 * self.half_x + 1
    }

    /// Value at lag `(lx, ly)` cells (0 outside).
    pub fn at(&self, lx: isize, ly: isize) -> f64 {
        let (hx, hy) = (self.half_x as isize, self.half_y as isize);
        if lx.abs() > hx || ly.abs() > hy {
            return 0.0;
        }
        self.values[((ly + hy) as usize) * self.width() + (lx + hx) as usize]
    }

    /// Bilinear interpolation at a lag `(x, y)` in metres.
    fn interpolate(&self, x: f64, y: f64) -> f64 {
        let (fx, fy) = (x / self.dx, y / self.dy);
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = (fx - x0, fy - y0);
        let (x0, y0) = (x0 as isize, y0 as isize);
        (1.0 - tx) * (1.0 - ty) * self.at(x0, y0)
            + tx * (1.0 - ty) * self.at(x0 + 1, y0)
            + (1.0 - tx) * ty * self.at(x0, y0 + 1)
            + tx * ty * self.at(x0 + 1, y0 + 1)
    }

    /// The central ellipse — the lags connected to the origin where `C ≥ level` — its second
    /// moments give the orientation and axis ratio; then the first side maximum along the short
    /// axis gives the wavelength (Salo et al. 2004).
    pub fn wakes(&self, level: f64) -> WakeMeasure {
        let (hx, hy) = (self.half_x as isize, self.half_y as isize);
        let w = self.width();
        let mut inside = vec![false; self.values.len()];
        let mut stack = vec![(0isize, 0isize)];
        inside[(hy as usize) * w + hx as usize] = true;
        let (mut sxx, mut syy, mut sxy, mut count) = (0.0, 0.0, 0.0, 0usize);
        while let Some((lx, ly)) = stack.pop() {
            let (x, y) = (lx as f64 * self.dx, ly as f64 * self.dy);
            sxx += x * x;
            syy += y * y;
            sxy += x * y;
            count += 1;
            for (nx, ny) in [(lx + 1, ly), (lx - 1, ly), (lx, ly + 1), (lx, ly - 1)] {
                if nx.abs() > hx || ny.abs() > hy {
                    continue;
                }
                let k = ((ny + hy) as usize) * w + (nx + hx) as usize;
                if !inside[k] && self.values[k] >= level {
                    inside[k] = true;
                    stack.push((nx, ny));
                }
            }
        }
        // Each cell also spreads over its own area: add the moment of a uniform cell so that a
        // lone central cell reads as isotropic for square cells.
        let n = count as f64;
        let (cxx, cyy, cxy) = (
            sxx / n + self.dx * self.dx / 12.0,
            syy / n + self.dy * self.dy / 12.0,
            sxy / n,
        );
        // Eigenvectors of [[cxx, cxy], [cxy, cyy]]: the long axis at angle φ from x.
        let phi = 0.5 * (2.0 * cxy).atan2(cxx - cyy);
        let mean = 0.5 * (cxx + cyy);
        let spread = (0.25 * (cxx - cyy).powi(2) + cxy * cxy).sqrt();
        let (long, short) = (mean + spread, (mean - spread).max(f64::MIN_POSITIVE));
        let (ax, ay) = (phi.cos(), phi.sin());
        // Pitch from +y, positive when x decreases along +y (trailing): atan2(−a_x, a_y).
        let mut pitch = (-ax).atan2(ay).to_degrees();
        if pitch > 90.0 {
            pitch -= 180.0;
        } else if pitch <= -90.0 {
            pitch += 180.0;
        }
        // Walk out along the short axis (perpendicular to the long one) to the first maximum
        // after the first minimum, both directions averaged.
        let (px, py) = (-ay, ax);
        let step = 0.25 * self.dx.min(self.dy);
        let reach = (self.half_x as f64 * self.dx).min(self.half_y as f64 * self.dy);
        let profile: Vec<f64> = (0..)
            .map(|k| k as f64 * step)
            .take_while(|s| *s <= reach)
            .map(|s| 0.5 * (self.interpolate(s * px, s * py) + self.interpolate(-s * px, -s * py)))
            .collect();
        let wavelength = first_side_maximum(&profile).map(|k| k as f64 * step);
        WakeMeasure {
            pitch_deg: pitch,
            wavelength_m: wavelength,
            anisotropy: (long / short).sqrt(),
        }
    }
}

/// Index of the first local maximum after the first local minimum of `profile` (which starts at
/// the central peak), if it rises above that minimum by a noticeable amount.
fn first_side_maximum(profile: &[f64]) -> Option<usize> {
    let mut k = 1;
    while k + 1 < profile.len() && profile[k + 1] <= profile[k] {
        k += 1;
    }
    let minimum = profile.get(k).copied()?;
    while k + 1 < profile.len() && profile[k + 1] >= profile[k] {
        k += 1;
    }
    (k + 1 < profile.len() && profile[k] - minimum > 0.02).then_some(k)
}
