//! What the pair loop (`compute`) and the wall loop (`wall`) share: one contact's law and
//! rolling update, and the reads and writes of LAMMPS's per-atom `double[3]` arrays.

use crate::history::{PairLaw, PluginNormalLaw, PluginState};
use mdr_contact::model::ContactInput;
use mdr_contact::rolling::{EpsdRollingLaw, EpsdRollingState, RollingInput, RollingLaw};
use nalgebra::Vector3;

/// One contact's response: the force on the first body, the moment `n × F` whose product with
/// each body's lever `-(r − δ/2)` is that body's torque from the force, and the rolling torque
/// on the first body (zero unless `ROLLING`; the second body takes its opposite).
pub(crate) struct Response {
    pub force: Vector3<f64>,
    pub moment: Vector3<f64>,
    pub rolling_torque: Vector3<f64>,
}

/// The contact law and, with `ROLLING`, the rolling law, advanced by one step of `dt` over
/// `input` and the relative rotation `rotation_increment` (first body minus second, over `dt`).
#[inline(always)]
pub(crate) fn respond<N: PluginNormalLaw, const ROLLING: bool>(
    law: &PairLaw<N>,
    rolling: &EpsdRollingLaw,
    (state, roll_state): (&mut PluginState<N::State>, &mut EpsdRollingState),
    input: &ContactInput,
    rotation_increment: Vector3<f64>,
) -> Response {
    let out = law.update(state, input);
    let moment = input.normal.cross(&out.force);
    let rolling_torque = if ROLLING {
        rolling
            .update(
                roll_state,
                &RollingInput {
                    normal: input.normal,
                    rotation_increment,
                    normal_force: out.normal_force,
                    normal_stiffness: out.normal.stiffness,
                },
            )
            .torque
    } else {
        Vector3::zeros()
    };
    Response {
        force: out.force,
        moment,
        rolling_torque,
    }
}

/// Atom `i`'s vector in a LAMMPS per-atom `double[3]` array.
///
/// # Safety
/// `p` must be valid for `3 (i + 1)` values.
#[inline(always)]
pub(crate) unsafe fn vec3(p: *const f64, i: usize) -> Vector3<f64> {
    Vector3::new(*p.add(3 * i), *p.add(3 * i + 1), *p.add(3 * i + 2))
}

/// Adds `v` to atom `i`'s vector in a LAMMPS per-atom `double[3]` array.
///
/// # Safety
/// `p` must be valid for `3 (i + 1)` values.
#[inline(always)]
pub(crate) unsafe fn add3(p: *mut f64, i: usize, v: &Vector3<f64>) {
    *p.add(3 * i) += v.x;
    *p.add(3 * i + 1) += v.y;
    *p.add(3 * i + 2) += v.z;
}
