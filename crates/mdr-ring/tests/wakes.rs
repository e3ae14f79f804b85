//! Wake diagnostics: the autocorrelation estimator on synthetic tilted stripes of known pitch and
//! wavelength, the shear-periodic continuation of the grid, Toomre's Q, and (ignored: minutes in a
//! debug build) a self-gravitating ring that forms wakes next to one without gravity.

use mdr_ring::boundary::ShearingBox;
use mdr_ring::prelude::*;
use mdr_ring::wakes::{critical_wavelength, toomre_q, SurfaceDensity};
use rapier3d_f64::math::Vector;

fn domain(side: f64) -> ShearingBox {
    ShearingBox::new(HillFrame::new(REBOUND_OMEGA).unwrap(), side, side).unwrap()
}

/// `Σ = 1 + 0.6 cos(k·r)` with `k = 2π (a, b) / L`: stripes along `(−b, a)`, pitch
/// `atan(b/a)` from the y axis (trailing for a, b > 0), wavelength `L / √(a² + b²)`.
fn stripes(n: usize, side: f64, a: f64, b: f64) -> SurfaceDensity {
    let cell = side / n as f64;
    let mut sigma = vec![0.0; n * n];
    for iy in 0..n {
        for ix in 0..n {
            let (x, y) = ((ix as f64 + 0.5) * cell, (iy as f64 + 0.5) * cell);
            let phase = 2.0 * std::f64::consts::PI * (a * x + b * y) / side;
            sigma[iy * n + ix] = 1.0 + 0.6 * phase.cos();
        }
    }
    SurfaceDensity {
        nx: n,
        ny: n,
        dx: cell,
        dy: cell,
        slide: 0.0,
        sigma,
        shot_noise: 0.0,
    }
}

#[test]
fn stripes_give_their_pitch_and_wavelength() {
    for (a, b) in [(5.0, 2.0), (4.0, 1.0), (3.0, 2.0), (6.0, -2.0)] {
        let side = 200.0;
        let grid = stripes(80, side, a, b);
        let w = grid.autocorrelation().wakes(0.5);
        let pitch = f64::atan2(b, a).to_degrees();
        let wavelength = side / f64::hypot(a, b);
        eprintln!(
            "a {a}, b {b}: pitch {:.2} (exact {pitch:.2}), wavelength {:?} (exact {wavelength:.2}), anisotropy {:.1}",
            w.pitch_deg, w.wavelength_m, w.anisotropy
        );
        assert!(
            (w.pitch_deg - pitch).abs() < 2.0,
            "pitch {} vs {pitch}",
            w.pitch_deg
        );
        let measured = w.wavelength_m.expect("a side maximum");
        // Half a cell of the 2.5 m grid.
        assert!(
            (measured - wavelength).abs() < 1.25,
            "{measured} vs {wavelength}"
        );
        assert!(w.anisotropy > 3.0, "{}", w.anisotropy);
    }
}

#[test]
fn random_particles_have_no_wakes() {
    // Uniform random positions (no structure): the central peak is one cell, isotropic.
    use rand::{Rng, SeedableRng};
    let d = domain(200.0);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    let mut p = Particles::default();
    for _ in 0..1500 {
        let x = (rng.random::<f64>() - 0.5) * 200.0;
        let y = (rng.random::<f64>() - 0.5) * 200.0;
        p.push(Vector::new(x, y, 0.0), Vector::ZERO, 1.6, 6.9e3);
    }
    let w = SurfaceDensity::of(&d, &p, 0.0, 2.5)
        .autocorrelation()
        .wakes(0.5);
    eprintln!("random: {w:?}");
    assert!(w.anisotropy < 1.5, "{}", w.anisotropy);
}

/// `Σ = 1 + cos(k·r)` periodic on the sheared lattice of the boundary, spanned by `(0, L_y)` and
/// `(L_x, −S)` (the image in the box at +x sits at `y − S`): `k_y = 2π b / L_y`,
/// `k_x = 2π (a + b S / L_y) / L_x`.
fn sheared_cosine(n: usize, side: f64, slide: f64, a: f64, b: f64) -> (SurfaceDensity, f64, f64) {
    let cell = side / n as f64;
    let ky = 2.0 * std::f64::consts::PI * b / side;
    let kx = 2.0 * std::f64::consts::PI * (a + b * slide / side) / side;
    let mut sigma = vec![0.0; n * n];
    for iy in 0..n {
        for ix in 0..n {
            sigma[iy * n + ix] = 1.0 + (kx * ix as f64 * cell + ky * iy as f64 * cell).cos();
        }
    }
    let grid = SurfaceDensity {
        nx: n,
        ny: n,
        dx: cell,
        dy: cell,
        slide,
        sigma,
        shot_noise: 0.0,
    };
    (grid, kx, ky)
}

#[test]
fn the_grid_continues_across_x_with_the_shear_slide() {
    // A field periodic on the sheared lattice has the autocorrelation cos(k·l) at every lag,
    // including the lags that cross the radial boundary, only if the grid continues across x with
    // the boundary's slide (here 10 cells of 2.5 m).
    let (n, side, slide) = (40, 100.0, 25.0);
    let worst = |grid_slide: f64| {
        let (mut grid, kx, ky) = sheared_cosine(n, side, slide, 1.0, 1.0);
        grid.slide = grid_slide;
        let acf = grid.autocorrelation();
        let mut worst: f64 = 0.0;
        for ly in -20..=20isize {
            for lx in -20..=20isize {
                let exact = (kx * lx as f64 * 2.5 + ky * ly as f64 * 2.5).cos();
                worst = worst.max((acf.at(lx, ly) - exact).abs());
            }
        }
        worst
    };
    assert!(worst(slide) < 1e-9, "{}", worst(slide));
    // The opposite slide (the lattice (L_x, +S)) breaks it: the check can fail.
    assert!(worst(side - slide) > 0.1, "{}", worst(side - slide));
    // SurfaceDensity::of takes the slide from the boundary: S(t) modulo L_y.
    let d = domain(side);
    let t = (slide + side) / d.shear_speed();
    let grid = SurfaceDensity::of(&d, &Particles::default(), t, 2.5);
    assert!((grid.slide - slide).abs() < 1e-9, "{}", grid.slide);
}

#[test]
fn toomre_q_and_critical_wavelength_of_rebound_sheet() {
    // REBOUND's sheet: Σ = 400 kg/m², Ω = 1.3143527e-4 /s → λ_cr = 4π² G Σ / Ω² ≈ 61 m; a radial
    // dispersion of 1 mm/s gives Q = 1e-3 Ω / (3.36 G Σ) ≈ 1.47.
    let g = mdr_ring::gravity::GRAVITATIONAL_CONSTANT;
    let lambda = critical_wavelength(REBOUND_OMEGA, g, 400.0);
    assert!((lambda - 60.98).abs() < 0.05, "{lambda}");
    let q = toomre_q(1e-3, REBOUND_OMEGA, g, 400.0);
    assert!((q - 1.4654).abs() < 1e-3, "{q}");
}

fn wake_anisotropy(
    gravity: Option<SelfGravity>,
    orbits: f64,
) -> (f64, mdr_ring::wakes::WakeMeasure) {
    let mut config = RingConfig::default().seed(2);
    config.gravity = gravity;
    let mut ring = RingSimulation::new(config, BridgesLaw::default()).unwrap();
    let domain = *ring.domain();
    let period = domain.frame().period();
    let mut acfs = Vec::new();
    let g = mdr_ring::gravity::GRAVITATIONAL_CONSTANT;
    let sigma = ring.particles().total_mass() / domain.area();
    let cell =
        mdr_ring::app::wake_cell(200.0, critical_wavelength(domain.frame().omega(), g, sigma));
    let result = ring
        .run(orbits, |s, p| {
            let k = (s.t_orbits * 10.0).round() as u64;
            if s.t_orbits >= 0.5 * orbits && k.is_multiple_of(5) {
                acfs.push(
                    SurfaceDensity::of(&domain, p, s.t_orbits * period, cell).autocorrelation(),
                );
            }
        })
        .unwrap();
    let w = mdr_ring::wakes::Autocorrelation::average(&acfs)
        .unwrap()
        .wakes(0.5);
    (result.summary.toomre_q, w)
}

/// A self-gravitating ring (REBOUND's 200 m sheet, tree gravity, 6 orbits) forms trailing wakes:
/// the autocorrelation's central ellipse is elongated well beyond what a ring without gravity
/// reaches. About 25 s (two 6-orbit runs of 1,500 particles); the measured values with
/// `cargo test --release -p mdr-ring --test wakes -- --nocapture`.
#[test]
fn self_gravitating_ring_forms_wakes() {
    let (q_none, none) = wake_anisotropy(None, 6.0);
    let (q_grav, grav) = wake_anisotropy(Some(SelfGravity::tree()), 6.0);
    eprintln!("no gravity: Q {q_none:.2}, {none:?}\ntree gravity: Q {q_grav:.2}, {grav:?}");
    assert!(none.anisotropy < 1.6, "{none:?}");
    assert!(grav.anisotropy > 2.0, "{grav:?}");
    assert!((5.0..45.0).contains(&grav.pitch_deg), "{grav:?}");
}
