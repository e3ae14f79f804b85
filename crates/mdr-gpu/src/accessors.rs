//! The methods [`crate::GpuBed`] and [`crate::GpuScene`] pass straight to the device system
//! they hold (a `system: System` field), written once.

/// Adds to an `impl` block of a type with a `system: System` field the methods that pass
/// straight to it: `len`, `is_empty`, `steps`, `device_bytes`, `rebuilds` and `positions`.
macro_rules! system_accessors {
    () => {
        /// Particles.
        pub fn len(&self) -> usize {
            self.system.len()
        }

        /// Whether there are no particles (never: an empty system is refused).
        pub fn is_empty(&self) -> bool {
            self.system.len() == 0
        }

        /// Steps done.
        pub fn steps(&self) -> u64 {
            self.system.steps()
        }

        /// Bytes of every device buffer of the system (particles, lists, histories, grid).
        pub fn device_bytes(&self) -> u64 {
            self.system.device_bytes()
        }

        /// Neighbour-list builds so far.
        pub fn rebuilds(&self) -> Result<u64, GpuError> {
            self.system.rebuilds()
        }

        /// Positions only (what a comparison or a checksum needs).
        pub fn positions(&self) -> Result<Vec<Vector3<f64>>, GpuError> {
            self.system.positions()
        }
    };
}

pub(crate) use system_accessors;
