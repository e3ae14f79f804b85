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
//! registered law by name too, and its impact-scene entry ([`SceneLawEntry`]), so rapier's
//! single-impact scene (`mdr-dem sim drop|pair`) does.
//!
//! Adding a normal law: write its file in `mdr-contact` (a [`NormalModel`] with a
//! [`Declared`] declaration and a state with a checkpoint record,
//! [`super::NormalHistoryRecord`]) and add `NormalEntry::of::<TheLaw>()` below
//! (docs/architecture.md, "Adding a law").
//!
//! The tangential, damping and rolling laws are registered alike, one line each, in the
//! invocations of `tangential_laws!`, `damping_laws!` and `rolling_laws!` below: each
//! line (`Variant: TheModel,`) adds the law's entry to [`TANGENTIAL_LAWS`], [`DAMPING_LAWS`] or
//! [`ROLLING_LAWS`] and its variant to the enums the steppers run ([`AnyTangential`],
//! [`AnyDamping`], [`AnyRolling`] and their laws bound to a pair), which dispatch per contact by
//! a `match` and build the model from the scene's validated values with the law's
//! [`Declared::from_values`]. [`SUB_MODEL_KINDS`] says which `[contact]` key names each kind's
//! law. Adding one: its file in `mdr-contact` (a model of its kind, Copy and PartialEq, with
//! a [`Declared`] declaration, and a per-contact history of its kind's history type or none)
//! and its line here (docs/architecture.md, "Tangential, damping and rolling laws").

use super::sub_models::{damping_laws, rolling_laws, sub_model_enums, tangential_laws};
use super::{HistoryIn, SceneNormal};
use crate::error::SimError;
use crate::run::coupling::{
    neighbour_list_stepper, rapier_pipeline_stepper, NeighbourListScene, RapierPipelineScene,
};
use crate::scene::{ContactSpec, NormalSpec, SubModelSpec, SubModelSpecs};
use mdr_contact::damping::{
    DampingLaw, DampingModel, HertzianViscous, NoDamping, StiffnessViscous,
};
use mdr_contact::model::ContactModel;
use mdr_contact::normal::{
    AdhesiveMdr, Hertz, MdrElastoPlastic, NormalModel, NormalResponse, Thornton,
};
use mdr_contact::params::{Declared, LawDeclaration, LawKind};
use mdr_contact::rolling::{
    EpsdRolling, EpsdRollingState, NoRolling, RollingInput, RollingLaw, RollingModel,
    RollingResponse,
};
use mdr_contact::tangential::{
    Frictionless, Mindlin, MindlinState, TangentialInput, TangentialLaw, TangentialModel,
    TangentialResponse,
};
use mdr_contact::{ContactError, ContactPair, Result};
use mdr_impact::DeclaredLaw;
use mdr_rapier::neighbour_list::Boundary;
use mdr_rapier::scenario::SceneLawEntry;

/// The normal laws of scenes, by name.
pub static NORMAL_LAWS: &[NormalEntry] = &[
    NormalEntry::of::<MdrElastoPlastic>(),
    NormalEntry::of::<Hertz>(),
    NormalEntry::of::<Thornton>(),
    NormalEntry::of::<AdhesiveMdr>(),
    #[cfg(feature = "demo-laws")]
    NormalEntry::of::<mdr_contact::normal::LinearSpring>(),
];

tangential_laws! {
    list: TANGENTIAL_LAWS, model: AnyTangential, law: AnyTangentialLaw, history: MindlinState,
    laws: [
        Frictionless: Frictionless,
        Mindlin: Mindlin,
    ]
}

damping_laws! {
    list: DAMPING_LAWS, model: AnyDamping, law: AnyDampingLaw,
    laws: [
        None: NoDamping,
        HertzianViscous: HertzianViscous,
        StiffnessViscous: StiffnessViscous,
        #[cfg(feature = "demo-laws")]
        LinearDashpot: mdr_contact::damping::LinearDashpot,
    ]
}

// The elastic–plastic spring is the default rolling law, off while its `rolling_friction` is 0.
rolling_laws! {
    list: ROLLING_LAWS, model: AnyRolling, law: AnyRollingLaw, history: EpsdRollingState,
    laws: [
        NoRolling: NoRolling,
        EpsdRolling: EpsdRolling,
    ]
}

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
/// units, ranges, defaults and equations) and its check. Each is a variant of its kind's enum
/// ([`AnyTangential`], [`AnyDamping`], [`AnyRolling`]), which the scenes' steppers run.
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
/// laws as the validation read them from their declarations. The steppers take the sub-models
/// by name ([`SceneParts::of`]); [`ContactSpec`]'s coefficients ([`ContactSpec::friction`] and
/// the others) are read from them by their declared keys.
pub fn contact_spec(
    normal: NormalSpec,
    tangential: SubModelSpec,
    damping: SubModelSpec,
    rolling: SubModelSpec,
) -> ContactSpec {
    ContactSpec {
        normal,
        works_of_adhesion: Vec::new(),
        sub_models: SubModelSpecs {
            tangential,
            damping,
            rolling,
        },
    }
}

/// The sub-models of a scene other than the normal law, as its steppers take them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneParts {
    /// The tangential law.
    pub tangential: AnyTangential,
    /// The damping law.
    pub damping: AnyDamping,
    /// The rolling-resistance law; `None` when the scene's cannot give a torque
    /// ([`AnyRolling::resists`]): the steppers then run without rolling history.
    pub rolling: Option<AnyRolling>,
}

impl SceneParts {
    /// The parts of `spec`: each registered law by its name, from its validated values.
    pub fn of(spec: &ContactSpec) -> Result<Self> {
        let laws = &spec.sub_models;
        let rolling = AnyRolling::of(&laws.rolling)?;
        Ok(Self {
            tangential: AnyTangential::of(&laws.tangential)?,
            damping: AnyDamping::of(&laws.damping)?,
            rolling: rolling.resists().then_some(rolling),
        })
    }

    /// The composed model with normal model `normal`.
    fn model<N: NormalModel>(&self, normal: N) -> ContactModel<N, AnyTangential, AnyDamping> {
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
    /// Rapier's single-impact scene (force mode) compiled for the law.
    pub impact_scene: SceneLawEntry,
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
            impact_scene: SceneLawEntry::of::<L>(),
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
