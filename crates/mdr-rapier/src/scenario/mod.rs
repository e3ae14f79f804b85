//! Single-impact scenes in rapier, in either coupling mode: a sphere launched without gravity at
//! a fixed half-space ("drop") or at a free sphere ("pair"), measuring the coefficients of
//! restitution as rapier integrates them. Used by `mdr-dem sim drop|pair`, the tests and the
//! docs; compare with the single-impact validator (`mdr-impact`). Besides the built-in laws, any
//! declared normal law runs in force mode through its entry ([`SceneLawEntry`]), which a scene
//! registry holds for every registered law.

mod declared;

pub use declared::{DeclaredSceneLaw, SceneLawEntry, MAX_SCENE_LAW_PARAMS};

use crate::error::{positive, CouplingError, Result};
use crate::force_mode::ForceModeStepper;
use crate::particles::{MaterialHandle, ParticleSet, SphereBuilder};
use crate::restitution::RestitutionHooks;
use crate::timestep::stable_time_step;
use mdr_contact::damping::DampingModel;
use mdr_contact::model::ContactModel;
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic, NormalModel, Thornton};
use mdr_contact::rolling::RollingModel;
use mdr_contact::tangential::Mindlin;
use mdr_contact::tangential::TangentialModel;
use mdr_contact::{ContactPair, Material};
use rapier3d_f64::prelude::*;

/// How the law enters rapier.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CouplingMode {
    /// Soft spheres: forces from the law, symplectic Euler ([`ForceModeStepper`]).
    Force,
    /// Hard spheres: impulses with the law's restitution ([`RestitutionHooks`]).
    Restitution,
}

/// The normal law of a scene. Hertz is [`MdrElastoPlastic::elastic`] (the MDR law without
/// plasticity is Hertz exactly, `docs/theory.md` §4); any other declared law is
/// [`SceneLaw::Declared`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SceneLaw {
    /// The MDR elasto-plastic law (or Hertz, when elastic): both coupling modes.
    Mdr(MdrElastoPlastic),
    /// Thornton's (1997) elastic–perfectly-plastic law: force mode only (the restitution hook
    /// keeps the MDR law's history).
    Thornton(Thornton),
    /// The adhesive MDR law (docs/theory.md §9): both coupling modes; an impact can stick.
    AdhesiveMdr(AdhesiveMdr),
    /// Any declared normal law with its parameter values, run by the force-mode stepper
    /// compiled for it ([`SceneLawEntry::of`]): force mode only.
    Declared(DeclaredSceneLaw),
}

impl From<DeclaredSceneLaw> for SceneLaw {
    fn from(law: DeclaredSceneLaw) -> Self {
        SceneLaw::Declared(law)
    }
}

impl From<AdhesiveMdr> for SceneLaw {
    fn from(model: AdhesiveMdr) -> Self {
        SceneLaw::AdhesiveMdr(model)
    }
}

impl From<MdrElastoPlastic> for SceneLaw {
    fn from(model: MdrElastoPlastic) -> Self {
        SceneLaw::Mdr(model)
    }
}

impl From<Thornton> for SceneLaw {
    fn from(model: Thornton) -> Self {
        SceneLaw::Thornton(model)
    }
}

/// What the sphere hits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// A fixed half-space.
    HalfSpace {
        /// Its material.
        material: Material,
    },
    /// A free sphere at rest.
    Sphere {
        /// Its radius (m).
        radius: f64,
        /// Its material.
        material: Material,
    },
}

/// One impact scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactScene {
    /// Radius of the launched sphere (m).
    pub radius: f64,
    /// Its material.
    pub material: Material,
    /// What it hits.
    pub target: Target,
    /// The normal law.
    pub model: SceneLaw,
    /// Friction coefficient `μ`.
    pub friction: f64,
    /// Approach speed (m/s): relative speed of the two bodies.
    pub speed: f64,
    /// Angle of the approach velocity from the normal (degrees, half-space only).
    pub angle_degrees: f64,
    /// Force mode: time steps per contact time (Hertz's; for a declared law the shorter of
    /// Hertz's and the law's, [`DeclaredSceneLaw::contact_time`]).
    pub steps_per_contact: f64,
}

/// What one scene produced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneOutcome {
    /// Approach speed (m/s).
    pub speed: f64,
    /// `e_n = −v_n,out / v_n,in` of the relative velocity (eq. 14).
    pub normal_restitution: f64,
    /// Tangential velocity of the launched sphere's centre after the impact (m/s), along the
    /// incoming tangential direction.
    pub tangential_velocity: f64,
    /// Its spin after the impact (rad/s), positive in the sense of rolling forward.
    pub spin: f64,
    /// Steps during which the bodies were in contact (restitution mode: the step the impulse
    /// was applied in, so 1).
    pub steps: u64,
    /// Time step used (s).
    pub time_step: f64,
    /// Whether the sphere stuck (adhesion): it turned back towards the target while the
    /// contact held, as the single-impact validator decides; `normal_restitution` is then 0.
    pub stuck: bool,
}

impl ImpactScene {
    /// The paper's steel ball (R = 0.635 cm, docs/theory.md §7) on a steel half-space at `speed`.
    pub fn paper_drop(speed: f64) -> Self {
        Self {
            radius: 0.635e-2,
            material: Material::paper_steel(),
            target: Target::HalfSpace {
                material: Material::paper_steel(),
            },
            model: SceneLaw::Mdr(MdrElastoPlastic::paper()),
            friction: 0.0,
            speed,
            angle_degrees: 0.0,
            steps_per_contact: 1000.0,
        }
    }

    /// The pair quantities of the scene.
    pub fn pair(&self) -> Result<ContactPair> {
        Ok(match self.target {
            Target::HalfSpace { material } => {
                ContactPair::sphere_on_half_space(self.radius, &self.material, &material)?
            }
            Target::Sphere { radius, material } => {
                ContactPair::sphere_on_sphere(self.radius, &self.material, radius, &material)?
            }
        })
    }

    fn validate(&self) -> Result<()> {
        positive("radius", self.radius)?;
        positive("v0", self.speed)?;
        positive("steps_per_contact", self.steps_per_contact)?;
        if !(self.angle_degrees.is_finite() && (0.0..90.0).contains(&self.angle_degrees)) {
            return Err(CouplingError::OutOfRange {
                name: "angle",
                value: self.angle_degrees,
                range: "[0, 90) degrees",
            });
        }
        if self.angle_degrees != 0.0 && matches!(self.target, Target::Sphere { .. }) {
            return Err(CouplingError::OutOfRange {
                name: "angle",
                value: self.angle_degrees,
                range: "0 for a sphere pair (oblique impacts are on the half-space)",
            });
        }
        Ok(())
    }

    /// Run the scene in `mode`.
    pub fn run(&self, mode: CouplingMode) -> Result<SceneOutcome> {
        self.validate()?;
        let pair = self.pair()?;
        let (vn, vt) = {
            let a = self.angle_degrees.to_radians();
            (self.speed * a.cos(), self.speed * a.sin())
        };
        let hertz_time = pair.hertz_contact_time(vn);
        // Force mode stops after 200 contact times without a separation.
        let (dt, max_steps) = match (mode, self.model) {
            // Hard spheres: any step; take the contact time so the flight is a few steps.
            (CouplingMode::Restitution, _) => (hertz_time, 0),
            // A law's own contact time may be shorter (stiffer) or longer (softer) than
            // Hertz's: the step resolves the shorter one, the run lasts for the longer one.
            (CouplingMode::Force, SceneLaw::Declared(law)) => {
                let law_time = law.contact_time(&pair, vn)?;
                let steps =
                    self.steps_per_contact * law_time.max(hertz_time) / law_time.min(hertz_time);
                (
                    law_time.min(hertz_time) / self.steps_per_contact,
                    (200.0 * steps) as u64 + 100,
                )
            }
            (CouplingMode::Force, _) => (
                stable_time_step(&pair, vn, self.steps_per_contact)?.time_step,
                (200.0 * self.steps_per_contact) as u64 + 100,
            ),
        };
        let mut world = PhysicsWorld {
            gravity: Vector::ZERO,
            ..PhysicsWorld::default()
        };
        world.integration_parameters.length_unit = 2.0 * self.radius;
        // Start 2.5 steps of flight apart: the first contact falls inside a step.
        let gap = 2.5 * vn * dt;
        let flight = Flight {
            world,
            dt,
            centre: Vector::new(0.0, self.radius + gap, 0.0),
            launch: Vector::new(vt, -vn, 0.0),
            normal_speed: vn,
            tangential_speed: vt,
            max_steps,
        };
        match (mode, self.model) {
            (CouplingMode::Force, SceneLaw::Mdr(model)) => self.run_force(model, flight),
            (CouplingMode::Force, SceneLaw::Thornton(model)) => self.run_force(model, flight),
            (CouplingMode::Force, SceneLaw::AdhesiveMdr(model)) => self.run_force(model, flight),
            (CouplingMode::Force, SceneLaw::Declared(law)) => law.run_force(self, flight),
            (CouplingMode::Restitution, SceneLaw::Thornton(_)) => Err(CouplingError::Unsupported(
                "restitution mode takes its e(v) and history from the MDR law (or Hertz); \
                     use force mode for Thornton's law",
            )),
            (CouplingMode::Restitution, SceneLaw::Declared(_)) => Err(CouplingError::Unsupported(
                "restitution mode takes its e(v) and history from the MDR law (or Hertz); \
                     use force mode for the other declared laws",
            )),
            (CouplingMode::Restitution, SceneLaw::Mdr(model)) => {
                let hooks = RestitutionHooks::new(model, self.friction)?;
                self.run_restitution(hooks, flight)
            }
            (CouplingMode::Restitution, SceneLaw::AdhesiveMdr(model)) => {
                let hooks = RestitutionHooks::new(*model.params(), self.friction)?
                    .with_work_of_adhesion(model.work_of_adhesion())?;
                self.run_restitution(hooks, flight)
            }
        }
    }

    /// Restitution mode with `hooks`: step until the bodies separate.
    fn run_restitution(&self, mut hooks: RestitutionHooks, flight: Flight) -> Result<SceneOutcome> {
        let Flight {
            mut world,
            dt,
            centre,
            launch,
            normal_speed: vn,
            tangential_speed: vt,
            ..
        } = flight;
        let (ball, target) = self.place_bodies(&mut hooks, &mut world, centre, launch)?;
        world.integration_parameters.dt = dt;
        world.integration_parameters.normalized_max_linear_velocity = f64::MAX;
        let mut steps = 0;
        for _ in 0..50 {
            hooks.step(&mut world)?;
            if separating(&world, ball, target) {
                steps += 1;
                // One more step to let the solver settle, then stop.
                hooks.step(&mut world)?;
                break;
            }
        }
        let mut outcome = self.outcome(&world, ball, target, vn, vt, steps, dt);
        // No rebound: the impact stuck (zero normal restitution from the law).
        outcome.stuck = hooks.work_of_adhesion() > 0.0 && outcome.normal_restitution <= 0.0;
        Ok(outcome)
    }

    /// Force mode with normal law `model`: step until the bodies have touched and separate.
    fn run_force<N: NormalModel>(&self, model: N, flight: Flight) -> Result<SceneOutcome> {
        let Flight {
            mut world,
            dt,
            centre,
            launch,
            normal_speed: vn,
            tangential_speed: vt,
            max_steps,
        } = flight;
        let model = ContactModel::new(model).with_tangential(Mindlin::new(self.friction)?);
        let mut stepper = ForceModeStepper::new(model);
        stepper.configure(&mut world.integration_parameters, dt, 0.2 * self.radius)?;
        let (ball, target) = self.place_bodies(&mut stepper, &mut world, centre, launch)?;
        let mut steps = 0;
        let mut touched = false;
        // Whether the sphere moved away while in contact: turning back towards the target
        // while the contact still holds (adhesion) is sticking, the validator's rule.
        let mut receding = false;
        for _ in 0..max_steps {
            let report = stepper.step(&mut world)?;
            if report.contacts > 0 {
                touched = true;
                steps += 1;
                let away = separating(&world, ball, target);
                if receding && !away {
                    let mut outcome = self.outcome(&world, ball, target, vn, vt, steps, dt);
                    outcome.normal_restitution = 0.0;
                    outcome.stuck = true;
                    return Ok(outcome);
                }
                receding = away;
            } else if touched && separating(&world, ball, target) {
                return Ok(self.outcome(&world, ball, target, vn, vt, steps, dt));
            }
        }
        Err(CouplingError::ContactDidNotEnd { steps: max_steps })
    }

    /// Insert the target (half-space or free sphere) and the launched ball through either
    /// coupling; returns the ball and, for a sphere target, its body.
    fn place_bodies(
        &self,
        coupling: &mut impl Inserter,
        world: &mut PhysicsWorld,
        centre: Vector,
        launch: Vector,
    ) -> Result<(RigidBodyHandle, Option<RigidBodyHandle>)> {
        let ball_material = coupling.particles_mut().insert_material(self.material);
        let target = match self.target {
            Target::HalfSpace { material } => {
                let m = coupling.particles_mut().insert_material(material);
                coupling.insert_surface(
                    world,
                    ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
                    None,
                    m,
                )?;
                None
            }
            Target::Sphere { radius, material } => {
                let m = coupling.particles_mut().insert_material(material);
                let (t, _) = coupling.insert_sphere(
                    world,
                    SphereBuilder::new(radius, m).translation(Vector::new(0.0, -radius, 0.0)),
                )?;
                Some(t)
            }
        };
        let (ball, _) = coupling.insert_sphere(
            world,
            SphereBuilder::new(self.radius, ball_material)
                .translation(centre)
                .linvel(launch),
        )?;
        Ok((ball, target))
    }

    #[allow(clippy::too_many_arguments)]
    fn outcome(
        &self,
        world: &PhysicsWorld,
        ball: RigidBodyHandle,
        target: Option<RigidBodyHandle>,
        vn: f64,
        vt: f64,
        steps: u64,
        dt: f64,
    ) -> SceneOutcome {
        let b = &world.bodies[ball];
        let rel = relative_velocity(world, ball, target);
        let tangential_velocity = if vt > 0.0 { b.linvel().x } else { 0.0 };
        SceneOutcome {
            speed: self.speed,
            normal_restitution: rel.y / vn,
            tangential_velocity,
            // Rolling forward along +x on a floor below (normal +y) is a negative z spin.
            spin: -b.angvel().z,
            steps,
            time_step: dt,
            stuck: false,
        }
    }
}

fn relative_velocity(
    world: &PhysicsWorld,
    ball: RigidBodyHandle,
    target: Option<RigidBodyHandle>,
) -> Vector {
    let v = world.bodies[ball].linvel();
    match target {
        Some(t) => v - world.bodies[t].linvel(),
        None => v,
    }
}

fn separating(
    world: &PhysicsWorld,
    ball: RigidBodyHandle,
    target: Option<RigidBodyHandle>,
) -> bool {
    relative_velocity(world, ball, target).y > 0.0
}

/// A scene's launch: the world, the step, where and how fast the sphere starts, and the force
/// mode's step budget.
struct Flight {
    world: PhysicsWorld,
    dt: f64,
    centre: Vector,
    launch: Vector,
    normal_speed: f64,
    tangential_speed: f64,
    max_steps: u64,
}

/// What [`ImpactScene::place_bodies`] needs from a coupling: both modes register bodies the same
/// way and differ only in how the collider is flagged (impulses off, or hooks on).
trait Inserter {
    fn particles_mut(&mut self) -> &mut ParticleSet;
    fn insert_sphere(
        &mut self,
        world: &mut PhysicsWorld,
        sphere: SphereBuilder,
    ) -> Result<(RigidBodyHandle, ColliderHandle)>;
    fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle>;
}

macro_rules! impl_inserter {
    ($ty:ty $(, $g:ident : $bound:path)*) => {
        impl<$($g: $bound),*> Inserter for $ty {
            fn particles_mut(&mut self) -> &mut ParticleSet {
                <$ty>::particles_mut(self)
            }
            fn insert_sphere(
                &mut self,
                world: &mut PhysicsWorld,
                sphere: SphereBuilder,
            ) -> Result<(RigidBodyHandle, ColliderHandle)> {
                <$ty>::insert_sphere(self, world, sphere)
            }
            fn insert_surface(
                &mut self,
                world: &mut PhysicsWorld,
                collider: ColliderBuilder,
                parent: Option<RigidBodyHandle>,
                material: MaterialHandle,
            ) -> Result<ColliderHandle> {
                <$ty>::insert_surface(self, world, collider, parent, material)
            }
        }
    };
}

impl_inserter!(ForceModeStepper<N, T, D, R>, N: NormalModel, T: TangentialModel, D: DampingModel, R: RollingModel);
impl_inserter!(RestitutionHooks);
