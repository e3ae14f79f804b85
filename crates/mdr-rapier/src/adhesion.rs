//! What the couplings need to know of an adhesive normal law beyond the per-contact update: how
//! far apart a contact can still hold.
//!
//! An adhesive contact ([`mdr_contact::normal::NormalLaw::holds`]) lets go at the latest at its
//! [`mdr_contact::normal::NormalLaw::detachment_overlap`], a negative overlap for a held neck.
//! A neighbour list must list every pair whose neck can still hold, so its cut-off covers the
//! largest separation at which any contact of the pair lets go. For an MDR law with Heß's rule
//! (docs/theory.md §9, eq. A11) that bound is the elastic JKR snap-off distance of the pair,
//! whatever the history: the plastic offsets only raise the crater's profile above the
//! sphere's parabola, and the edge of an attached disc of radius `a` sits at its limit at
//! `δ(a) = h(a) − √(2π a Δγ / E*) ≥ a²/R − √(2π a Δγ / E*) ≥ −(3/4) (π² Δγ² R / E*²)^{1/3}`.
//! With the JKR pull-off force `F_c = (3/2) π Δγ R` ([`mdr_contact::normal::NormalLaw::pull_off_force`])
//! it reads `(3/4) (4 F_c² / (9 R E*²))^{1/3}`, zero without adhesion.

use mdr_contact::ContactPair;

/// The largest separation (m, ≥ 0) at which a contact of `pair` under a law with the JKR
/// pull-off force `pull_off_force` (N) can still hold: `(3/4) (4 F_c² / (9 R E*²))^{1/3}`
/// (docs/theory.md §9, eq. A11; the module documentation derives it). Zero when
/// `pull_off_force` is zero.
pub fn neck_reach(pull_off_force: f64, pair: &ContactPair) -> f64 {
    if pull_off_force.is_nan() || pull_off_force <= 0.0 {
        return 0.0;
    }
    let (radius, modulus) = (pair.effective_radius(), pair.effective_modulus());
    0.75 * (4.0 * pull_off_force * pull_off_force / (9.0 * radius * modulus * modulus)).cbrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic, NormalLaw, NormalModel};
    use mdr_contact::Material;
    use std::f64::consts::PI;

    /// The reach is JKR's snap-off distance under displacement control,
    /// `(3/4) (π² Δγ² R / E*²)^{1/3}` (Johnson, Kendall & Roberts 1971), and bounds the let-go
    /// separation of every history the adhesive MDR law reaches (elastic and plastic loadings
    /// to many depths, unloaded part-way).
    #[test]
    fn neck_reach_is_jkr_snap_off_and_bounds_every_let_go() {
        let glass = Material::new(63e9, 0.22, 2500.0).unwrap();
        let pair = ContactPair::sphere_on_sphere(5e-6, &glass, 5e-6, &glass).unwrap();
        let w = 0.2;
        let jkr = 0.75
            * (PI * PI * w * w * pair.effective_radius()
                / (pair.effective_modulus() * pair.effective_modulus()))
            .cbrt();
        for params in [
            MdrElastoPlastic::elastic(),
            MdrElastoPlastic::new(20.0, 0.05).unwrap(),
            MdrElastoPlastic::new(20.0, 0.5).unwrap(),
        ] {
            let law = AdhesiveMdr::new(params, w).unwrap().bind(&pair).unwrap();
            let reach = neck_reach(law.pull_off_force(), &pair);
            assert!((reach - jkr).abs() < 1e-12 * jkr, "{reach} vs {jkr}");
            let mut deepest: f64 = 0.0;
            for depth in [1e-9, 1e-8, 5e-8, 2e-7, 1e-6] {
                let mut state = Default::default();
                law.update(&mut state, depth);
                for back in [0.5, 0.0, -0.5 * jkr] {
                    law.update(&mut state, depth * back.max(0.0) + back.min(0.0));
                    if law.holds(&state) {
                        deepest = deepest.max(-law.detachment_overlap(&state));
                    }
                }
            }
            assert!(deepest > 0.5 * jkr, "some neck holds apart: {deepest}");
            assert!(deepest <= reach * (1.0 + 1e-9), "{deepest} > {reach}");
        }
        assert_eq!(neck_reach(0.0, &pair), 0.0);
    }
}
