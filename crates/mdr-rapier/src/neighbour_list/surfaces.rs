//! Particles against rapier colliders (walls, meshes, containers, user bodies): candidate pairs
//! found at neighbour-list rebuilds with parry distance queries, exact contacts every step with
//! [`crate::geometry::sphere_shape`] (or a closed form: half-spaces through
//! [`crate::geometry::sphere_half_space`], convex polyhedra through the face projection of
//! [`crate::geometry::sphere_convex`], surfaces of revolution), histories carried over rebuilds
//! by `(particle, surface)`.

use crate::convert::AnyVector;
use crate::geometry::{
    convex_distance_within, half_space_distance, sphere_convex, sphere_convex_signed,
    sphere_half_space, sphere_half_space_signed, sphere_shape, sphere_shape_signed, ConvexFaces,
    SurfaceContact, SurfaceOfRevolution,
};
use crate::kernel::PairWrench;
use crate::particles::MaterialHandle;
use nalgebra::Vector3;
use rapier3d_f64::math::{Pose, Vector};
use rapier3d_f64::prelude::{Collider, ColliderHandle, RigidBodyHandle};
use std::sync::Arc;

/// A rapier collider registered as a surface of the neighbour-list path.
#[derive(Debug, Clone)]
pub struct NeighbourListSurface {
    /// The collider.
    pub collider: ColliderHandle,
    /// Its parent body, if any (receives the reaction forces when dynamic).
    pub body: Option<RigidBodyHandle>,
    /// Material of the surface.
    pub material: MaterialHandle,
    /// Pose at the last neighbour-list build.
    pub pose_at_build: Pose,
    /// Radius of the collider's local bounding sphere (infinite for a half-space), to bound the
    /// displacement of its points under a rotation.
    pub bounding_radius: f64,
    /// The faces of a convex-polyhedron collider (its contacts then take the exact face
    /// projection of [`crate::geometry::sphere_convex`] instead of parry's GJK).
    pub convex: Option<Arc<ConvexFaces>>,
    /// An exact surface of revolution standing for the collider's shape (a cylinder, cone or
    /// orifice-plate wall whose collider is made of flat pieces): its contacts and candidates take
    /// [`SurfaceOfRevolution`]'s closed form instead of the collider's shape.
    pub revolution: Option<Arc<SurfaceOfRevolution>>,
    /// The outward unit normal, in the collider's frame, of a half-space collider (a plane
    /// wall): its contacts take the closed form of [`crate::geometry::sphere_half_space`]
    /// instead of parry's projection.
    pub plane: Option<Vector3<f64>>,
}

impl NeighbourListSurface {
    /// [`NeighbourListSurface::plane`] in rapier's vector type.
    pub fn plane_normal(&self) -> Option<Vector> {
        self.plane.map(|n| n.glam())
    }

    /// Contact of a sphere with this surface's collider `co`.
    #[inline]
    pub fn sphere_contact(
        &self,
        co: &Collider,
        center: impl AnyVector,
        radius: f64,
    ) -> Option<SurfaceContact> {
        let center = &center.na();
        if let Some(surface) = &self.revolution {
            return surface.sphere_contact(center, radius, co.position());
        }
        if let Some(normal) = &self.plane {
            return sphere_half_space(center, radius, normal, co.position());
        }
        match &self.convex {
            Some(faces) => sphere_convex(center, radius, faces, co.shape(), co.position()),
            None => sphere_shape(center, radius, co.shape(), co.position()),
        }
    }

    /// [`NeighbourListSurface::sphere_contact`] at any distance: a negative overlap while the
    /// sphere is apart (a held adhesive contact; see [`crate::geometry::sphere_sphere_signed`]).
    pub fn sphere_contact_signed(
        &self,
        co: &Collider,
        center: impl AnyVector,
        radius: f64,
    ) -> Option<SurfaceContact> {
        let center = &center.na();
        if let Some(surface) = &self.revolution {
            return surface.sphere_contact_signed(center, radius, co.position());
        }
        if let Some(normal) = &self.plane {
            return Some(sphere_half_space_signed(
                center,
                radius,
                normal,
                co.position(),
            ));
        }
        match &self.convex {
            Some(faces) => sphere_convex_signed(center, radius, faces, co.shape(), co.position()),
            None => sphere_shape_signed(center, radius, co.shape(), co.position()),
        }
    }

    /// Whether the centre `x` is within `reach` of the collider `co`.
    pub fn within(&self, co: &Collider, x: impl AnyVector, reach: f64) -> bool {
        let x = &x.na();
        if let Some(surface) = &self.revolution {
            return surface.within(x, co.position(), reach);
        }
        if let Some(normal) = &self.plane {
            return half_space_distance(x, normal, co.position()) < reach;
        }
        match &self.convex {
            Some(faces) => convex_distance_within(x, faces, co.position(), reach).is_some(),
            None => co.shape().distance_to_point(co.position(), x.glam(), true) < reach,
        }
    }
}

/// Particle–surface candidate pairs, sorted by `(particle, surface)`.
#[derive(Debug, Clone, Default)]
pub struct SurfacePairs<H> {
    /// Particle of each pair.
    pub particle: Vec<u32>,
    /// Surface index (into the stepper's surface list, sorted by collider index).
    pub surface: Vec<u32>,
    /// Whether the pair touched at the last force evaluation.
    pub active: Vec<bool>,
    /// Contact history.
    pub history: Vec<H>,
    /// Wrench at the last force evaluation (force on the particle; `torque2` on the surface's
    /// body); zero where not `active`.
    pub wrench: Vec<PairWrench>,
    /// Contact geometry at the last force evaluation (overlap, normal from the surface towards
    /// the particle, point); meaningful only where `active`.
    pub contact: Vec<SurfaceContact>,
    /// `start[i]..start[i + 1]`: the pairs of particle `i`.
    pub start: Vec<u32>,
}

impl<H: Default> SurfacePairs<H> {
    /// Number of candidate pairs.
    pub fn len(&self) -> usize {
        self.particle.len()
    }

    /// Whether there are no candidates.
    pub fn is_empty(&self) -> bool {
        self.particle.is_empty()
    }

    /// The same pairs with every history mapped by `f` (e.g. to other work books).
    pub fn map_history<H2>(self, f: impl FnMut(H) -> H2) -> SurfacePairs<H2> {
        SurfacePairs {
            particle: self.particle,
            surface: self.surface,
            active: self.active,
            history: self.history.into_iter().map(f).collect(),
            wrench: self.wrench,
            contact: self.contact,
            start: self.start,
        }
    }

    /// Bytes held (capacity).
    pub fn bytes(&self) -> usize {
        self.particle.capacity() * 4
            + self.surface.capacity() * 4
            + self.active.capacity()
            + self.history.capacity() * std::mem::size_of::<H>()
            + self.wrench.capacity() * std::mem::size_of::<PairWrench>()
            + self.contact.capacity() * std::mem::size_of::<SurfaceContact>()
            + self.start.capacity() * 4
    }

    /// Replace the candidates by `candidates` (sorted by `(particle, surface)`), carrying the
    /// histories of `old` over by key.
    pub(crate) fn rebuild_from(
        &mut self,
        candidates: &[(u32, u32)],
        n_particles: usize,
        old: &mut SurfacePairs<H>,
    ) {
        self.particle.clear();
        self.surface.clear();
        self.active.clear();
        self.history.clear();
        self.wrench.clear();
        self.contact.clear();
        self.start.clear();
        self.start.resize(n_particles + 1, 0);
        let mut q = 0;
        for &(i, s) in candidates {
            while q < old.len() && (old.particle[q], old.surface[q]) < (i, s) {
                q += 1;
            }
            if q < old.len() && (old.particle[q], old.surface[q]) == (i, s) {
                self.history.push(std::mem::take(&mut old.history[q]));
                self.active.push(old.active[q]);
                // Carried over: what stays active in `old` was dropped by this rebuild.
                old.active[q] = false;
                self.wrench.push(old.wrench[q]);
                self.contact.push(old.contact[q]);
                q += 1;
            } else {
                self.history.push(H::default());
                self.active.push(false);
                self.wrench.push(PairWrench::default());
                self.contact.push(SurfaceContact::default());
            }
            self.particle.push(i);
            self.surface.push(s);
            self.start[i as usize + 1] += 1;
        }
        for i in 0..n_particles {
            self.start[i + 1] += self.start[i];
        }
    }
}

/// Largest distance any point of a surface moved between two poses, bounded by the translation
/// of its origin plus the rotation angle times its bounding radius.
pub(crate) fn surface_displacement(surface: &NeighbourListSurface, now: &Pose) -> f64 {
    let before = &surface.pose_at_build;
    let dt = (now.translation - before.translation).length();
    let angle = (now.rotation * before.rotation.inverse())
        .to_axis_angle()
        .1
        .abs();
    if angle == 0.0 {
        dt
    } else {
        dt + angle * surface.bounding_radius
    }
}
