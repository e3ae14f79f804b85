//! What a verification test reports: checks with stated tolerances, and figures that overlay the
//! reference.

use std::fmt;

/// How a check's error is measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tolerance {
    /// `|value − reference| ≤ tol · |reference|`.
    Relative(f64),
    /// `|value − reference| ≤ tol`.
    Absolute(f64),
    /// `value ≤ reference + tol` (a bound).
    AtMost(f64),
}

/// One number compared with its reference.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// What is compared (quantity, case, implementation).
    pub name: String,
    /// Computed value.
    pub value: f64,
    /// Reference value.
    pub reference: f64,
    /// Allowed deviation.
    pub tolerance: Tolerance,
}

impl Check {
    /// A check of `value` against `reference` within `tolerance`.
    pub fn new(name: impl Into<String>, value: f64, reference: f64, tolerance: Tolerance) -> Self {
        Self {
            name: name.into(),
            value,
            reference,
            tolerance,
        }
    }

    /// The deviation in the tolerance's measure (relative for [`Tolerance::Relative`]).
    pub fn error(&self) -> f64 {
        match self.tolerance {
            Tolerance::Relative(_) => (self.value - self.reference).abs() / self.reference.abs(),
            Tolerance::Absolute(_) => (self.value - self.reference).abs(),
            Tolerance::AtMost(_) => self.value - self.reference,
        }
    }

    /// Whether the check holds (a NaN never does).
    pub fn passed(&self) -> bool {
        let limit = match self.tolerance {
            Tolerance::Relative(t) | Tolerance::Absolute(t) | Tolerance::AtMost(t) => t,
        };
        self.error() <= limit
    }
}

impl fmt::Display for Check {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (kind, tol) = match self.tolerance {
            Tolerance::Relative(t) => ("rel", t),
            Tolerance::Absolute(t) => ("abs", t),
            Tolerance::AtMost(t) => ("bound", t),
        };
        write!(
            f,
            "{} {:<62} value {:>13.6e}  ref {:>13.6e}  {kind} err {:>9.2e} (tol {:.1e})",
            if self.passed() { "ok  " } else { "FAIL" },
            self.name,
            self.value,
            self.reference,
            self.error(),
            tol
        )
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A reference curve.
    Line,
    /// A dashed reference curve (a limit that is not expected to hold everywhere).
    Dashed,
    /// Simulated points.
    Points,
    /// Measured (experimental) points: filled black squares.
    Measured,
}

/// A labelled set of points.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points `(x, y)`.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
}

/// One figure of a test.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// File stem (`verify_test4_et` → `verify_test4_et.svg`).
    pub name: String,
    /// Title.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// The series.
    pub series: Vec<Series>,
}

/// The result of one Chung & Ooi test.
#[derive(Debug, Clone, PartialEq)]
pub struct TestReport {
    /// Test number, 1–8.
    pub number: u8,
    /// Title.
    pub title: String,
    /// The checks.
    pub checks: Vec<Check>,
    /// Figures overlaying the reference.
    pub figures: Vec<Figure>,
    /// Measured differences that are physical, not errors (reported, not asserted).
    pub notes: Vec<String>,
}

impl TestReport {
    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.checks.iter().all(Check::passed)
    }

    /// The checks that failed.
    pub fn failures(&self) -> Vec<&Check> {
        self.checks.iter().filter(|c| !c.passed()).collect()
    }
}

impl fmt::Display for TestReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "Test {}: {}", self.number, self.title)?;
        for c in &self.checks {
            writeln!(f, "  {c}")?;
        }
        for n in &self.notes {
            writeln!(f, "  note: {n}")?;
        }
        let failed = self.failures().len();
        writeln!(
            f,
            "  => {} ({} checks, {} failed)",
            if failed == 0 { "PASSED" } else { "FAILED" },
            self.checks.len(),
            failed
        )
    }
}
