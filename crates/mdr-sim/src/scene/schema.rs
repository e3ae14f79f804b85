//! The scene file as written by the user: plain serde structs, one per TOML table, every key
//! carrying its unit in its name. Unknown keys are refused (`deny_unknown_fields`; in
//! `[contact]`, whose law parameters come from the laws' declarations, by the validation); the
//! values are checked afterwards by [`super::validate`], which knows every key's allowed range.

use mdr_contact::params::LawKind;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A whole scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// `[run]`: time stepping, outputs, seed.
    pub run: RunSection,
    /// `[gravity]`: optional; no gravity when absent.
    #[serde(default)]
    pub gravity: Option<GravitySection>,
    /// `[[material]]`: named materials.
    #[serde(default)]
    pub material: Vec<MaterialSection>,
    /// `[contact]`: the contact model shared by every pair.
    pub contact: ContactSection,
    /// `[[particles]]`: groups of spheres.
    #[serde(default)]
    pub particles: Vec<ParticleGroup>,
    /// `[[walls]]`: fixed or kinematic boundaries.
    #[serde(default)]
    pub walls: Vec<WallSection>,
}

/// `dt_s`: a number of seconds or `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum TimeStep {
    /// A fixed step (s).
    Seconds(f64),
    /// `"auto"`: the plugin's time-step helper (Hertz contact time at the largest expected speed).
    Auto(AutoKeyword),
}

/// The keyword `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AutoKeyword {
    /// `"auto"`.
    Auto,
}

/// How the law enters rapier.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CouplingMode {
    /// Soft spheres: forces from the law (exact; `mdr_rapier::ForceModeStepper`).
    #[default]
    Force,
    /// Hard spheres: restitution from the law's energy route (`mdr_rapier::RestitutionHooks`).
    Restitution,
}

/// Which force-mode implementation runs a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ForcePath {
    /// `mdr_rapier::neighbour_list::NeighbourListStepper`: binned neighbour lists with a skin, the walls as
    /// rapier colliders registered as surfaces (the default).
    #[default]
    NeighbourList,
    /// `mdr_rapier::ForceModeStepper`: rapier's broad and narrow phase every step.
    Rapier,
}

/// Which headline quantity the run reports at the end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Headline {
    /// Nothing beyond the energy books.
    #[default]
    None,
    /// Granular column collapse: run-out distance and final height.
    Column,
    /// Hopper discharge: steady mass flow rate against Beverloo.
    Hopper,
    /// Rotating drum: dynamic angle of repose.
    Drum,
    /// Single-sphere drop: coefficient of restitution of the first bounce.
    Drop,
    /// Funnel discharge: spheres left in the funnel against time (the discharge curve).
    Funnel,
}

/// `[run]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSection {
    /// Name used for output file names.
    pub name: String,
    /// Seed of the random generator (placement, size distributions).
    #[serde(default)]
    pub seed: u64,
    /// Simulated time (s).
    pub duration_s: f64,
    /// Time step (s) or `"auto"`.
    pub dt_s: TimeStep,
    /// Largest expected relative speed (m/s), for `dt_s = "auto"` and the step check.
    #[serde(default)]
    pub max_speed_m_per_s: Option<f64>,
    /// Steps per Hertz contact for `dt_s = "auto"` (default 50).
    #[serde(default)]
    pub steps_per_contact: Option<f64>,
    /// Interval between output frames (s).
    pub output_interval_s: f64,
    /// Interval between checkpoints (s); none when absent.
    #[serde(default)]
    pub checkpoint_interval_s: Option<f64>,
    /// Interval between energy-book rows (s); defaults to `output_interval_s / 10`.
    #[serde(default)]
    pub energy_interval_s: Option<f64>,
    /// Energy guard: the largest drift of the energy balance, as a fraction of the run's energy
    /// scale ([`crate::output::energy::BalanceDrift`]), before the run is stopped (default
    /// [`crate::scene::validate::DEFAULT_MAX_ENERGY_DRIFT`]). Left out of the serialisation when
    /// absent, as `force_path`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_energy_drift: Option<f64>,
    /// Coupling mode.
    #[serde(default)]
    pub coupling: CouplingMode,
    /// Force mode: `"neighbour_list"` (default) or `"rapier"`. Left out of the file's
    /// serialisation when absent, so checkpoints of scenes without it keep their fingerprint.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force_path: Option<ForcePath>,
    /// Neighbour-list path: the skin (m) of the neighbour lists (default a tenth of the mean
    /// diameter). Left out of the serialisation when absent, as `force_path`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub neighbour_skin_m: Option<f64>,
    /// Headline quantity.
    #[serde(default)]
    pub headline: Headline,
    /// Also write the contact network (pairs, force, overlap, plastic indentation) per frame.
    #[serde(default)]
    pub contact_network: bool,
    /// Hopper and funnel: height (m) below which a particle counts as discharged.
    #[serde(default)]
    pub discharge_height_m: Option<f64>,
    /// Height (m, along −gravity) below which a sphere is removed from the run (counted as
    /// discharged and parked at rest out of reach); none when absent.
    #[serde(default)]
    pub delete_below_m: Option<f64>,
    /// Hopper only: run the scene once per orifice diameter (m) in this list (at least three)
    /// and fit Beverloo's `C` and `k` to the measured flow rates.
    #[serde(default)]
    pub orifice_sweep_m: Option<Vec<f64>>,
    /// Neighbour-list path: the box is periodic in x over `[lo, hi]` (m), together with
    /// `periodic_y_m`. Left out of the serialisation when absent, as `force_path`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub periodic_x_m: Option<[f64; 2]>,
    /// Neighbour-list path: the box is periodic in y over `[lo, hi]` (m), with `periodic_x_m`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub periodic_y_m: Option<[f64; 2]>,
}

/// `[gravity]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GravitySection {
    /// Gravitational acceleration (m/s²).
    pub acceleration_m_per_s2: [f64; 3],
}

/// `[[material]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// Name the particles and walls refer to.
    pub name: String,
    /// Young's modulus `E` (Pa).
    pub youngs_pa: f64,
    /// Poisson's ratio `ν` (dimensionless).
    pub poisson_ratio: f64,
    /// Density `ρ` (kg/m³).
    pub density_kg_per_m3: f64,
    /// Work of adhesion `Δγ` of the material against itself (J/m², ≥ 0, default 0): a pair
    /// of materials adheres with `√(Δγ_i Δγ_j)` through the adhesive MDR law. Left out of the
    /// serialisation when absent, as `force_path`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub work_of_adhesion_j_per_m2: Option<f64>,
}

/// `[contact]`: the law of each kind by its registered name (`crate::laws::registry`) and,
/// besides, the declared parameters of those laws ([`mdr_contact::params`]; e.g.
/// `critical_line_load_n_per_m` of `mdr`, `friction` of `mindlin`): the validation checks each
/// against its law's declaration and refuses any key no chosen law declares.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct ContactSection {
    /// Normal law: the name of a registered law (`mdr`, `hertz`, `thornton`, …).
    pub normal: String,
    /// Tangential law (default `none`).
    #[serde(default)]
    pub tangential: Option<String>,
    /// Damping law (default `none`).
    #[serde(default)]
    pub damping: Option<String>,
    /// Rolling-resistance law (default `epsd`, off while its `rolling_friction` is 0).
    #[serde(default)]
    pub rolling: Option<String>,
    /// The other keys: the chosen laws' parameters by their declared keys (in key order).
    #[serde(flatten)]
    pub law_parameters: BTreeMap<String, ParamValue>,
}

impl ContactSection {
    /// The law of `kind` the table names, if it names one.
    pub fn chosen(&self, kind: LawKind) -> Option<&str> {
        match kind {
            LawKind::Normal => Some(&self.normal),
            LawKind::Tangential => self.tangential.as_deref(),
            LawKind::Damping => self.damping.as_deref(),
            LawKind::Rolling => self.rolling.as_deref(),
        }
    }

    /// The number given for `key`, if any.
    pub fn number(&self, key: &str) -> Option<f64> {
        match self.law_parameters.get(key) {
            Some(ParamValue::Number(v)) => Some(*v),
            _ => None,
        }
    }
}

/// Written in one fixed order, so that a scene's serialisation (which a checkpoint's
/// fingerprint hashes) does not depend on where its keys came from: `normal`, the normal law's
/// parameters in key order, `tangential` (if given), then each sub-model kind's parameters in
/// [`crate::laws::registry::SubModelKind::keys`] order with `damping` (always, `none` when not
/// given) before the damping laws' and `rolling` (if given) before the rolling laws'.
impl Serialize for ContactSection {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use crate::laws::registry::{is_sub_model_key, SUB_MODEL_KINDS};
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("normal", &self.normal)?;
        for (key, value) in &self.law_parameters {
            if !is_sub_model_key(key) {
                map.serialize_entry(key, value)?;
            }
        }
        for kind in &SUB_MODEL_KINDS {
            let name = match kind.kind {
                // `damping` is written even when not given (as `none`).
                LawKind::Damping => self.chosen(kind.kind).or(Some(kind.default)),
                _ => self.chosen(kind.kind),
            };
            if let Some(name) = name {
                map.serialize_entry(kind.key, name)?;
            }
            for key in kind.keys() {
                if let Some(value) = self.law_parameters.get(key) {
                    map.serialize_entry(key, value)?;
                }
            }
        }
        map.end()
    }
}

/// The value of a law's parameter in `[contact]`: a number, or anything else (refused by the
/// validation, with the key's line).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ParamValue {
    /// A number (an integer is read as its `f64`).
    Number(f64),
    /// Any other value.
    Other(toml::Value),
}

/// How particle radii are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SizeDistribution {
    /// Every particle has `radius_m`.
    Mono,
    /// Uniform in `[radius_min_m, radius_max_m]`.
    Uniform,
    /// Normal with `radius_m` mean and `radius_std_m`, truncated to `[radius_min_m, radius_max_m]`.
    Normal,
}

/// How particles are placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PlacementKind {
    /// Simple cubic lattice filling the region, spacing `2 r_max (1 + gap_fraction)`.
    Lattice,
    /// Random non-overlapping fill of the region (seeded).
    Random,
    /// Read `x_m,y_m,z_m,radius_m` columns (optional `vx_m_per_s,vy_m_per_s,vz_m_per_s`) from CSV.
    Csv,
    /// Read a LAMMPS data file (`atom_style sphere`: id type diameter density x y z).
    Lammps,
}

/// `[[particles]]`: one group of spheres.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParticleGroup {
    /// Material name.
    pub material: String,
    /// Number of particles (lattice and random; for files, at most this many are read).
    #[serde(default)]
    pub count: Option<u64>,
    /// Radius (m): the mono-size radius, or the mean of `normal`.
    #[serde(default)]
    pub radius_m: Option<f64>,
    /// Size distribution (default `mono`).
    #[serde(default)]
    pub size_distribution: Option<SizeDistribution>,
    /// Smallest radius (m) of `uniform`/`normal`.
    #[serde(default)]
    pub radius_min_m: Option<f64>,
    /// Largest radius (m) of `uniform`/`normal`.
    #[serde(default)]
    pub radius_max_m: Option<f64>,
    /// Standard deviation (m) of `normal`.
    #[serde(default)]
    pub radius_std_m: Option<f64>,
    /// `uniform`/`normal`: round every drawn radius down to one of this many + 1 equally spaced
    /// values from `radius_min_m` to `radius_max_m` (2 to 255; the neighbour-list path binds its laws per
    /// distinct radius and holds at most 256 species); continuous when absent.
    #[serde(default)]
    pub radius_classes: Option<u32>,
    /// Placement.
    pub placement: PlacementKind,
    /// Lower corner of the region (m) for `lattice`/`random`.
    #[serde(default)]
    pub region_min_m: Option<[f64; 3]>,
    /// Upper corner of the region (m) for `lattice`/`random`.
    #[serde(default)]
    pub region_max_m: Option<[f64; 3]>,
    /// `lattice`/`random`: keep only the spheres whose centre lies within this distance (m) of
    /// the region's central line parallel to z (a cylindrical region); `count` is the number
    /// placed in the box before this trim.
    #[serde(default)]
    pub region_radius_m: Option<f64>,
    /// Lattice: extra gap between neighbours as a fraction of the diameter (default 0.01).
    #[serde(default)]
    pub gap_fraction: Option<f64>,
    /// Lattice: random jitter of each centre as a fraction of the gap (default 0; seeded).
    #[serde(default)]
    pub jitter_fraction: Option<f64>,
    /// `csv`/`lammps`: file, relative to the scene file.
    #[serde(default)]
    pub file: Option<String>,
    /// `lammps`: metres per LAMMPS length unit (default 1).
    #[serde(default)]
    pub length_scale_m: Option<f64>,
    /// Largest initial overlap of this group's spheres with any sphere or wall, as a fraction
    /// of the smaller radius (default 0.01): raise it to start from a settled packing, whose
    /// contacts overlap. Left out of the serialisation when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_initial_overlap_fraction: Option<f64>,
    /// Initial velocity of every particle of the group (m/s).
    #[serde(default)]
    pub velocity_m_per_s: Option<[f64; 3]>,
}

/// Kind of wall.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WallKind {
    /// An infinite plane (half-space) through `point_m` with outward `normal`.
    Plane,
    /// An open-top (or closed) box container between `min_m` and `max_m`, walls `thickness_m`.
    Box,
    /// A cylindrical container (inner surface; triangle mesh) around `axis` through `center_m`.
    Cylinder,
    /// A triangle mesh read from an STL or OBJ file.
    Mesh,
    /// A horizontal disc with a circular hole (a flat-bottomed hopper's bottom).
    OrificePlate,
    /// A conical funnel (frustum, open at both ends) around `axis` from `center_m` (radius
    /// `radius_m`) to `length_m` along the axis (radius `top_radius_m`).
    Cone,
}

/// `[[walls]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallSection {
    /// Kind of wall.
    pub kind: WallKind,
    /// Material name.
    pub material: String,
    /// Plane: a point on it (m).
    #[serde(default)]
    pub point_m: Option<[f64; 3]>,
    /// Plane: outward unit normal (normalised on reading); cylinder: axis direction.
    #[serde(default)]
    pub normal: Option<[f64; 3]>,
    /// Box: lower corner of the inside (m).
    #[serde(default)]
    pub min_m: Option<[f64; 3]>,
    /// Box: upper corner of the inside (m).
    #[serde(default)]
    pub max_m: Option<[f64; 3]>,
    /// Box: whether the top face is open (default true).
    #[serde(default)]
    pub open_top: Option<bool>,
    /// Box / orifice plate / cylinder / cone: wall thickness (m), default: a tenth of the smallest
    /// inside size (box), a tenth of the outer radius (plate), a fifth of the radius (cylinder), a
    /// tenth of the larger radius (cone).
    #[serde(default)]
    pub thickness_m: Option<f64>,
    /// Cylinder: centre of the axis (m); cone: centre of its `radius_m` end (m); orifice plate:
    /// centre of the hole (m).
    #[serde(default)]
    pub center_m: Option<[f64; 3]>,
    /// Cylinder / cone: unit axis (default `[0, 0, 1]`).
    #[serde(default)]
    pub axis: Option<[f64; 3]>,
    /// Cylinder: inner radius (m); cone: inner radius at `center_m` (m).
    #[serde(default)]
    pub radius_m: Option<f64>,
    /// Cone: inner radius at the far end, `length_m` along the axis from `center_m` (m).
    #[serde(default)]
    pub top_radius_m: Option<f64>,
    /// Cylinder / cone: length along the axis (m).
    #[serde(default)]
    pub length_m: Option<f64>,
    /// Cylinder: whether both ends are closed by discs (default false).
    #[serde(default)]
    pub capped: Option<bool>,
    /// Cylinder / cone / orifice plate: number of segments around the circle (default 48).
    #[serde(default)]
    pub segments: Option<u32>,
    /// Cylinder / cone / orifice plate: on the neighbour-list path the spheres touch the exact surface of
    /// revolution (no facets, as LAMMPS's `region cylinder` / `region cone` walls) instead of the
    /// `segments` flat pieces, which rapier still uses for its bounding boxes (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exact_surface: Option<bool>,
    /// Orifice plate: outer radius of the plate (m).
    #[serde(default)]
    pub outer_radius_m: Option<f64>,
    /// Orifice plate: hole diameter (m).
    #[serde(default)]
    pub orifice_diameter_m: Option<f64>,
    /// Mesh: STL or OBJ file, relative to the scene file.
    #[serde(default)]
    pub file: Option<String>,
    /// Mesh: scale factor from file units to metres (default 1).
    #[serde(default)]
    pub scale: Option<f64>,
    /// Mesh: translation applied after scaling (m).
    #[serde(default)]
    pub offset_m: Option<[f64; 3]>,
    /// Kinematic rotation about `rotation_center_m` (rad/s); fixed wall when absent.
    #[serde(default)]
    pub angular_velocity_rad_per_s: Option<[f64; 3]>,
    /// Centre of the kinematic rotation (m), default the origin.
    #[serde(default)]
    pub rotation_center_m: Option<[f64; 3]>,
    /// Simulated time (s) at which the wall is removed (a plug that opens); never when absent.
    #[serde(default)]
    pub removed_at_s: Option<f64>,
}
