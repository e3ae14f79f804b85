//! The C ABI the C++ shim calls (declared again in `shim/mdrdem.h`). Every function catches
//! panics and reports errors as a message in a caller-provided buffer, so that the shim can raise
//! a LAMMPS error instead of crashing.

use crate::coeffs::{CoeffLine, CoeffTable};
use crate::compute::{compute, evaluate_one, MdrdemAtoms, MdrdemNeighbours, MdrdemTally};
use crate::error::PluginError;
use crate::history::HistoryLayout;
use crate::wall::{compute_wall, MdrdemWallContacts, WallTable};
use nalgebra::Vector3;
use std::ffi::{c_char, c_int, c_void, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Copy `message` into `err` (`errlen` bytes, NUL-terminated, truncated if needed).
fn write_error(err: *mut c_char, errlen: usize, message: &str) {
    if err.is_null() || errlen == 0 {
        return;
    }
    let bytes = message.as_bytes();
    let n = bytes.len().min(errlen - 1);
    // SAFETY: the caller provides `errlen` writable bytes at `err`.
    unsafe {
        std::ptr::copy_nonoverlapping(bytes.as_ptr(), err.cast::<u8>(), n);
        *err.add(n) = 0;
    }
}

/// Run `body`, turning an error or a panic into `-1` and a message.
fn guarded(
    err: *mut c_char,
    errlen: usize,
    body: impl FnOnce() -> Result<c_int, PluginError>,
) -> c_int {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(v)) => v,
        Ok(Err(e)) => {
            write_error(err, errlen, &e.to_string());
            -1
        }
        Err(_) => {
            write_error(err, errlen, "internal error (panic) in the mdrdem plugin");
            -1
        }
    }
}

/// The `nwords` words at `words` as strings.
///
/// # Safety
/// `words` holds `nwords` NUL-terminated strings (or is null with `nwords` ≤ 0).
unsafe fn read_words(
    nwords: c_int,
    words: *const *const c_char,
) -> Result<Vec<String>, PluginError> {
    if nwords > 0 && words.is_null() {
        return Err(PluginError::Abi("null words"));
    }
    let mut parsed = Vec::with_capacity(nwords.max(0) as usize);
    for w in 0..nwords.max(0) as usize {
        let p = *words.add(w);
        if p.is_null() {
            return Err(PluginError::Abi("null word"));
        }
        parsed.push(CStr::from_ptr(p).to_string_lossy().into_owned());
    }
    Ok(parsed)
}

fn table<'a>(handle: *const c_void) -> Result<&'a CoeffTable, PluginError> {
    if handle.is_null() {
        return Err(PluginError::Abi("null handle"));
    }
    // SAFETY: non-null handles come from `mdrdem_new`.
    Ok(unsafe { &*handle.cast::<CoeffTable>() })
}

fn table_mut<'a>(handle: *mut c_void) -> Result<&'a mut CoeffTable, PluginError> {
    if handle.is_null() {
        return Err(PluginError::Abi("null handle"));
    }
    // SAFETY: non-null handles come from `mdrdem_new`; the shim owns it exclusively.
    Ok(unsafe { &mut *handle.cast::<CoeffTable>() })
}

/// A coefficient table for atom types `1..=ntypes`; free it with [`mdrdem_free`].
#[no_mangle]
pub extern "C" fn mdrdem_new(ntypes: c_int) -> *mut c_void {
    let n = ntypes.max(0) as usize;
    Box::into_raw(Box::new(CoeffTable::new(n))).cast()
}

/// Free a table from [`mdrdem_new`] (null is ignored).
///
/// # Safety
/// `handle` must come from [`mdrdem_new`] and not be used afterwards.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_free(handle: *mut c_void) {
    if !handle.is_null() {
        drop(Box::from_raw(handle.cast::<CoeffTable>()));
    }
}

/// Apply one `pair_coeff` line (the words after `I J`) to types `ilo..=ihi` × `jlo..=jhi`.
/// Returns the number of type pairs set, or −1 with a message naming the keyword.
///
/// # Safety
/// `words` holds `nwords` NUL-terminated strings; `err` has `errlen` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_coeff(
    handle: *mut c_void,
    ilo: c_int,
    ihi: c_int,
    jlo: c_int,
    jhi: c_int,
    nwords: c_int,
    words: *const *const c_char,
    err: *mut c_char,
    errlen: usize,
) -> c_int {
    guarded(err, errlen, || {
        let table = table_mut(handle)?;
        let line = CoeffLine::parse(&read_words(nwords, words)?)?;
        let to = |v: c_int| v.max(0) as usize;
        let count = table.set((to(ilo), to(ihi)), (to(jlo), to(jhi)), line)?;
        Ok(count as c_int)
    })
}

/// Build the model of type pair `(i, j)` (LAMMPS `init_one`); 0, or −1 with a message.
///
/// # Safety
/// `err` has `errlen` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_init_one(
    handle: *mut c_void,
    i: c_int,
    j: c_int,
    err: *mut c_char,
    errlen: usize,
) -> c_int {
    guarded(err, errlen, || {
        table_mut(handle)?.init_one(i.max(0) as usize, j.max(0) as usize)?;
        Ok(0)
    })
}

/// Whether type pair `(i, j)` has an explicit `pair_coeff` line (1) or not (0).
#[no_mangle]
pub extern "C" fn mdrdem_is_set(handle: *const c_void, i: c_int, j: c_int) -> c_int {
    match table(handle) {
        Ok(t) if i >= 1 && j >= 1 && (i.max(j) as usize) <= t.ntypes() => {
            t.line(i as usize, j as usize).is_some() as c_int
        }
        _ => 0,
    }
}

/// Values per contact in the history (after every `init_one`): 5, 10 with rolling, one more
/// with adhesion.
#[no_mangle]
pub extern "C" fn mdrdem_history_size(handle: *const c_void) -> c_int {
    match table(handle) {
        Ok(t) => HistoryLayout::for_table(t).size() as c_int,
        Err(_) => 0,
    }
}

/// Whether any type pair is adhesive (1) or none (0), after every `init_one`.
#[no_mangle]
pub extern "C" fn mdrdem_adhesive(handle: *const c_void) -> c_int {
    match table(handle) {
        Ok(t) => t.has_adhesion() as c_int,
        Err(_) => 0,
    }
}

/// Write the sign of each history slot as seen from the partner atom for histories of `dnum`
/// values (`out` holds `dnum` values); 0, or −1 when no layout has `dnum` values.
///
/// # Safety
/// `out` must have room for `dnum` doubles.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_partner_signs(dnum: c_int, out: *mut f64) -> c_int {
    let Ok(layout) = HistoryLayout::of_size(dnum.max(0) as usize) else {
        return -1;
    };
    if out.is_null() {
        return -1;
    }
    let signs = layout.partner_signs();
    std::ptr::copy_nonoverlapping(signs.as_ptr(), out, signs.len());
    0
}

/// The largest separation at which a contact between spheres of radii `ri` (type `i`) and `rj`
/// (type `j`) can still hold adhesively (after `init_one`; 0 without adhesion): the extra
/// neighbour cut-off (docs/theory.md eq. A11, [`crate::PairModel::neck_reach`]).
#[no_mangle]
pub extern "C" fn mdrdem_neck_reach(
    handle: *const c_void,
    i: c_int,
    j: c_int,
    ri: f64,
    rj: f64,
) -> f64 {
    let Ok(t) = table(handle) else { return 0.0 };
    match t.model(i.max(0) as usize, j.max(0) as usize) {
        Some(m) if ri > 0.0 && rj > 0.0 => m.neck_reach(ri * rj / (ri + rj)),
        _ => 0.0,
    }
}

/// Forces, torques and tallies of a whole half neighbour list; 0, or −1 with a message.
///
/// # Safety
/// See [`crate::compute::compute`].
#[no_mangle]
pub unsafe extern "C" fn mdrdem_compute(
    handle: *const c_void,
    atoms: *const MdrdemAtoms,
    list: *const MdrdemNeighbours,
    tally: *const MdrdemTally,
    dt: f64,
    err: *mut c_char,
    errlen: usize,
) -> c_int {
    guarded(err, errlen, || {
        if atoms.is_null() || list.is_null() || tally.is_null() {
            return Err(PluginError::Abi("null argument"));
        }
        compute(table(handle)?, &*atoms, &*list, &*tally, dt)?;
        Ok(0)
    })
}

/// One contact from its stored history, without advancing it (LAMMPS `single()`, see
/// [`evaluate_one`]): writes the force on `i` (3 values), the normal force and the overlap to
/// `out` (5 values). 0, or −1 with a message.
///
/// # Safety
/// Vector arguments hold 3 doubles, `history` the layout's size, `out` 5 doubles.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_single(
    handle: *const c_void,
    itype: c_int,
    jtype: c_int,
    radius_mass: *const f64,
    delta: *const f64,
    relative_velocity: *const f64,
    omega_i: *const f64,
    omega_j: *const f64,
    history: *const f64,
    out: *mut f64,
    err: *mut c_char,
    errlen: usize,
) -> c_int {
    guarded(err, errlen, || {
        let t = table(handle)?;
        let model = t
            .model(itype.max(0) as usize, jtype.max(0) as usize)
            .ok_or(PluginError::NotSet {
                i: itype.max(0) as usize,
                j: jtype.max(0) as usize,
            })?;
        let v3 = |p: *const f64| Vector3::new(*p, *p.add(1), *p.add(2));
        let layout = HistoryLayout::for_table(t);
        let values = std::slice::from_raw_parts(history, layout.size());
        let rm = std::slice::from_raw_parts(radius_mass, 4);
        let (force, fn_, overlap) = evaluate_one(
            model,
            (rm[0], rm[2]),
            (rm[1], rm[3]),
            (
                &v3(delta),
                &v3(relative_velocity),
                &v3(omega_i),
                &v3(omega_j),
            ),
            values,
            layout,
        )?;
        let o = std::slice::from_raw_parts_mut(out, 5);
        o.copy_from_slice(&[force.x, force.y, force.z, fn_, overlap]);
        Ok(0)
    })
}

fn wall<'a>(handle: *const c_void) -> Result<&'a WallTable, PluginError> {
    if handle.is_null() {
        return Err(PluginError::Abi("null wall handle"));
    }
    // SAFETY: non-null wall handles come from `mdrdem_wall_new`.
    Ok(unsafe { &*handle.cast::<WallTable>() })
}

/// A wall of `fix wall/mdrdem` from the keyword-value words of its line (the keywords of
/// `pair_coeff`); free it with [`mdrdem_wall_free`]. Null, with a message naming the keyword,
/// when the line is refused.
///
/// # Safety
/// `words` holds `nwords` NUL-terminated strings; `err` has `errlen` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_wall_new(
    nwords: c_int,
    words: *const *const c_char,
    err: *mut c_char,
    errlen: usize,
) -> *mut c_void {
    let mut handle: *mut c_void = std::ptr::null_mut();
    guarded(err, errlen, || {
        let line = CoeffLine::parse(&read_words(nwords, words)?)?;
        handle = Box::into_raw(Box::new(WallTable::new(line))).cast();
        Ok(0)
    });
    handle
}

/// Free a wall from [`mdrdem_wall_new`] (null is ignored).
///
/// # Safety
/// `handle` must come from [`mdrdem_wall_new`] and not be used afterwards.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_wall_free(handle: *mut c_void) {
    if !handle.is_null() {
        drop(Box::from_raw(handle.cast::<WallTable>()));
    }
}

/// Mix the wall with the sphere types of a pair style's table (LAMMPS `init`); 0, or −1 with a
/// message.
///
/// # Safety
/// `err` has `errlen` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_wall_init(
    handle: *mut c_void,
    pair: *const c_void,
    err: *mut c_char,
    errlen: usize,
) -> c_int {
    guarded(err, errlen, || {
        if handle.is_null() {
            return Err(PluginError::Abi("null wall handle"));
        }
        let particles = table(pair)?;
        (*handle.cast::<WallTable>()).init(particles)?;
        Ok(0)
    })
}

/// History values per wall contact: 5, 10 with `rolling`, one more with `adhesion`.
#[no_mangle]
pub extern "C" fn mdrdem_wall_history_size(handle: *const c_void) -> c_int {
    match wall(handle) {
        Ok(w) => w.layout().size() as c_int,
        Err(_) => 0,
    }
}

/// `c` of the reach `c R^{1/3}` beyond contact of an adhesive contact between the wall and a
/// sphere of type `t` with effective radius `R` (after [`mdrdem_wall_init`]; 0 without adhesion),
/// see [`WallTable::neck_coefficient`].
#[no_mangle]
pub extern "C" fn mdrdem_wall_neck_coefficient(handle: *const c_void, t: c_int) -> f64 {
    match wall(handle) {
        Ok(w) => w.neck_coefficient(t.max(0) as usize),
        Err(_) => 0.0,
    }
}

/// Forces and torques of one wall on a batch of spheres (see [`compute_wall`]); writes the sum of
/// the forces on the spheres to `total_force` (3 values). 0, or −1 with a message.
///
/// # Safety
/// See [`compute_wall`]; `total_force` holds 3 doubles.
#[no_mangle]
pub unsafe extern "C" fn mdrdem_wall_compute(
    handle: *const c_void,
    atoms: *const MdrdemAtoms,
    contacts: *const MdrdemWallContacts,
    dt: f64,
    total_force: *mut f64,
    err: *mut c_char,
    errlen: usize,
) -> c_int {
    guarded(err, errlen, || {
        if atoms.is_null() || contacts.is_null() || total_force.is_null() {
            return Err(PluginError::Abi("null argument"));
        }
        let total = compute_wall(wall(handle)?, &*atoms, &*contacts, dt)?;
        std::ptr::copy_nonoverlapping(total.as_ptr(), total_force, 3);
        Ok(0)
    })
}
