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
        self.insert(Particle {
            collider,
            body: Some(body),
            shape: ParticleShape::Sphere {
                radius: ball.radius,
            },
            material,
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
        self.insert(Particle {
            collider,
            body: co.parent(),
            shape: ParticleShape::Surface,
            material,
        });
        Ok(())
    }

    /// Insert `sphere` (a dynamic body and its ball collider, the collider prepared by `flag`:
    /// the coupling's impulse or hook flags) into `world` and register it.
    pub(crate) fn insert_sphere_flagged(
        &mut self,
        world: &mut PhysicsWorld,
        sphere: SphereBuilder,
        flag: impl FnOnce(ColliderBuilder) -> ColliderBuilder,
    ) -> Result<(RigidBodyHandle, ColliderHandle)> {
        let (body, collider) = sphere.builders(self)?;
        let (b, c) = world.insert(body, flag(collider));
        self.register_sphere(&world.colliders, c, sphere.material)?;
        Ok((b, c))
    }

    /// Insert `collider` (any shape, optionally on `parent`, prepared by `flag`) into `world` and
    /// register it as a surface of `material`.
    pub(crate) fn insert_surface_flagged(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
        flag: impl FnOnce(ColliderBuilder) -> ColliderBuilder,
    ) -> Result<ColliderHandle> {
        self.material(material)?;
        let c = world.insert_collider(flag(collider), parent);
        self.register_surface(&world.colliders, c, material)?;
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

/// Describes a sphere to insert into a world: radius, material, initial pose and velocities.
/// The mass follows from the material's density.
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
        }
    }

    /// Initial centre (m).
    pub fn translation(mut self, translation: Vector) -> Self {
        self.translation = translation;
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

    /// The rapier body and collider builders (the caller adds coupling-specific collider flags).
    pub(crate) fn builders(
        &self,
        particles: &ParticleSet,
    ) -> Result<(RigidBodyBuilder, ColliderBuilder)> {
        positive("radius", self.radius)?;
        let density = particles.material(self.material)?.density();
        let body = RigidBodyBuilder::dynamic()
            .translation(self.translation)
            .linvel(self.linvel)
            .angvel(self.angvel)
            .can_sleep(false);
        let collider = ColliderBuilder::ball(self.radius).density(density);
        Ok((body, collider))
    }
}
