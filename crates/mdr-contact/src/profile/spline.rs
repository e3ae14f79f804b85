//! A clamped cubic spline through tabulated points, with end slopes taken from the cubic through
//! the four end points. It reproduces every cubic exactly (so a tabulated paraboloid is exact) and
//! is fourth-order accurate for smooth data; its derivative is continuous, which the Abel
//! transform of eq. (1) needs.

use crate::error::{ContactError, Result};

/// A C² cubic spline `y(x)` through strictly increasing knots.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CubicSpline {
    knots: Vec<f64>,
    values: Vec<f64>,
    /// Second derivatives at the knots.
    curvatures: Vec<f64>,
}

/// Smallest number of rows a table needs (the end slopes use four points).
pub(crate) const MIN_TABLE_ROWS: usize = 4;

impl CubicSpline {
    /// Spline through `(knots[i], values[i])`. The table (named `name` in errors) needs at least
    /// four rows, equal lengths, finite entries and strictly increasing knots.
    pub fn new(name: &'static str, knots: &[f64], values: &[f64]) -> Result<Self> {
        if knots.len() != values.len() {
            return Err(ContactError::InvalidTable {
                name,
                reason: format!(
                    "{} abscissae but {} values: the columns must have equal length",
                    knots.len(),
                    values.len()
                ),
            });
        }
        if knots.len() < MIN_TABLE_ROWS {
            return Err(ContactError::TooFew {
                name,
                value: knots.len(),
                min: MIN_TABLE_ROWS,
            });
        }
        if let Some(i) = (0..knots.len()).find(|&i| !knots[i].is_finite() || !values[i].is_finite())
        {
            return Err(ContactError::InvalidTable {
                name,
                reason: format!(
                    "row {i} = ({}, {}) is not finite: every entry must be a finite number",
                    knots[i], values[i]
                ),
            });
        }
        if let Some(i) = (1..knots.len()).find(|&i| knots[i] <= knots[i - 1]) {
            return Err(ContactError::InvalidTable {
                name,
                reason: format!(
                    "abscissae must increase strictly, but row {i} has {} after {}",
                    knots[i],
                    knots[i - 1]
                ),
            });
        }
        let n = knots.len();
        let start_slope = end_slope(&knots[..4], &values[..4], knots[0]);
        let end_slope = end_slope(&knots[n - 4..], &values[n - 4..], knots[n - 1]);
        // Tridiagonal system for the second derivatives M (clamped ends), solved by Thomas.
        let h: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
        let secant: Vec<f64> = (0..n - 1)
            .map(|i| (values[i + 1] - values[i]) / h[i])
            .collect();
        let mut diag = vec![0.0; n];
        let mut upper = vec![0.0; n];
        let mut lower = vec![0.0; n];
        let mut rhs = vec![0.0; n];
        diag[0] = 2.0 * h[0];
        upper[0] = h[0];
        rhs[0] = 6.0 * (secant[0] - start_slope);
        for i in 1..n - 1 {
            lower[i] = h[i - 1];
            diag[i] = 2.0 * (h[i - 1] + h[i]);
            upper[i] = h[i];
            rhs[i] = 6.0 * (secant[i] - secant[i - 1]);
        }
        lower[n - 1] = h[n - 2];
        diag[n - 1] = 2.0 * h[n - 2];
        rhs[n - 1] = 6.0 * (end_slope - secant[n - 2]);
        for i in 1..n {
            let factor = lower[i] / diag[i - 1];
            diag[i] -= factor * upper[i - 1];
            rhs[i] -= factor * rhs[i - 1];
        }
        let mut curvatures = vec![0.0; n];
        curvatures[n - 1] = rhs[n - 1] / diag[n - 1];
        for i in (0..n - 1).rev() {
            curvatures[i] = (rhs[i] - upper[i] * curvatures[i + 1]) / diag[i];
        }
        Ok(Self {
            knots: knots.to_vec(),
            values: values.to_vec(),
            curvatures,
        })
    }

    /// The knots.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Index `i` of the interval `[x_i, x_{i+1}]` holding `x` (the end intervals extend outward).
    fn interval(&self, x: f64) -> usize {
        let n = self.knots.len();
        self.knots.partition_point(|&k| k <= x).clamp(1, n - 1) - 1
    }

    /// `y(x)`; outside the knots the end cubic pieces are extended.
    pub fn value(&self, x: f64) -> f64 {
        let i = self.interval(x);
        let h = self.knots[i + 1] - self.knots[i];
        let (a, b) = (self.knots[i + 1] - x, x - self.knots[i]);
        let (m0, m1) = (self.curvatures[i], self.curvatures[i + 1]);
        (m0 * a * a * a + m1 * b * b * b) / (6.0 * h)
            + (self.values[i] / h - m0 * h / 6.0) * a
            + (self.values[i + 1] / h - m1 * h / 6.0) * b
    }

    /// `y'(x)`; outside the knots the end cubic pieces are extended.
    pub fn derivative(&self, x: f64) -> f64 {
        let i = self.interval(x);
        let h = self.knots[i + 1] - self.knots[i];
        let (a, b) = (self.knots[i + 1] - x, x - self.knots[i]);
        let (m0, m1) = (self.curvatures[i], self.curvatures[i + 1]);
        (m1 * b * b - m0 * a * a) / (2.0 * h) + (self.values[i + 1] - self.values[i]) / h
            - (m1 - m0) * h / 6.0
    }
}

/// Slope at `at` of the cubic through four points (Lagrange form).
fn end_slope(xs: &[f64], ys: &[f64], at: f64) -> f64 {
    let mut slope = 0.0;
    for j in 0..4 {
        let denominator: f64 = (0..4).filter(|&k| k != j).map(|k| xs[j] - xs[k]).product();
        let numerator: f64 = (0..4)
            .filter(|&m| m != j)
            .map(|m| {
                (0..4)
                    .filter(|&k| k != j && k != m)
                    .map(|k| at - xs[k])
                    .product::<f64>()
            })
            .sum();
        slope += ys[j] * numerator / denominator;
    }
    slope
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_a_cubic_exactly_on_an_uneven_grid() {
        let cubic = |x: f64| 1.0 - 2.0 * x + 0.5 * x * x + 0.3 * x * x * x;
        let slope = |x: f64| -2.0 + x + 0.9 * x * x;
        let knots = [0.0, 0.1, 0.35, 0.4, 0.8, 1.3, 1.31, 2.0];
        let values: Vec<f64> = knots.iter().map(|&x| cubic(x)).collect();
        let spline = CubicSpline::new("t", &knots, &values).unwrap();
        for k in 0..=200 {
            let x = 2.0 * k as f64 / 200.0;
            assert!((spline.value(x) - cubic(x)).abs() < 1e-12, "x = {x}");
            assert!((spline.derivative(x) - slope(x)).abs() < 1e-11, "x = {x}");
        }
    }

    #[test]
    fn is_fourth_order_for_smooth_data() {
        let error = |n: usize| {
            let knots: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
            let values: Vec<f64> = knots.iter().map(|&x| x.sin()).collect();
            let spline = CubicSpline::new("t", &knots, &values).unwrap();
            (0..1000)
                .map(|k| {
                    let x = k as f64 / 999.0;
                    (spline.value(x) - x.sin()).abs()
                })
                .fold(0.0, f64::max)
        };
        let ratio = error(21) / error(41);
        assert!(ratio > 12.0, "halving h reduced the error only {ratio}×");
    }
}
