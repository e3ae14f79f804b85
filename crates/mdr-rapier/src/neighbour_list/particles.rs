//! Particle data of the neighbour-list path in structure-of-arrays form: one array per quantity, indexed
//! by particle, plus a small table of species (material, radius, mass, inertia) so that the
//! laws can be bound once per species pair instead of once per contact.

use crate::convert::AnyVector;
use crate::error::{positive, CouplingError, Result};
use crate::particles::MaterialHandle;
use nalgebra::Vector3;
use rapier3d_f64::math::{Rotation, Vector};

/// Largest number of distinct species (the species-pair law table has this many squared).
pub const MAX_SPECIES: usize = 256;

/// What sets a particle's law: material, radius and mass properties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Species {
    /// Material.
    pub material: MaterialHandle,
    /// Radius.
    pub radius: f64,
    /// Mass (rapier's `1 / inv_mass` of a ball of the material's density).
    pub mass: f64,
    /// `1 / mass`.
    pub inv_mass: f64,
    /// Inverse of the (isotropic) moment of inertia.
    pub inv_inertia: f64,
}

/// Structure-of-arrays particle data. The vector arrays are in the law crate's type (the pair
/// loop hands them to the law as they are); [`NeighbourListParticles::position_of`] and the other
/// accessors read and write one particle's in rapier's vector type.
#[derive(Debug, Clone, Default)]
pub struct NeighbourListParticles {
    /// Centres.
    pub position: Vec<Vector3<f64>>,
    /// Velocities of the centres.
    pub linvel: Vec<Vector3<f64>>,
    /// Angular velocities.
    pub angvel: Vec<Vector3<f64>>,
    /// Orientations (integrated as rapier does; spheres do not need them for contacts).
    pub rotation: Vec<Rotation>,
    /// Radii (copied from the species for the pair loop).
    pub radius: Vec<f64>,
    /// Species index of each particle.
    pub species: Vec<u16>,
    /// The species table.
    pub species_table: Vec<Species>,
}

impl NeighbourListParticles {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// Whether there are no particles.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Centre of particle `i` (m), in rapier's vector type.
    pub fn position_of(&self, i: usize) -> Vector {
        self.position[i].glam()
    }

    /// Velocity of particle `i` (m/s), in rapier's vector type.
    pub fn linvel_of(&self, i: usize) -> Vector {
        self.linvel[i].glam()
    }

    /// Angular velocity of particle `i` (rad/s), in rapier's vector type.
    pub fn angvel_of(&self, i: usize) -> Vector {
        self.angvel[i].glam()
    }

    /// Move particle `i` to `position` (m). The neighbour lists are not rebuilt by this:
    /// call `NeighbourListStepper::request_rebuild` after moving particles by hand.
    pub fn set_position(&mut self, i: usize, position: impl AnyVector) {
        self.position[i] = position.na();
    }

    /// Set the velocity of particle `i` (m/s).
    pub fn set_linvel(&mut self, i: usize, linvel: impl AnyVector) {
        self.linvel[i] = linvel.na();
    }

    /// Set the angular velocity of particle `i` (rad/s).
    pub fn set_angvel(&mut self, i: usize, angvel: impl AnyVector) {
        self.angvel[i] = angvel.na();
    }

    /// Index of the species, added if new.
    pub(crate) fn species_of(&mut self, species: Species) -> Result<u16> {
        positive("radius", species.radius)?;
        if let Some(k) = self.species_table.iter().position(|s| *s == species) {
            return Ok(k as u16);
        }
        if self.species_table.len() >= MAX_SPECIES {
            return Err(CouplingError::OutOfRange {
                name: "number of particle species (material, radius, mass)",
                value: (self.species_table.len() + 1) as f64,
                range: "[1, 256]",
            });
        }
        self.species_table.push(species);
        Ok((self.species_table.len() - 1) as u16)
    }

    /// Append a particle.
    pub(crate) fn push(
        &mut self,
        species: u16,
        position: Vector3<f64>,
        linvel: Vector3<f64>,
        angvel: Vector3<f64>,
    ) -> usize {
        self.position.push(position);
        self.linvel.push(linvel);
        self.angvel.push(angvel);
        self.rotation.push(Rotation::IDENTITY);
        self.radius
            .push(self.species_table[species as usize].radius);
        self.species.push(species);
        self.position.len() - 1
    }

    /// Bytes held per particle by these arrays (capacity / particles).
    pub fn bytes(&self) -> usize {
        self.position.capacity() * 24
            + self.linvel.capacity() * 24
            + self.angvel.capacity() * 24
            + self.rotation.capacity() * std::mem::size_of::<Rotation>()
            + self.radius.capacity() * 8
            + self.species.capacity() * 2
            + self.species_table.capacity() * std::mem::size_of::<Species>()
    }
}
