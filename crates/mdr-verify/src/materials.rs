//! The materials of the Chung & Ooi (2011) tests. Sources and doubts: `docs/verification.md` §1.

use mdr_contact::Material;

fn material(youngs_modulus: f64, poisson_ratio: f64, density: f64) -> Material {
    Material::new(youngs_modulus, poisson_ratio, density).expect("tabulated values are valid")
}

/// Glass (test 1): E = 48 GPa, ν = 0.20, ρ = 2800 kg/m³.
pub fn glass() -> Material {
    material(4.8e10, 0.20, 2800.0)
}

/// Limestone (test 1): E = 20 GPa, ν = 0.25, ρ = 2500 kg/m³.
pub fn limestone() -> Material {
    material(2.0e10, 0.25, 2500.0)
}

/// Aluminium alloy (tests 2, 4, 6–8): E = 70 GPa, ν = 0.33, ρ = 2700 kg/m³.
pub fn aluminium_alloy() -> Material {
    material(7.0e10, 0.33, 2700.0)
}

/// Magnesium alloy (test 2): E = 40 GPa, ν = 0.35, ρ = 1800 kg/m³.
pub fn magnesium_alloy() -> Material {
    material(4.0e10, 0.35, 1800.0)
}

/// Aluminium oxide (tests 3, 4; Kharaz et al. 2001): E = 380 GPa, ν = 0.23, ρ = 4000 kg/m³.
pub fn aluminium_oxide() -> Material {
    material(3.8e11, 0.23, 4000.0)
}

/// Cast iron (test 3): E = 100 GPa, ν = 0.25, ρ = 7000 kg/m³.
pub fn cast_iron() -> Material {
    material(1.0e11, 0.25, 7000.0)
}

/// Steel (test 5): E = 208 GPa, ν = 0.30, ρ = 7850 kg/m³ (docs/verification.md §1).
pub fn steel() -> Material {
    material(2.08e11, 0.30, 7850.0)
}

/// Polyethylene (test 5): E = 1.0 GPa, ν = 0.40, ρ = 1400 kg/m³.
pub fn polyethylene() -> Material {
    material(1.0e9, 0.40, 1400.0)
}

/// Copper (test 7): E = 120 GPa, ν = 0.35, ρ = 8900 kg/m³.
pub fn copper() -> Material {
    material(1.2e11, 0.35, 8900.0)
}

/// Nylon (tests 6, 8): E = 2.5 GPa, ν = 0.40, ρ = 1000 kg/m³.
pub fn nylon() -> Material {
    material(2.5e9, 0.40, 1000.0)
}

/// Stiffness factor of a "rigid" plane: the paper's plane is rigid; a plane of the sphere's
/// material `RIGID_FACTOR` times stiffer gives `E*` and `G*` within `1/RIGID_FACTOR` of the rigid
/// limit (as Chung & Ooi and the Yade scripts do with a factor 1000; ours is smaller error).
pub const RIGID_FACTOR: f64 = 1.0e6;

/// A rigid plane for a sphere of `sphere`: same `ν` and `ρ`, `E` times [`RIGID_FACTOR`].
pub fn rigid_for(sphere: &Material) -> Material {
    material(
        sphere.youngs_modulus() * RIGID_FACTOR,
        sphere.poisson_ratio(),
        sphere.density(),
    )
}
