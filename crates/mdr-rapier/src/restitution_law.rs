//! Restitution laws for hard-sphere (restitution-mode) collisions behind one trait: the
//! coefficient of restitution of a pair at its normal approach speed, with a per-contact history.
//! A hook generic over [`RestitutionLaw`] (e.g. the planetary-ring hook of `mdr-ring`) can then
//! switch laws per run; [`crate::RestitutionHooks`] is the MDR-only hook with its lock-free store.
//!
//! - [`MdrRestitution`]: the MDR elasto-plastic law of `mdr-contact` through its energy route
//!   ([`MdrLaw::impact`], docs/theory.md §4, eqs. 7–14); the history is the pair's largest indentation.
//!   With a work of adhesion ([`MdrRestitution::with_work_of_adhesion`]) the rebound also pays
//!   the adhesive hysteresis of the unloading ([`unloading_restitution`]); an impact whose
//!   rebound energy it takes whole sticks (`e = 0`).
//! - [`ConstantRestitution`]: one ε for every impact, not contact mechanics of the MDR model but
//!   the simplest law to compare it with.
//!
//! The empirical law of Bridges, Hatzes & Lin (1984) for ring particles is next to the ring, in
//! `mdr-ring` (`mdr_ring::law::BridgesLaw`).

use mdr_contact::normal::{
    AdhesiveMdr, AdhesiveMdrLaw, AdhesiveMdrState, EnergyRouteImpact, MdrElastoPlastic, MdrLaw,
    MdrState, NormalLaw, NormalModel,
};
use mdr_contact::{ContactPair, Material};

/// What a restitution law may need to know about the two spheres of an impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactPair {
    /// Radius of the first sphere (m).
    pub radius1: f64,
    /// Radius of the second sphere (m).
    pub radius2: f64,
    /// Mass of the first sphere (kg).
    pub mass1: f64,
    /// Mass of the second sphere (kg).
    pub mass2: f64,
}

impl ImpactPair {
    /// Effective radius `R₁R₂/(R₁ + R₂)` (m).
    pub fn effective_radius(&self) -> f64 {
        self.radius1 * self.radius2 / (self.radius1 + self.radius2)
    }

    /// Reduced mass `m₁m₂/(m₁ + m₂)` (kg).
    pub fn reduced_mass(&self) -> f64 {
        self.mass1 * self.mass2 / (self.mass1 + self.mass2)
    }
}

/// A coefficient-of-restitution law: the normal restitution of a pair at normal approach speed
/// `v > 0` (m/s), given and updating the pair's contact history.
///
/// Implementors must return a value in `[0, 1]`. The history lives as long as the contact
/// (created at first touch, dropped when the pair separates); a law without memory uses `()`.
pub trait RestitutionLaw: Send + Sync {
    /// Per-contact history.
    type History: Clone + Default + std::fmt::Debug + Send + Sync;

    /// The restitution of an impact at `approach_speed`; updates `history`.
    fn restitution(
        &self,
        pair: &ImpactPair,
        history: &mut Self::History,
        approach_speed: f64,
    ) -> f64;

    /// The restitution of a first impact (fresh history) without side effects, for plots.
    fn first_impact(&self, pair: &ImpactPair, approach_speed: f64) -> f64 {
        self.restitution(pair, &mut Self::History::default(), approach_speed)
    }

    /// A short name for reports (`mdr`, `bridges`, `constant`).
    fn name(&self) -> &'static str;
}

/// The restitution of an impact by the energy route through any normal law, given the history
/// `state` at the deepest point `overlap` of the impact and the kinetic energy `kinetic` (J) the
/// impact came in with: the contact returns the elastic energy stored there
/// ([`NormalLaw::elastic_energy`]) less what it dissipates on the way out, the work its let-go
/// springs held ([`NormalLaw::dissipated_work`] grows by it while unloading to the let-go
/// overlap [`NormalLaw::detachment_overlap`]; nothing without adhesion), so
/// `e² = (E_el(δ_max) − W_let-go) / W_in` (eq. 14; docs/theory.md §9). Zero when the let-go
/// work takes the whole rebound energy: the impact sticks. The unloading is one monotone path
/// from `δ_max` to the let-go, as in a head-on impact.
pub fn unloading_restitution<L: NormalLaw>(
    law: &L,
    state: &L::State,
    overlap: f64,
    kinetic: f64,
) -> f64 {
    if kinetic.is_nan() || kinetic <= 0.0 {
        return 0.0;
    }
    let stored = law.elastic_energy(state, overlap);
    let mut released = state.clone();
    let before = law.dissipated_work(&released);
    let mut below = law.detachment_overlap(&released);
    // Just past the let-go overlap (the law holds at it); a few tries cover a let-go overlap
    // that moves as springs let go.
    for _ in 0..8 {
        below -= below.abs().max(f64::MIN_POSITIVE) * 1e-9 + f64::MIN_POSITIVE;
        law.update(&mut released, below);
        if !law.holds(&released) {
            break;
        }
        below = law.detachment_overlap(&released);
    }
    let returned = stored - (law.dissipated_work(&released) - before);
    if returned > 0.0 {
        (returned / kinetic).sqrt().min(1.0)
    } else {
        0.0
    }
}

/// One impact of the adhesive MDR law by the energy route, on the history `state` of the MDR
/// law `law` with the work of adhesion `work_of_adhesion` (J/m²): the loading is the MDR law's
/// ([`MdrLaw::impact`]: Heß's rule attaches a spring with zero elongation, so the adhesion does
/// no work on the way in), the rebound [`unloading_restitution`] of the adhesive law at the
/// impact's deepest point. Without adhesion it is [`MdrLaw::impact`] exactly.
///
/// # Errors
/// [`MdrLaw::impact`]'s: a negative, NaN or infinite `speed`, or a `mass` that is not positive.
pub fn adhesive_impact(
    law: &MdrLaw,
    work_of_adhesion: f64,
    state: &MdrState,
    mass: f64,
    speed: f64,
) -> mdr_contact::Result<EnergyRouteImpact> {
    let impact = law.impact(state, mass, speed)?;
    if work_of_adhesion == 0.0 {
        return Ok(impact);
    }
    let adhesive = AdhesiveMdrLaw::new(*law, work_of_adhesion);
    let mut loaded = AdhesiveMdrState {
        max_overlap: impact.state.max_overlap,
        ..AdhesiveMdrState::default()
    };
    adhesive.update(&mut loaded, impact.max_overlap);
    Ok(EnergyRouteImpact {
        restitution: unloading_restitution(
            &adhesive,
            &loaded,
            impact.max_overlap,
            0.5 * mass * speed * speed,
        ),
        ..impact
    })
}

/// The MDR elasto-plastic law (Lyashenko & Popov 2018) for spheres of one material: each impact
/// binds the law to the pair (`E*` eq. 3, `R`, `m`) and evaluates the energy route
/// ([`MdrLaw::impact`]): `e² = W_returned / W_in` (eq. 14), with re-impacts of a contact that
/// already yielded seeing the flattened profile (eq. 13).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MdrRestitution {
    material: Material,
    model: MdrElastoPlastic,
    work_of_adhesion: f64,
    effective_modulus: f64,
    effective_shear_modulus: f64,
}

impl MdrRestitution {
    /// Spheres of `material` with the MDR parameters `model` (`q_c`, `Θ`).
    pub fn new(material: Material, model: MdrElastoPlastic) -> mdr_contact::Result<Self> {
        // Validate the hardening against E* now rather than at the first impact.
        let probe = ContactPair::sphere_on_sphere(1.0, &material, 1.0, &material)?;
        model.bind(&probe)?;
        Ok(Self {
            material,
            model,
            work_of_adhesion: 0.0,
            effective_modulus: probe.effective_modulus(),
            effective_shear_modulus: probe.effective_shear_modulus(),
        })
    }

    /// Ice ring particles (docs/rings.md §6): `E = 9 GPa`, `ν = 0.33` (solid ice, Petrenko &
    /// Whitworth 1999), `ρ = 400 kg/m³` (REBOUND's porous particles), `q_c = 8·10³ N/m` and
    /// `Θ = 0.2 E*`, fitted to the Bridges law over 0.05–5 mm/s for a pair of 1.6 m particles
    /// (the mean radius). The mean pressure at yield, `q_c / a_y ≈ 5.6 MPa`, is the compressive
    /// strength of cold ice.
    pub fn ice() -> Self {
        let ice = Material::new(9.0e9, 0.33, 400.0).expect("valid ice constants");
        let model = MdrElastoPlastic::new(8.0e3, 0.2).expect("valid MDR parameters");
        Self::new(ice, model).expect("valid ice law")
    }

    /// The same law with the work of adhesion `work_of_adhesion` (J/m², finite, ≥ 0): impacts
    /// pay the adhesive hysteresis ([`adhesive_impact`]) and slow ones stick.
    pub fn with_work_of_adhesion(mut self, work_of_adhesion: f64) -> mdr_contact::Result<Self> {
        AdhesiveMdr::new(self.model, work_of_adhesion)?;
        self.work_of_adhesion = work_of_adhesion;
        Ok(self)
    }

    /// The work of adhesion `Δγ` (J/m²).
    pub fn work_of_adhesion(&self) -> f64 {
        self.work_of_adhesion
    }

    /// The material.
    pub fn material(&self) -> Material {
        self.material
    }

    /// The MDR parameters.
    pub fn model(&self) -> MdrElastoPlastic {
        self.model
    }

    /// The law bound to `pair`: `E*`, `G*` of the material pair (eq. 3), `R = R₁R₂/(R₁+R₂)`,
    /// `m = m₁m₂/(m₁+m₂)`, bound by `mdr-contact` ([`MdrElastoPlastic::bind`]). Fails only for a
    /// non-positive radius or mass.
    pub fn bind(&self, pair: &ImpactPair) -> mdr_contact::Result<MdrLaw> {
        let contact = ContactPair::new(
            self.effective_modulus,
            self.effective_shear_modulus,
            pair.effective_radius(),
            pair.reduced_mass(),
        )?;
        self.model.bind(&contact)
    }

    /// Speed below which the first impact of `pair` is elastic (m/s).
    pub fn yield_speed(&self, pair: &ImpactPair) -> mdr_contact::Result<f64> {
        Ok(self.bind(pair)?.yield_speed(pair.reduced_mass()))
    }
}

impl RestitutionLaw for MdrRestitution {
    type History = MdrState;

    fn restitution(&self, pair: &ImpactPair, history: &mut MdrState, approach_speed: f64) -> f64 {
        // A pair that cannot be bound (non-positive radius or mass) or an approach speed that is
        // not finite and ≥ 0 (caller bugs, never user input, which is validated when the ring is
        // built) is treated as elastic.
        let Ok(law) = self.bind(pair) else {
            return 1.0;
        };
        let Ok(outcome) = adhesive_impact(
            &law,
            self.work_of_adhesion,
            history,
            pair.reduced_mass(),
            approach_speed,
        ) else {
            return 1.0;
        };
        *history = outcome.state;
        outcome.restitution.clamp(0.0, 1.0)
    }

    fn name(&self) -> &'static str {
        "mdr"
    }
}

/// A constant coefficient of restitution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstantRestitution {
    value: f64,
}

impl ConstantRestitution {
    /// `ε` in `[0, 1]`.
    pub fn new(value: f64) -> crate::Result<Self> {
        if !(value.is_finite() && (0.0..=1.0).contains(&value)) {
            return Err(crate::CouplingError::OutOfRange {
                name: "eps",
                value,
                range: "[0, 1]",
            });
        }
        Ok(Self { value })
    }

    /// The value.
    pub fn value(&self) -> f64 {
        self.value
    }
}

impl RestitutionLaw for ConstantRestitution {
    type History = ();

    fn restitution(&self, _: &ImpactPair, _: &mut (), _: f64) -> f64 {
        self.value
    }

    fn name(&self) -> &'static str {
        "constant"
    }
}
