//! Any declared normal law in the impact scene: its entry ([`SceneLawEntry::of`], the scene's
//! force-mode run compiled for the law) and one instance with its parameter values
//! ([`DeclaredSceneLaw`], [`super::SceneLaw::Declared`]). A scene registry (`mdr_sim`'s
//! `NORMAL_LAWS`) holds each registered law's entry, so a law added as one file and one registry
//! line runs in `mdr-dem sim drop|pair` too. The run is chosen once per scene through the entry's
//! function pointer; inside it the stepper is monomorphised for the law, so nothing is looked up
//! per contact.

use super::{Flight, ImpactScene, SceneOutcome};
use crate::error::Result;
use mdr_contact::normal::{NormalLaw, NormalModel};
use mdr_contact::params::{Declared, LawDeclaration};
use mdr_contact::{ContactError, ContactPair};

/// The most parameters a declared law may have in the impact scene (values are held inline, so
/// that a [`DeclaredSceneLaw`] is `Copy` like the other laws of [`super::SceneLaw`]).
pub const MAX_SCENE_LAW_PARAMS: usize = 8;

/// A declared normal law with the impact scene's force-mode run compiled for it.
#[derive(Clone, Copy)]
pub struct SceneLawEntry {
    /// Name, parameters, ranges, equations.
    pub declaration: LawDeclaration,
    check: fn(&[f64]) -> mdr_contact::Result<()>,
    contact_time: fn(&[f64], &ContactPair, f64) -> mdr_contact::Result<f64>,
    run_force: fn(&ImpactScene, &[f64], Flight) -> Result<SceneOutcome>,
}

impl SceneLawEntry {
    /// The entry of law `L`.
    pub const fn of<L: NormalModel + Declared + 'static>() -> Self {
        Self {
            declaration: L::DECLARATION,
            check: check::<L>,
            contact_time: contact_time::<L>,
            run_force: run_force::<L>,
        }
    }

    /// The law with parameter `values` in declared order, checked against the declared ranges
    /// and the law's own constructor.
    pub fn with_values(&'static self, values: &[f64]) -> mdr_contact::Result<DeclaredSceneLaw> {
        if values.len() > MAX_SCENE_LAW_PARAMS {
            return Err(ContactError::InvalidTable {
                name: self.declaration.name,
                reason: format!(
                    "{} parameters; the impact scene holds at most {MAX_SCENE_LAW_PARAMS}",
                    values.len()
                ),
            });
        }
        (self.check)(values)?;
        let mut held = [0.0; MAX_SCENE_LAW_PARAMS];
        held[..values.len()].copy_from_slice(values);
        Ok(DeclaredSceneLaw {
            entry: self,
            values: held,
            len: values.len(),
        })
    }
}

impl std::fmt::Debug for SceneLawEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneLawEntry")
            .field("declaration", &self.declaration)
            .finish_non_exhaustive()
    }
}

/// One declared law with its parameter values, as the impact scene runs it.
#[derive(Debug, Clone, Copy)]
pub struct DeclaredSceneLaw {
    entry: &'static SceneLawEntry,
    values: [f64; MAX_SCENE_LAW_PARAMS],
    len: usize,
}

impl PartialEq for DeclaredSceneLaw {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name() && self.values() == other.values()
    }
}

impl DeclaredSceneLaw {
    /// The law's declared name.
    pub fn name(&self) -> &'static str {
        self.entry.declaration.name
    }

    /// The law's declaration.
    pub fn declaration(&self) -> &'static LawDeclaration {
        &self.entry.declaration
    }

    /// The parameter values, in declared order.
    pub fn values(&self) -> &[f64] {
        &self.values[..self.len]
    }

    /// The contact time (s) the scene's time step resolves for an impact of `pair` at normal
    /// speed `speed`: half a period of the law's stiffness at Hertz's largest overlap,
    /// `π √(m*/k)` (the exact contact time of a linear spring; 0.78 of Hertz's own for Hertz,
    /// docs/coupling.md), Hertz's contact time where the law has no finite positive stiffness
    /// there.
    pub fn contact_time(&self, pair: &ContactPair, speed: f64) -> Result<f64> {
        Ok((self.entry.contact_time)(self.values(), pair, speed)?)
    }

    pub(super) fn run_force(&self, scene: &ImpactScene, flight: Flight) -> Result<SceneOutcome> {
        (self.entry.run_force)(scene, self.values(), flight)
    }
}

fn check<L: Declared>(values: &[f64]) -> mdr_contact::Result<()> {
    L::from_values(values).map(|_| ())
}

fn contact_time<L: NormalModel + Declared>(
    values: &[f64],
    pair: &ContactPair,
    speed: f64,
) -> mdr_contact::Result<f64> {
    let law = L::from_values(values)?.bind(pair)?;
    let overlap = pair.hertz_max_overlap(speed);
    let stiffness = law.update(&mut Default::default(), overlap).stiffness;
    Ok(if stiffness.is_finite() && stiffness > 0.0 {
        std::f64::consts::PI * (pair.reduced_mass() / stiffness).sqrt()
    } else {
        pair.hertz_contact_time(speed)
    })
}

fn run_force<L: NormalModel + Declared>(
    scene: &ImpactScene,
    values: &[f64],
    flight: Flight,
) -> Result<SceneOutcome> {
    scene.run_force(L::from_values(values)?, flight)
}
