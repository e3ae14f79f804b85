//! The sink (`[run] delete_below_m`) on the device: the CPU run's [`Sink`] (its height, its
//! direction, gravity, its jump distance and every sphere's parking spot, the same values), as
//! `bed.wgsl`'s constants and the spots after the species in its `tables`, and the parking of a
//! state the host puts on the device (the scene's set-up, a checkpoint), where the CPU run parks
//! at the start of the step.
//!
//! The device parks in its integration kernel, after the update to `x_{k+1}`, what the CPU run
//! parks at the start of step `k + 1` (`Sim::scene_events`, before that step's force pass): the
//! same spheres, the same arithmetic, and the same rebuild request.

use crate::system::{GpuBooks, GpuState};
use crate::walls::wgsl_vector;
use mdr_sim::walls::Sink;
use nalgebra::Vector3;

/// `__SINK_CONSTANTS__` of `bed.wgsl`: the height, the unit vector against gravity, the
/// magnitude of gravity and the jump distance of `sink` (zeros without one, where `SINK` is
/// false and the kernel reads none of them).
pub(crate) fn sink_constants(sink: Option<&Sink>) -> String {
    let (height, up, gravity, jump) = sink.map_or((0.0, Vector3::zeros(), 0.0, 0.0), |s| {
        (s.height, s.up, s.gravity, s.jump_distance())
    });
    format!(
        "const SINK_HEIGHT: f64 = {height:?}lf;\nconst SINK_UP = {};\n\
         const SINK_GRAVITY: f64 = {gravity:?}lf;\nconst SINK_JUMP_DISTANCE: f64 = {jump:?}lf;",
        wgsl_vector(&up)
    )
}

/// The spots of `n` spheres, three words each, as `bed.wgsl`'s `tables` holds them after the
/// species.
pub(crate) fn spot_words(sink: &Sink, n: usize) -> Vec<f64> {
    (0..n)
        .flat_map(|i| {
            let s = sink.spot(i);
            [s.x, s.y, s.z]
        })
        .collect()
}

/// Park the spheres of `state` below `sink` as the CPU run parks them at the start of a step
/// (`Sink::apply`, spheres of mass `mass[i]` and radius `radius[i]`, `I = (2/5) m r²`): the
/// energy they take out of the run joins the first particle's removed energy, and a jump onto
/// a spot makes the next step rebuild the lists. A state the device wrote is parked already and
/// stays as it is.
pub(crate) fn park_state(sink: &Sink, state: &mut GpuState, mass: &[f64], radius: &[f64]) {
    let parking = sink.apply(
        &mut state.position,
        &mut state.linvel,
        &mut state.angvel,
        |i| (mass[i], 0.4 * mass[i] * radius[i] * radius[i]),
    );
    if parking.energy != 0.0 {
        if state.books.is_empty() {
            state
                .books
                .resize(state.position.len(), GpuBooks::default());
        }
        if let Some(first) = state.books.first_mut() {
            first.removed += parking.energy;
        }
    }
    state.rebuild_due |= parking.jumped;
}
