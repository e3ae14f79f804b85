//! Device selection: a Vulkan, Metal or DX12 adapter with 64-bit floats in shaders
//! (`Features::SHADER_F64`, Vulkan `shaderFloat64`), and the typed errors of the GPU path.

use mdr_rapier::neighbour_list::bed::BedError;

/// What a Linux user without a GPU is told to install.
const LAVAPIPE_HINT: &str = "on Linux, Mesa's lavapipe (Debian/Ubuntu package \
     `mesa-vulkan-drivers`) provides a Vulkan device with 64-bit floats on the CPU";

/// Errors of the GPU path.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No Vulkan, Metal or DX12 adapter at all.
    #[error(
        "--device gpu: no Vulkan, Metal or DX12 adapter was found (is a GPU driver and the \
         Vulkan loader libvulkan.so.1 installed?); {LAVAPIPE_HINT}"
    )]
    NoAdapter,
    /// Adapters exist, but none has 64-bit floats in shaders.
    #[error(
        "--device gpu: no adapter has 64-bit floats in shaders (Vulkan shaderFloat64 / wgpu \
         SHADER_F64), which the f64 physics needs; adapters found: {adapters}; {LAVAPIPE_HINT}"
    )]
    NoF64 {
        /// The adapters found, by name and backend.
        adapters: String,
    },
    /// The adapter refused the device (features or limits).
    #[error("--device gpu: the adapter `{adapter}` refused the device: {message}")]
    RequestDevice {
        /// The adapter.
        adapter: String,
        /// wgpu's message.
        message: String,
    },
    /// A buffer for this many particles exceeds what the adapter can hold or bind.
    #[error(
        "--device gpu: {particles} particles need a `{buffer}` buffer of {bytes} bytes; the \
         adapter `{adapter}` allows at most {limit} bytes ({limit_name}); use fewer particles \
         (a smaller --tile)"
    )]
    TooLarge {
        /// Particles asked for.
        particles: usize,
        /// The buffer.
        buffer: &'static str,
        /// Its size.
        bytes: u64,
        /// The adapter.
        adapter: String,
        /// The limit.
        limit: u64,
        /// The limit's wgpu name.
        limit_name: &'static str,
    },
    /// The adapter binds fewer storage buffers per shader than the step needs.
    #[error(
        "--device gpu: the adapter `{adapter}` binds {available} storage buffers per shader \
         stage; the step needs {needed}"
    )]
    TooFewBindings {
        /// The adapter.
        adapter: String,
        /// Its limit.
        available: u32,
        /// What the step needs.
        needed: u32,
    },
    /// A particle had more neighbours than the list holds per particle.
    #[error(
        "--device gpu: particle {particle} has more than {max_neighbours} neighbours within \
         the cutoff (the list's slots per particle); raise `max_neighbours`"
    )]
    NeighbourOverflow {
        /// The particle (0-based).
        particle: u32,
        /// Slots per particle.
        max_neighbours: u32,
    },
    /// A cell of the binning grid had more particles than it holds.
    #[error(
        "--device gpu: cell {cell} of the neighbour grid holds more than {capacity} particles \
         (particles far outside the bed's height, or overlapping heavily)"
    )]
    CellOverflow {
        /// The cell.
        cell: u32,
        /// Its capacity.
        capacity: u32,
    },
    /// A sphere sank deeper than the wall guard allows (`mdr_sim::run::CROSSING_OVERLAP` of its
    /// radius) into a device wall: it is going through the wall. The first step it happened at,
    /// and the particle and device wall of that step (the largest slot of those that did).
    #[error(
        "--device gpu: sphere {particle} sank more than {} of its radius into device wall {wall} \
         at step {step}: it is going through the wall. Lower dt_s or declare a larger \
         max_speed_m_per_s if it is that fast",
        mdr_sim::run::CROSSING_OVERLAP
    )]
    WallCrossing {
        /// The sphere.
        particle: u32,
        /// The device wall (the device's order).
        wall: u32,
        /// The first step with a crossing.
        step: u64,
    },
    /// The system is not one the GPU path has.
    #[error("--device gpu: {0}")]
    Unsupported(String),
    /// A parameter is out of range.
    #[error("--device gpu: parameter `{name}` = {value} is outside the allowed range {range}")]
    OutOfRange {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The allowed range.
        range: &'static str,
    },
    /// The device refused a buffer, the shader or a dispatch (wgpu's validation or
    /// out-of-memory error).
    #[error("--device gpu: the device refused the work: {0}")]
    Device(String),
    /// Reading results back from the device failed.
    #[error("--device gpu: reading back from the device failed: {0}")]
    Readback(String),
    /// The bed, or the CPU path of a comparison, failed.
    #[error(transparent)]
    Bed(#[from] BedError),
}

impl From<mdr_rapier::error::CouplingError> for GpuError {
    fn from(e: mdr_rapier::error::CouplingError) -> Self {
        GpuError::Bed(BedError::Coupling(e))
    }
}

/// A law parameter the law crate refused (it names the parameter).
impl From<mdr_contact::ContactError> for GpuError {
    fn from(e: mdr_contact::ContactError) -> Self {
        mdr_rapier::error::CouplingError::from(e).into()
    }
}

/// A device with 64-bit floats in shaders, and its queue.
pub struct GpuContext {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) limits: wgpu::Limits,
    info: wgpu::AdapterInfo,
}

impl std::fmt::Debug for GpuContext {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuContext")
            .field("adapter", &self.adapter_name())
            .finish()
    }
}

impl GpuContext {
    /// The first Vulkan, Metal or DX12 adapter with `SHADER_F64`, discrete GPUs first, then
    /// integrated ones, then CPU devices (lavapipe). The error names what is missing: any
    /// adapter at all ([`GpuError::NoAdapter`]) or 64-bit floats ([`GpuError::NoF64`]).
    pub fn new() -> Result<Self, GpuError> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::VULKAN | wgpu::Backends::METAL | wgpu::Backends::DX12;
        let instance = wgpu::Instance::new(desc);
        let adapters = pollster::block_on(instance.enumerate_adapters(desc_backends()));
        if adapters.is_empty() {
            return Err(GpuError::NoAdapter);
        }
        let rank = |a: &wgpu::Adapter| match a.get_info().device_type {
            wgpu::DeviceType::DiscreteGpu => 0,
            wgpu::DeviceType::IntegratedGpu => 1,
            wgpu::DeviceType::VirtualGpu => 2,
            wgpu::DeviceType::Cpu => 3,
            wgpu::DeviceType::Other => 4,
        };
        let Some(adapter) = adapters
            .iter()
            .filter(|a| a.features().contains(wgpu::Features::SHADER_F64))
            .min_by_key(|a| rank(a))
        else {
            let names: Vec<String> = adapters
                .iter()
                .map(|a| {
                    let i = a.get_info();
                    format!("{} ({:?})", i.name, i.backend)
                })
                .collect();
            return Err(GpuError::NoF64 {
                adapters: names.join(", "),
            });
        };
        let info = adapter.get_info();
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("mdr-gpu"),
            required_features: wgpu::Features::SHADER_F64,
            required_limits: limits.clone(),
            ..Default::default()
        }))
        .map_err(|e| GpuError::RequestDevice {
            adapter: info.name.clone(),
            message: e.to_string(),
        })?;
        Ok(Self {
            device,
            queue,
            limits,
            info,
        })
    }

    /// The adapter's name and backend, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)`.
    pub fn adapter_name(&self) -> String {
        format!("{} ({:?})", self.info.name, self.info.backend)
    }

    /// Whether the adapter is a CPU device (lavapipe): correct, but no measure of GPU speed.
    pub fn is_cpu_device(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }
}

fn desc_backends() -> wgpu::Backends {
    wgpu::Backends::VULKAN | wgpu::Backends::METAL | wgpu::Backends::DX12
}
