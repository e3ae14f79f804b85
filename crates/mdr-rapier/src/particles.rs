//! The colliders the plugin handles: spheres (dynamic bodies with a ball collider) and surfaces
//! (any other collider: half-space, cuboid, trimesh …), each with a [`Material`].
//!
//! Lookups are by the collider handle's arena index into a dense table, so the per-pair cost is
//! two array reads.

use crate::error::{positive, CouplingError, Result};
use mdr_contact::material::{effective_modulus, effective_shear_modulus};
use mdr_contact::Material;
use rapier3d_f64::prelude::*;

/// Index of a material in a [`ParticleSet`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct MaterialHandle(pub u32);

/// What a registered collider is, for the law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParticleShape {
    /// A ball of the given radius (m) on a rigid body.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// Any other collider; contacts with spheres use the sphere's radius as effective radius
    /// (a locally flat counterpart).
    Surface,
}

/// A collider registered with the plugin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Particle {
    /// The rapier collider.
    pub collider: ColliderHandle,
    /// Its parent body, if any.
    pub body: Option<RigidBodyHandle>,
    /// Sphere or surface.
    pub shape: ParticleShape,
    /// Its material.
    pub material: MaterialHandle,
    /// The collider's active hooks as the user set them, before the coupling added its own
    /// (the composed hooks call the user's `PhysicsHooks` only where the user asked for them).
    pub user_hooks: ActiveHooks,
}

impl Particle {
    /// The sphere radius, `None` for a surface.
    #[inline]
    pub fn radius(&self) -> Option<f64> {
        match self.shape {
            ParticleShape::Sphere { radius } => Some(radius),
            ParticleShape::Surface => None,
        }
    }
}

/// Materials and registered colliders, with the pair moduli `E*` (eq. 3) and `G*` of every
/// material pair precomputed.
#[derive(Debug, Clone, Default)]
pub struct ParticleSet {
    materials: Vec<Material>,
    /// `(E*, G*)` of material pair `(i, j)` at `i * n + j`.
    moduli: Vec<(f64, f64)>,
    /// Indexed by collider arena index.
    slots: Vec<Option<Particle>>,
    len: usize,
}

impl ParticleSet {
    /// An empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Add a material and return its handle.
    pub fn insert_material(&mut self, material: Material) -> MaterialHandle {
        self.materials.push(material);
        let n = self.materials.len();
        let mut moduli = Vec::with_capacity(n * n);
        for a in &self.materials {
            for b in &self.materials {
                moduli.push((effective_modulus(a, b), effective_shear_modulus(a, b)));
            }
        }
        self.moduli = moduli;
        MaterialHandle(n as u32 - 1)
    }

    /// The material behind a handle.
    pub fn material(&self, handle: MaterialHandle) -> Result<&Material> {
        self.materials
            .get(handle.0 as usize)
            .ok_or(CouplingError::UnknownMaterial(
                handle.0,
                self.materials.len(),
            ))
    }

    /// `(E*, G*)` of two materials (Pa), eq. (3) and docs/theory.md §5.
    #[inline]
    pub fn pair_moduli(&self, a: MaterialHandle, b: MaterialHandle) -> (f64, f64) {
        self.moduli[a.0 as usize * self.materials.len() + b.0 as usize]
    }

    /// Register an existing ball collider (attached to a rigid body) as a sphere.
    pub fn register_sphere(
        &mut self,
        colliders: &ColliderSet,
        collider: ColliderHandle,
        material: MaterialHandle,
    ) -> Result<()> {
        self.material(material)?;
        let co = colliders
            .get(collider)
            .ok_or(CouplingError::UnknownCollider(collider))?;
        let ball = co
            .shape()
            .as_ball()
            .ok_or(CouplingError::NotABall(collider))?;
        let body = co.parent().ok_or(CouplingError::NoParentBody(collider))?;
        let user_hooks = self.user_hooks_of(collider, co.active_hooks());
        self.insert(Particle {
            collider,
            body: Some(body),
            shape: ParticleShape::Sphere {
                radius: ball.radius,
            },
            material,
            user_hooks,
        });
        Ok(())
    }

    /// Register an existing collider of any shape as a surface.
    pub fn register_surface(
        &mut self,
        colliders: &ColliderSet,
        collider: ColliderHandle,
        material: MaterialHandle,
    ) -> Result<()> {
        self.material(material)?;
        let co = colliders
            .get(collider)
            .ok_or(CouplingError::UnknownCollider(collider))?;
        let user_hooks = self.user_hooks_of(collider, co.active_hooks());
        self.insert(Particle {
            collider,
            body: co.parent(),
            shape: ParticleShape::Surface,
            material,
            user_hooks,
        });
        Ok(())
    }

    /// The user's hooks of `collider`: those it holds now, less what the coupling added when it
    /// was registered before (re-registration keeps the user's original flags).
    fn user_hooks_of(&self, collider: ColliderHandle, current: ActiveHooks) -> ActiveHooks {
        self.get(collider).map_or(current, |p| p.user_hooks)
    }

    /// Insert `sphere` (a dynamic body and its ball collider) into rapier's sets, with the
    /// collider's flags completed by `flag` (the coupling's solver group or hook flag, added to
    /// the user's), and register it.
    pub(crate) fn insert_sphere_into_sets(
        &mut self,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
        sphere: SphereBuilder,
        flag: impl FnOnce(&mut Collider),
    ) -> Result<(RigidBodyHandle, ColliderHandle)> {
        let (body, collider) = sphere.builders(self)?;
        let b = bodies.insert(body);
        let c = colliders.insert_with_parent(collider, b, bodies);
        self.register_sphere(colliders, c, sphere.material)?;
        if let Some(co) = colliders.get_mut(c) {
            flag(co);
        }
        Ok((b, c))
    }

    /// Insert `collider` (any shape, optionally on `parent`) into rapier's sets, with its flags
    /// completed by `flag`, and register it as a surface of `material`.
    pub(crate) fn insert_surface_into_sets(
        &mut self,
        collider: impl Into<Collider>,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
        flag: impl FnOnce(&mut Collider),
    ) -> Result<ColliderHandle> {
        self.material(material)?;
        let c = match parent {
            Some(parent) => {
                if bodies.get(parent).is_none() {
                    return Err(CouplingError::UnknownBody(parent));
                }
                colliders.insert_with_parent(collider, parent, bodies)
            }
            None => colliders.insert(collider),
        };
        self.register_surface(colliders, c, material)?;
        if let Some(co) = colliders.get_mut(c) {
            flag(co);
        }
        Ok(c)
    }

    fn insert(&mut self, particle: Particle) {
        let index = particle.collider.into_raw_parts().0 as usize;
        if index >= self.slots.len() {
            self.slots.resize(index + 1, None);
        }
        if self.slots[index].replace(particle).is_none() {
            self.len += 1;
        }
    }

    /// Forget a collider (call it when the collider is removed from rapier).
    pub fn remove(&mut self, collider: ColliderHandle) -> Option<Particle> {
        let index = collider.into_raw_parts().0 as usize;
        let slot = self.slots.get_mut(index)?;
        if slot.is_some_and(|p| p.collider == collider) {
            self.len -= 1;
            slot.take()
        } else {
            None
        }
    }

    /// The registered particle of a collider, if any (generation checked).
    #[inline]
    pub fn get(&self, collider: ColliderHandle) -> Option<&Particle> {
        let index = collider.into_raw_parts().0 as usize;
        match self.slots.get(index) {
            Some(Some(p)) if p.collider == collider => Some(p),
            _ => None,
        }
    }

    /// Number of registered colliders.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no collider is registered.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// All registered colliders, in collider-index order.
    pub fn iter(&self) -> impl Iterator<Item = &Particle> {
        self.slots.iter().flatten()
    }

    /// All registered spheres, in collider-index order.
    pub fn spheres(&self) -> impl Iterator<Item = &Particle> {
        self.iter()
            .filter(|p| matches!(p.shape, ParticleShape::Sphere { .. }))
    }
}

/// Describes a sphere to insert into a world: radius, material, initial pose and velocities,
/// and the rapier options of its body and collider (the same names as `RigidBodyBuilder` and
/// `ColliderBuilder`). The mass follows from the material's density. Options left unset keep
/// rapier's defaults, except sleeping, which is off unless [`SphereBuilder::can_sleep`] turns
/// it on (a resting DEM sphere still carries contact forces).
///
/// The coupling adds its own solver group (force mode) or hook flag (restitution mode) to the
/// collision groups, solver groups and active hooks given here; it never replaces them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereBuilder {
    /// Radius (m).
    pub radius: f64,
    /// Material.
    pub material: MaterialHandle,
    /// Initial centre (m).
    pub translation: Vector,
    /// Initial velocity (m/s).
    pub linvel: Vector,
    /// Initial angular velocity (rad/s).
    pub angvel: Vector,
    /// Initial orientation as a scaled axis (rad), as `RigidBodyBuilder::rotation`.
    pub rotation: Vector,
    /// Whether the body may fall asleep (`RigidBodyBuilder::can_sleep`; default `false`).
    pub can_sleep: bool,
    /// Whether the body starts asleep (`RigidBodyBuilder::sleeping`).
    pub sleeping: bool,
    /// Body options that keep rapier's defaults unless set.
    pub body: SphereBodyOptions,
    /// Collider options that keep rapier's defaults unless set.
    pub collider: SphereColliderOptions,
}

/// Rigid-body options of a [`SphereBuilder`] (`None`: rapier's default).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SphereBodyOptions {
    /// `RigidBodyBuilder::user_data`.
    pub user_data: Option<u128>,
    /// `RigidBodyBuilder::linear_damping`.
    pub linear_damping: Option<f64>,
    /// `RigidBodyBuilder::angular_damping`.
    pub angular_damping: Option<f64>,
    /// `RigidBodyBuilder::gravity_scale`.
    pub gravity_scale: Option<f64>,
    /// `RigidBodyBuilder::dominance_group`.
    pub dominance_group: Option<i8>,
    /// `RigidBodyBuilder::ccd_enabled`.
    pub ccd_enabled: Option<bool>,
    /// `RigidBodyBuilder::locked_axes`.
    pub locked_axes: Option<LockedAxes>,
}

/// Collider options of a [`SphereBuilder`] (`None`: rapier's default).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SphereColliderOptions {
    /// `ColliderBuilder::user_data`.
    pub user_data: Option<u128>,
    /// `ColliderBuilder::collision_groups`.
    pub collision_groups: Option<InteractionGroups>,
    /// `ColliderBuilder::solver_groups` (the coupling adds its own group to them).
    pub solver_groups: Option<InteractionGroups>,
    /// `ColliderBuilder::active_hooks` (the coupling adds its own flag to them).
    pub active_hooks: Option<ActiveHooks>,
    /// `ColliderBuilder::active_events`.
    pub active_events: Option<ActiveEvents>,
    /// `ColliderBuilder::active_collision_types`.
    pub active_collision_types: Option<ActiveCollisionTypes>,
    /// `ColliderBuilder::friction` (restitution mode with [`crate::FrictionRule::Colliders`];
    /// force mode takes friction from its tangential law).
    pub friction: Option<f64>,
    /// `ColliderBuilder::friction_combine_rule`.
    pub friction_combine_rule: Option<CoefficientCombineRule>,
    /// `ColliderBuilder::contact_force_event_threshold`.
    pub contact_force_event_threshold: Option<f64>,
}

impl SphereBuilder {
    /// A sphere of radius `radius` (m) made of `material`, at rest at the origin.
    pub fn new(radius: f64, material: MaterialHandle) -> Self {
        Self {
            radius,
            material,
            translation: Vector::ZERO,
            linvel: Vector::ZERO,
            angvel: Vector::ZERO,
            rotation: Vector::ZERO,
            can_sleep: false,
            sleeping: false,
            body: SphereBodyOptions::default(),
            collider: SphereColliderOptions::default(),
        }
    }

    /// Initial centre (m).
    pub fn translation(mut self, translation: Vector) -> Self {
        self.translation = translation;
        self
    }

    /// Initial orientation as a scaled axis (rad).
    pub fn rotation(mut self, rotation: Vector) -> Self {
        self.rotation = rotation;
        self
    }

    /// Initial velocity (m/s).
    pub fn linvel(mut self, linvel: Vector) -> Self {
        self.linvel = linvel;
        self
    }

    /// Initial angular velocity (rad/s).
    pub fn angvel(mut self, angvel: Vector) -> Self {
        self.angvel = angvel;
        self
    }

    /// Whether the body may fall asleep (default `false`).
    pub fn can_sleep(mut self, can_sleep: bool) -> Self {
        self.can_sleep = can_sleep;
        self
    }

    /// Whether the body starts asleep.
    pub fn sleeping(mut self, sleeping: bool) -> Self {
        self.sleeping = sleeping;
        self
    }

    /// User data of the rigid body.
    pub fn body_user_data(mut self, data: u128) -> Self {
        self.body.user_data = Some(data);
        self
    }

    /// Linear damping of the rigid body.
    pub fn linear_damping(mut self, factor: f64) -> Self {
        self.body.linear_damping = Some(factor);
        self
    }

    /// Angular damping of the rigid body.
    pub fn angular_damping(mut self, factor: f64) -> Self {
        self.body.angular_damping = Some(factor);
        self
    }

    /// Gravity scale of the rigid body.
    pub fn gravity_scale(mut self, scale: f64) -> Self {
        self.body.gravity_scale = Some(scale);
        self
    }

    /// Dominance group of the rigid body.
    pub fn dominance_group(mut self, group: i8) -> Self {
        self.body.dominance_group = Some(group);
        self
    }

    /// Continuous collision detection of the rigid body.
    pub fn ccd_enabled(mut self, enabled: bool) -> Self {
        self.body.ccd_enabled = Some(enabled);
        self
    }

    /// Locked translation/rotation axes of the rigid body.
    pub fn locked_axes(mut self, axes: LockedAxes) -> Self {
        self.body.locked_axes = Some(axes);
        self
    }

    /// User data of the collider.
    pub fn user_data(mut self, data: u128) -> Self {
        self.collider.user_data = Some(data);
        self
    }

    /// Collision groups of the collider.
    pub fn collision_groups(mut self, groups: InteractionGroups) -> Self {
        self.collider.collision_groups = Some(groups);
        self
    }

    /// Solver groups of the collider (the coupling adds its own group).
    pub fn solver_groups(mut self, groups: InteractionGroups) -> Self {
        self.collider.solver_groups = Some(groups);
        self
    }

    /// Active hooks of the collider (the coupling adds its own flag).
    pub fn active_hooks(mut self, hooks: ActiveHooks) -> Self {
        self.collider.active_hooks = Some(hooks);
        self
    }

    /// Active events of the collider (collision and contact-force events).
    pub fn active_events(mut self, events: ActiveEvents) -> Self {
        self.collider.active_events = Some(events);
        self
    }

    /// Active collision types of the collider.
    pub fn active_collision_types(mut self, types: ActiveCollisionTypes) -> Self {
        self.collider.active_collision_types = Some(types);
        self
    }

    /// Friction coefficient of the collider.
    pub fn friction(mut self, friction: f64) -> Self {
        self.collider.friction = Some(friction);
        self
    }

    /// Friction combine rule of the collider.
    pub fn friction_combine_rule(mut self, rule: CoefficientCombineRule) -> Self {
        self.collider.friction_combine_rule = Some(rule);
        self
    }

    /// Contact-force event threshold of the collider (N).
    pub fn contact_force_event_threshold(mut self, threshold: f64) -> Self {
        self.collider.contact_force_event_threshold = Some(threshold);
        self
    }

    /// The rapier body and collider builders this sphere describes (before the coupling adds
    /// its solver group or hook flag at registration).
    pub fn builders(&self, particles: &ParticleSet) -> Result<(RigidBodyBuilder, ColliderBuilder)> {
        positive("radius", self.radius)?;
        let density = particles.material(self.material)?.density();
        let mut body = RigidBodyBuilder::dynamic()
            .translation(self.translation)
            .linvel(self.linvel)
            .angvel(self.angvel)
            .can_sleep(self.can_sleep);
        if self.rotation != Vector::ZERO {
            body = body.rotation(self.rotation);
        }
        if self.sleeping {
            body = body.sleeping(true);
        }
        let b = &self.body;
        if let Some(v) = b.user_data {
            body = body.user_data(v);
        }
        if let Some(v) = b.linear_damping {
            body = body.linear_damping(v);
        }
        if let Some(v) = b.angular_damping {
            body = body.angular_damping(v);
        }
        if let Some(v) = b.gravity_scale {
            body = body.gravity_scale(v);
        }
        if let Some(v) = b.dominance_group {
            body = body.dominance_group(v);
        }
        if let Some(v) = b.ccd_enabled {
            body = body.ccd_enabled(v);
        }
        if let Some(v) = b.locked_axes {
            body = body.locked_axes(v);
        }
        let mut collider = ColliderBuilder::ball(self.radius).density(density);
        let c = &self.collider;
        if let Some(v) = c.user_data {
            collider = collider.user_data(v);
        }
        if let Some(v) = c.collision_groups {
            collider = collider.collision_groups(v);
        }
        if let Some(v) = c.solver_groups {
            collider = collider.solver_groups(v);
        }
        if let Some(v) = c.active_hooks {
            collider = collider.active_hooks(v);
        }
        if let Some(v) = c.active_events {
            collider = collider.active_events(v);
        }
        if let Some(v) = c.active_collision_types {
            collider = collider.active_collision_types(v);
        }
        if let Some(v) = c.friction {
            collider = collider.friction(v);
        }
        if let Some(v) = c.friction_combine_rule {
            collider = collider.friction_combine_rule(v);
        }
        if let Some(v) = c.contact_force_event_threshold {
            collider = collider.contact_force_event_threshold(v);
        }
        Ok((body, collider))
    }
}
