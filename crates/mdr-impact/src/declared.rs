//! Any declared normal law in the validator ([`DeclaredLaw`]): the law's declaration
//! ([`mdr_contact::params::LawDeclaration`]) with the integrators compiled for it
//! ([`DeclaredLaw::of`]), and one instance with its parameter values ([`DeclaredNormal`],
//! [`crate::NormalSpec::Declared`]). A law a scene registry lists (`mdr_sim::laws::registry`)
//! carries its entry, so a law added as one file and one registry line runs in impacts too:
//! head-on (time integration), traced, and oblique with the Mindlin tangential law.

use crate::error::{ImpactError, Result};
use crate::impact::{Impact, ImpactOutcome, LawVisitor, NormalVisitor, ObliqueVisitor};
use crate::integrate::{NormalRun, TracePoint};
use mdr_contact::normal::{NormalLaw, NormalModel};
use mdr_contact::params::{Declared, LawDeclaration};
use mdr_contact::{ContactError, ContactPair};

/// The most parameters a declared law may have in the validator (values are held inline, so
/// that a [`DeclaredNormal`] is `Copy` like the other laws of [`crate::NormalSpec`]).
pub const MAX_DECLARED_PARAMS: usize = 8;

/// A declared normal law with the validator's integrators compiled for it: one function per
/// kind of run, each instantiated for the law, chosen once per impact.
#[derive(Clone, Copy)]
pub struct DeclaredLaw {
    /// Name, parameters, ranges, equations.
    pub declaration: LawDeclaration,
    check: fn(&[f64]) -> mdr_contact::Result<()>,
    head_on: HeadOnRun,
    oblique: fn(&Impact, &[f64]) -> Result<ImpactOutcome>,
    yield_speed: fn(&[f64], &ContactPair) -> mdr_contact::Result<f64>,
}

/// A head-on run of one law: the impact, the parameter values, and the trace to record.
type HeadOnRun = fn(&Impact, &[f64], Option<&mut Vec<TracePoint>>) -> Result<NormalRun>;

impl DeclaredLaw {
    /// The entry of law `L`.
    pub const fn of<L: NormalModel + Declared + 'static>() -> Self {
        Self {
            declaration: L::DECLARATION,
            check: check::<L>,
            head_on: head_on::<L>,
            oblique: oblique::<L>,
            yield_speed: yield_speed::<L>,
        }
    }

    /// The law with parameter `values` in declared order, checked against the declared ranges
    /// and the law's own constructor.
    pub fn with_values(&'static self, values: &[f64]) -> mdr_contact::Result<DeclaredNormal> {
        if values.len() > MAX_DECLARED_PARAMS {
            return Err(ContactError::InvalidTable {
                name: self.declaration.name,
                reason: format!(
                    "{} parameters; the validator holds at most {MAX_DECLARED_PARAMS}",
                    values.len()
                ),
            });
        }
        (self.check)(values)?;
        let mut held = [0.0; MAX_DECLARED_PARAMS];
        held[..values.len()].copy_from_slice(values);
        Ok(DeclaredNormal {
            law: self,
            values: held,
            len: values.len(),
        })
    }
}

impl std::fmt::Debug for DeclaredLaw {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DeclaredLaw")
            .field("declaration", &self.declaration)
            .finish_non_exhaustive()
    }
}

/// One declared law with its parameter values, as an impact runs it.
#[derive(Debug, Clone, Copy)]
pub struct DeclaredNormal {
    law: &'static DeclaredLaw,
    values: [f64; MAX_DECLARED_PARAMS],
    len: usize,
}

impl PartialEq for DeclaredNormal {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name() && self.values() == other.values()
    }
}

impl DeclaredNormal {
    /// The law's declared name.
    pub fn name(&self) -> &'static str {
        self.law.declaration.name
    }

    /// The law's declaration.
    pub fn declaration(&self) -> &'static LawDeclaration {
        &self.law.declaration
    }

    /// The parameter values, in declared order.
    pub fn values(&self) -> &[f64] {
        &self.values[..self.len]
    }

    pub(crate) fn head_on(
        &self,
        impact: &Impact,
        trace: Option<&mut Vec<TracePoint>>,
    ) -> Result<NormalRun> {
        (self.law.head_on)(impact, self.values(), trace)
    }

    pub(crate) fn oblique(&self, impact: &Impact) -> Result<ImpactOutcome> {
        (self.law.oblique)(impact, self.values())
    }

    /// Speed (m/s) below which an impact of `pair` stays on the law's elastic branch; `inf` if
    /// the law never yields.
    pub fn yield_speed(&self, pair: &ContactPair) -> Result<f64> {
        (self.law.yield_speed)(self.values(), pair).map_err(ImpactError::parameter("law"))
    }
}

fn check<L: Declared>(values: &[f64]) -> mdr_contact::Result<()> {
    L::from_values(values).map(|_| ())
}

fn bind<L: NormalModel + Declared>(values: &[f64], pair: &ContactPair) -> Result<L::Law> {
    L::from_values(values)
        .and_then(|model| model.bind(pair))
        .map_err(ImpactError::parameter("law"))
}

fn head_on<L: NormalModel + Declared>(
    impact: &Impact,
    values: &[f64],
    trace: Option<&mut Vec<TracePoint>>,
) -> Result<NormalRun> {
    NormalVisitor { impact, trace }.visit(&bind::<L>(values, impact.pair())?)
}

fn oblique<L: NormalModel + Declared>(impact: &Impact, values: &[f64]) -> Result<ImpactOutcome> {
    ObliqueVisitor { impact }.visit(&bind::<L>(values, impact.pair())?)
}

/// The speed whose kinetic energy `m* v² / 2` is the elastic energy stored at the yield
/// overlap `δ_y` (the work of loading up to it, all of it returned below yield).
fn yield_speed<L: NormalModel + Declared>(
    values: &[f64],
    pair: &ContactPair,
) -> mdr_contact::Result<f64> {
    let law = L::from_values(values)?.bind(pair)?;
    let yield_overlap = law.yield_overlap();
    if !yield_overlap.is_finite() {
        return Ok(f64::INFINITY);
    }
    let mut state = Default::default();
    law.update(&mut state, yield_overlap);
    let energy = law.elastic_energy(&state, yield_overlap);
    Ok((2.0 * energy / pair.reduced_mass()).sqrt())
}
