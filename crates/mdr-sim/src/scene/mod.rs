//! Scenes: the TOML file ([`schema`]), its validation with file/line/key of every problem
//! ([`validate`], [`problems`]) and the checked, ready-to-build [`Scene`].

pub mod problems;
pub mod schema;
pub mod validate;

use crate::placement::ParticleInit;
use crate::walls::Wall;
use mdr_contact::params::LawDeclaration;
use mdr_contact::Material;
use nalgebra::Vector3;
use std::path::PathBuf;

pub use problems::{Problem, Problems, Severity};
pub use schema::{CouplingMode, ForcePath, Headline, SceneFile};
pub use validate::load_scene;

/// The normal law of a scene: a registered law's name ([`crate::laws::registry`]) and the
/// values of its declared parameters, in declared order (checked by the law crate).
#[derive(Debug, Clone, PartialEq)]
pub struct NormalSpec {
    /// The law's name (`normal = "…"`).
    pub law: &'static str,
    /// Its parameters' values, in the order of its declaration.
    pub values: Vec<f64>,
}

impl NormalSpec {
    /// The value of the parameter with scene key `key`, if the law declares it.
    pub fn value(&self, key: &str) -> Option<f64> {
        let entry = crate::laws::registry::normal_law(self.law)?;
        let k = entry.declaration.params.iter().position(|p| p.key == key)?;
        self.values.get(k).copied()
    }
}

/// A tangential, damping or rolling law of a scene: a registered law's declaration
/// ([`crate::laws::registry::SUB_MODEL_KINDS`]) and the values of its parameters, in declared
/// order (checked against the declaration and by the law's constructor).
#[derive(Debug, Clone, PartialEq)]
pub struct SubModelSpec {
    /// The law's declaration.
    pub declaration: LawDeclaration,
    /// Its parameters' values, in the order of its declaration.
    pub values: Vec<f64>,
}

impl SubModelSpec {
    /// The value of the parameter with scene key `key`, if the law declares it.
    pub fn value(&self, key: &str) -> Option<f64> {
        let k = self.declaration.params.iter().position(|p| p.key == key)?;
        self.values.get(k).copied()
    }
}

/// The damping law of a scene as the built-in laws' coefficients ([`ContactSpec::damping`]), a
/// view of [`SubModelSpecs::damping`], which the scenes' steppers take by name.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DampingSpec {
    /// None.
    None,
    /// `hertzian_viscous` with `γ_n` (1/(m·s)).
    HertzianViscous(f64),
    /// `stiffness_viscous` with `η`.
    StiffnessViscous(f64),
    /// Another registered damping law, by name (its values in [`SubModelSpecs::damping`]).
    Other(&'static str),
}

impl DampingSpec {
    /// The view of a validated damping law: each built-in law's coefficient read by its
    /// declared key.
    pub fn of(law: &SubModelSpec) -> Self {
        use mdr_contact::damping::{HertzianViscous, NoDamping, StiffnessViscous};
        use mdr_contact::params::Declared;
        let value = |key| law.value(key).unwrap_or(0.0);
        match law.declaration.name {
            n if n == NoDamping::DECLARATION.name => DampingSpec::None,
            n if n == HertzianViscous::DECLARATION.name => {
                DampingSpec::HertzianViscous(value(HERTZIAN_GAMMA_KEY))
            }
            n if n == StiffnessViscous::DECLARATION.name => {
                DampingSpec::StiffnessViscous(value(STIFFNESS_ETA_KEY))
            }
            n => DampingSpec::Other(n),
        }
    }
}

/// A scene's tangential, damping and rolling laws, each its registered name and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct SubModelSpecs {
    /// The tangential law (`[contact] tangential`).
    pub tangential: SubModelSpec,
    /// The damping law (`[contact] damping`).
    pub damping: SubModelSpec,
    /// The rolling-resistance law (`[contact] rolling`).
    pub rolling: SubModelSpec,
}

/// The contact model of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSpec {
    /// Normal law.
    pub normal: NormalSpec,
    /// The tangential, damping and rolling laws by name with their values: the one place a
    /// scene's sub-models are held. The steppers build from them
    /// ([`crate::laws::registry::SceneParts::of`]); [`ContactSpec::friction`],
    /// [`ContactSpec::damping`], [`ContactSpec::tangential_damping_ratio`] and
    /// [`ContactSpec::rolling_friction`] read them by their declared keys.
    pub sub_models: SubModelSpecs,
    /// Each material's work of adhesion `Δγ_i` (J/m², in [`Scene::materials`] order) when the
    /// scene gives adhesion per material: the contacts of materials `i` and `j` then run
    /// [`ContactSpec::normal`]'s law with the pair's mixed `Δγ_ij = √(Δγ_i Δγ_j)`
    /// ([`ContactSpec::pair_normal_values`]). Empty when every pair runs `normal` as it is.
    pub works_of_adhesion: Vec<f64>,
}

impl ContactSpec {
    /// The tangential law's Coulomb coefficient `μ` ([`FRICTION_KEY`]), where it declares one;
    /// 0 for a law without (the frictionless law).
    pub fn friction(&self) -> f64 {
        self.sub_models
            .tangential
            .value(FRICTION_KEY)
            .unwrap_or(0.0)
    }

    /// The damping law as the built-in laws' coefficients ([`DampingSpec::of`]).
    pub fn damping(&self) -> DampingSpec {
        DampingSpec::of(&self.sub_models.damping)
    }

    /// The tangential dashpot over the normal one ([`DAMPING_TANGENTIAL_RATIO_KEY`]), where the
    /// damping law declares it; 0 for a law without.
    pub fn tangential_damping_ratio(&self) -> f64 {
        self.sub_models
            .damping
            .value(DAMPING_TANGENTIAL_RATIO_KEY)
            .unwrap_or(0.0)
    }

    /// The rolling-resistance coefficient `μ_r` ([`ROLLING_FRICTION_KEY`]), where the rolling
    /// law declares it; 0 (off) for a law without.
    pub fn rolling_friction(&self) -> f64 {
        self.sub_models
            .rolling
            .value(ROLLING_FRICTION_KEY)
            .unwrap_or(0.0)
    }

    /// The work of adhesion (J/m²) of the contacts between materials `a` and `b`: their mixed
    /// `Δγ_ij` where the scene gives adhesion per material, else the normal law's
    /// `work_of_adhesion_j_per_m2` (0 for a law without adhesion).
    pub fn pair_work_of_adhesion(&self, a: usize, b: usize) -> f64 {
        match (self.works_of_adhesion.get(a), self.works_of_adhesion.get(b)) {
            (Some(&wa), Some(&wb)) => validate::mixed_work_of_adhesion(wa, wb),
            _ => self.normal.value(WORK_OF_ADHESION_KEY).unwrap_or(0.0),
        }
    }

    /// The normal law's parameter values for the contacts between materials `a` and `b`:
    /// [`ContactSpec::normal`]'s with the pair's mixed work of adhesion, where the scene gives
    /// adhesion per material; `None` where the pair runs `normal`'s values as they are.
    pub fn pair_normal_values(&self, a: usize, b: usize) -> Option<Vec<f64>> {
        if self.works_of_adhesion.is_empty() {
            return None;
        }
        let entry = crate::laws::registry::normal_law(self.normal.law)?;
        let k = entry
            .declaration
            .params
            .iter()
            .position(|p| p.key == WORK_OF_ADHESION_KEY)?;
        let mut values = self.normal.values.clone();
        values[k] = self.pair_work_of_adhesion(a, b);
        Some(values)
    }
}

/// The scene key of the adhesive law's work of adhesion (`[contact]` and `[[material]]`).
pub const WORK_OF_ADHESION_KEY: &str = "work_of_adhesion_j_per_m2";

/// The scene key of a tangential law's Coulomb coefficient `μ` (Mindlin's).
pub const FRICTION_KEY: &str = "friction";

/// The scene key of the tangential dashpot's ratio both viscous damping laws declare.
pub const DAMPING_TANGENTIAL_RATIO_KEY: &str = "damping_tangential_ratio";

/// The scene key of the Hertzian viscous damping law's `γ_n`.
pub const HERTZIAN_GAMMA_KEY: &str = "damping_gamma_n_per_m_s";

/// The scene key of the stiffness-viscous damping law's `η`.
pub const STIFFNESS_ETA_KEY: &str = "damping_eta";

/// The scene key of a rolling law's coefficient `μ_r` (the elastic–plastic spring's).
pub const ROLLING_FRICTION_KEY: &str = "rolling_friction";

/// A checked scene: every value within its range, particles placed without overlap.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The scene file (outputs and relative paths refer to it).
    pub file: PathBuf,
    /// The file as parsed (kept for the checkpoint's compatibility check).
    pub source: SceneFile,
    /// Run name.
    pub name: String,
    /// Seed.
    pub seed: u64,
    /// Simulated time (s).
    pub duration: f64,
    /// Time step (s), resolved if `"auto"`.
    pub dt: f64,
    /// Whether the step was chosen automatically.
    pub dt_auto: bool,
    /// Largest expected relative speed (m/s).
    pub max_speed: f64,
    /// Shortest Hertz contact time among the scene's pairs at `max_speed` (s).
    pub contact_time: f64,
    /// Output frame interval (s).
    pub output_interval: f64,
    /// Checkpoint interval (s).
    pub checkpoint_interval: Option<f64>,
    /// Energy-book interval (s).
    pub energy_interval: f64,
    /// Energy guard: the run stops once the balance drifts by more than this fraction of its
    /// energy scale; `None` in restitution mode, whose books do not itemise the impulses' losses.
    pub max_energy_drift: Option<f64>,
    /// Coupling mode.
    pub coupling: CouplingMode,
    /// Force mode's implementation (ignored in restitution mode, which the validation refuses
    /// together with an explicit `force_path`).
    pub force_path: ForcePath,
    /// Headline quantity.
    pub headline: Headline,
    /// Write the contact network.
    pub contact_network: bool,
    /// Hopper: discharge height (m).
    pub discharge_height: Option<f64>,
    /// The x and y ranges (m) of a box periodic in x and y (neighbour-list path); open space
    /// when `None`.
    pub periodic: Option<[(f64, f64); 2]>,
    /// Gravity (m/s²).
    pub gravity: Vector3<f64>,
    /// Materials, by name.
    pub materials: Vec<(String, Material)>,
    /// Contact model.
    pub contact: ContactSpec,
    /// Particles to create, in creation order.
    pub particles: Vec<ParticleInit>,
    /// Walls.
    pub walls: Vec<Wall>,
    /// Warnings found while checking (the run goes on).
    pub warnings: Vec<Problem>,
}

impl Scene {
    /// Number of steps of the whole run.
    pub fn total_steps(&self) -> u64 {
        (self.duration / self.dt).ceil() as u64
    }
}
