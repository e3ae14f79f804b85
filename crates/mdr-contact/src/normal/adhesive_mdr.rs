//! The adhesive MDR elasto-plastic law in its continuum closed form for the parabolic profile
//! (`docs/theory.md`, "Adhesion: Heß's rule on the plastic springs"). O(1) time and state.
//!
//! The springs of the MDR bed follow eqs. (10)–(13) as in [`super::MdrLaw`]; on top of them
//! Heß's adhesion rule (Popov & Heß, the paper's ref. [12]): a spring attaches when it touches,
//! with zero elongation; an attached spring carries tension; the outermost attached spring, at
//! the contact radius `a`, lets go when its elongation exceeds `Δl_max(a) = √(2π a Δγ / E*)`.
//! With the plastic offsets of eq. (13) the springs sit on the crater's profile
//! `h(x) = g(x) + u_pl(x)`, so the whole state is `d_max`, the attached radius `a` and the
//! adhesive work booked so far.

use super::{
    AfterTouching, MdrElastoPlastic, MdrLaw, MdrState, NormalLaw, NormalModel, NormalResponse,
    Touching,
};
use crate::error::{non_negative, Result};
use crate::material::ContactPair;
use std::f64::consts::PI;

/// Parameters of the adhesive MDR law (a [`NormalModel`]): the MDR parameters `q_c`, `Θ` and the
/// work of adhesion `Δγ` (J/m²).
///
/// ```
/// use mdr_contact::prelude::*;
/// let pair = ContactPair::paper_fig2();
/// let law = AdhesiveMdr::new(MdrElastoPlastic::elastic(), 0.1).unwrap().bind(&pair).unwrap();
/// // JKR pull-off force (3/2) π Δγ R.
/// let r = pair.effective_radius();
/// assert!((law.pull_off_force() - 1.5 * std::f64::consts::PI * 0.1 * r).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AdhesiveMdr {
    params: MdrElastoPlastic,
    work_of_adhesion: f64,
}

impl AdhesiveMdr {
    /// The MDR parameters `params` with the work of adhesion `work_of_adhesion` (J/m², finite,
    /// ≥ 0; zero gives [`MdrLaw`] exactly).
    pub fn new(params: MdrElastoPlastic, work_of_adhesion: f64) -> Result<Self> {
        non_negative("work_of_adhesion", work_of_adhesion)?;
        Ok(Self {
            params,
            work_of_adhesion,
        })
    }

    /// The MDR parameters `q_c`, `Θ`.
    pub fn params(&self) -> &MdrElastoPlastic {
        &self.params
    }

    /// `Δγ` (J/m²).
    pub fn work_of_adhesion(&self) -> f64 {
        self.work_of_adhesion
    }
}

impl NormalModel for AdhesiveMdr {
    type Law = AdhesiveMdrLaw;
    fn bind(&self, pair: &ContactPair) -> Result<AdhesiveMdrLaw> {
        Ok(AdhesiveMdrLaw::new(
            self.params.bind(pair)?,
            self.work_of_adhesion,
        ))
    }
}

/// History of one adhesive MDR contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AdhesiveMdrState {
    /// Largest overlap so far, `d_max` (m): fixes the plastic offsets (eq. 13).
    pub max_overlap: f64,
    /// Radius of the attached springs `a` (m); zero when the contact does not hold.
    pub contact_radius: f64,
    /// Energy the springs held when they let go, summed (J): the adhesive hysteresis.
    pub adhesive_work: f64,
}

/// The adhesive MDR closed-form law bound to one pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdhesiveMdrLaw {
    mdr: MdrLaw,
    work_of_adhesion: f64,
    /// `√(2π Δγ / E*)`: `Δl_max(a) = detach_coefficient · √a`.
    detach_coefficient: f64,
    /// `2π Δγ / E*`: `Δl_max(a)² = this · a`.
    detach_coefficient_sq: f64,
    /// `(3/2) π Δγ R`.
    pull_off: f64,
    /// `1/R`.
    inv_radius: f64,
    /// `(2/3)(1 − θ)√R`: `(2/3)(1 − θ) b³/R = this · s^{3/2}` (A3).
    crater_volume_coefficient: f64,
    /// The sphere's branch of the crater, `h = x²/R` (outside the plastic radius).
    outer: Branch,
    /// The flattened branch, `h = θx²/R + (1 − θ)s` (inside the plastic radius).
    inner: Branch,
    /// `(c R/4)^{2/3}`: the stationary point of `δ` on the outer branch (A7).
    outer_weakest_edge: f64,
    /// `(c R/(4θ))^{2/3}`: the stationary point of `δ` on the inner branch (A7).
    inner_weakest_edge: f64,
}

/// One branch `h = κx² + h₀` of the crater, for the edge that retreats on the branch of the
/// touching radius `a_t` (`κ a_t² = d − h₀`; docs/theory.md, eqs. A12–A13).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Branch {
    /// `√(2πΔγ/E*)/κ`: `ε = Δl_max(a_t)/(d − h₀) = this · a_t^{−3/2}`.
    eps_coefficient: f64,
    /// `2πΔγ/(E*κ²)`, the square of `eps_coefficient`: the edge `a` on the branch holds while
    /// `(a² − a_t²)² ≤ this · a` (A5 squared, divided by `κ²`).
    hold_coefficient: f64,
    /// `(hold_coefficient / SERIES_EDGE_LIMIT²)^{1/3}`: `ε ≤ SERIES_EDGE_LIMIT` where `a_t` is
    /// at least this (the band of `a_t³ ≥ 256 (c/κ)²`, up to the rounding of the cube root).
    series_radius: f64,
    /// `(hold_coefficient / FITTED_EDGE_LIMIT²)^{1/3}`: `ε ≤ FITTED_EDGE_LIMIT` where `a_t` is
    /// at least this.
    fitted_radius: f64,
    /// `(hold_coefficient / WIDE_EDGE_LIMIT²)^{1/3}`: `ε ≤ WIDE_EDGE_LIMIT` where `a_t` is at
    /// least this.
    wide_radius: f64,
    /// `2E*κ/3`: the annulus `a_t < x < a` pulls `(2E*κ/3)(a − a_t)²(a + 2a_t)` (A13).
    pull_coefficient: f64,
}

impl Branch {
    fn new(detach_coefficient: f64, effective_modulus: f64, kappa: f64) -> Self {
        let eps_coefficient = detach_coefficient / kappa;
        Self {
            eps_coefficient,
            hold_coefficient: eps_coefficient * eps_coefficient,
            series_radius: (eps_coefficient * eps_coefficient
                / (SERIES_EDGE_LIMIT * SERIES_EDGE_LIMIT))
                .cbrt(),
            fitted_radius: (eps_coefficient * eps_coefficient
                / (FITTED_EDGE_LIMIT * FITTED_EDGE_LIMIT))
                .cbrt(),
            wide_radius: (eps_coefficient * eps_coefficient / (WIDE_EDGE_LIMIT * WIDE_EDGE_LIMIT))
                .cbrt(),
            pull_coefficient: 2.0 / 3.0 * effective_modulus * kappa,
        }
    }
}

/// Below this `ε` the series (A12) to `ε⁸` is the edge to round-off.
const SERIES_EDGE_LIMIT: f64 = 1.0 / 16.0;
/// Up to this `ε` the fit of [`edge_fit`] is the edge to round-off.
const FITTED_EDGE_LIMIT: f64 = 0.5;
/// Up to this `ε` the fit of [`edge_fit_wide`] is the edge to round-off; beyond it the
/// iteration of [`AdhesiveMdrLaw::retreat_by_halley`].
const WIDE_EDGE_LIMIT: f64 = 2.0;

/// `y/ε` with `y = u² − 1` of the largest root `u` of `u⁴ − εu − 1 = 0`, from its series
/// (docs/theory.md, eq. A12) to `ε⁸`: `y/ε = 1/2 − ε²/64 + ε³/128 − 9ε⁴/4096 + 55ε⁶/131072
/// − 9ε⁷/32768 + 1547ε⁸/16777216 + O(ε¹⁰)` (the terms in `ε`, `ε⁵`, `ε⁹` vanish). For
/// `ε ≤ 1/16` the first term left out is below `5·10⁻¹⁷` of the sum.
#[inline]
fn edge_series(eps: f64) -> f64 {
    let e2 = eps * eps;
    let high = 55.0 / 131072.0 + eps * (-9.0 / 32768.0 + eps * (1547.0 / 16777216.0));
    0.5 + e2 * (-1.0 / 64.0 + eps * (1.0 / 128.0 + eps * (-9.0 / 4096.0 + e2 * high)))
}

/// The middle of the fitted band `1/16 < ε ≤ 1/2`.
const EDGE_FIT_CENTRE: f64 = 9.0 / 32.0;

/// Coefficients of [`edge_fit`], of `(ε − 9/32)¹²` down to `(ε − 9/32)⁰`.
const EDGE_FIT: [f64; 13] = [
    -1.992404867428227e-6,
    2.3642759635774487e-6,
    2.0106728254983943e-6,
    -1.838655713757549e-5,
    5.514066179338563e-5,
    -1.010916017429161e-4,
    6.442672025061706e-5,
    3.599489725888206e-4,
    -1.8745341744308029e-3,
    5.475940719746653e-3,
    -1.0045565279632239e-2,
    -7.127072868476349e-3,
    0.49892426982073995,
];

/// `y/ε` of the largest root of `u⁴ − εu − 1 = 0` (as [`edge_series`]) for
/// `1/16 < ε ≤ 1/2`, where the series converges too slowly: the polynomial of degree 12 in
/// `ε − 9/32` nearest to it in the maximum norm on the band (a Chebyshev fit to the root found
/// at 50 digits; docs/theory.md, eq. A12a). The fit is within `6·10⁻¹⁹` of `y/ε ≈ 1/2`, and its
/// evaluation in double precision within `10⁻¹⁶` of it: the root to round-off.
#[inline]
fn edge_fit(eps: f64) -> f64 {
    let x = eps - EDGE_FIT_CENTRE;
    let mut sum = EDGE_FIT[0];
    for &c in &EDGE_FIT[1..] {
        sum = sum * x + c;
    }
    sum
}

/// The middle of the wide fitted band `1/2 < ε ≤ 2`.
const EDGE_FIT_WIDE_CENTRE: f64 = 1.25;

/// Coefficients of [`edge_fit_wide`], of `(ε − 5/4)¹⁷` down to `(ε − 5/4)⁰`.
const EDGE_FIT_WIDE: [f64; 18] = [
    1.464374774178623e-10,
    -3.0523683423078364e-10,
    -5.975650824551518e-11,
    1.912955072760476e-09,
    -9.590323676004934e-09,
    3.630877074746764e-08,
    -1.1024783309362301e-07,
    2.627001756711316e-07,
    -3.850603345854547e-07,
    -5.039958625627242e-07,
    7.1441760035500145e-06,
    -3.7625473417398904e-05,
    0.00015007887378059743,
    -0.0004955711165628972,
    0.001293114127092354,
    -0.0015229623379989438,
    -0.016412805761664626,
    0.48623040072786733,
];

/// `y/ε` of the largest root of `u⁴ − εu − 1 = 0` for `1/2 < ε ≤ 2` (edges near letting go,
/// micro contacts): the polynomial of degree 17 in `ε − 5/4` nearest to it in the maximum norm
/// on that band (docs/theory.md, eq. A12a), within `3·10⁻¹⁸` of it; evaluated in double
/// precision within `8·10⁻¹⁷` relative.
#[inline]
fn edge_fit_wide(eps: f64) -> f64 {
    let x = eps - EDGE_FIT_WIDE_CENTRE;
    let mut sum = EDGE_FIT_WIDE[0];
    for &c in &EDGE_FIT_WIDE[1..] {
        sum = sum * x + c;
    }
    sum
}

/// The crater's profile `h(x) = g(x) + u_pl(x)` of one history (docs/theory.md, eq. A1):
/// `θ x²/R + (1 − θ) s` inside the plastic radius `b = √(R s)`, `x²/R` outside.
#[derive(Debug, Clone, Copy)]
struct Crater {
    radius: f64,
    /// `1/R`.
    inv_radius: f64,
    theta: f64,
    /// `s₊ = (d_max − u_c)₊`.
    plastic_overlap: f64,
    /// `(2/3)(1 − θ)√R`.
    volume_coefficient: f64,
    /// `(1 − θ) s₊`: the residual depth `h(0)`.
    depth: f64,
    /// `b² = R s₊`.
    plastic_radius_sq: f64,
}

impl Crater {
    #[inline]
    fn height(&self, a: f64) -> f64 {
        if a * a < self.plastic_radius_sq {
            self.theta * a * a * self.inv_radius + self.depth
        } else {
            a * a * self.inv_radius
        }
    }

    /// `dh/da`.
    #[inline]
    fn slope(&self, a: f64) -> f64 {
        if a * a < self.plastic_radius_sq {
            2.0 * self.theta * a * self.inv_radius
        } else {
            2.0 * a * self.inv_radius
        }
    }

    /// `∫₀^a h dx` (eq. A3).
    #[inline]
    fn integral(&self, a: f64) -> f64 {
        let cube = a * a * a * self.inv_radius * (1.0 / 3.0);
        if a * a <= self.plastic_radius_sq {
            self.theta * cube + self.depth * a
        } else if self.plastic_overlap > 0.0 {
            // (2/3)(1 − θ) b³/R with b³ = (R s)^{3/2}.
            cube + self.volume_coefficient * self.plastic_overlap * self.plastic_overlap.sqrt()
        } else {
            cube
        }
    }

    /// Touching radius at overlap `d`: the largest `a` with `h(a) ≤ d` (zero if `d ≤ h(0)`).
    #[cfg(test)]
    fn touching_radius(&self, d: f64) -> f64 {
        if d <= self.depth {
            return 0.0;
        }
        let outer = self.radius * d;
        if outer >= self.plastic_radius_sq {
            outer.sqrt()
        } else {
            (self.radius * (d - self.depth) / self.theta).sqrt()
        }
    }

    /// `E* ∫_{−a}^{a} (d − h)² dx / 2`: the energy of the attached springs (eq. A6).
    fn spring_energy(&self, modulus: f64, d: f64, a: f64) -> f64 {
        let r = self.radius;
        let inner = a.min(self.plastic_radius_sq.sqrt());
        let e = d - self.depth;
        let k = self.theta / r;
        let mut integral =
            e * e * inner - 2.0 / 3.0 * e * k * inner.powi(3) + k * k * inner.powi(5) / 5.0;
        if a > inner {
            let p = |x: f64| d * d * x - 2.0 / 3.0 * d * x.powi(3) / r + x.powi(5) / (5.0 * r * r);
            integral += p(a) - p(inner);
        }
        modulus * integral
    }
}

impl AdhesiveMdrLaw {
    /// The MDR law `mdr` with the work of adhesion `work_of_adhesion` (J/m², not checked: use
    /// [`AdhesiveMdr`] for user input).
    pub fn new(mdr: MdrLaw, work_of_adhesion: f64) -> Self {
        let modulus = mdr.effective_modulus();
        let radius = mdr.effective_radius();
        let theta = mdr.hardening_ratio();
        let detach_coefficient = (2.0 * PI * work_of_adhesion / modulus).sqrt();
        // The square of the rounded coefficient, as the shader forms it.
        let detach_coefficient_sq = detach_coefficient * detach_coefficient;
        let inv_radius = 1.0 / radius;
        Self {
            mdr,
            work_of_adhesion,
            detach_coefficient,
            detach_coefficient_sq,
            pull_off: 1.5 * PI * work_of_adhesion * radius,
            inv_radius,
            crater_volume_coefficient: 2.0 / 3.0 * (1.0 - theta) * radius.sqrt(),
            outer: Branch::new(detach_coefficient, modulus, inv_radius),
            // With θ = 0 the flattened branch never touches (`MdrLaw`): its ε is infinite.
            inner: Branch::new(detach_coefficient, modulus, theta * inv_radius),
            // Outer branch h = a²/R: dδ/dt = 4t³/R − c = 0 (t = √a); inner branch
            // h = θa²/R + (1 − θ)s: 4θt³/R = c.
            outer_weakest_edge: (detach_coefficient * radius / 4.0).powf(2.0 / 3.0),
            inner_weakest_edge: (detach_coefficient * radius / (4.0 * theta)).powf(2.0 / 3.0),
        }
    }

    /// The non-adhesive law underneath.
    pub fn mdr(&self) -> &MdrLaw {
        &self.mdr
    }

    /// `Δγ` (J/m²).
    pub fn work_of_adhesion(&self) -> f64 {
        self.work_of_adhesion
    }

    /// `Δl_max(a) = √(2π a Δγ / E*)` (m): the elongation at which the spring at the contact
    /// radius `a` lets go.
    pub fn critical_elongation(&self, contact_radius: f64) -> f64 {
        self.detach_coefficient * contact_radius.sqrt()
    }

    fn crater(&self, max_overlap: f64) -> Crater {
        // (d_max − u_c)₊ as a compare-and-select (no NaN handling needed on this path).
        let excess = max_overlap - self.mdr.yield_overlap();
        let s = if excess > 0.0 { excess } else { 0.0 };
        let theta = self.mdr.hardening_ratio();
        Crater {
            radius: self.mdr.effective_radius(),
            inv_radius: self.inv_radius,
            theta,
            plastic_overlap: s,
            volume_coefficient: self.crater_volume_coefficient,
            depth: (1.0 - theta) * s,
            plastic_radius_sq: self.mdr.effective_radius() * s,
        }
    }

    /// The branch of the crater the touching radius lies on at overlap `d` after loading to
    /// `max_overlap`, and whether it is the flattened one: `d < s = d_max − u_c`, the test
    /// [`MdrLaw`] takes its touching radius by.
    #[cfg(test)]
    fn branch(&self, max_overlap: f64, d: f64) -> (&Branch, bool) {
        if d < max_overlap - self.mdr.yield_overlap() {
            (&self.inner, true)
        } else {
            (&self.outer, false)
        }
    }

    /// The retreat `a_r − a_t` of the edge by the `ε` band the law takes it in
    /// ([`Self::series_retreat`], [`Self::fitted_retreat`]; `None` past the fits' reach,
    /// `ε > 2`).
    #[cfg(test)]
    fn retreated_edge(&self, branch: &Branch, touching: f64) -> Option<f64> {
        if touching >= branch.series_radius {
            Some(Self::series_retreat(branch, touching))
        } else {
            Self::fitted_retreat(branch, touching)
        }
    }

    /// The retreat `a_r − a_t` of the edge when the springs at the touching radius
    /// `a_t = touching` are in compression, with `a_r` the root of (A5) on the branch of the
    /// touching radius, for `ε ≤ 1/16`: the series (A12) to `ε⁸`.
    /// On a branch `h = κ a² + h₀` (A5) in `t = √a` is the quartic `κ t⁴ − c t − (d − h₀) = 0`;
    /// with `t = √a_t u` and `κ a_t² = d − h₀` it reads `u⁴ − ε u − 1 = 0`,
    /// `ε = c √a_t/(d − h₀) = (c/κ) a_t^{−3/2}`, and `a_r − a_t = a_t (u² − 1) = a_t ε (y/ε)`
    /// (docs/theory.md, eq. A12) with `a_t ε = (c/κ)/√a_t`. Whether `a_r` stays on the branch
    /// is the caller's test.
    #[inline]
    fn series_retreat(branch: &Branch, touching: f64) -> f64 {
        let scale = branch.eps_coefficient / touching.sqrt();
        scale * edge_series(scale / touching)
    }

    /// The retreat for `1/16 < ε ≤ 2`: `a_t ε (y/ε)` with `y/ε` from [`edge_fit`] up to
    /// `ε = 1/2`, from [`edge_fit_wide`] above; `None` for `ε > 2`. Always inlined: out of
    /// line, its call spills the pair loop's registers.
    #[inline(always)]
    fn fitted_retreat(branch: &Branch, touching: f64) -> Option<f64> {
        if touching >= branch.fitted_radius {
            let scale = branch.eps_coefficient / touching.sqrt();
            Some(scale * edge_fit(scale / touching))
        } else if touching >= branch.wide_radius {
            Some(Self::wide_retreat(branch, touching))
        } else {
            None
        }
    }

    /// The retreat for `1/2 < ε ≤ 2` by [`edge_fit_wide`]: edges near letting go, out of line.
    #[cold]
    #[inline(never)]
    fn wide_retreat(branch: &Branch, touching: f64) -> f64 {
        let scale = branch.eps_coefficient / touching.sqrt();
        scale * edge_fit_wide(scale / touching)
    }

    /// Unloading with stretched springs at the edge in every case [`Self::unload_on_branch`] and
    /// [`Self::held_edge`] do not cover (the edge spring past its limit where the series does
    /// not apply: no spring touching, a root on the other branch, `ε > 2`): the edge holds or retreats by
    /// [`Self::retreat_by_halley`], the force from (A3); where that finds no root of (A5) on the
    /// attached disc, `d` is below the smallest `δ` over it (A7) and the contact lets go. With
    /// the work the springs that let go held (eq. A6).
    #[cold]
    fn unload_by_iteration(
        &self,
        max_overlap: f64,
        previous: f64,
        d: f64,
        touching: f64,
    ) -> (NormalResponse, f64) {
        let crater = self.crater(max_overlap);
        let on_spheres_branch = if touching > 0.0 && d < crater.plastic_overlap {
            self.edge_on_spheres_branch(&crater, previous, d)
        } else {
            None
        };
        let a = match on_spheres_branch {
            Some(a) => a,
            None => self.retreat_by_halley(&crater, previous, d, touching),
        };
        if a == 0.0 {
            return (
                NormalResponse::default(),
                self.let_go_work(&crater, previous),
            );
        }
        let two_modulus = 2.0 * self.mdr.effective_modulus();
        let response = NormalResponse {
            force: two_modulus * (a * d - crater.integral(a)),
            contact_radius: a,
            stiffness: two_modulus * a,
        };
        (response, self.annulus_work(previous, a))
    }

    /// The edge where springs touch on the flattened branch (`0 < a_t`, `d < s`) but the root of
    /// (A5) is not that branch's (it lies beyond the plastic radius `b`, or `ε > 2` there):
    /// the sphere's branch `h = x²/R` has the root of the same quartic with its own touching
    /// radius `√(R d)` in (A12). Where that root `a_r` lies beyond `b` it is the largest root of
    /// (A5) on the crater (`h` is the sphere's there), and as `δ` is convex in `√a` and below
    /// `d` at `a_t`, `δ ≤ d` on `(a_t, a_r]`: the edge is `min(a_r, a₀)`. `None` where
    /// `ε > 2` on the sphere's branch or its root lies inside `b`.
    fn edge_on_spheres_branch(&self, crater: &Crater, previous: f64, d: f64) -> Option<f64> {
        let branch = &self.outer;
        let touching = (crater.radius * d).sqrt();
        let retreat = if touching >= branch.series_radius {
            Self::series_retreat(branch, touching)
        } else {
            Self::fitted_retreat(branch, touching)?
        };
        let root = touching + retreat;
        if root * root < crater.plastic_radius_sq {
            return None;
        }
        Some(if root < previous { root } else { previous })
    }

    /// The retreating edge by Halley's method from the previous edge, for every case the series
    /// of [`Self::series_retreat`] and [`Self::fitted_retreat`] do not cover (no spring in
    /// compression, a root on the other branch, a large perturbation); zero when the contact
    /// lets go.
    fn retreat_by_halley(&self, crater: &Crater, previous: f64, d: f64, touching: f64) -> f64 {
        let c = self.detach_coefficient;
        // φ(t) = h(t²) − c t − d, t = √a, convex in t.
        let phi = |t: f64| crater.height(t * t) - c * t - d;
        let mut t = previous.sqrt();
        let value = phi(t);
        if value <= 0.0 {
            return previous;
        }
        if 2.0 * t * crater.slope(t * t) - c <= 0.0 {
            // φ > 0 and falling at the edge: positive on the whole disc, every spring lets go.
            return 0.0;
        }
        // Halley's method from the right: on each branch of the crater φ is a quartic in t,
        // `φ' = 2t h'(t²) − c`, `φ'' = 12 κ t² = 6 h'(t²)` (κ = θ/R inside the plastic radius,
        // 1/R outside), so a step costs one division like Newton's but converges cubically.
        // From the right of the largest root of a convex φ, any overshoot past it is of the
        // cube of the error (round-off) and ends the loop.
        let floor = touching.sqrt();
        let mut value = value;
        for _ in 0..100 {
            let edge_slope = crater.slope(t * t);
            let slope = 2.0 * t * edge_slope - c;
            if slope <= 0.0 {
                // Past the minimum of φ while still positive: no root, every spring lets go.
                return 0.0;
            }
            let curvature = 6.0 * edge_slope;
            let denominator = 2.0 * slope * slope - value * curvature;
            let step = if denominator > 0.0 {
                2.0 * value * slope / denominator
            } else {
                value / slope
            };
            let next = (t - step).max(floor);
            if t - next <= 1e-15 * t {
                t = next;
                break;
            }
            t = next;
            value = phi(t);
            if value <= 0.0 {
                break;
            }
        }
        (t * t).max(touching)
    }

    /// The overlap `δ(a) = h(a) − Δl_max(a)` at which the edge of an attached disc of radius
    /// `a` sits at its limit (eq. A4).
    fn edge_overlap(&self, crater: &Crater, a: f64) -> f64 {
        crater.height(a) - self.critical_elongation(a)
    }

    /// `π Δγ (outer² − inner²)`.
    #[inline]
    fn annulus_work(&self, outer: f64, inner: f64) -> f64 {
        PI * self.work_of_adhesion * (outer * outer - inner * inner)
    }

    /// Energy the springs of an attached disc of radius `previous` held when the whole contact
    /// lets go (eq. A6): the front first retreats to the weakest edge `a*` (eq. A7), releasing
    /// `π Δγ (previous² − a*²)`, and the springs inside it let go at once with the energy they
    /// hold at `δ(a*)`.
    #[cold]
    fn let_go_work(&self, crater: &Crater, previous: f64) -> f64 {
        let (weakest, weakest_overlap) = self.weakest_edge(crater, previous);
        self.annulus_work(previous, weakest)
            + crater.spring_energy(self.mdr.effective_modulus(), weakest_overlap, weakest)
    }

    /// `(a*, δ(a*))` with `δ(a*)` the smallest `δ(a')` over `0 < a' ≤ a` (eq. A7): `δ` is
    /// convex in `√a'`, so the minimum is at its stationary point on either branch of the
    /// crater, at the plastic radius, or at the edge `a`.
    fn weakest_edge(&self, crater: &Crater, a: f64) -> (f64, f64) {
        let b_sq = crater.plastic_radius_sq;
        let mut best = (a, self.edge_overlap(crater, a));
        let mut consider = |x: f64| {
            let overlap = self.edge_overlap(crater, x);
            if overlap < best.1 {
                best = (x, overlap);
            }
        };
        let outer = self.outer_weakest_edge;
        if outer * outer >= b_sq && outer <= a {
            consider(outer);
        }
        if b_sq > 0.0 && b_sq < a * a {
            consider(b_sq.sqrt());
        }
        if crater.theta > 0.0 {
            let inner = self.inner_weakest_edge;
            if inner * inner < b_sq && inner <= a {
                consider(inner);
            }
        }
        best
    }

    /// The edge at `previous` on unloading where [`Self::unload_on_branch`] does not apply (no
    /// spring touching, `a_t = 0`: the neck held by adhesion alone; `ε > 2`; a root on the
    /// other branch): it holds while its spring's elongation `h(a) − d` is within
    /// `Δl_max(a) = c√a` (A5), and the force is (A3) on the attached disc; `None` when the
    /// edge's spring is past its limit (the edge retreats or the contact lets go). The edge
    /// lies beyond the touching radius, `h(a) > d`: the elongation is positive and the test
    /// `(h(a) − d)² ≤ c² a` needs no square root.
    #[inline]
    fn held_edge(&self, max_overlap: f64, previous: f64, d: f64) -> Option<NormalResponse> {
        let crater = self.crater(max_overlap);
        let elongation = crater.height(previous) - d;
        if elongation * elongation > self.detach_coefficient_sq * previous {
            return None;
        }
        let two_modulus = 2.0 * self.mdr.effective_modulus();
        Some(NormalResponse {
            force: two_modulus * (previous * d - crater.integral(previous)),
            contact_radius: previous,
            stiffness: two_modulus * previous,
        })
    }

    /// Unloading with springs touching out to `a_t = touching.contact_radius` (> 0) and
    /// stretched springs beyond it, on the touching radius's branch `h = κa² + h₀` of the
    /// crater. For `ε = (c/κ) a_t^{−3/2} ≤ 1/16` (tested as `a_t ≥ (256 (c/κ)²)^{1/3}`, without a
    /// root) the edge is the series root of (A5) on the branch (A12) where
    /// that lies inside the previous edge, and holds otherwise: on unloading such an edge
    /// mostly retreats. For larger `ε`, where edges mostly hold, the edge at `previous` on the
    /// same branch is tested first: its spring's elongation is `h(a) − d = κ(a² − a_t²)` (as
    /// `κa_t² = d − h₀`), so it holds while `κ²(a² − a_t²)² ≤ c²a` (A5 squared; both sides
    /// positive), a test without a square root or a division; otherwise it retreats to the
    /// root ([`Self::fitted_retreat`]; δ is convex in √a and below d at the touching radius).
    /// `None` where the root lies on the other branch, where the series does not reach, and
    /// for an edge beyond the plastic radius that the flattened branch's root does not place.
    /// Always inlined: out of line in a pair loop, its call and spills cost more than the held
    /// edge it settles.
    #[inline(always)]
    fn unload_on_branch(
        &self,
        state: &mut AdhesiveMdrState,
        touching: &NormalResponse,
        max_overlap: f64,
        inner: bool,
    ) -> Option<NormalResponse> {
        let a_t = touching.contact_radius;
        let previous = state.contact_radius;
        let branch = if inner { &self.inner } else { &self.outer };
        // On the flattened branch the edge must lie inside the plastic radius, b² = R s.
        let beyond_plastic_radius = |a: f64| {
            inner && a * a >= self.mdr.effective_radius() * (max_overlap - self.mdr.yield_overlap())
        };
        let square_gap = (previous - a_t) * (previous + a_t);
        let root = if a_t >= branch.series_radius {
            a_t + Self::series_retreat(branch, a_t)
        } else if square_gap * square_gap <= branch.hold_coefficient * previous
            && !beyond_plastic_radius(previous)
        {
            return Some(self.stretched_response(branch, touching, previous));
        } else {
            a_t + Self::fitted_retreat(branch, a_t)?
        };
        if beyond_plastic_radius(root) {
            return None;
        }
        let a = if root < previous { root } else { previous };
        state.adhesive_work += self.annulus_work(previous, a);
        state.contact_radius = a;
        Some(self.stretched_response(branch, touching, a))
    }

    /// The response with springs touching out to `a_t = touching.contact_radius` and the edge
    /// at `a` on the same branch of the crater: the disc beyond the touching radius pulls
    /// `2E* ∫_{a_t}^{a} (h − d) dx = (2E*κ/3)(a − a_t)²(a + 2a_t)` (A13); the attached springs
    /// are elastic on unloading: 2 E* a.
    #[inline]
    fn stretched_response(
        &self,
        branch: &Branch,
        touching: &NormalResponse,
        a: f64,
    ) -> NormalResponse {
        let a_t = touching.contact_radius;
        let annulus = a - a_t;
        NormalResponse {
            force: touching.force - branch.pull_coefficient * annulus * annulus * (a + 2.0 * a_t),
            contact_radius: a,
            stiffness: 2.0 * self.mdr.effective_modulus() * a,
        }
    }

    /// The elastic JKR pull-off force `(3/2) π Δγ R` (N).
    pub fn jkr_pull_off_force(&self) -> f64 {
        self.pull_off
    }
}

/// The attached disc's update after the MDR law's response at the touching radius
/// ([`MdrLaw::touching`]).
struct AttachedEdge<'a> {
    law: &'a AdhesiveMdrLaw,
    state: &'a mut AdhesiveMdrState,
    d: f64,
}

impl AfterTouching for AttachedEdge<'_> {
    type Output = NormalResponse;

    /// The update after the MDR law's `touching` response at overlap `d` (`part`: the part of
    /// the crater it touches on; `max_overlap`: `d_max` after the update): the edge of the
    /// attached disc by (A5) and its force. Always inlined, into each of the MDR law's branches
    /// with its constant `part`.
    #[inline(always)]
    fn after(self, touching: NormalResponse, part: Touching, max_overlap: f64) -> NormalResponse {
        let Self { law, state, d } = self;
        state.max_overlap = max_overlap;
        let previous = state.contact_radius;
        let a_t = touching.contact_radius;
        if a_t >= previous {
            state.contact_radius = a_t;
            return touching;
        }
        // Unloading with stretched springs at the edge (a new maximum always touches wider),
        // on the branch of the crater the MDR law found the touching radius on.
        let on_branch = match part {
            Touching::Sphere => law.unload_on_branch(state, &touching, max_overlap, false),
            Touching::Flattened => law.unload_on_branch(state, &touching, max_overlap, true),
            Touching::Nothing => None,
        };
        if let Some(response) = on_branch {
            return response;
        }
        if let Some(response) = law.held_edge(max_overlap, previous, d) {
            return response;
        }
        let (response, work) = law.unload_by_iteration(max_overlap, previous, d, a_t);
        state.adhesive_work += work;
        state.contact_radius = response.contact_radius;
        response
    }
}

impl NormalLaw for AdhesiveMdrLaw {
    type State = AdhesiveMdrState;

    /// With `Δγ = 0` this is [`MdrLaw::update`]. Otherwise `F = 2E* (a d − ∫₀^a h dx)` over the
    /// attached disc (eq. A3), negative when the attached springs are stretched.
    #[inline(always)]
    fn update(&self, state: &mut AdhesiveMdrState, d: f64) -> NormalResponse {
        if self.work_of_adhesion == 0.0 {
            let mut inner = MdrState {
                max_overlap: state.max_overlap,
            };
            let response = self.mdr.update(&mut inner, d);
            state.max_overlap = inner.max_overlap;
            state.contact_radius = response.contact_radius;
            return response;
        }
        // While the springs touch out to the attached edge, every attached spring is in
        // compression and the law is the non-adhesive one (A3 at the touching radius is §4).
        let mut plain = MdrState {
            max_overlap: state.max_overlap,
        };
        self.mdr.touching(
            &mut plain,
            d,
            AttachedEdge {
                law: self,
                state,
                d,
            },
        )
    }

    fn max_overlap(&self, state: &AdhesiveMdrState) -> f64 {
        state.max_overlap
    }

    fn residual_overlap(&self, state: &AdhesiveMdrState) -> f64 {
        self.mdr.residual_depth(state.max_overlap)
    }

    /// Plastic work (a function of `d_max`, as for [`MdrLaw`]) plus the adhesive work.
    fn dissipated_work(&self, state: &AdhesiveMdrState) -> f64 {
        self.mdr.dissipated_work(&MdrState {
            max_overlap: state.max_overlap,
        }) + state.adhesive_work
    }

    fn elastic_energy(&self, state: &AdhesiveMdrState, overlap: f64) -> f64 {
        if self.work_of_adhesion == 0.0 {
            return self.mdr.elastic_energy(
                &MdrState {
                    max_overlap: state.max_overlap,
                },
                overlap,
            );
        }
        let mut trial = *state;
        self.update(&mut trial, overlap);
        let crater = self.crater(trial.max_overlap);
        crater.spring_energy(self.mdr.effective_modulus(), overlap, trial.contact_radius)
    }

    fn yield_overlap(&self) -> f64 {
        self.mdr.yield_overlap()
    }

    fn holds(&self, state: &AdhesiveMdrState) -> bool {
        // Both tests without a branch between them: the pair loop asks this of every listed
        // pair.
        (self.work_of_adhesion > 0.0) & (state.contact_radius > 0.0)
    }

    /// `min δ(a')` over the attached disc `0 < a' ≤ a` (eq. A7).
    fn detachment_overlap(&self, state: &AdhesiveMdrState) -> f64 {
        if !self.holds(state) {
            return self.residual_overlap(state);
        }
        let crater = self.crater(state.max_overlap);
        self.weakest_edge(&crater, state.contact_radius).1
    }

    fn pull_off_force(&self) -> f64 {
        self.pull_off
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The crater's profile written out anew from the paper's geometry (hardened cap
    /// `θ x²/R + (1 − θ) s` inside the plastic radius `b = √(R s)`, the sphere outside), and
    /// Simpson's rule on it (64 panels): the tests' reference for the force of (A3), independent
    /// of the law's own crater.
    struct IndependentCrater {
        r: f64,
        theta: f64,
        depth: f64,
        b: f64,
    }

    impl IndependentCrater {
        fn profile(&self, x: f64) -> f64 {
            if x < self.b {
                self.theta * x * x / self.r + self.depth
            } else {
                x * x / self.r
            }
        }

        fn simpson(&self, lo: f64, hi: f64) -> f64 {
            let n = 64;
            let step = (hi - lo) / n as f64;
            let inner: f64 = (1..n)
                .map(|k| self.profile(lo + k as f64 * step) * if k % 2 == 1 { 4.0 } else { 2.0 })
                .sum();
            (self.profile(lo) + self.profile(hi) + inner) * step / 3.0
        }
    }

    /// On every unloading step whose edge retreats, the new edge spring sits exactly at its
    /// limit: `h(a) − d = Δl_max(a)` (eq. A5) to round-off, on the elastic and the plastic
    /// branch of the crater, from small and large retreats.
    #[test]
    fn retreating_edge_sits_at_its_limit() {
        let pair = ContactPair::paper_fig2();
        for params in [
            MdrElastoPlastic::elastic(),
            MdrElastoPlastic::paper(),
            MdrElastoPlastic::new(3.8e5, 0.02).unwrap(),
        ] {
            let law = AdhesiveMdr::new(params, 5.0).unwrap().bind(&pair).unwrap();
            let peak = 20.0 * law.yield_overlap().min(1e-5);
            let mut state = AdhesiveMdrState::default();
            law.update(&mut state, peak);
            let mut retreats = 0;
            for k in 1..400 {
                let d = peak * (1.0 - 0.004 * k as f64 * (1.0 + (k % 7) as f64));
                let previous = state.contact_radius;
                law.update(&mut state, d);
                let a = state.contact_radius;
                if a == 0.0 {
                    break;
                }
                let crater = law.crater(state.max_overlap);
                if a < previous && a > crater.touching_radius(d) {
                    retreats += 1;
                    let gap = crater.height(a) - d - law.critical_elongation(a);
                    assert!(
                        gap.abs() <= 1e-12 * law.critical_elongation(a),
                        "{params:?} step {k}: {gap:e}"
                    );
                }
            }
            assert!(retreats >= 3, "{params:?}: {retreats} retreating steps");
        }
    }
    /// The series edge (eq. A12 to `ε⁸`; above `ε = 1/16` the fits of eq. A12a) is the root of
    /// (A5) to round-off for `ε` from 10⁻⁵ to the fits' limit 2 (64 values, log-spaced, and
    /// the bands' limits), on the sphere's branch and on the crater's flattened branch; past
    /// the limit it defers to the iteration. The root is checked through (A5) itself,
    /// `h(a) − d = Δl_max(a)`, with `h` evaluated on the crater; a wrong series or fit
    /// coefficient (one fit coefficient changed by `10⁻¹²`) leaves more than the round-off. Through
    /// [`NormalLaw::update`], an edge outside the root retreats to it and one inside holds.
    #[test]
    fn series_edge_is_the_root_on_both_branches() {
        let pair = ContactPair::paper_fig2();
        let params = MdrElastoPlastic::paper();
        let plain = params.bind(&pair).unwrap();
        let e = pair.effective_modulus();
        let max_overlap = 12.0 * plain.yield_overlap();
        let s = max_overlap - plain.yield_overlap();
        let theta = plain.hardening_ratio();
        let depth = (1.0 - theta) * s;
        // (d, d − h₀, branch): outside the plastic radius (d ≥ s), and inside it, close enough
        // to the residual depth that the retreated edge stays on the flattened branch.
        let outer = 0.95 * max_overlap;
        let inner = depth + 0.05 * (s - depth);
        let mut epsilons: Vec<f64> = (0..64)
            .map(|k| 1e-5 * (1.99e5_f64).powf(k as f64 / 63.0))
            .collect();
        epsilons.extend([
            SERIES_EDGE_LIMIT,
            FITTED_EDGE_LIMIT,
            WIDE_EDGE_LIMIT * (1.0 - 1e-12),
            2.5,
        ]);
        for (d, excess, on_inner) in [(outer, outer, false), (inner, inner - depth, true)] {
            // The touching radius as the law takes it: the non-adhesive law's.
            let touching = plain
                .update(&mut MdrState { max_overlap }, d)
                .contact_radius;
            for &eps in &epsilons {
                // Δγ such that c = √(2πΔγ/E*) gives this ε.
                let c = eps * excess / touching.sqrt();
                let gamma = c * c * e / (2.0 * PI);
                let law = AdhesiveMdr::new(params, gamma)
                    .unwrap()
                    .bind(&pair)
                    .unwrap();
                let crater = law.crater(max_overlap);
                assert_eq!(touching * touching < crater.plastic_radius_sq, on_inner);
                let (branch, inner_branch) = law.branch(max_overlap, d);
                assert_eq!(inner_branch, on_inner);
                let Some(retreat) = law.retreated_edge(branch, touching) else {
                    assert!(eps > WIDE_EDGE_LIMIT, "ε = {eps}: no series edge");
                    continue;
                };
                assert!(eps <= WIDE_EDGE_LIMIT, "ε = {eps}: past the fits' limit");
                let a = touching + retreat;
                assert!(a > touching);
                assert!(a * a < crater.plastic_radius_sq || !on_inner);
                let limit = law.critical_elongation(a);
                let gap = crater.height(a) - d - limit;
                // Round-off: of `h(a) − d` itself (4 ulp of `d`, which dominates where `Δl_max`
                // is 10⁻³ of the overlap) and 1e-15 of the limit.
                assert!(
                    gap.abs() <= 1e-15 * limit + 4.0 * f64::EPSILON * d,
                    "inner {on_inner}, ε = {eps}: {gap:e}"
                );
                for (previous, expected) in [
                    (touching + 2.0 * (a - touching), a),
                    (
                        touching + 0.5 * (a - touching),
                        touching + 0.5 * (a - touching),
                    ),
                ] {
                    let mut state = AdhesiveMdrState {
                        max_overlap,
                        contact_radius: previous,
                        adhesive_work: 0.0,
                    };
                    law.update(&mut state, d);
                    assert_eq!(state.contact_radius, expected, "ε = {eps}, from {previous}");
                }
            }
        }
    }

    /// Where the root of (A5) on the flattened branch would lie beyond the plastic radius `b`,
    /// the edge is found on the sphere's branch: after one step from the maximum (`2 u_c`) to just below
    /// `s` (the touching radius just inside `b`), the edge lies beyond `b` and satisfies (A5)
    /// on the crater's profile (written out anew here), for `ε = 0.1` on the flattened branch
    /// (its root about `1.05 b`; `ε ≈ 0.04` on the sphere's branch, the series) and `ε = 0.8`
    /// (`ε ≈ 0.3` on the sphere's branch, the fit), with the
    /// adhesive work `π Δγ (a₀² − a²)`; an edge inside that root holds. Taking the flattened
    /// branch's root there leaves a gap of 5 % of the overlap, and the sphere's branch with its
    /// touching radius `√(R d)` off by `5·10⁻⁷` more than `10⁻¹²` of the limit.
    #[test]
    fn edge_beyond_the_plastic_radius_is_on_the_spheres_branch() {
        let pair = ContactPair::paper_fig2();
        let params = MdrElastoPlastic::paper();
        let (r, e) = (pair.effective_radius(), pair.effective_modulus());
        let plain = params.bind(&pair).unwrap();
        // Loaded to 2 u_c: the loaded edge √(R d_max) is √2 b, beyond the root at ε = 0.8.
        let max_overlap = 2.0 * plain.yield_overlap();
        let s = max_overlap - plain.yield_overlap();
        let theta = plain.hardening_ratio();
        let depth = (1.0 - theta) * s;
        let b = (r * s).sqrt();
        let crater = IndependentCrater { r, theta, depth, b };
        let d = s * (1.0 - 1e-3);
        let touching = plain
            .update(&mut MdrState { max_overlap }, d)
            .contact_radius;
        assert!(touching < b);
        for eps in [0.1, 0.8] {
            let c = eps * (d - depth) / touching.sqrt();
            let gamma = c * c * e / (2.0 * PI);
            let law = AdhesiveMdr::new(params, gamma)
                .unwrap()
                .bind(&pair)
                .unwrap();
            let mut state = AdhesiveMdrState::default();
            law.update(&mut state, max_overlap);
            let previous = state.contact_radius;
            law.update(&mut state, d);
            let a = state.contact_radius;
            assert!(a > b && a < previous, "ε = {eps}: edge {a}, b = {b}");
            let limit = c * a.sqrt();
            let gap = crater.profile(a) - d - limit;
            assert!(gap.abs() <= 1e-12 * limit, "ε = {eps}: {gap:e}");
            let work = PI * gamma * (previous * previous - a * a);
            assert!(
                (state.adhesive_work - work).abs() <= 1e-9 * work,
                "ε = {eps}: work {} vs {work}",
                state.adhesive_work
            );
            let inside = a * (1.0 - 1e-6);
            let mut held = AdhesiveMdrState {
                max_overlap,
                contact_radius: inside,
                adhesive_work: 0.0,
            };
            law.update(&mut held, d);
            assert_eq!(
                held.contact_radius, inside,
                "ε = {eps}: an edge inside its root"
            );
        }
    }

    /// With springs touching out to `a_t > 0` and `ε > 1/16` (the held-edge test of
    /// `unload_on_branch`, before any root), on the sphere's and on the flattened branch, in
    /// the two fitted bands (`ε = 0.3`, `0.8`) and beyond them (`ε = 3`, Halley's iteration):
    /// an edge just inside the
    /// root of (A5), found here by bisection on the crater's profile, holds, with the force of
    /// (A3) against Simpson's rule on that profile, `2E* a` and no adhesive work; an edge just
    /// outside it retreats to the root and books the work `π Δγ (a_prev² − a²)`. Kills a hold
    /// test that holds past the limit (`4c²a` for `c²a`) and a pull of the annulus with
    /// `a + a_t` for `a + 2a_t`.
    #[test]
    fn edge_on_the_touching_branch_holds_to_its_limit() {
        let pair = ContactPair::paper_fig2();
        let params = MdrElastoPlastic::paper();
        let (r, e) = (pair.effective_radius(), pair.effective_modulus());
        let plain = params.bind(&pair).unwrap();
        let max_overlap = 12.0 * plain.yield_overlap();
        let s = max_overlap - plain.yield_overlap();
        let theta = plain.hardening_ratio();
        let depth = (1.0 - theta) * s;
        let b = (r * s).sqrt();
        let crater = IndependentCrater { r, theta, depth, b };
        let profile = |x: f64| crater.profile(x);
        let simpson = |lo: f64, hi: f64| crater.simpson(lo, hi);
        let outer = 0.95 * max_overlap;
        let inner = depth + 0.02 * (s - depth);
        for (d, excess, kappa) in [(outer, outer, 1.0 / r), (inner, inner - depth, theta / r)] {
            let touching = plain
                .update(&mut MdrState { max_overlap }, d)
                .contact_radius;
            for eps in [0.3, 0.8, 3.0] {
                let c = eps * excess / touching.sqrt();
                let gamma = c * c * e / (2.0 * PI);
                let law = AdhesiveMdr::new(params, gamma)
                    .unwrap()
                    .bind(&pair)
                    .unwrap();
                // The root of h(a) − d = c√a beyond the touching radius, by bisection.
                let c = law.critical_elongation(1.0);
                let (mut lo, mut hi) = (touching, 4.0 * touching);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if profile(mid) - d - c * mid.sqrt() > 0.0 {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                let root = 0.5 * (lo + hi);
                assert!(
                    root < b || kappa == 1.0 / r,
                    "root beyond b on the flattened branch"
                );
                let what = format!("κ = {kappa:e}, ε = {eps}");
                let unload = |previous: f64| {
                    let mut state = AdhesiveMdrState {
                        max_overlap,
                        contact_radius: previous,
                        adhesive_work: 0.0,
                    };
                    (law.update(&mut state, d), state)
                };
                let held = root * (1.0 - 1e-9);
                let (response, state) = unload(held);
                assert_eq!(
                    state.contact_radius, held,
                    "{what}: the edge inside its limit"
                );
                let integral = if held < b {
                    simpson(0.0, held)
                } else {
                    simpson(0.0, b) + simpson(b, held)
                };
                let expected = 2.0 * e * (held * d - integral);
                assert!(
                    (response.force - expected).abs() <= 1e-12 * 2.0 * e * held * profile(held),
                    "{what}: {} vs {expected}",
                    response.force
                );
                assert_eq!(response.stiffness, 2.0 * e * held);
                assert_eq!(state.adhesive_work, 0.0);
                let beyond = root * (1.0 + 1e-9);
                let (_, state) = unload(beyond);
                assert!(
                    (state.contact_radius - root).abs() <= 1e-12 * root,
                    "{what}: retreated to {} for the root {root}",
                    state.contact_radius
                );
                let work = PI * gamma * (beyond * beyond - state.contact_radius.powi(2));
                assert!(
                    (state.adhesive_work - work).abs() <= 1e-6 * work,
                    "{what}: work {} vs {work}",
                    state.adhesive_work
                );
            }
        }
    }

    /// A neck held by adhesion alone (no spring touching: the overlap below the crater's
    /// residual depth, or apart) holds at its edge while the edge spring's elongation
    /// `h(a) − d` is within `Δl_max(a) = √(2π a Δγ/E*)` (A5), with the force of (A3) on the
    /// attached disc, here against Simpson's rule on the crater's profile written out anew;
    /// just past that overlap the edge retreats or lets go. Kills a hold test that holds past
    /// the limit (`4c²a` for `c²a`); one that declines too early only costs time, as the
    /// iteration then holds the edge itself.
    #[test]
    fn neck_with_no_touching_spring_holds_to_its_edge_limit() {
        let pair = ContactPair::paper_fig2();
        let params = MdrElastoPlastic::paper();
        let (r, e) = (pair.effective_radius(), pair.effective_modulus());
        let plain = params.bind(&pair).unwrap();
        let max_overlap = 8.0 * plain.yield_overlap();
        let s = max_overlap - plain.yield_overlap();
        let theta = plain.hardening_ratio();
        let depth = (1.0 - theta) * s;
        let b = (r * s).sqrt();
        let crater = IndependentCrater { r, theta, depth, b };
        let profile = |x: f64| crater.profile(x);
        let simpson = |lo: f64, hi: f64| crater.simpson(lo, hi);
        // An edge beyond the plastic radius whose limit lies apart (d < 0), and one inside it
        // whose limit lies in the residual crater (0 < d < h(0)): Δγ such that
        // Δl_max(a) = 2 (h(a) − h(0)), so the limit overlap 2h(0) − h(a) is below h(0).
        for a in [1.2 * b, 0.9 * b] {
            let limit = 2.0 * (profile(a) - depth);
            let gamma = e * limit * limit / (2.0 * PI * a);
            let law = AdhesiveMdr::new(params, gamma)
                .unwrap()
                .bind(&pair)
                .unwrap();
            let at_limit = profile(a) - limit;
            assert!(at_limit < depth);
            let unload = |d: f64| {
                let mut state = AdhesiveMdrState {
                    max_overlap,
                    contact_radius: a,
                    adhesive_work: 0.0,
                };
                (law.update(&mut state, d), state)
            };
            for d in [at_limit + 1e-9 * limit, 0.5 * (at_limit + depth)] {
                let (response, state) = unload(d);
                assert_eq!(state.contact_radius, a, "edge {a}, d = {d}");
                let integral = simpson(0.0, a.min(b)) + simpson(a.min(b), a);
                let expected = 2.0 * e * (a * d - integral);
                assert!(
                    (response.force - expected).abs() <= 1e-12 * 2.0 * e * a * profile(a),
                    "edge {a}, d = {d}: {} vs {expected}",
                    response.force
                );
                assert_eq!(response.stiffness, 2.0 * e * a);
                assert_eq!(state.adhesive_work, 0.0);
            }
            let (_, state) = unload(at_limit - 1e-9 * limit);
            assert!(state.contact_radius < a, "edge {a}: held past its limit");
            assert!(state.adhesive_work > 0.0);
        }
    }
}
