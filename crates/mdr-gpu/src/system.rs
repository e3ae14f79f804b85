//! A system of spheres on the device: several species with their laws bound per species pair,
//! walls (`crate::walls`), open space or the x/y periodic box, gravity; buffers, pipelines, steps and
//! read-back ([`System`]). The settled bed ([`crate::GpuBed`]) and the scenes
//! ([`crate::GpuScene`]) are systems.

use crate::device::{GpuContext, GpuError};
use crate::law::LawConstants;
use crate::sink::{sink_constants, spot_words};
use crate::walls::{wall_constants, DeviceWall};
use mdr_rapier::neighbour_list::particles::Species;
use mdr_sim::walls::Sink;
use nalgebra::Vector3;
use wgpu::util::DeviceExt;

/// Threads per workgroup of the particle and cell kernels (`WG` of `bed.wgsl`).
const WORKGROUP: u32 = 64;
/// Steps encoded per command buffer between two status checks.
const STEPS_PER_SUBMIT: usize = 200;
/// Storage buffers the step binds.
const STORAGE_BINDINGS: u32 = 20;
/// Set in a key while its pair touches (`ACTIVE` of `bed.wgsl`).
const ACTIVE: u32 = 0x8000_0000;
/// f64 words of a bound law (`Law` of `bed.wgsl`).
const LAW_WORDS: u64 = (std::mem::size_of::<LawConstants>() / 8) as u64;
/// Status words (`S_*` of `bed.wgsl`).
const STATUS_WORDS: usize = 7;
/// `S_CROSSING_STEP` of `bed.wgsl` while no sphere crossed a wall.
const NO_CROSSING: u32 = u32::MAX;

/// Settings of a GPU system's lists and grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpuOptions {
    /// Neighbour slots per particle (every neighbour within `r_i + r_j + skin`; the reference
    /// bed has at most 11 with the default skin). A particle with more stops the run with
    /// [`GpuError::NeighbourOverflow`].
    pub max_neighbours: u32,
    /// Particles per cell of the binning grid (cells of side `2 r_max + skin`; the reference
    /// bed has at most 4). More stops the run with [`GpuError::CellOverflow`].
    pub cell_capacity: u32,
    /// The bed's contact model, when it is not the one of
    /// [`mdr_rapier::neighbour_list::bed::BenchSettings::law`] (that normal law with Mindlin and
    /// damping, no rolling resistance): another normal law (Thornton, the adhesive MDR law) or
    /// rolling resistance. Scenes take their contact model from the scene file.
    pub laws: Option<crate::GpuLaws>,
}

impl Default for GpuOptions {
    fn default() -> Self {
        Self {
            max_neighbours: 16,
            cell_capacity: 12,
            laws: None,
        }
    }
}

impl GpuOptions {
    /// Check both sizes: `max_neighbours` in `[1, 64]`, `cell_capacity` in `[1, 64]`.
    pub fn validate(&self) -> Result<(), GpuError> {
        for (name, value) in [
            ("max_neighbours", self.max_neighbours),
            ("cell_capacity", self.cell_capacity),
        ] {
            if !(1..=64).contains(&value) {
                return Err(GpuError::OutOfRange {
                    name,
                    value: f64::from(value),
                    range: "[1, 64]",
                });
            }
        }
        Ok(())
    }
}

/// The uniform block of `bed.wgsl` (`Params`), field for field.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    box_lo: [f64; 2],
    box_len: [f64; 2],
    grid_lo: [f64; 3],
    cell_side: [f64; 3],
    skin: f64,
    dt: f64,
    gravity: [f64; 3],
    search_reach: f64,
    n: u32,
    law: u32,
    orientation: u32,
    groups_x: u32,
    cells_x: u32,
    cells_y: u32,
    cells_z: u32,
    cell_groups_x: u32,
    species: u32,
    walls: u32,
    periodic: u32,
    walls_removed: u32,
}

/// Everything a [`System`] is made of.
pub(crate) struct SystemSpec<'a> {
    pub position: &'a [Vector3<f64>],
    pub linvel: &'a [Vector3<f64>],
    pub angvel: &'a [Vector3<f64>],
    /// Species index of each particle.
    pub species: Vec<u32>,
    pub species_table: Vec<Species>,
    /// Sphere laws by species pair `(a, b)` at `a · species + b`.
    pub sphere_laws: Vec<LawConstants>,
    /// Wall laws by `(species, wall)` at `species · walls + wall`.
    pub wall_laws: Vec<LawConstants>,
    pub walls: Vec<DeviceWall>,
    /// The x/y periodic box `(lo, hi)`, or open space.
    pub periodic: Option<([f64; 2], [f64; 2])>,
    pub gravity: Vector3<f64>,
    pub dt: f64,
    pub skin: f64,
    /// The adhesive necks' reach (added to the list's cut-off).
    pub neck_reach: f64,
    /// The normal law's code and f64 words of state (`DeviceLaw`).
    pub law_code: u32,
    pub normal_words: u32,
    pub rolling: bool,
    /// Whether the dashpot is the stiffness-viscous one (`LawConstants`' `η` and reduced mass)
    /// rather than the Hertzian one.
    pub stiffness_damping: bool,
    pub orientation: bool,
    /// Whether the force pass books the contacts' works ([`GpuBooks`]).
    pub books: bool,
    /// The scene's sink (`[run] delete_below_m`), whose spheres the integration parks.
    pub sink: Option<&'a Sink>,
    pub options: GpuOptions,
}

/// The works one particle's contacts booked on the device since the start (J), summed over
/// its steps in the force pass (`bed.wgsl`, `BOOKED`); a sphere pair books half of each work
/// into each of its spheres. The energy the particle took out of the run when the sink parked
/// it is booked by the integration. The field order is the shader's (`B_*`).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuBooks {
    /// Plastic work of the contacts that ended (`NormalLaw::dissipated_work` less the adhesive
    /// work); the live contacts' is a function of their histories.
    pub plastic: f64,
    /// Work dissipated by friction (Mindlin's gross slip).
    pub friction: f64,
    /// Work dissipated by the normal and tangential dashpots.
    pub damping: f64,
    /// Work dissipated by rolling resistance (its slip, and the springs released when their
    /// contacts opened).
    pub rolling: f64,
    /// Energy the tangential springs gained without work (negative when lost).
    pub tangential_stiffness: f64,
    /// Energy the rolling springs gained without work (negative when lost).
    pub rolling_stiffness: f64,
    /// Adhesive work: the energy the adhesive springs held when they let go.
    pub adhesive: f64,
    /// Work the turning walls did on the particle (their force times the wall's velocity at
    /// the contact point, per step).
    pub wall_work: f64,
    /// Kinetic and gravitational energy the particle took out of the run when the sink
    /// (`[run] delete_below_m`) parked it, less what it has on its spot.
    pub removed: f64,
}

impl GpuBooks {
    /// `f64` words per particle (`BOOK_WORDS` of `bed.wgsl`).
    const WORDS: u64 = (std::mem::size_of::<GpuBooks>() / 8) as u64;

    /// Add `other` field by field.
    pub fn add(&mut self, other: &GpuBooks) {
        self.plastic += other.plastic;
        self.friction += other.friction;
        self.damping += other.damping;
        self.rolling += other.rolling;
        self.tangential_stiffness += other.tangential_stiffness;
        self.rolling_stiffness += other.rolling_stiffness;
        self.adhesive += other.adhesive;
        self.wall_work += other.wall_work;
        self.removed += other.removed;
    }

    /// The sum over `books`, in their order.
    pub fn total(books: &[GpuBooks]) -> GpuBooks {
        books.iter().fold(GpuBooks::default(), |mut t, b| {
            t.add(b);
            t
        })
    }
}

/// One sphere–sphere pair of the device's list, as the CPU's half list has it (`i < j`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpuPair {
    /// The lower index.
    pub i: u32,
    /// The higher index.
    pub j: u32,
    /// Image code of `j` as seen from `i` (`Image::code`).
    pub image: u8,
    /// Whether it touched (or held, adhesively) at the last force evaluation.
    pub active: bool,
    /// The normal law's history: the largest overlap so far.
    pub max_overlap: f64,
    /// The rest of the normal law's state: Thornton's unloading coefficient and residual
    /// overlap, or the adhesive law's attached radius (then zero); zero for Hertz and MDR.
    pub normal_state: [f64; 2],
    /// Mindlin's tangential displacement `ξ`.
    pub displacement: Vector3<f64>,
    /// Mindlin's contact radius of the last step.
    pub contact_radius: f64,
    /// The rolling resistance spring's torque (zero without rolling resistance).
    pub rolling_torque: Vector3<f64>,
    /// The rolling resistance spring's stiffness of the last step (zero without rolling
    /// resistance).
    pub rolling_stiffness: f64,
}

/// The device state read back: particles, the touching pairs' histories, the wall contacts.
#[derive(Debug, Clone, PartialEq)]
pub struct GpuState {
    /// Positions.
    pub position: Vec<Vector3<f64>>,
    /// Velocities.
    pub linvel: Vec<Vector3<f64>>,
    /// Angular velocities.
    pub angvel: Vec<Vector3<f64>>,
    /// Orientations `(x, y, z, w)` (identity when not integrated).
    pub rotation: Vec<[f64; 4]>,
    /// The list, one entry per pair (`i < j`), sorted by `(i, j, image)`.
    pub pairs: Vec<GpuPair>,
    /// Pairs whose two entries (in `i`'s slots and in `j`'s) differ in any bit or where one
    /// is missing: zero, since both particles evaluate a pair with the same arithmetic.
    pub asymmetric_pairs: usize,
    /// Per wall slot (`particle · walls + wall`; per particle on the bed, whose one wall is
    /// the floor): the contact's `(max overlap, ξ, contact radius)`, `None` when apart.
    pub floor: Vec<Option<(f64, Vector3<f64>, f64)>>,
    /// Per wall slot: the contact's rolling torque (zero when apart or without rolling
    /// resistance).
    pub floor_rolling_torque: Vec<Vector3<f64>>,
    /// Per wall slot: the rest of the normal law's state (as [`GpuPair::normal_state`]).
    pub floor_normal_state: Vec<[f64; 2]>,
    /// Per wall slot: the rolling spring's stiffness (as [`GpuPair::rolling_stiffness`]).
    pub floor_rolling_stiffness: Vec<f64>,
    /// Positions at the last list build (zero before the first).
    pub built: Vec<Vector3<f64>>,
    /// Whether the next force pass builds the lists (a particle moved more than half the skin
    /// since the last build, or none was made yet).
    pub rebuild_due: bool,
    /// Walls (wall slots per particle).
    pub walls: usize,
    /// Neighbour-list builds so far.
    pub rebuilds: u64,
    /// Per particle, the works its contacts booked on the device ([`GpuBooks`]); empty for a
    /// system that keeps no books (the settled bed's benchmark).
    pub books: Vec<GpuBooks>,
}

struct Buffers {
    params: wgpu::Buffer,
    pos: wgpu::Buffer,
    vel: wgpu::Buffer,
    angvel: wgpu::Buffer,
    built: wgpu::Buffer,
    wrench: wgpu::Buffer,
    rotation: wgpu::Buffer,
    walls: wgpu::Buffer,
    counts: wgpu::Buffer,
    keys: wgpu::Buffer,
    h_state: wgpu::Buffer,
    h_xi: wgpu::Buffer,
    h_radius: wgpu::Buffer,
    cell_count: wgpu::Buffer,
    cell_items: wgpu::Buffer,
    status: wgpu::Buffer,
    species: wgpu::Buffer,
    tables: wgpu::Buffer,
    laws: wgpu::Buffer,
    books: wgpu::Buffer,
    indirect: wgpu::Buffer,
}

impl Buffers {
    fn all(&self) -> [&wgpu::Buffer; 21] {
        [
            &self.params,
            &self.pos,
            &self.vel,
            &self.angvel,
            &self.built,
            &self.wrench,
            &self.rotation,
            &self.walls,
            &self.counts,
            &self.keys,
            &self.h_state,
            &self.h_xi,
            &self.h_radius,
            &self.cell_count,
            &self.cell_items,
            &self.status,
            &self.species,
            &self.tables,
            &self.laws,
            &self.books,
            &self.indirect,
        ]
    }
}

struct Pipelines {
    decide: wgpu::ComputePipeline,
    clear_cells: wgpu::ComputePipeline,
    bin: wgpu::ComputePipeline,
    search: wgpu::ComputePipeline,
    forces: wgpu::ComputePipeline,
    integrate: wgpu::ComputePipeline,
}

/// A system of spheres stepped on the device.
pub(crate) struct System {
    device: wgpu::Device,
    queue: wgpu::Queue,
    buffers: Buffers,
    pipelines: Pipelines,
    bind_group: wgpu::BindGroup,
    decide_group: wgpu::BindGroup,
    n: usize,
    walls: usize,
    max_neighbours: u32,
    cell_capacity: u32,
    groups: (u32, u32),
    normal_words: u32,
    state_words: u32,
    wall_words: u32,
    books: bool,
    device_bytes: u64,
    /// The uniform block as on the device (the host writes its removal stage).
    params: Params,
    steps: u64,
    /// The forces of step `steps` are evaluated and its integration is still to come
    /// ([`System::step_and_evaluate`]).
    pending_integration: bool,
}

impl std::fmt::Debug for System {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("System")
            .field("particles", &self.n)
            .field("steps", &self.steps)
            .finish()
    }
}

/// Validation and out-of-memory errors of the device calls between [`ErrorScopes::push`] and
/// [`ErrorScopes::pop`], returned as [`GpuError::Device`] instead of wgpu's default panic.
struct ErrorScopes {
    validation: wgpu::ErrorScopeGuard,
    memory: wgpu::ErrorScopeGuard,
}

impl ErrorScopes {
    fn push(device: &wgpu::Device) -> Self {
        let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        Self { validation, memory }
    }

    fn pop(self) -> Result<(), GpuError> {
        let validation = pollster::block_on(self.validation.pop());
        let memory = pollster::block_on(self.memory.pop());
        match validation.or(memory) {
            Some(e) => Err(GpuError::Device(e.to_string())),
            None => Ok(()),
        }
    }
}

/// `a · b · …` in bytes, or `None` on overflow.
fn bytes_of(factors: &[u64]) -> Option<u64> {
    factors.iter().try_fold(1u64, |acc, &f| acc.checked_mul(f))
}

/// The lower and upper end of `values`.
fn range_of(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

impl System {
    /// Upload `spec` to `ctx`'s device. Every buffer is checked against the adapter's limits
    /// before it is allocated.
    pub fn new(ctx: &GpuContext, spec: &SystemSpec<'_>) -> Result<Self, GpuError> {
        let options = &spec.options;
        options.validate()?;
        let n = spec.position.len();
        if n == 0 {
            return Err(GpuError::OutOfRange {
                name: "particles",
                value: 0.0,
                range: "[1, inf)",
            });
        }
        let nspecies = spec.species_table.len();
        let nwalls = spec.walls.len();
        if spec.linvel.len() != n
            || spec.angvel.len() != n
            || spec.species.len() != n
            || spec.species.iter().any(|&s| s as usize >= nspecies)
            || spec.sphere_laws.len() != nspecies * nspecies
            || spec.wall_laws.len() != nspecies * nwalls
        {
            return Err(GpuError::Unsupported(
                "inconsistent system: particle arrays, species and law tables differ in size"
                    .to_owned(),
            ));
        }
        // f64 words per slot: the normal law's state and the rolling law's (torque, stiffness).
        let normal_words = spec.normal_words;
        let state_words = normal_words + if spec.rolling { 4 } else { 0 };
        // Per wall slot: active, that state, ξ (3), a.
        let wall_words = 1 + state_words + 4;
        let r_max = spec
            .species_table
            .iter()
            .map(|s| s.radius)
            .fold(0.0, f64::max);
        // A held adhesive pair is at most the neck's reach apart (the CPU list's cut-off).
        let search_reach = spec.skin + spec.neck_reach;
        let cutoff = 2.0 * r_max + search_reach;

        // The binning grid: cells of side ≥ cutoff; periodic x/y cells over the box, or cells
        // over the particles' extent with a margin (particles beyond it are clamped into the
        // edge cells, which keeps neighbouring cells neighbours).
        // The sink's parking spots lie in the grid too: parked spheres fill no edge cell.
        let spots = spec
            .sink
            .map(|sink| spot_words(sink, n))
            .unwrap_or_default();
        let extent = || {
            spec.position
                .iter()
                .copied()
                .chain(spots.chunks_exact(3).map(Vector3::from_column_slice))
        };
        let (xr, yr, zr) = (
            range_of(extent().map(|p| p.x)),
            range_of(extent().map(|p| p.y)),
            range_of(extent().map(|p| p.z)),
        );
        let open_axis = |(lo, hi): (f64, f64)| {
            let margin = 0.5 * (hi - lo) + cutoff;
            let (lo, hi) = (lo - margin, hi + margin);
            let cells = (((hi - lo) / cutoff).floor() as u64).max(1);
            (lo, cells, (hi - lo) / cells as f64)
        };
        let (box_lo, box_len, x_axis, y_axis) = match spec.periodic {
            Some((lo, hi)) => {
                let len = [hi[0] - lo[0], hi[1] - lo[1]];
                let axis = |k: usize| {
                    let cells = ((len[k] / cutoff).floor() as u64).max(1);
                    (lo[k], cells, len[k] / cells as f64)
                };
                (lo, len, axis(0), axis(1))
            }
            None => ([0.0; 2], [0.0; 2], open_axis(xr), open_axis(yr)),
        };
        let z_lo = zr.0 - cutoff;
        let cells_z = ((zr.1 - z_lo) / cutoff).floor() as u64 + 3;
        let (cells_x, cells_y) = (x_axis.1, y_axis.1);
        let ncells = bytes_of(&[cells_x, cells_y, cells_z]).unwrap_or(u64::MAX);

        let limits = &ctx.limits;
        let adapter = ctx.adapter_name();
        if limits.max_storage_buffers_per_shader_stage < STORAGE_BINDINGS {
            return Err(GpuError::TooFewBindings {
                adapter,
                available: limits.max_storage_buffers_per_shader_stage,
                needed: STORAGE_BINDINGS,
            });
        }
        let n64 = n as u64;
        let slots = u64::from(options.max_neighbours);
        let cap = u64::from(options.cell_capacity);
        // Sizes, checked before anything is allocated; indices in the shaders are u32.
        let ns64 = nspecies as u64;
        let book_bytes = if spec.books {
            bytes_of(&[n64, GpuBooks::WORDS, 8])
        } else {
            Some(0)
        };
        let sizes: [(&'static str, Option<u64>); 18] = [
            ("position", bytes_of(&[n64, 24])),
            ("velocity", bytes_of(&[n64, 24])),
            ("angular velocity", bytes_of(&[n64, 24])),
            ("positions at the build", bytes_of(&[n64, 24])),
            ("wrench", bytes_of(&[n64, 48])),
            ("rotation", bytes_of(&[n64, 32])),
            (
                "wall histories",
                bytes_of(&[n64, nwalls as u64, u64::from(wall_words), 8]),
            ),
            ("neighbour counts", bytes_of(&[n64, 4])),
            ("neighbour keys", bytes_of(&[n64, slots, 4])),
            (
                "normal histories",
                bytes_of(&[n64, slots, u64::from(state_words), 8]),
            ),
            ("tangential histories", bytes_of(&[n64, slots, 24])),
            ("contact radii", bytes_of(&[n64, slots, 8])),
            ("cell counts", bytes_of(&[ncells, 4])),
            ("cell items", bytes_of(&[ncells, cap, 4])),
            ("species", bytes_of(&[n64, 4])),
            ("tables", bytes_of(&[4 * ns64 + spots.len() as u64, 8])),
            (
                "laws",
                bytes_of(&[ns64, ns64 + nwalls as u64, 8 * LAW_WORDS]),
            ),
            ("work books", book_bytes),
        ];
        let u32_indices = bytes_of(&[n64, slots, u64::from(state_words.max(3))])
            .is_some_and(|k| k <= u64::from(u32::MAX))
            && bytes_of(&[n64, nwalls as u64, u64::from(wall_words)])
                .is_some_and(|k| k <= u64::from(u32::MAX))
            && bytes_of(&[ncells, cap]).is_some_and(|k| k <= u64::from(u32::MAX))
            && bytes_of(&[n64, 9]).is_some_and(|k| k < u64::from(ACTIVE));
        let mut device_bytes = 0u64;
        for (buffer, bytes) in sizes {
            let bytes = bytes.unwrap_or(u64::MAX);
            for (limit, limit_name) in [
                (
                    limits.max_storage_buffer_binding_size,
                    "max_storage_buffer_binding_size",
                ),
                (limits.max_buffer_size, "max_buffer_size"),
            ] {
                if bytes > limit {
                    return Err(GpuError::TooLarge {
                        particles: n,
                        buffer,
                        bytes,
                        adapter: adapter.clone(),
                        limit,
                        limit_name,
                    });
                }
            }
            device_bytes = device_bytes.saturating_add(bytes);
        }
        if !u32_indices {
            return Err(GpuError::TooLarge {
                particles: n,
                buffer: "neighbour keys",
                bytes: bytes_of(&[n64, slots, 3]).unwrap_or(u64::MAX),
                adapter,
                limit: u64::from(u32::MAX),
                limit_name: "32-bit shader indices",
            });
        }
        let max_groups = u64::from(limits.max_compute_workgroups_per_dimension);
        let groups = n64.div_ceil(u64::from(WORKGROUP));
        let groups_x = groups.min(max_groups);
        let groups_y = groups.div_ceil(groups_x);
        let cell_groups = ncells.div_ceil(u64::from(WORKGROUP));
        let cell_groups_x = cell_groups.min(max_groups);
        if groups_y > max_groups || cell_groups.div_ceil(cell_groups_x) > max_groups {
            return Err(GpuError::TooLarge {
                particles: n,
                buffer: "dispatch",
                bytes: groups.max(cell_groups),
                adapter,
                limit: max_groups * max_groups,
                limit_name: "max_compute_workgroups_per_dimension²",
            });
        }

        let params = Params {
            box_lo,
            box_len,
            grid_lo: [x_axis.0, y_axis.0, z_lo],
            cell_side: [x_axis.2, y_axis.2, cutoff],
            skin: spec.skin,
            dt: spec.dt,
            gravity: spec.gravity.into(),
            search_reach,
            n: n as u32,
            law: spec.law_code,
            orientation: u32::from(spec.orientation),
            groups_x: groups_x as u32,
            cells_x: cells_x as u32,
            cells_y: cells_y as u32,
            cells_z: cells_z as u32,
            cell_groups_x: cell_groups_x as u32,
            species: nspecies as u32,
            walls: nwalls as u32,
            periodic: u32::from(spec.periodic.is_some()),
            walls_removed: 0,
        };
        let tables: Vec<f64> = spec
            .species_table
            .iter()
            .flat_map(|s| [s.radius, s.mass, s.inv_mass, s.inv_inertia])
            .chain(spots.iter().copied())
            .collect();
        let laws: Vec<LawConstants> = spec
            .sphere_laws
            .iter()
            .chain(&spec.wall_laws)
            .copied()
            .collect();

        let device = ctx.device.clone();
        let queue = ctx.queue.clone();
        let scopes = ErrorScopes::push(&device);
        let storage = wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST;
        let init = |label: &str, contents: &[u8], extra: wgpu::BufferUsages| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: storage | extra,
            })
        };
        let zeroed = |label: &str, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(16),
                usage: storage,
                mapped_at_creation: false,
            })
        };
        let flat =
            |v: &[Vector3<f64>]| -> Vec<f64> { v.iter().flat_map(|p| [p.x, p.y, p.z]).collect() };
        let identity: Vec<f64> = (0..n).flat_map(|_| [0.0, 0.0, 0.0, 1.0]).collect();
        let mut status = [0u32; STATUS_WORDS];
        status[0] = 1; // the first step builds the lists
        status[5] = NO_CROSSING;
        let buffers = Buffers {
            params: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("params"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            }),
            pos: init(
                "position",
                bytemuck::cast_slice(&flat(spec.position)),
                wgpu::BufferUsages::empty(),
            ),
            vel: init(
                "velocity",
                bytemuck::cast_slice(&flat(spec.linvel)),
                wgpu::BufferUsages::empty(),
            ),
            angvel: init(
                "angular velocity",
                bytemuck::cast_slice(&flat(spec.angvel)),
                wgpu::BufferUsages::empty(),
            ),
            built: zeroed("positions at the build", n64 * 24),
            wrench: zeroed("wrench", n64 * 48),
            rotation: init(
                "rotation",
                bytemuck::cast_slice(&identity),
                wgpu::BufferUsages::empty(),
            ),
            walls: zeroed(
                "wall histories",
                n64 * nwalls as u64 * u64::from(wall_words) * 8,
            ),
            counts: zeroed("neighbour counts", n64 * 4),
            keys: zeroed("neighbour keys", n64 * slots * 4),
            h_state: zeroed("normal histories", n64 * slots * u64::from(state_words) * 8),
            h_xi: zeroed("tangential histories", n64 * slots * 24),
            h_radius: zeroed("contact radii", n64 * slots * 8),
            cell_count: zeroed("cell counts", ncells * 4),
            cell_items: zeroed("cell items", ncells * cap * 4),
            status: init(
                "status",
                bytemuck::cast_slice(&status),
                wgpu::BufferUsages::empty(),
            ),
            species: init(
                "species",
                bytemuck::cast_slice(&spec.species),
                wgpu::BufferUsages::empty(),
            ),
            tables: init(
                "tables",
                bytemuck::cast_slice(&tables),
                wgpu::BufferUsages::empty(),
            ),
            laws: init(
                "laws",
                bytemuck::cast_slice(&laws),
                wgpu::BufferUsages::empty(),
            ),
            books: zeroed("work books", book_bytes.unwrap_or(0)),
            indirect: init(
                "indirect",
                bytemuck::cast_slice(&[0u32; 8]),
                wgpu::BufferUsages::INDIRECT,
            ),
        };

        let source = include_str!("bed.wgsl")
            .replace(
                "__MAXNCARRY__",
                &((state_words + 4) * options.max_neighbours).to_string(),
            )
            .replace("__NN__", &normal_words.to_string())
            .replace("__ROLLING__", if spec.rolling { "true" } else { "false" })
            .replace(
                "__STIFFNESS_DAMPING__",
                if spec.stiffness_damping {
                    "true"
                } else {
                    "false"
                },
            )
            .replace("__BOOKED__", if spec.books { "true" } else { "false" })
            .replace(
                "__SINK__",
                if spec.sink.is_some() { "true" } else { "false" },
            )
            .replace("__SINK_CONSTANTS__", &sink_constants(spec.sink))
            .replace("__WALLS__", &nwalls.to_string())
            .replace("__WALL_CONSTANTS__", &wall_constants(&spec.walls))
            .replace(
                "__CROSSING__",
                &format!("{:?}", mdr_sim::run::CROSSING_OVERLAP),
            )
            .replace("__MAXN__", &options.max_neighbours.to_string())
            .replace("__CELLCAP__", &options.cell_capacity.to_string());
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("bed.wgsl"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        // The decision kernel writes the indirect arguments: it alone binds them (a dispatch
        // may not read a buffer as indirect arguments while it is bound for storage).
        let entry = |binding: u32| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: if binding == 0 {
                    wgpu::BufferBindingType::Uniform
                } else {
                    wgpu::BufferBindingType::Storage { read_only: false }
                },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let all = buffers.all();
        let group = |bindings: u32| {
            let entries: Vec<_> = (0..bindings).map(entry).collect();
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("bed"),
                entries: &entries,
            });
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("bed"),
                layout: &layout,
                entries: &all[..bindings as usize]
                    .iter()
                    .enumerate()
                    .map(|(k, b)| wgpu::BindGroupEntry {
                        binding: k as u32,
                        resource: b.as_entire_binding(),
                    })
                    .collect::<Vec<_>>(),
            });
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("bed"),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
            (group, pipeline_layout)
        };
        let (bind_group, step_layout) = group(all.len() as u32 - 1);
        let (decide_group, decide_layout) = group(all.len() as u32);
        let pipeline = |entry: &str, layout: &wgpu::PipelineLayout| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let pipelines = Pipelines {
            decide: pipeline("decide", &decide_layout),
            clear_cells: pipeline("clear_cells", &step_layout),
            bin: pipeline("bin", &step_layout),
            search: pipeline("search", &step_layout),
            forces: pipeline("forces", &step_layout),
            integrate: pipeline("integrate", &step_layout),
        };
        scopes.pop()?;
        Ok(Self {
            device,
            queue,
            buffers,
            pipelines,
            bind_group,
            decide_group,
            n,
            walls: nwalls,
            max_neighbours: options.max_neighbours,
            cell_capacity: options.cell_capacity,
            groups: (groups_x as u32, groups_y as u32),
            normal_words,
            state_words,
            wall_words,
            books: spec.books,
            device_bytes,
            params,
            steps: 0,
            pending_integration: false,
        })
    }

    /// Particles.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Steps done.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Bytes of every device buffer of the system (particles, lists, histories, grid).
    pub fn device_bytes(&self) -> u64 {
        self.device_bytes
    }

    /// The step whose force pass comes next: `steps`, or `steps + 1` when the forces of step
    /// `steps` are evaluated and its integration is pending ([`System::step_and_evaluate`]).
    pub fn next_force_step(&self) -> u64 {
        self.steps + u64::from(self.pending_integration)
    }

    /// From the next force pass on, the walls of removal stage at most `stage` act no more
    /// (`Params::walls_removed` of `bed.wgsl`).
    pub fn set_walls_removed(&mut self, stage: u32) -> Result<(), GpuError> {
        if self.params.walls_removed == stage {
            return Ok(());
        }
        self.params.walls_removed = stage;
        let scopes = ErrorScopes::push(&self.device);
        self.queue
            .write_buffer(&self.buffers.params, 0, bytemuck::bytes_of(&self.params));
        self.queue.submit([]);
        scopes.pop()
    }

    /// `steps` steps: per step, the rebuild decision, the list build when due (indirect
    /// dispatches of zero size otherwise, so the host never waits inside a batch), the forces
    /// and the integration. Waits for the device at the end and checks the overflow flags.
    pub fn step(&mut self, steps: usize) -> Result<(), GpuError> {
        self.advance(steps, false)
    }

    /// `steps` steps, then the next step's forces without its integration: the state read
    /// back then holds `x_k`, `v_k` and the contacts of the force pass at `x_k`, as the CPU
    /// run samples them. The next [`System::step`] or [`System::step_and_evaluate`] begins
    /// with that integration, so the dispatches are those of plain steps.
    pub fn step_and_evaluate(&mut self, steps: usize) -> Result<(), GpuError> {
        self.advance(steps, true)
    }

    /// The kernels of `steps` steps in batches of [`STEPS_PER_SUBMIT`], finishing a pending
    /// integration first; `evaluate`: end with the next step's forces.
    fn advance(&mut self, steps: usize, evaluate: bool) -> Result<(), GpuError> {
        // The kernel sequence: `true` for a step's forces (decision, build, forces), `false`
        // for its integration.
        let mut sequence = Vec::with_capacity(2 * steps + 1);
        let mut pending = self.pending_integration;
        for _ in 0..steps {
            if !pending {
                sequence.push(true);
            }
            sequence.push(false);
            pending = false;
        }
        if evaluate && !pending {
            sequence.push(true);
            pending = true;
        }
        for batch in sequence.chunks(2 * STEPS_PER_SUBMIT) {
            let scopes = ErrorScopes::push(&self.device);
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("steps"),
                });
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("steps"),
                    timestamp_writes: None,
                });
                let p = &self.pipelines;
                for &forces in batch {
                    if forces {
                        pass.set_bind_group(0, &self.decide_group, &[]);
                        pass.set_pipeline(&p.decide);
                        pass.dispatch_workgroups(1, 1, 1);
                        pass.set_bind_group(0, &self.bind_group, &[]);
                        pass.set_pipeline(&p.clear_cells);
                        pass.dispatch_workgroups_indirect(&self.buffers.indirect, 12);
                        pass.set_pipeline(&p.bin);
                        pass.dispatch_workgroups_indirect(&self.buffers.indirect, 0);
                        pass.set_pipeline(&p.search);
                        pass.dispatch_workgroups_indirect(&self.buffers.indirect, 0);
                        pass.set_pipeline(&p.forces);
                        pass.dispatch_workgroups(self.groups.0, self.groups.1, 1);
                    } else {
                        pass.set_bind_group(0, &self.bind_group, &[]);
                        pass.set_pipeline(&p.integrate);
                        pass.dispatch_workgroups(self.groups.0, self.groups.1, 1);
                    }
                }
            }
            self.queue.submit([encoder.finish()]);
            scopes.pop()?;
            self.steps += batch.iter().filter(|&&forces| !forces).count() as u64;
            self.check_status()?;
        }
        self.pending_integration = pending;
        Ok(())
    }

    /// Wait for the device and turn its overflow flags into errors.
    fn check_status(&self) -> Result<[u32; STATUS_WORDS], GpuError> {
        let status: Vec<u32> = self.read(&self.buffers.status, 4 * STATUS_WORDS as u64)?;
        if status[2] != 0 {
            return Err(GpuError::NeighbourOverflow {
                particle: status[2] - 1,
                max_neighbours: self.max_neighbours,
            });
        }
        if status[3] != 0 {
            return Err(GpuError::CellOverflow {
                cell: status[3] - 1,
                capacity: self.cell_capacity,
            });
        }
        if status[5] != NO_CROSSING && self.walls > 0 {
            let slot = (status[6] - 1) as usize;
            // The step from its low 32 bits: at most one batch ago.
            let back = (self.steps as u32).wrapping_sub(status[5]);
            return Err(GpuError::WallCrossing {
                particle: (slot / self.walls) as u32,
                wall: (slot % self.walls) as u32,
                step: self.steps.saturating_sub(u64::from(back)),
            });
        }
        let mut words = [0u32; STATUS_WORDS];
        words.copy_from_slice(&status[..STATUS_WORDS]);
        Ok(words)
    }

    /// Neighbour-list builds so far.
    pub fn rebuilds(&self) -> Result<u64, GpuError> {
        Ok(u64::from(self.check_status()?[1]))
    }

    /// Copy `bytes` of `buffer` back to the host.
    fn read<T: bytemuck::Pod>(
        &self,
        buffer: &wgpu::Buffer,
        bytes: u64,
    ) -> Result<Vec<T>, GpuError> {
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read-back"),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("read-back"),
            });
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, bytes);
        self.queue.submit([encoder.finish()]);
        let slice = staging.slice(..);
        let (send, receive) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = send.send(r);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        receive
            .recv()
            .map_err(|e| GpuError::Readback(e.to_string()))?
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        let data = {
            let view = slice
                .get_mapped_range()
                .map_err(|e| GpuError::Readback(e.to_string()))?;
            bytemuck::pod_collect_to_vec::<u8, T>(&view)
        };
        staging.unmap();
        Ok(data)
    }

    fn read_vectors(&self, buffer: &wgpu::Buffer) -> Result<Vec<Vector3<f64>>, GpuError> {
        let flat: Vec<f64> = self.read(buffer, self.n as u64 * 24)?;
        Ok(flat
            .chunks_exact(3)
            .map(|c| Vector3::new(c[0], c[1], c[2]))
            .collect())
    }

    /// Positions only (what a comparison or a checksum needs).
    pub fn positions(&self) -> Result<Vec<Vector3<f64>>, GpuError> {
        self.read_vectors(&self.buffers.pos)
    }

    /// The whole state, read back.
    pub fn state(&self) -> Result<GpuState, GpuError> {
        let n = self.n;
        let slots = self.max_neighbours as usize;
        let status = self.check_status()?;
        let position = self.read_vectors(&self.buffers.pos)?;
        let built = self.read_vectors(&self.buffers.built)?;
        let linvel = self.read_vectors(&self.buffers.vel)?;
        let angvel = self.read_vectors(&self.buffers.angvel)?;
        let rotation: Vec<f64> = self.read(&self.buffers.rotation, n as u64 * 32)?;
        let fw = self.wall_words as usize;
        let sw = self.state_words as usize;
        let nw = self.normal_words as usize;
        let floor_flat: Vec<f64> =
            self.read(&self.buffers.walls, (n * self.walls * fw) as u64 * 8)?;
        let counts: Vec<u32> = self.read(&self.buffers.counts, n as u64 * 4)?;
        let total = (n * slots) as u64;
        let keys: Vec<u32> = self.read(&self.buffers.keys, total * 4)?;
        let h_state: Vec<f64> = self.read(&self.buffers.h_state, total * sw as u64 * 8)?;
        let h_xi: Vec<f64> = self.read(&self.buffers.h_xi, total * 24)?;
        let h_radius: Vec<f64> = self.read(&self.buffers.h_radius, total * 8)?;
        let books: Vec<GpuBooks> = if self.books {
            self.read(&self.buffers.books, n as u64 * GpuBooks::WORDS * 8)?
        } else {
            Vec::new()
        };
        let entry = |i: usize, s: usize| -> GpuPair {
            let k = i * slots + s;
            let key = keys[k] & !ACTIVE;
            let active = keys[k] & ACTIVE != 0;
            let j = key / 9;
            let code = (key % 9) as u8;
            let (lo, hi, image) = if (i as u32) < j {
                (i as u32, j, code)
            } else {
                (j, i as u32, 8 - code)
            };
            GpuPair {
                i: lo,
                j: hi,
                image,
                active,
                max_overlap: if active { h_state[sw * k] } else { 0.0 },
                normal_state: if active {
                    [1, 2].map(|w| if w < nw { h_state[sw * k + w] } else { 0.0 })
                } else {
                    [0.0; 2]
                },
                displacement: if active {
                    Vector3::new(h_xi[3 * k], h_xi[3 * k + 1], h_xi[3 * k + 2])
                } else {
                    Vector3::zeros()
                },
                contact_radius: if active { h_radius[k] } else { 0.0 },
                rolling_torque: if active && sw > nw {
                    Vector3::new(
                        h_state[sw * k + nw],
                        h_state[sw * k + nw + 1],
                        h_state[sw * k + nw + 2],
                    )
                } else {
                    Vector3::zeros()
                },
                rolling_stiffness: if active && sw > nw {
                    h_state[sw * k + nw + 3]
                } else {
                    0.0
                },
            }
        };
        let mut pairs = Vec::new();
        let mut mirrored = Vec::new();
        for (i, &count) in counts.iter().enumerate() {
            for s in 0..count as usize {
                let e = entry(i, s);
                if e.i == i as u32 {
                    pairs.push(e);
                } else {
                    mirrored.push(e);
                }
            }
        }
        pairs.sort_by_key(|e| (e.i, e.j, e.image));
        mirrored.sort_by_key(|e| (e.i, e.j, e.image));
        let bits = |e: &GpuPair| {
            (
                e.i,
                e.j,
                e.image,
                e.active,
                e.max_overlap.to_bits(),
                e.normal_state.map(f64::to_bits),
                e.displacement.map(f64::to_bits),
                e.contact_radius.to_bits(),
                e.rolling_torque.map(f64::to_bits),
                e.rolling_stiffness.to_bits(),
            )
        };
        let asymmetric_pairs = if pairs.len() == mirrored.len() {
            pairs
                .iter()
                .zip(&mirrored)
                .filter(|(a, b)| bits(a) != bits(b))
                .count()
        } else {
            pairs.len().abs_diff(mirrored.len()).max(1)
        };
        // Per wall slot: active, the normal state (nw), ξ (3), a, the rolling state.
        let floor = floor_flat
            .chunks_exact(fw)
            .map(|h| {
                let t = 1 + nw;
                (h[0] != 0.0).then(|| (h[1], Vector3::new(h[t], h[t + 1], h[t + 2]), h[t + 3]))
            })
            .collect();
        let floor_rolling_torque = floor_flat
            .chunks_exact(fw)
            .map(|h| {
                let t = 1 + nw + 4;
                if h[0] != 0.0 && fw > t {
                    Vector3::new(h[t], h[t + 1], h[t + 2])
                } else {
                    Vector3::zeros()
                }
            })
            .collect();
        let floor_normal_state = floor_flat
            .chunks_exact(fw)
            .map(|h| [2, 3].map(|w| if h[0] != 0.0 && w <= nw { h[w] } else { 0.0 }))
            .collect();
        let floor_rolling_stiffness = floor_flat
            .chunks_exact(fw)
            .map(|h| {
                let t = 1 + nw + 4 + 3;
                if h[0] != 0.0 && fw > t {
                    h[t]
                } else {
                    0.0
                }
            })
            .collect();
        Ok(GpuState {
            position,
            linvel,
            angvel,
            rotation: rotation
                .chunks_exact(4)
                .map(|q| [q[0], q[1], q[2], q[3]])
                .collect(),
            pairs,
            asymmetric_pairs,
            floor,
            floor_rolling_torque,
            floor_normal_state,
            floor_rolling_stiffness,
            built,
            rebuild_due: status[0] != 0,
            walls: self.walls,
            rebuilds: u64::from(status[1]),
            books,
        })
    }

    /// Put `state` on the device as the state after `steps` steps, before the force pass of
    /// the next one (the inverse of [`System::state`] read there): particles, positions at the
    /// build, the lists with the touching pairs' histories (`state.pairs` is the half list;
    /// each pair goes into the slots of both its particles, sorted by key as a build sorts
    /// them), the wall contacts, the rebuild decision and count. A particle with more listed
    /// neighbours than the slots is refused ([`GpuError::NeighbourOverflow`]).
    pub fn load(&mut self, state: &GpuState, steps: u64) -> Result<(), GpuError> {
        let n = self.n;
        let slots = self.max_neighbours as usize;
        let (nw, sw, fw) = (
            self.normal_words as usize,
            self.state_words as usize,
            self.wall_words as usize,
        );
        let sized = state.position.len() == n
            && state.linvel.len() == n
            && state.angvel.len() == n
            && state.rotation.len() == n
            && state.built.len() == n
            && state.walls == self.walls
            && [
                state.floor.len(),
                state.floor_rolling_torque.len(),
                state.floor_normal_state.len(),
                state.floor_rolling_stiffness.len(),
            ]
            .iter()
            .all(|&len| len == n * self.walls)
            && (state.books.is_empty() || state.books.len() == n)
            && state
                .pairs
                .iter()
                .all(|p| p.i < p.j && (p.j as usize) < n && p.image < 9);
        if !sized {
            return Err(GpuError::Unsupported(format!(
                "the state to load does not fit the system of {n} particles and {} device walls",
                self.walls
            )));
        }
        // Each particle's slots: (key, pair).
        let mut entries: Vec<Vec<(u32, usize)>> = vec![Vec::new(); n];
        for (q, pair) in state.pairs.iter().enumerate() {
            entries[pair.i as usize].push((pair.j * 9 + u32::from(pair.image), q));
            entries[pair.j as usize].push((pair.i * 9 + 8 - u32::from(pair.image), q));
        }
        let total = n * slots;
        let mut counts = vec![0u32; n];
        let mut keys = vec![0u32; total];
        let mut h_state = vec![0.0f64; total * sw];
        let mut h_xi = vec![0.0f64; total * 3];
        let mut h_radius = vec![0.0f64; total];
        for (i, list) in entries.iter_mut().enumerate() {
            if list.len() > slots {
                return Err(GpuError::NeighbourOverflow {
                    particle: i as u32,
                    max_neighbours: self.max_neighbours,
                });
            }
            list.sort_unstable();
            counts[i] = list.len() as u32;
            for (s, &(key, q)) in list.iter().enumerate() {
                let pair = &state.pairs[q];
                let k = i * slots + s;
                if !pair.active {
                    keys[k] = key;
                    continue;
                }
                keys[k] = key | ACTIVE;
                let h = &mut h_state[sw * k..sw * (k + 1)];
                h[0] = pair.max_overlap;
                h[1..nw].copy_from_slice(&pair.normal_state[..nw - 1]);
                if sw > nw {
                    h[nw..nw + 3].copy_from_slice(pair.rolling_torque.as_slice());
                    h[nw + 3] = pair.rolling_stiffness;
                }
                h_xi[3 * k..3 * k + 3].copy_from_slice(pair.displacement.as_slice());
                h_radius[k] = pair.contact_radius;
            }
        }
        // Per wall slot: active, the normal state (nw), ξ (3), a, the rolling state.
        let mut walls = vec![0.0f64; n * self.walls * fw];
        for (slot, contact) in state.floor.iter().enumerate() {
            let Some((max_overlap, xi, radius)) = contact else {
                continue;
            };
            let h = &mut walls[fw * slot..fw * (slot + 1)];
            h[0] = 1.0;
            h[1] = *max_overlap;
            h[2..1 + nw].copy_from_slice(&state.floor_normal_state[slot][..nw - 1]);
            let t = 1 + nw;
            h[t..t + 3].copy_from_slice(xi.as_slice());
            h[t + 3] = *radius;
            if fw > t + 4 {
                h[t + 4..t + 7].copy_from_slice(state.floor_rolling_torque[slot].as_slice());
                h[t + 7] = state.floor_rolling_stiffness[slot];
            }
        }
        let flat =
            |v: &[Vector3<f64>]| -> Vec<f64> { v.iter().flat_map(|p| [p.x, p.y, p.z]).collect() };
        let rotation: Vec<f64> = state.rotation.iter().flatten().copied().collect();
        let mut status = [0u32; STATUS_WORDS];
        status[0] = u32::from(state.rebuild_due);
        status[1] = u32::try_from(state.rebuilds).unwrap_or(u32::MAX);
        // The force passes' count modulo 2³², as the shader keeps it.
        status[4] = steps as u32;
        status[5] = NO_CROSSING;
        let scopes = ErrorScopes::push(&self.device);
        let b = &self.buffers;
        let write = |buffer: &wgpu::Buffer, bytes: &[u8]| {
            if !bytes.is_empty() {
                self.queue.write_buffer(buffer, 0, bytes);
            }
        };
        write(&b.pos, bytemuck::cast_slice(&flat(&state.position)));
        write(&b.vel, bytemuck::cast_slice(&flat(&state.linvel)));
        write(&b.angvel, bytemuck::cast_slice(&flat(&state.angvel)));
        write(&b.built, bytemuck::cast_slice(&flat(&state.built)));
        write(&b.rotation, bytemuck::cast_slice(&rotation));
        write(&b.walls, bytemuck::cast_slice(&walls));
        write(&b.counts, bytemuck::cast_slice(&counts));
        write(&b.keys, bytemuck::cast_slice(&keys));
        write(&b.h_state, bytemuck::cast_slice(&h_state));
        write(&b.h_xi, bytemuck::cast_slice(&h_xi));
        write(&b.h_radius, bytemuck::cast_slice(&h_radius));
        write(&b.status, bytemuck::cast_slice(&status));
        if self.books {
            let mut books = state.books.clone();
            books.resize(n, GpuBooks::default());
            write(&b.books, bytemuck::cast_slice(&books));
        }
        self.queue.submit([]);
        scopes.pop()?;
        self.steps = steps;
        self.pending_integration = false;
        self.check_status()?;
        Ok(())
    }
}
