// The settled-bed step of the neighbour-list path in f64 (docs/gpu.md): list build by cell
// binning, pair forces with histories (Hertz or MDR normal law, Mindlin, Hertzian viscous
// damping), the floor plane, the x/y periodic box, and rapier's symplectic Euler integration.
// Every formula is the CPU path's, written in the same order (mdr-contact and mdr-rapier's
// kernel): `normal_law` is `HertzLaw::update` / `MdrLaw::update`, `contact_update` is
// `ContactLaw::update` with `MindlinLaw::update`, `integrate` is the stepper's step 4.
//
// `MAXN` (neighbour slots per particle) and `CELLCAP` (particles per cell) are written in by the
// host before the module is compiled.


const MAXN: u32 = __MAXN__u;
const CELLCAP: u32 = __CELLCAP__u;
const WG: u32 = 64u;
const ACTIVE: u32 = 0x80000000u;

// Status words (atomics): rebuild requested, rebuilds done, neighbour overflow (1 + particle),
// cell overflow (1 + cell).
const S_REBUILD: u32 = 0u;
const S_REBUILDS: u32 = 1u;
const S_NEIGHBOUR_OVERFLOW: u32 = 2u;
const S_CELL_OVERFLOW: u32 = 3u;

// The constants of one bound law (a pair of spheres, or a sphere and the floor).
struct Law {
    effective_modulus: f64,
    sqrt_radius: f64,
    force_coefficient: f64,
    flat_radius_sqrt: f64,
    flat_force_coefficient: f64,
    yield_displacement: f64,
    plastic_fraction: f64,
    shear_modulus: f64,
    friction: f64,
    dashpot: f64,
    tangential_ratio: f64,
    pad: f64,
}

struct Params {
    sphere: Law,
    floor: Law,
    box_lo: vec2<f64>,
    box_len: vec2<f64>,
    cell_side: vec2<f64>,
    z_lo: f64,
    inv_cell_z: f64,
    radius: f64,
    mass: f64,
    inv_mass: f64,
    inv_inertia: f64,
    skin: f64,
    dt: f64,
    gravity_z: f64,
    floor_z: f64,
    n: u32,
    law: u32,          // 0 Hertz, 1 MDR
    orientation: u32,  // 1: integrate orientations
    groups_x: u32,     // workgroups along x of a particle dispatch
    cells_x: u32,
    cells_y: u32,
    cells_z: u32,
    cell_groups_x: u32,
}

@group(0) @binding(0) var<uniform> p: Params;
@group(0) @binding(1) var<storage, read_write> pos: array<f64>;
@group(0) @binding(2) var<storage, read_write> vel: array<f64>;
@group(0) @binding(3) var<storage, read_write> angvel: array<f64>;
@group(0) @binding(4) var<storage, read_write> built: array<f64>;
@group(0) @binding(5) var<storage, read_write> wrench: array<f64>;      // force (3), torque (3)
@group(0) @binding(6) var<storage, read_write> rotation: array<f64>;    // x, y, z, w
@group(0) @binding(7) var<storage, read_write> floor_hist: array<f64>;  // active, d_max, ξ (3), a
@group(0) @binding(8) var<storage, read_write> counts: array<u32>;
@group(0) @binding(9) var<storage, read_write> keys: array<u32>;        // ACTIVE | (j · 9 + image)
@group(0) @binding(10) var<storage, read_write> h_normal: array<f64>;   // normal law state
@group(0) @binding(11) var<storage, read_write> h_xi: array<f64>;       // Mindlin ξ, (slot, axis)
@group(0) @binding(12) var<storage, read_write> h_radius: array<f64>;   // Mindlin contact radius
@group(0) @binding(13) var<storage, read_write> cell_count: array<atomic<u32>>;
@group(0) @binding(14) var<storage, read_write> cell_items: array<u32>;
@group(0) @binding(15) var<storage, read_write> status: array<atomic<u32>>;
@group(0) @binding(16) var<storage, read_write> indirect: array<u32>;   // particles (3), cells (3)

fn particle_index(gid: vec3<u32>) -> u32 {
    return gid.x + gid.y * p.groups_x * WG;
}

// Three consecutive f64 of a buffer (storage pointers cannot be passed to functions).
fn load_pos(i: u32) -> vec3<f64> {
    return vec3<f64>(pos[3u * i], pos[3u * i + 1u], pos[3u * i + 2u]);
}

fn store_pos(i: u32, v: vec3<f64>) {
    pos[3u * i] = v.x;
    pos[3u * i + 1u] = v.y;
    pos[3u * i + 2u] = v.z;
}

fn load_vel(i: u32) -> vec3<f64> {
    return vec3<f64>(vel[3u * i], vel[3u * i + 1u], vel[3u * i + 2u]);
}

fn store_vel(i: u32, v: vec3<f64>) {
    vel[3u * i] = v.x;
    vel[3u * i + 1u] = v.y;
    vel[3u * i + 2u] = v.z;
}

fn load_angvel(i: u32) -> vec3<f64> {
    return vec3<f64>(angvel[3u * i], angvel[3u * i + 1u], angvel[3u * i + 2u]);
}

fn store_angvel(i: u32, v: vec3<f64>) {
    angvel[3u * i] = v.x;
    angvel[3u * i + 1u] = v.y;
    angvel[3u * i + 2u] = v.z;
}

fn load_built(i: u32) -> vec3<f64> {
    return vec3<f64>(built[3u * i], built[3u * i + 1u], built[3u * i + 2u]);
}

fn store_built(i: u32, v: vec3<f64>) {
    built[3u * i] = v.x;
    built[3u * i + 1u] = v.y;
    built[3u * i + 2u] = v.z;
}

fn load_wrench(i: u32) -> vec3<f64> {
    return vec3<f64>(wrench[3u * i], wrench[3u * i + 1u], wrench[3u * i + 2u]);
}

fn store_wrench(i: u32, v: vec3<f64>) {
    wrench[3u * i] = v.x;
    wrench[3u * i + 1u] = v.y;
    wrench[3u * i + 2u] = v.z;
}

// nalgebra's `dot` of three components: (a.x b.x + a.y b.y) + a.z b.z.
fn dot3(a: vec3<f64>, b: vec3<f64>) -> f64 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// nalgebra's `cross`.
fn cross3(a: vec3<f64>, b: vec3<f64>) -> vec3<f64> {
    return vec3<f64>(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

// ---------------------------------------------------------------------------------------------
// List build.

// One workgroup per 64 particles; the decision of the CPU stepper's step 1.
@compute @workgroup_size(1)
fn decide() {
    let due = atomicExchange(&status[S_REBUILD], 0u);
    if due != 0u {
        atomicAdd(&status[S_REBUILDS], 1u);
        let groups = (p.n + WG - 1u) / WG;
        indirect[0] = p.groups_x;
        indirect[1] = (groups + p.groups_x - 1u) / p.groups_x;
        indirect[2] = 1u;
        let ncells = p.cells_x * p.cells_y * p.cells_z;
        let cgroups = (ncells + WG - 1u) / WG;
        indirect[3] = p.cell_groups_x;
        indirect[4] = (cgroups + p.cell_groups_x - 1u) / p.cell_groups_x;
        indirect[5] = 1u;
    } else {
        for (var k = 0u; k < 6u; k++) {
            indirect[k] = 0u;
        }
    }
}

@compute @workgroup_size(64)
fn clear_cells(@builtin(global_invocation_id) gid: vec3<u32>) {
    let c = gid.x + gid.y * p.cell_groups_x * WG;
    if c < p.cells_x * p.cells_y * p.cells_z {
        atomicStore(&cell_count[c], 0u);
    }
}

fn cell_coord(x: f64, lo: f64, side: f64, cells: u32) -> u32 {
    let c = floor((x - lo) / side);
    return u32(clamp(c, 0.0lf, f64(cells - 1u)));
}

// `Boundary::wrap`, the positions at the build, then the particle into its cell.
@compute @workgroup_size(64)
fn bin(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = particle_index(gid);
    if i >= p.n {
        return;
    }
    var x = load_pos(i);
    for (var k = 0; k < 2; k++) {
        let lo = p.box_lo[k];
        let len = p.box_len[k];
        let hi = lo + len;
        if x[k] < lo || x[k] >= hi {
            x[k] -= floor((x[k] - lo) / len) * len;
            if x[k] >= hi {
                x[k] = lo;
            }
        }
    }
    store_pos(i, x);
    store_built(i, x);
    let cx = cell_coord(x.x, p.box_lo.x, p.cell_side.x, p.cells_x);
    let cy = cell_coord(x.y, p.box_lo.y, p.cell_side.y, p.cells_y);
    let cz = u32(clamp(floor((x.z - p.z_lo) * p.inv_cell_z), 0.0lf, f64(p.cells_z - 1u)));
    let c = (cz * p.cells_y + cy) * p.cells_x + cx;
    let at = atomicAdd(&cell_count[c], 1u);
    if at < CELLCAP {
        cell_items[c * CELLCAP + at] = i;
    } else {
        atomicMax(&status[S_CELL_OVERFLOW], c + 1u);
    }
}

// The neighbours of particle `i` (every `j ≠ i` and image closer than `r_i + r_j + skin`),
// sorted by `(j, image)`, each with the history of the same key from the last list if that
// pair was touching (the CPU list's merge by key).
@compute @workgroup_size(64)
fn search(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = particle_index(gid);
    if i >= p.n {
        return;
    }
    let xi = load_pos(i);
    let cx = i32(cell_coord(xi.x, p.box_lo.x, p.cell_side.x, p.cells_x));
    let cy = i32(cell_coord(xi.y, p.box_lo.y, p.cell_side.y, p.cells_y));
    let cz = i32(u32(clamp(floor((xi.z - p.z_lo) * p.inv_cell_z), 0.0lf, f64(p.cells_z - 1u))));
    let reach = p.radius + p.radius + p.skin;
    var found: array<u32, MAXN>;
    var m = 0u;
    var overflow = false;
    for (var oz = -1; oz <= 1; oz++) {
        let z = cz + oz;
        if z < 0 || z >= i32(p.cells_z) {
            continue;
        }
        for (var oy = -1; oy <= 1; oy++) {
            var y = cy + oy;
            var iy = 0;
            if y < 0 { y += i32(p.cells_y); iy = -1; }
            if y >= i32(p.cells_y) { y -= i32(p.cells_y); iy = 1; }
            for (var ox = -1; ox <= 1; ox++) {
                var x = cx + ox;
                var ix = 0;
                if x < 0 { x += i32(p.cells_x); ix = -1; }
                if x >= i32(p.cells_x) { x -= i32(p.cells_x); ix = 1; }
                let c = (u32(z) * p.cells_y + u32(y)) * p.cells_x + u32(x);
                let len = min(atomicLoad(&cell_count[c]), CELLCAP);
                let shift = vec3<f64>(f64(ix) * p.box_len.x, f64(iy) * p.box_len.y, 0.0lf);
                let code = u32((ix + 1) * 3 + (iy + 1));
                for (var k = 0u; k < len; k++) {
                    let j = cell_items[c * CELLCAP + k];
                    if j == i {
                        continue;
                    }
                    // The lower index minus the other's image (the CPU search's arithmetic),
                    // so that `i` lists `j` exactly when `j` lists `i`.
                    var d: vec3<f64>;
                    if i < j {
                        d = xi - (load_pos(j) + shift);
                    } else {
                        d = load_pos(j) - (xi - shift);
                    }
                    if d.x * d.x + d.y * d.y + d.z * d.z < reach * reach {
                        if m < MAXN {
                            found[m] = j * 9u + code;
                            m++;
                        } else {
                            overflow = true;
                        }
                    }
                }
            }
        }
    }
    if overflow {
        atomicMax(&status[S_NEIGHBOUR_OVERFLOW], i + 1u);
    }
    // Insertion sort: a handful of keys.
    for (var a = 1u; a < m; a++) {
        let key = found[a];
        var b = a;
        while b > 0u && found[b - 1u] > key {
            found[b] = found[b - 1u];
            b--;
        }
        found[b] = key;
    }
    // Carry the live histories over by key (the thread owns particle i's slots).
    let base = i * MAXN;
    let old_m = counts[i];
    var old_keys: array<u32, MAXN>;
    var old_h: array<f64, __MAXN5__u>;
    for (var q = 0u; q < old_m; q++) {
        old_keys[q] = keys[base + q];
        old_h[5u * q] = h_normal[base + q];
        old_h[5u * q + 1u] = h_xi[3u * (base + q)];
        old_h[5u * q + 2u] = h_xi[3u * (base + q) + 1u];
        old_h[5u * q + 3u] = h_xi[3u * (base + q) + 2u];
        old_h[5u * q + 4u] = h_radius[base + q];
    }
    var q = 0u;
    for (var s = 0u; s < m; s++) {
        let key = found[s];
        while q < old_m && (old_keys[q] & ~ACTIVE) < key {
            q++;
        }
        if q < old_m && old_keys[q] == (key | ACTIVE) {
            keys[base + s] = key | ACTIVE;
            h_normal[base + s] = old_h[5u * q];
            h_xi[3u * (base + s)] = old_h[5u * q + 1u];
            h_xi[3u * (base + s) + 1u] = old_h[5u * q + 2u];
            h_xi[3u * (base + s) + 2u] = old_h[5u * q + 3u];
            h_radius[base + s] = old_h[5u * q + 4u];
        } else {
            keys[base + s] = key;
        }
    }
    counts[i] = m;
}

// ---------------------------------------------------------------------------------------------
// Contact laws.

struct NormalOut {
    force: f64,
    radius: f64,
}

// `HertzLaw::update` (eq. 5) or `MdrLaw::update` (the closed form of docs/theory.md §4);
// `state` is the largest overlap so far.
fn normal_law(law: Law, state: ptr<function, f64>, d: f64) -> NormalOut {
    var out = NormalOut(0.0lf, 0.0lf);
    if p.law == 0u {
        let sqrt_d = sqrt(d);
        if d <= 0.0lf {
            return out;
        }
        if d > *state {
            *state = d;
        }
        out.radius = law.sqrt_radius * sqrt_d;
        out.force = law.force_coefficient * d * sqrt_d;
        return out;
    }
    if d <= 0.0lf {
        return out;
    }
    *state = max(*state, d);
    let s0 = *state - law.yield_displacement;
    if d >= s0 {
        let sqrt_d = sqrt(d);
        let s = max(s0, 0.0lf);
        let sqrt_s = sqrt(s);
        out.radius = law.sqrt_radius * sqrt_d;
        out.force = law.force_coefficient * (d * sqrt_d - law.plastic_fraction * s * sqrt_s);
        return out;
    }
    let excess = d - law.plastic_fraction * s0;
    if excess <= 0.0lf {
        return out;
    }
    let sqrt_excess = sqrt(excess);
    out.radius = law.flat_radius_sqrt * sqrt_excess;
    out.force = law.flat_force_coefficient * excess * sqrt_excess;
    return out;
}

struct History {
    normal: f64,
    xi: vec3<f64>,
    radius: f64,
}

// `ContactLaw::update` with `MindlinLaw::update` (displacement form, rescaled on unloading) and
// `HertzianViscousLaw`: the force on body 1.
fn contact_update(law: Law, h: ptr<function, History>, overlap: f64, n: vec3<f64>,
                  rv: vec3<f64>) -> vec3<f64> {
    var normal_state = (*h).normal;
    let normal = normal_law(law, &normal_state, overlap);
    (*h).normal = normal_state;
    if normal.force <= 0.0lf && normal.radius <= 0.0lf {
        (*h).xi = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
        (*h).radius = 0.0lf;
        return vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    }
    let normal_speed = dot3(rv, n);
    let approach_rate = -normal_speed;
    var dashpot = 0.0lf;
    if overlap > 0.0lf {
        dashpot = law.dashpot * sqrt(overlap);
    }
    let damping = dashpot * approach_rate;
    let normal_force = max(normal.force + damping, min(normal.force, 0.0lf));
    // Mindlin, with the Coulomb cap on the total normal force.
    let a = normal.radius;
    let cap_force = normal_force + 0.0lf;
    var t_force = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    var sliding = false;
    if a <= 0.0lf || cap_force <= 0.0lf {
        (*h).xi = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
        (*h).radius = 0.0lf;
    } else {
        var xi = (*h).xi;
        let old_len2 = dot3(xi, xi);
        let k = 2.0lf * law.shear_modulus * a;
        if old_len2 > 0.0lf {
            let along_normal = dot3(n, xi);
            xi = xi - n * along_normal;
            let tilt = along_normal * along_normal;
            var frame = 1.0lf;
            if tilt < 1e-6lf * old_len2 {
                let t = tilt / old_len2;
                frame = 1.0lf + t * (0.5lf + 0.375lf * t);
            } else {
                let new_len2 = dot3(xi, xi);
                if new_len2 > 0.0lf {
                    frame = sqrt(old_len2 / new_len2);
                }
            }
            let previous = (*h).radius;
            var ratio = 1.0lf;
            if previous > 0.0lf && a < previous {
                ratio = a / previous;
            }
            xi = xi * (frame * ratio);
        }
        let inc = rv * p.dt;
        let du = inc - n * dot3(n, inc);
        xi = xi + du;
        let cap = law.friction * cap_force;
        let len2 = dot3(xi, xi);
        if k * k * len2 > cap * cap {
            let len = sqrt(len2);
            let trial = k * len;
            var keep = 0.0lf;
            if trial > 0.0lf {
                keep = cap / trial;
            }
            xi = xi * keep;
            sliding = true;
        }
        (*h).xi = xi;
        (*h).radius = a;
        t_force = xi * (-k);
    }
    var force = n * normal_force + t_force;
    if !sliding {
        let eta_t = law.tangential_ratio * dashpot;
        if eta_t > 0.0lf {
            let v_t = rv - n * normal_speed;
            force = force - v_t * eta_t;
        }
    }
    return force;
}

// ---------------------------------------------------------------------------------------------
// Forces: each particle gathers its own wrench (floor first, then its neighbours in key order).
// A pair is always evaluated with its lower index as body 1, so both particles compute the same
// bits and get exactly opposite forces and identical histories.

@compute @workgroup_size(64)
fn forces(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = particle_index(gid);
    if i >= p.n {
        return;
    }
    let xi = load_pos(i);
    let vi = load_vel(i);
    let wi = load_angvel(i);
    let r = p.radius;
    var force = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    var torque = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    // The floor `z = floor_z`, normal +z (`sphere_half_space`).
    {
        let fb = 6u * i;
        let signed = xi.z - p.floor_z;
        let overlap = r - signed;
        if overlap <= 0.0lf {
            for (var k = 0u; k < 6u; k++) {
                floor_hist[fb + k] = 0.0lf;
            }
        } else {
            let n = vec3<f64>(0.0lf, 0.0lf, 1.0lf);
            let point = xi - n * (signed + 0.5lf * overlap);
            let arm1 = point - xi;
            var h = History(floor_hist[fb + 1u],
                            vec3<f64>(floor_hist[fb + 2u], floor_hist[fb + 3u], floor_hist[fb + 4u]),
                            floor_hist[fb + 5u]);
            let rv = vi + cross3(wi, arm1);
            let f = contact_update(p.floor, &h, overlap, n, rv);
            floor_hist[fb] = 1.0lf;
            floor_hist[fb + 1u] = h.normal;
            floor_hist[fb + 2u] = h.xi.x;
            floor_hist[fb + 3u] = h.xi.y;
            floor_hist[fb + 4u] = h.xi.z;
            floor_hist[fb + 5u] = h.radius;
            force = f;
            torque = cross3(arm1, f);
        }
    }
    let base = i * MAXN;
    let m = counts[i];
    for (var s = 0u; s < m; s++) {
        let key = keys[base + s];
        let j = (key & ~ACTIVE) / 9u;
        let code = (key & ~ACTIVE) % 9u;
        // Body 1 is the lower index; `image` is body 2's image as seen from body 1.
        var b1 = i;
        var b2 = j;
        var image = code;
        if j < i {
            b1 = j;
            b2 = i;
            image = 8u - code;
        }
        let ix = f64(i32(image / 3u) - 1);
        let iy = f64(i32(image % 3u) - 1);
        let x1 = load_pos(b1);
        let x2 = load_pos(b2) + vec3<f64>(ix * p.box_len.x, iy * p.box_len.y, 0.0lf);
        let d = x1 - x2;
        let dist2 = dot3(d, d);
        let reach = r + r;
        let touch = !(dist2 >= reach * reach || dist2 == 0.0lf);
        if !touch {
            // Separated: inactive, the history left as it is (reset when it touches again).
            keys[base + s] = key & ~ACTIVE;
            continue;
        }
        var h = History(0.0lf, vec3<f64>(0.0lf, 0.0lf, 0.0lf), 0.0lf);
        if (key & ACTIVE) != 0u {
            h = History(h_normal[base + s],
                        vec3<f64>(h_xi[3u * (base + s)], h_xi[3u * (base + s) + 1u],
                                  h_xi[3u * (base + s) + 2u]),
                        h_radius[base + s]);
        }
        let dist = sqrt(dist2);
        let overlap = reach - dist;
        let n = d * (1.0lf / dist);
        let lever1 = r - 0.5lf * overlap;
        let lever2 = r - 0.5lf * overlap;
        let w1 = load_angvel(b1);
        let w2 = load_angvel(b2);
        let rv = (load_vel(b1) - load_vel(b2)) - cross3(w1 * lever1 + w2 * lever2, n);
        let f = contact_update(p.sphere, &h, overlap, n, rv);
        keys[base + s] = key | ACTIVE;
        h_normal[base + s] = h.normal;
        h_xi[3u * (base + s)] = h.xi.x;
        h_xi[3u * (base + s) + 1u] = h.xi.y;
        h_xi[3u * (base + s) + 2u] = h.xi.z;
        h_radius[base + s] = h.radius;
        let moment = cross3(n, f);
        if i == b1 {
            force = force + f;
            torque = torque + moment * (-lever1);
        } else {
            force = force + (-f);
            torque = torque + moment * (-lever2);
        }
    }
    store_wrench(2u * i, force);
    store_wrench(2u * i + 1u, torque);
}

// ---------------------------------------------------------------------------------------------
// Integration: the CPU stepper's step 4 (rapier's symplectic Euler with one solver iteration),
// and the rebuild decision of the next step (a particle moved more than half the skin).

@compute @workgroup_size(64)
fn integrate(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = particle_index(gid);
    if i >= p.n {
        return;
    }
    let force = load_wrench(2u * i);
    let torque = load_wrench(2u * i + 1u);
    let total = force + vec3<f64>(0.0lf * p.mass, 0.0lf * p.mass, p.gravity_z * p.mass);
    let v = load_vel(i) + total * p.inv_mass * p.dt;
    let w = load_angvel(i) + torque * p.inv_inertia * p.dt;
    let x = load_pos(i) + v * p.dt;
    store_vel(i, v);
    store_angvel(i, w);
    store_pos(i, x);
    if p.orientation != 0u {
        // rapier's linearised update `(1 + ω dt/2) q`, renormalised.
        let h = w * (p.dt * 0.5lf);
        let q = vec4<f64>(rotation[4u * i], rotation[4u * i + 1u], rotation[4u * i + 2u],
                          rotation[4u * i + 3u]);
        var r = vec4<f64>(
            1.0lf * q.x + h.x * q.w + h.y * q.z - h.z * q.y,
            1.0lf * q.y - h.x * q.z + h.y * q.w + h.z * q.x,
            1.0lf * q.z + h.x * q.y - h.y * q.x + h.z * q.w,
            1.0lf * q.w - h.x * q.x - h.y * q.y - h.z * q.z);
        let eps = r.x * r.x + r.y * r.y + r.z * r.z + r.w * r.w - 1.0lf;
        if abs(eps) < 1e-6lf {
            r = r * (1.0lf - 0.5lf * eps + 0.375lf * eps * eps);
        } else {
            r = r * (1.0lf / sqrt(eps + 1.0lf));
        }
        for (var k = 0u; k < 4u; k++) {
            rotation[4u * i + k] = r[k];
        }
    }
    let b = load_built(i);
    let e = x - b;
    if sqrt(dot3(e, e)) > 0.5lf * p.skin {
        atomicOr(&status[S_REBUILD], 1u);
    }
}
