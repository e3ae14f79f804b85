//! The fits of the headlines: a least-squares line, and Beverloo's `C` and `k` from measured
//! flow rates.

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
}
