//! The adhesive MDR law's plastic crater written out (docs/theory.md §9), for the tests that
//! hold the law to it: the profile (A1), integrals by Gauss–Legendre quadrature (exact for the
//! polynomials of each branch), the force (A3), the stored energy (A6), the overlap at which an
//! edge sits at its limit (A4), the let-go overlap (A7) by a search over the attached disc, and
//! the edge (A5) an edge past its limit retreats to, by bisection. Included by the test files
//! that use it (`#[path]`), so that none of the other tests compiles it.
#![allow(dead_code)] // each including test reads only some of it

/// The crater of the history `d_max` (eq. A1) of a law with `E*`, `R`, `u_c`, `θ` and the
/// let-go coefficient `c = √(2πΔγ/E*)`.
#[derive(Debug, Clone, Copy)]
pub struct Crater {
    /// `E*` (Pa).
    pub modulus: f64,
    /// `R` (m).
    pub radius: f64,
    /// `θ`.
    pub theta: f64,
    /// `c = √(2πΔγ/E*)` (m^½).
    pub c: f64,
    /// `s = (d_max − u_c)₊` (m).
    pub s: f64,
}

impl Crater {
    /// The crater after loading to `max_overlap`.
    pub fn new(
        modulus: f64,
        radius: f64,
        yield_overlap: f64,
        theta: f64,
        c: f64,
        max_overlap: f64,
    ) -> Self {
        Self {
            modulus,
            radius,
            theta,
            c,
            s: (max_overlap - yield_overlap).max(0.0),
        }
    }

    /// `b = √(R s)`.
    pub fn plastic_radius(&self) -> f64 {
        (self.radius * self.s).sqrt()
    }

    /// The residual depth `h(0) = (1 − θ) s`.
    pub fn depth(&self) -> f64 {
        (1.0 - self.theta) * self.s
    }

    /// (A1): `θx²/R + (1 − θ)s` inside `b`, `x²/R` outside.
    pub fn h(&self, x: f64) -> f64 {
        if x < self.plastic_radius() {
            self.theta * x * x / self.radius + self.depth()
        } else {
            x * x / self.radius
        }
    }

    /// `∫₀^a f(x) dx` for `f` polynomial of degree ≤ 5 on each branch: three-point
    /// Gauss–Legendre on `[0, min(a, b)]` and `[b, a]`.
    pub fn integrate(&self, a: f64, f: impl Fn(f64) -> f64) -> f64 {
        let gauss = |lo: f64, hi: f64| {
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            let node = 0.6f64.sqrt() * half;
            half * (5.0 / 9.0 * (f(mid - node) + f(mid + node)) + 8.0 / 9.0 * f(mid))
        };
        let b = self.plastic_radius().min(a);
        gauss(0.0, b) + if a > b { gauss(b, a) } else { 0.0 }
    }

    /// (A3): `2E* (a d − ∫₀^a h dx)`.
    pub fn force(&self, d: f64, a: f64) -> f64 {
        2.0 * self.modulus * (a * d - self.integrate(a, |x| self.h(x)))
    }

    /// (A6): `(E*/2) ∫_{−a}^{a} (d − h)² dx`.
    pub fn energy(&self, d: f64, a: f64) -> f64 {
        self.modulus * self.integrate(a, |x| (d - self.h(x)).powi(2))
    }

    /// (A4): `δ(a) = h(a) − c√a`, the overlap at which the edge at `a` is at its limit.
    pub fn edge_overlap(&self, a: f64) -> f64 {
        self.h(a) - self.c * a.sqrt()
    }

    /// (A7) by search: `(a*, δ(a*))` minimising `δ` over `0 < a' ≤ a`, from a grid of 20 000
    /// points in `√a'` refined by golden section on each side of the best point (δ is convex
    /// in `√a'` on each branch, with a kink at `b`).
    pub fn weakest_edge(&self, a: f64) -> (f64, f64) {
        let delta = |t: f64| self.edge_overlap(t * t);
        let n = 20_000;
        let top = a.sqrt();
        let grid = |i: usize| top * i as f64 / n as f64;
        let best = (1..=n)
            .min_by(|&i, &j| delta(grid(i)).total_cmp(&delta(grid(j))))
            .unwrap();
        let mut found = (grid(best), delta(grid(best)));
        let golden = 0.5 * (5f64.sqrt() - 1.0);
        let b = self.plastic_radius().sqrt();
        for (mut lo, mut hi) in [
            (grid(best - 1), grid(best)),
            (grid(best), grid((best + 1).min(n))),
        ] {
            // Keep each bracket on one branch.
            if lo < b && b < hi {
                if delta(b) < found.1 {
                    found = (b, delta(b));
                }
                continue;
            }
            for _ in 0..200 {
                let x1 = hi - golden * (hi - lo);
                let x2 = lo + golden * (hi - lo);
                if delta(x1) < delta(x2) {
                    hi = x2;
                } else {
                    lo = x1;
                }
            }
            let t = 0.5 * (lo + hi);
            if delta(t) < found.1 {
                found = (t, delta(t));
            }
        }
        (found.0 * found.0, found.1)
    }

    /// The edge (A5) that an edge at `previous`, past its limit at `d` (`δ(previous) > d`),
    /// retreats to: the largest root of `δ(a) = d`, by bisection in `√a` between the smallest
    /// `δ` on a grid of 20 000 points (δ is convex in `√a`, so rising right of it) and
    /// `√previous`.
    pub fn retreated_edge(&self, previous: f64, d: f64) -> f64 {
        let delta = |t: f64| self.edge_overlap(t * t);
        let n = 20_000;
        let top = previous.sqrt();
        let lowest = (1..=n)
            .map(|i| top * i as f64 / n as f64)
            .min_by(|x, y| delta(*x).total_cmp(&delta(*y)))
            .unwrap();
        assert!(delta(lowest) < d && d < delta(top), "no retreat at d = {d}");
        let (mut lo, mut hi) = (lowest, top);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if delta(mid) > d {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let t = 0.5 * (lo + hi);
        t * t
    }
}
