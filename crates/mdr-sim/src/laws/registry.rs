//! The normal laws a scene can name, one line each ([`NORMAL_LAWS`]). An entry holds the law's
//! declaration ([`mdr_contact::params::LawDeclaration`]: name, parameters with units, ranges and
//! equations) and the steppers of both force paths compiled for it: a scene names the law
//! (`normal = "…"`), its `[contact]` keys are the declared parameters' keys, their range
//! errors come from the declaration, and the run is dispatched once, when it is built, to the
//! stepper compiled for that law. The pair loop is monomorphised per law; nothing is looked up
//! per contact.
//!
//! Each entry also carries the law's validator entry ([`mdr_impact::DeclaredLaw`]), so the
//! single-impact validator (`mdr-dem impact …`, Python's `curve`/`oblique`) runs every
//! registered law by name too.
//!
//! Adding a normal law: write its file in `mdr-contact` (a [`NormalModel`] with a
//! [`Declared`] declaration and a state with a checkpoint record,
//! [`super::NormalHistoryRecord`]) and add `NormalEntry::of::<TheLaw>()` below
//! (docs/architecture.md, "Adding a law").
//!
//! The tangential, damping and rolling laws are registered alike, one line each
//! ([`TANGENTIAL_LAWS`], [`DAMPING_LAWS`], [`ROLLING_LAWS`]); [`SUB_MODEL_KINDS`] says which
//! `[contact]` key names each kind's law. The scenes' steppers take them in fixed concrete
//! types ([`SceneParts`], [`contact_spec`]), so a new one also needs its place there
//! (docs/architecture.md, "Tangential, damping and rolling laws").

use super::{AnyDamping, AnyRolling, SceneNormal};
use crate::error::SimError;
use crate::run::coupling::{
    neighbour_list_stepper, rapier_pipeline_stepper, NeighbourListScene, RapierPipelineScene,
};
use crate::scene::{ContactSpec, DampingSpec, NormalSpec, SubModelSpec};
use mdr_contact::damping::{HertzianViscous, NoDamping, StiffnessViscous};
use mdr_contact::model::ContactModel;
use mdr_contact::normal::{AdhesiveMdr, Hertz, MdrElastoPlastic, NormalModel, Thornton};
use mdr_contact::params::{Declared, LawDeclaration, LawKind};
use mdr_contact::rolling::{EpsdRolling, NoRolling};
use mdr_contact::tangential::{Frictionless, Mindlin};
use mdr_contact::Result;
use mdr_impact::DeclaredLaw;
use mdr_rapier::neighbour_list::Boundary;

/// The normal laws of scenes, by name.
pub static NORMAL_LAWS: &[NormalEntry] = &[
    NormalEntry::of::<MdrElastoPlastic>(),
    NormalEntry::of::<Hertz>(),
    NormalEntry::of::<Thornton>(),
    NormalEntry::of::<AdhesiveMdr>(),
    #[cfg(feature = "demo-laws")]
    NormalEntry::of::<mdr_contact::normal::LinearSpring>(),
];

/// The tangential laws of scenes (`[contact] tangential = "…"`), by name.
pub static TANGENTIAL_LAWS: &[SubModelEntry] = &[
    SubModelEntry::of::<Frictionless>(),
    SubModelEntry::of::<Mindlin>(),
];

/// The damping laws of scenes (`[contact] damping = "…"`), by name.
pub static DAMPING_LAWS: &[SubModelEntry] = &[
    SubModelEntry::of::<NoDamping>(),
    SubModelEntry::of::<HertzianViscous>(),
    SubModelEntry::of::<StiffnessViscous>(),
];

/// The rolling-resistance laws of scenes (`[contact] rolling = "…"`, default `epsd`): the
/// elastic–plastic spring, on when its `rolling_friction` is above 0.
pub static ROLLING_LAWS: &[SubModelEntry] = &[
    SubModelEntry::of::<NoRolling>(),
    SubModelEntry::of::<EpsdRolling>(),
];

/// The registered normal law named `name`.
pub fn normal_law(name: &str) -> Option<&'static NormalEntry> {
    NORMAL_LAWS.iter().find(|e| e.declaration.name == name)
}

/// The names of the registered normal laws, in registry order.
pub fn normal_law_names() -> Vec<&'static str> {
    NORMAL_LAWS.iter().map(|e| e.declaration.name).collect()
}

/// The registered sub-model of `kind` named `name` (tangential, damping or rolling).
pub fn sub_model(kind: LawKind, name: &str) -> Option<&'static SubModelEntry> {
    sub_model_kind(kind)?
        .laws
        .iter()
        .find(|e| e.declaration.name == name)
}

/// One kind of sub-model as a scene's `[contact]` table chooses it: the key naming the law
/// (`tangential = "mindlin"`), the law taken when the key is absent, and the registered laws.
#[derive(Debug, Clone, Copy)]
pub struct SubModelKind {
    /// Tangential, damping or rolling.
    pub kind: LawKind,
    /// The `[contact]` key naming the law.
    pub key: &'static str,
    /// The law of a scene that does not name one.
    pub default: &'static str,
    /// The registered laws of the kind.
    pub laws: &'static [SubModelEntry],
}

impl SubModelKind {
    /// The registered law named `name`.
    pub fn law(&self, name: &str) -> Option<&'static SubModelEntry> {
        self.laws.iter().find(|e| e.declaration.name == name)
    }

    /// The names of the registered laws, in registry order.
    pub fn names(&self) -> Vec<&'static str> {
        self.laws.iter().map(|e| e.declaration.name).collect()
    }

    /// The scene keys of the kind's parameters, each once: those one law declares in registry
    /// order, then those several laws share (the order a scene file is written in, which a
    /// checkpoint's fingerprint hashes).
    pub fn keys(&self) -> Vec<&'static str> {
        let params = || self.laws.iter().flat_map(|e| e.declaration.params);
        let shared = |key: &str| {
            self.laws
                .iter()
                .filter(|e| e.declaration.param(key).is_some())
                .count()
                > 1
        };
        let mut keys: Vec<&'static str> = Vec::new();
        for key in params()
            .map(|p| p.key)
            .filter(|k| !shared(k))
            .chain(params().map(|p| p.key).filter(|k| shared(k)))
        {
            if !keys.contains(&key) {
                keys.push(key);
            }
        }
        keys
    }

    /// The names of the registered laws declaring the parameter `key`.
    pub fn declaring(&self, key: &str) -> Vec<&'static str> {
        self.laws
            .iter()
            .filter(|e| e.declaration.param(key).is_some())
            .map(|e| e.declaration.name)
            .collect()
    }
}

/// The kinds of sub-model besides the normal law, in the order of a scene's `[contact]` table.
/// Rolling resistance defaults to the elastic–plastic spring, which is off at its default
/// `rolling_friction = 0`.
pub static SUB_MODEL_KINDS: [SubModelKind; 3] = [
    SubModelKind {
        kind: LawKind::Tangential,
        key: "tangential",
        default: Frictionless::DECLARATION.name,
        laws: TANGENTIAL_LAWS,
    },
    SubModelKind {
        kind: LawKind::Damping,
        key: "damping",
        default: NoDamping::DECLARATION.name,
        laws: DAMPING_LAWS,
    },
    SubModelKind {
        kind: LawKind::Rolling,
        key: "rolling",
        default: EpsdRolling::DECLARATION.name,
        laws: ROLLING_LAWS,
    },
];

/// The scene's choice of sub-model `kind`.
pub fn sub_model_kind(kind: LawKind) -> Option<&'static SubModelKind> {
    SUB_MODEL_KINDS.iter().find(|k| k.kind == kind)
}

/// Whether `key` is a parameter of a registered tangential, damping or rolling law.
pub fn is_sub_model_key(key: &str) -> bool {
    SUB_MODEL_KINDS
        .iter()
        .flat_map(|k| k.laws)
        .any(|e| e.declaration.param(key).is_some())
}

/// A registered tangential, damping or rolling law: its declaration (name, parameters with
/// units, ranges, defaults and equations) and its check. The scenes' steppers are compiled for
/// the concrete combinations of these laws ([`SceneParts`]: Mindlin, the damping enum, rolling
/// off or on), chosen once when a run is built (docs/architecture.md).
#[derive(Debug, Clone, Copy)]
pub struct SubModelEntry {
    /// Name, kind, parameters.
    pub declaration: LawDeclaration,
    check: fn(&[f64]) -> Result<()>,
}

impl SubModelEntry {
    /// The entry of sub-model `M`.
    pub const fn of<M: Declared>() -> Self {
        Self {
            declaration: M::DECLARATION,
            check: check::<M>,
        }
    }

    /// Check parameter values given in declared order: the declared ranges, then whatever the
    /// law's constructor checks beyond them.
    pub fn check(&self, values: &[f64]) -> Result<()> {
        (self.check)(values)
    }
}

/// The contact model of a scene from its normal law and its tangential, damping and rolling
/// laws as the validation read them from their declarations. The steppers take these laws in
/// fixed concrete types ([`SceneParts`]); a registered law of a kind they have no place for is
/// refused here, by name (docs/architecture.md, "Tangential, damping and rolling laws").
pub fn contact_spec(
    normal: NormalSpec,
    tangential: &SubModelSpec,
    damping: &SubModelSpec,
    rolling: &SubModelSpec,
) -> std::result::Result<ContactSpec, UnplacedSubModel> {
    let unsupported = |law: &SubModelSpec| UnplacedSubModel {
        kind: law.declaration.kind,
        law: law.declaration.name,
    };
    let friction = match tangential.declaration.name {
        n if n == Frictionless::DECLARATION.name => 0.0,
        n if n == Mindlin::DECLARATION.name => tangential.values[0],
        _ => return Err(unsupported(tangential)),
    };
    let damping_law = match damping.declaration.name {
        n if n == NoDamping::DECLARATION.name => DampingSpec::None,
        n if n == HertzianViscous::DECLARATION.name => {
            DampingSpec::HertzianViscous(damping.values[0])
        }
        n if n == StiffnessViscous::DECLARATION.name => {
            DampingSpec::StiffnessViscous(damping.values[0])
        }
        _ => return Err(unsupported(damping)),
    };
    let rolling_friction = match rolling.declaration.name {
        n if n == NoRolling::DECLARATION.name => 0.0,
        n if n == EpsdRolling::DECLARATION.name => rolling.values[0],
        _ => return Err(unsupported(rolling)),
    };
    Ok(ContactSpec {
        normal,
        friction,
        damping: damping_law,
        // The tangential ratio both viscous laws declare.
        tangential_damping_ratio: damping
            .value(HertzianViscous::DECLARATION.params[1].key)
            .unwrap_or(0.0),
        rolling_friction,
        works_of_adhesion: Vec::new(),
    })
}

/// A registered tangential, damping or rolling law that the scenes' steppers have no place for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error(
    "`{law}` is registered, but the scenes' steppers have no place for it \
     (docs/architecture.md, \"Tangential, damping and rolling laws\")"
)]
pub struct UnplacedSubModel {
    /// Its kind.
    pub kind: LawKind,
    /// Its name.
    pub law: &'static str,
}

/// The sub-models of a scene other than the normal law, as its steppers take them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneParts {
    /// Mindlin with the scene's `μ` (0: frictionless).
    pub tangential: Mindlin,
    /// Damping.
    pub damping: AnyDamping,
    /// Rolling resistance, off or on.
    pub rolling: AnyRolling,
}

impl SceneParts {
    /// The parts of `spec`.
    pub fn of(spec: &ContactSpec) -> Result<Self> {
        let damping = match spec.damping {
            DampingSpec::None => AnyDamping::None(NoDamping),
            DampingSpec::HertzianViscous(g) => AnyDamping::HertzianViscous(
                HertzianViscous::new(g)?.with_tangential_ratio(spec.tangential_damping_ratio)?,
            ),
            DampingSpec::StiffnessViscous(e) => AnyDamping::StiffnessViscous(
                StiffnessViscous::new(e)?.with_tangential_ratio(spec.tangential_damping_ratio)?,
            ),
        };
        let rolling = if spec.rolling_friction > 0.0 {
            AnyRolling(Some(EpsdRolling::new(spec.rolling_friction)?))
        } else {
            AnyRolling(None)
        };
        Ok(Self {
            tangential: Mindlin::new(spec.friction)?,
            damping,
            rolling,
        })
    }

    /// The composed model with normal model `normal`.
    fn model<N: NormalModel>(&self, normal: N) -> ContactModel<N, Mindlin, AnyDamping> {
        ContactModel::new(normal)
            .with_tangential(self.tangential)
            .with_damping(self.damping)
    }
}

/// The registered normal law of `spec` and the scene's other sub-models.
pub fn scene_law(spec: &ContactSpec) -> Result<(&'static NormalEntry, SceneParts), SimError> {
    let entry = normal_law(spec.normal.law).ok_or_else(|| {
        SimError::Build(format!(
            "no registered normal law is named `{}` (registered: {})",
            spec.normal.law,
            normal_law_names().join(", ")
        ))
    })?;
    Ok((entry, SceneParts::of(spec)?))
}

/// One registered normal law: its declaration and its steppers.
pub struct NormalEntry {
    /// Name, parameters, ranges, equations.
    pub declaration: LawDeclaration,
    /// Check the parameter values (declared ranges, then the law's own checks).
    check: fn(&[f64]) -> Result<()>,
    /// The neighbour-list stepper compiled for the law.
    neighbour_list: NeighbourListBuilder,
    /// The rapier pipeline stepper compiled for the law.
    rapier_pipeline: RapierPipelineBuilder,
    /// The single-impact validator's integrators compiled for the law.
    pub impact: DeclaredLaw,
}

/// Builds the neighbour-list stepper of one law from its parameter values.
type NeighbourListBuilder = fn(&[f64], SceneParts, Boundary) -> Result<Box<dyn NeighbourListScene>>;

/// Builds the rapier pipeline stepper of one law from its parameter values.
type RapierPipelineBuilder = fn(&[f64], SceneParts) -> Result<Box<dyn RapierPipelineScene>>;

impl NormalEntry {
    /// The entry of law `L`.
    pub const fn of<L: SceneNormal + Declared>() -> Self {
        Self {
            declaration: L::DECLARATION,
            check: check::<L>,
            neighbour_list: neighbour_list::<L>,
            rapier_pipeline: rapier_pipeline::<L>,
            impact: DeclaredLaw::of::<L>(),
        }
    }

    /// Check parameter values given in declared order: the declared ranges, then whatever the
    /// law's constructor checks beyond them.
    pub fn check(&self, values: &[f64]) -> Result<()> {
        (self.check)(values)
    }

    /// The neighbour-list stepper for the law with parameter `values`.
    pub fn neighbour_list(
        &self,
        values: &[f64],
        parts: SceneParts,
        boundary: Boundary,
    ) -> Result<Box<dyn NeighbourListScene>> {
        (self.neighbour_list)(values, parts, boundary)
    }

    /// The rapier pipeline stepper for the law with parameter `values`.
    pub fn rapier_pipeline(
        &self,
        values: &[f64],
        parts: SceneParts,
    ) -> Result<Box<dyn RapierPipelineScene>> {
        (self.rapier_pipeline)(values, parts)
    }
}

impl std::fmt::Debug for NormalEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NormalEntry")
            .field("declaration", &self.declaration)
            .finish_non_exhaustive()
    }
}

fn check<L: Declared>(values: &[f64]) -> Result<()> {
    L::from_values(values).map(|_| ())
}

fn neighbour_list<L: SceneNormal + Declared>(
    values: &[f64],
    parts: SceneParts,
    boundary: Boundary,
) -> Result<Box<dyn NeighbourListScene>> {
    let model = parts.model(L::from_values(values)?);
    Ok(neighbour_list_stepper(model, parts.rolling, boundary))
}

fn rapier_pipeline<L: SceneNormal + Declared>(
    values: &[f64],
    parts: SceneParts,
) -> Result<Box<dyn RapierPipelineScene>> {
    let model = parts.model(L::from_values(values)?);
    Ok(rapier_pipeline_stepper(model, parts.rolling))
}
