//! The settled-bed system of `mdr-dem bench bed` on the GPU ([`GpuBed`]): one species on the
//! floor `z = 0` in the x/y periodic box.

use crate::accessors::system_accessors;
use crate::device::{GpuContext, GpuError};
use crate::law::{BoundLaws, DeviceLaw, GpuLaws};
use crate::system::{System, SystemSpec};
use crate::walls::{DeviceWall, Plane};
use mdr_rapier::neighbour_list::bed::{Bed, BedError, BenchSettings};
use mdr_rapier::neighbour_list::boundary::Boundary;
use nalgebra::Vector3;

pub use crate::system::{GpuBooks, GpuOptions, GpuPair, GpuState};

/// The reference bed system (`reference_system` of `mdr_rapier::neighbour_list::bed`: the
/// floor `z = 0`, x/y periodic box, `g = 1` along −z, `dt = 1e-4`, Hertz or MDR with Mindlin and
/// Hertzian viscous damping, or the contact model of [`GpuOptions::laws`]) stepped on the device.
#[derive(Debug)]
pub struct GpuBed {
    system: System,
    laws: GpuLaws,
    yield_overlap: f64,
}

impl GpuBed {
    /// The system of `settings` (law, skin, orientation, tile) on `bed` (the reference bed:
    /// every sphere of diameter 1 and density 1), uploaded to `ctx`'s device; the contact model
    /// is `options.laws` where given. Every buffer is checked against the adapter's limits
    /// before it is allocated.
    pub fn new(
        ctx: &GpuContext,
        bed: &Bed,
        settings: &BenchSettings,
        options: &GpuOptions,
    ) -> Result<Self, GpuError> {
        settings.validate()?;
        options.validate()?;
        if let Some(i) = (0..bed.len()).find(|&i| {
            (bed.diameter[i] - 1.0).abs() > 1e-12 || (bed.density[i] - 1.0).abs() > 1e-12
        }) {
            return Err(BedError::NotReference {
                sphere: i + 1,
                diameter: bed.diameter[i],
                density: bed.density[i],
            }
            .into());
        }
        if bed.is_empty() {
            return Err(GpuError::OutOfRange {
                name: "particles",
                value: 0.0,
                range: "[1, inf)",
            });
        }
        let tiled;
        let bed = if settings.tile > 1 {
            tiled = bed.tiled(settings.tile, settings.tile)?;
            &tiled
        } else {
            bed
        };
        let n = bed.len();
        let laws = options.laws.unwrap_or_else(|| GpuLaws::of(settings));
        let bound = BoundLaws::of_reference_system(bed, settings, &laws)?;
        let Boundary::PeriodicXY { lo, hi } = bound.boundary else {
            return Err(GpuError::Unsupported(
                "the bed has the x/y periodic box of the reference bed only".to_owned(),
            ));
        };
        let cutoff = 2.0 * bound.species.radius + settings.skin + bound.neck_reach;
        bound.boundary.check_cutoff(cutoff)?;
        let zeros = vec![Vector3::zeros(); n];
        let system = System::new(
            ctx,
            &SystemSpec {
                position: &bed.position,
                linvel: &zeros,
                angvel: &zeros,
                species: vec![0; n],
                species_table: vec![bound.species],
                sphere_laws: vec![bound.sphere],
                wall_laws: vec![bound.floor],
                walls: vec![DeviceWall::fixed_plane(
                    0,
                    Plane::infinite(Vector3::z(), Vector3::zeros()),
                )],
                periodic: Some((lo, hi)),
                gravity: Vector3::new(0.0, 0.0, bound.gravity_z),
                dt: bound.dt,
                skin: settings.skin,
                neck_reach: bound.neck_reach,
                law_code: laws.normal.code(),
                normal_words: laws.normal.state_words(),
                rolling: laws.rolling.is_some(),
                // The reference system's Hertzian dashpot.
                stiffness_damping: false,
                orientation: settings.orientation,
                // The benchmark keeps no books (the CPU bench's `NoBooks`).
                books: false,
                sink: None,
                options: *options,
            },
        )?;
        Ok(Self {
            system,
            laws,
            yield_overlap: bound.yield_overlap,
        })
    }

    system_accessors!();

    /// `steps` steps: per step, the rebuild decision, the list build when due (indirect
    /// dispatches of zero size otherwise, so the host never waits inside a batch), the forces
    /// and the integration. Waits for the device at the end and checks the overflow flags.
    pub fn step(&mut self, steps: usize) -> Result<(), GpuError> {
        self.system.step(steps)
    }

    /// The contact model.
    pub fn laws(&self) -> GpuLaws {
        self.laws
    }

    /// The whole state, read back (its wall slots are the floor contacts, one per particle).
    pub fn state(&self) -> Result<GpuState, GpuError> {
        self.system.state()
    }

    /// The yield overlap `u_c` of the sphere–sphere law (infinite for Hertz).
    pub fn yield_overlap(&self) -> f64 {
        self.yield_overlap
    }
}
