//! Materials and the pair quantities of a contact: `E*` (eq. 3), `G*`, effective radius and
//! reduced mass (docs/theory.md §1, §5).

use crate::error::{finite, positive, ContactError, Result};

/// An isotropic elastic material with a density, in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Material {
    youngs_modulus: f64,
    poisson_ratio: f64,
    density: f64,
}

impl Material {
    /// A material from Young's modulus `E` (Pa, > 0), Poisson's ratio `ν` (in (−1, 0.5]) and
    /// density `ρ` (kg/m³, > 0).
    ///
    /// ```
    /// use mdr_contact::Material;
    /// let steel = Material::new(2.0e11, 0.286, 7800.0).unwrap();
    /// assert!(Material::new(2.0e11, 0.6, 7800.0).is_err());
    /// ```
    pub fn new(youngs_modulus: f64, poisson_ratio: f64, density: f64) -> Result<Self> {
        positive("youngs_modulus", youngs_modulus)?;
        finite("poisson_ratio", poisson_ratio)?;
        if !(poisson_ratio > -1.0 && poisson_ratio <= 0.5) {
            return Err(ContactError::OutOfRange {
                name: "poisson_ratio",
                value: poisson_ratio,
                range: "(-1, 0.5]",
            });
        }
        positive("density", density)?;
        Ok(Self {
            youngs_modulus,
            poisson_ratio,
            density,
        })
    }

    /// A material by named parameters, so that `E`, `ν` and `ρ` cannot be swapped:
    /// `Material::builder().youngs(E).poisson(ν).density(ρ).build()`. A parameter left unset is
    /// an error naming it.
    ///
    /// ```
    /// use mdr_contact::Material;
    /// let glass = Material::builder().youngs(6.3e10).poisson(0.2).density(2500.0).build().unwrap();
    /// assert_eq!(glass, Material::new(6.3e10, 0.2, 2500.0).unwrap());
    /// assert!(Material::builder().youngs(6.3e10).poisson(0.2).build().is_err());
    /// ```
    pub fn builder() -> MaterialBuilder {
        MaterialBuilder::default()
    }

    /// The paper's steel (Fig. 2): `E = 2·10¹¹ Pa`, `ν = 0.286`, `ρ = 7800 kg/m³`.
    pub fn paper_steel() -> Self {
        Self {
            youngs_modulus: 2.0e11,
            poisson_ratio: 0.286,
            density: 7800.0,
        }
    }

    /// Young's modulus `E` (Pa).
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }

    /// Poisson's ratio `ν`.
    pub fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }

    /// Density `ρ` (kg/m³).
    pub fn density(&self) -> f64 {
        self.density
    }

    /// Shear modulus `G = E / (2 (1 + ν))` (Pa).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Mass of a sphere of radius `radius` (m) made of this material (kg).
    pub fn sphere_mass(&self, radius: f64) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * radius.powi(3) * self.density
    }
}

/// Named-parameter construction of a [`Material`] ([`Material::builder`]); every parameter is
/// required and validated by [`Material::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialBuilder {
    youngs_modulus: f64,
    poisson_ratio: f64,
    density: f64,
}

impl Default for MaterialBuilder {
    fn default() -> Self {
        // NaN marks "unset": `Material::new` rejects it with the parameter's name.
        Self {
            youngs_modulus: f64::NAN,
            poisson_ratio: f64::NAN,
            density: f64::NAN,
        }
    }
}

impl MaterialBuilder {
    /// Young's modulus `E` (Pa, > 0).
    pub fn youngs(mut self, youngs_modulus: f64) -> Self {
        self.youngs_modulus = youngs_modulus;
        self
    }

    /// Poisson's ratio `ν` (in (−1, 0.5]).
    pub fn poisson(mut self, poisson_ratio: f64) -> Self {
        self.poisson_ratio = poisson_ratio;
        self
    }

    /// Density `ρ` (kg/m³, > 0).
    pub fn density(mut self, density: f64) -> Self {
        self.density = density;
        self
    }

    /// The material, or an error naming the first parameter that is unset or out of range.
    pub fn build(self) -> Result<Material> {
        Material::new(self.youngs_modulus, self.poisson_ratio, self.density)
    }
}

/// Effective (contact) modulus `E*` of two materials, eq. (3):
/// `1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂`. For identical materials this is eq. (16),
/// `E* = E / (2 (1 − ν²))`.
pub fn effective_modulus(a: &Material, b: &Material) -> f64 {
    let compliance = (1.0 - a.poisson_ratio.powi(2)) / a.youngs_modulus
        + (1.0 - b.poisson_ratio.powi(2)) / b.youngs_modulus;
    1.0 / compliance
}

/// Effective shear modulus `G*` of two materials (docs/theory.md §5):
/// `1/G* = (2 − ν₁)/(4 G₁) + (2 − ν₂)/(4 G₂)`.
pub fn effective_shear_modulus(a: &Material, b: &Material) -> f64 {
    let compliance = (2.0 - a.poisson_ratio) / (4.0 * a.shear_modulus())
        + (2.0 - b.poisson_ratio) / (4.0 * b.shear_modulus());
    1.0 / compliance
}

/// What a sphere touches: another sphere, or a half-space (a wall of infinite radius and mass).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Counterpart {
    /// A sphere of the given radius (m), made of the given material.
    Sphere {
        /// Radius (m).
        radius: f64,
        /// Material of the second sphere.
        material: Material,
    },
    /// A flat half-space of the given material, fixed in space.
    HalfSpace {
        /// Material of the half-space.
        material: Material,
    },
}

/// The quantities of one contact pair that every law needs (docs/theory.md §1):
/// effective modulus `E*`, effective shear modulus `G*`, effective radius `R` and reduced mass `m`.
///
/// ```
/// use mdr_contact::{ContactPair, Material};
/// let steel = Material::paper_steel();
/// let pair = ContactPair::sphere_on_half_space(0.635e-2, &steel, &steel).unwrap();
/// assert!((pair.effective_modulus() - 1.0899e11).abs() < 1e8);
/// assert!((pair.reduced_mass() - 8.366e-3).abs() < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactPair {
    effective_modulus: f64,
    effective_shear_modulus: f64,
    effective_radius: f64,
    reduced_mass: f64,
}

impl ContactPair {
    /// A pair from its four quantities directly (`E*` Pa, `G*` Pa, `R` m, `m` kg), all > 0.
    pub fn new(
        effective_modulus: f64,
        effective_shear_modulus: f64,
        effective_radius: f64,
        reduced_mass: f64,
    ) -> Result<Self> {
        Ok(Self {
            effective_modulus: positive("effective_modulus", effective_modulus)?,
            effective_shear_modulus: positive("effective_shear_modulus", effective_shear_modulus)?,
            effective_radius: positive("effective_radius", effective_radius)?,
            reduced_mass: positive("reduced_mass", reduced_mass)?,
        })
    }

    /// A sphere of radius `radius` (m) and material `sphere` hitting a fixed half-space of
    /// material `wall`: `R = R₁`, `m = m₁`.
    pub fn sphere_on_half_space(radius: f64, sphere: &Material, wall: &Material) -> Result<Self> {
        positive("radius", radius)?;
        Self::new(
            effective_modulus(sphere, wall),
            effective_shear_modulus(sphere, wall),
            radius,
            sphere.sphere_mass(radius),
        )
    }

    /// Two free spheres: `R = R₁R₂/(R₁ + R₂)`, `m = m₁m₂/(m₁ + m₂)`.
    pub fn sphere_on_sphere(
        radius1: f64,
        material1: &Material,
        radius2: f64,
        material2: &Material,
    ) -> Result<Self> {
        positive("radius", radius1)?;
        positive("target_radius", radius2)?;
        let m1 = material1.sphere_mass(radius1);
        let m2 = material2.sphere_mass(radius2);
        Self::new(
            effective_modulus(material1, material2),
            effective_shear_modulus(material1, material2),
            radius1 * radius2 / (radius1 + radius2),
            m1 * m2 / (m1 + m2),
        )
    }

    /// A sphere of radius `radius` and material `material` against a [`Counterpart`].
    pub fn with_counterpart(radius: f64, material: &Material, other: &Counterpart) -> Result<Self> {
        match other {
            Counterpart::Sphere {
                radius: r2,
                material: m2,
            } => Self::sphere_on_sphere(radius, material, *r2, m2),
            Counterpart::HalfSpace { material: m2 } => {
                Self::sphere_on_half_space(radius, material, m2)
            }
        }
    }

    /// The paper's Fig. 2 pair: a steel ball of radius 0.635 cm on a steel half-space.
    pub fn paper_fig2() -> Self {
        let steel = Material::paper_steel();
        Self::sphere_on_half_space(0.635e-2, &steel, &steel).expect("paper values are valid")
    }

    /// The same pair with another reduced mass (kg, > 0).
    pub fn with_reduced_mass(mut self, reduced_mass: f64) -> Result<Self> {
        self.reduced_mass = positive("reduced_mass", reduced_mass)?;
        Ok(self)
    }

    /// Effective modulus `E*` (Pa), eq. (3).
    pub fn effective_modulus(&self) -> f64 {
        self.effective_modulus
    }

    /// Effective shear modulus `G*` (Pa), docs/theory.md §5.
    pub fn effective_shear_modulus(&self) -> f64 {
        self.effective_shear_modulus
    }

    /// Effective radius `R` (m).
    pub fn effective_radius(&self) -> f64 {
        self.effective_radius
    }

    /// Reduced mass `m` (kg).
    pub fn reduced_mass(&self) -> f64 {
        self.reduced_mass
    }

    /// Hertz contact duration of an elastic impact at normal speed `v0` (m/s):
    /// `t_c = 2.868 (m² / (R E*² v0))^{1/5}`.
    pub fn hertz_contact_time(&self, v0: f64) -> f64 {
        2.868
            * (self.reduced_mass.powi(2)
                / (self.effective_radius * self.effective_modulus.powi(2) * v0.abs()))
            .powf(0.2)
    }

    /// Largest overlap of an elastic (Hertz) impact at normal speed `v0` (m/s):
    /// `δ_max = (15 m v0² / (16 E* √R))^{2/5}`.
    pub fn hertz_max_overlap(&self, v0: f64) -> f64 {
        (15.0 * self.reduced_mass * v0 * v0
            / (16.0 * self.effective_modulus * self.effective_radius.sqrt()))
        .powf(0.4)
    }
}
