// The step of the neighbour-list path in f64 (docs/gpu.md): list build by cell binning, pair
// forces with histories (Hertz, MDR, Thornton or adhesive MDR normal law, Mindlin, Hertzian or
// stiffness-viscous damping, optionally rolling resistance) bound per species pair, walls
// (half-spaces, a box's slabs and exact surfaces of revolution, fixed, turning about their own
// axis or removed at a stage set by the host), open space or the x/y periodic box, gravity, and
// rapier's symplectic Euler integration. The settled bed is the case of one species, one floor plane and the periodic box.
// Every formula is the CPU path's,
// written in the same order (mdr-contact and mdr-rapier's kernel): `normal_law` is
// `HertzLaw::update` / `MdrLaw::update` / `ThorntonLaw::update` / `AdhesiveMdrLaw::update`,
// `contact_update` is `ContactLaw::update` with `MindlinLaw::update`, `rolling_update` is
// `EpsdRollingLaw::update`, `pair_wrench` is `evaluate_pair`, `integrate` is the stepper's
// step 4.
//
// `MAXN` (neighbour slots per particle), `CELLCAP` (particles per cell), `NN` (f64 words of the
// normal law's state), `ROLLING`, `STIFFNESS_DAMPING` and `BOOKED` are written in by the host
// before the module is compiled.
//
// With `BOOKED`, the force pass books each contact's dissipated works as the CPU path's
// `ContactLaw::update`, `MindlinLaw::update`, `EpsdRollingLaw::update` and
// `AdhesiveMdrLaw::update` book them, at the step they happen, into its particle's words of
// `books` (`BOOK_WORDS` per particle; a sphere pair books half into each sphere's words, so
// both particles' threads, which evaluate the pair with the same bits, book it alike): friction,
// damping, rolling, the energy the tangential and rolling springs gain without work, the
// adhesive work, and the plastic work of each contact that ends (the normal law's
// `dissipated_work` less its adhesive work, when the contact separates or a rebuild drops it).
// The plastic work of the live contacts is a function of their histories, read back at a
// sample.
//
// With `SINK` (a scene's `[run] delete_below_m`, its constants written in by the host),
// the integration parks every sphere whose new centre lies below `SINK_HEIGHT` along `SINK_UP`
// as the CPU run's `Sink::apply` does at the start of the next step: on its own spot (`tables`
// after the species, three words per particle), at rest, booking the kinetic energy and the
// gravitational energy above its spot into its `B_REMOVED` word, and requesting a rebuild when
// it moved more than the sink's jump distance.


const MAXN: u32 = __MAXN__u;
const CELLCAP: u32 = __CELLCAP__u;
const NN: u32 = __NN__u;
const ROLLING: bool = __ROLLING__;
// The stiffness-viscous dashpot (`StiffnessViscousLaw`) in place of the Hertzian one: a
// constant of the run, so the other laws' force pass has no branch for it.
const STIFFNESS_DAMPING: bool = __STIFFNESS_DAMPING__;
const BOOKED: bool = __BOOKED__;
const SINK: bool = __SINK__;
// Words per particle of `books` (`crate::system::GpuBooks`); the force pass books the first
// `CONTACT_BOOK_WORDS`, the integration the energy parked spheres take out of the run.
const BOOK_WORDS: u32 = 9u;
const CONTACT_BOOK_WORDS: u32 = 8u;
const B_PLASTIC: u32 = 0u;
const B_FRICTION: u32 = 1u;
const B_DAMPING: u32 = 2u;
const B_ROLLING: u32 = 3u;
const B_TANGENTIAL_STIFFNESS: u32 = 4u;
const B_ROLLING_STIFFNESS: u32 = 5u;
const B_ADHESIVE: u32 = 6u;
const B_WALL_WORK: u32 = 7u;
const B_REMOVED: u32 = 8u;
__SINK_CONSTANTS__
// f64 words per slot of `h_state`: the normal law's state, then the rolling law's (torque,
// stiffness).
const NR: u32 = select(0u, 4u, ROLLING);
const NS: u32 = NN + NR;
// f64 words per (particle, wall) of `wall_hist`: active, the normal state, ξ (3), a, the rolling
// state.
const FS: u32 = 1u + NS + 4u;
// f64 words per slot carried over by a rebuild: the normal and rolling state, ξ (3), a.
const CARRY: u32 = NS + 4u;
const WG: u32 = 64u;
const PI: f64 = 3.141592653589793lf;
const LAW_HERTZ: u32 = 0u;
const LAW_MDR: u32 = 1u;
const LAW_THORNTON: u32 = 2u;
const LAW_ADHESIVE_MDR: u32 = 3u;
const ACTIVE: u32 = 0x80000000u;

// Status words (atomics): rebuild requested, rebuilds done, neighbour overflow (1 + particle),
// cell overflow (1 + cell), force passes begun (the step, modulo 2³²), the wall guard: the first
// step at which a sphere sank deeper than `CROSSING` of its radius into a wall (all ones: none),
// and the largest such wall slot of that step (1 + particle · walls + wall).
const S_REBUILD: u32 = 0u;
const S_REBUILDS: u32 = 1u;
const S_NEIGHBOUR_OVERFLOW: u32 = 2u;
const S_CELL_OVERFLOW: u32 = 3u;
const S_PASSES: u32 = 4u;
const S_CROSSING_STEP: u32 = 5u;
const S_CROSSING_SLOT: u32 = 6u;
// The wall guard's depth, a fraction of the radius (`mdr_sim::run::CROSSING_OVERLAP`), written
// in by the host.
const CROSSING: f64 = __CROSSING__lf;
// f64 words per species in `tables` (radius, mass, 1/mass, 1/inertia).
const SPECIES_WORDS: u32 = 4u;
// The walls, written in by the host (constants, so that the compiler folds a floor's normal
// `(0, 0, 1)` into its arithmetic; `crate::walls::wall_constants`), one entry per wall in each
// array: its kind (`WALL_PLANE`, `WALL_REVOLUTION` or `WALL_SLAB`); a plane's outward normal
// and a point of the plane; the origin (the CPU collider's pose: a slab's centre, a surface of
// revolution's origin); a slab's half extents; a surface of revolution's axis point relative to
// its origin, its unit axis and its profile points `(radius, axial position)`
// `PROFILE[WALL_PROFILE_START[k] .. WALL_PROFILE_END[k]]`; the angular velocity and a point of
// its axis (zero: a fixed wall); the removal stage from which on the wall acts no more
// (`Params::walls_removed`; all ones: never).
const WALLS: u32 = __WALLS__u;
const WALL_PLANE: u32 = 0u;
const WALL_REVOLUTION: u32 = 1u;
const WALL_SLAB: u32 = 2u;
__WALL_CONSTANTS__

// The constants of one bound law (a pair of species, or a species and a wall).
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
    stiffness_coefficient: f64,
    effective_radius: f64,
    hardening_ratio: f64,
    yield_pressure: f64,
    yield_force: f64,
    detach_coefficient: f64,
    pull_off: f64,
    rolling_arm: f64,
    rolling_stiffness_ratio: f64,
    // The stiffness-viscous dashpot's `η` and the pair's reduced mass `m`.
    stiffness_eta: f64,
    reduced_mass: f64,
}

struct Params {
    box_lo_x: f64,     // the periodic box (x, y), when `periodic`
    box_lo_y: f64,
    box_len_x: f64,
    box_len_y: f64,
    grid_lo_x: f64,    // the binning grid's corner and cell sides
    grid_lo_y: f64,
    grid_lo_z: f64,
    cell_side_x: f64,
    cell_side_y: f64,
    cell_side_z: f64,
    skin: f64,
    dt: f64,
    gravity_x: f64,
    gravity_y: f64,
    gravity_z: f64,
    search_reach: f64, // skin + the adhesive neck reach: r_i + r_j + search_reach lists a pair
    n: u32,
    law: u32,          // LAW_*
    orientation: u32,  // 1: integrate orientations
    groups_x: u32,     // workgroups along x of a particle dispatch
    cells_x: u32,
    cells_y: u32,
    cells_z: u32,
    cell_groups_x: u32,
    species: u32,      // species (the sphere laws are `species²`, then `species · walls`)
    walls: u32,
    periodic: u32,     // 1: x/y periodic box; 0: open space
    walls_removed: u32, // removal stages reached: a wall of `WALL_STAGE` at most this is gone
}

@group(0) @binding(0) var<uniform> p: Params;
@group(0) @binding(1) var<storage, read_write> pos: array<f64>;
@group(0) @binding(2) var<storage, read_write> vel: array<f64>;
@group(0) @binding(3) var<storage, read_write> angvel: array<f64>;
@group(0) @binding(4) var<storage, read_write> built: array<f64>;
@group(0) @binding(5) var<storage, read_write> wrench: array<f64>;      // force (3), torque (3)
@group(0) @binding(6) var<storage, read_write> rotation: array<f64>;    // x, y, z, w
@group(0) @binding(7) var<storage, read_write> wall_hist: array<f64>;   // FS per (particle, wall)
@group(0) @binding(8) var<storage, read_write> counts: array<u32>;
@group(0) @binding(9) var<storage, read_write> keys: array<u32>;        // ACTIVE | (j · 9 + image)
@group(0) @binding(10) var<storage, read_write> h_state: array<f64>;    // NS per slot
@group(0) @binding(11) var<storage, read_write> h_xi: array<f64>;       // Mindlin ξ, (slot, axis)
@group(0) @binding(12) var<storage, read_write> h_radius: array<f64>;   // Mindlin contact radius
@group(0) @binding(13) var<storage, read_write> cell_count: array<atomic<u32>>;
@group(0) @binding(14) var<storage, read_write> cell_items: array<u32>;
@group(0) @binding(15) var<storage, read_write> status: array<atomic<u32>>;
@group(0) @binding(16) var<storage, read_write> species_of: array<u32>;
@group(0) @binding(17) var<storage, read_write> tables: array<f64>;     // the species
@group(0) @binding(18) var<storage, read_write> laws: array<Law>;       // sphere, then wall laws
@group(0) @binding(19) var<storage, read_write> books: array<f64>;      // BOOK_WORDS per particle
@group(0) @binding(20) var<storage, read_write> indirect: array<u32>;   // particles (3), cells (3)

// The works the current thread's contacts booked in this pass, and the share of the contact
// being evaluated that is this particle's (1 for a wall contact, ½ for a sphere pair).
var<private> booked: array<f64, CONTACT_BOOK_WORDS>;
var<private> book_share: f64;

fn book(word: u32, work: f64) {
    if BOOKED {
        booked[word] += book_share * work;
    }
}

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
    atomicAdd(&status[S_PASSES], 1u);
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

// The cell of a centre (one beyond the grid is clamped into an edge cell, which keeps
// neighbouring cells neighbours).
fn cell_coords(x: vec3<f64>) -> vec3<u32> {
    return vec3<u32>(cell_coord(x.x, p.grid_lo_x, p.cell_side_x, p.cells_x),
                     cell_coord(x.y, p.grid_lo_y, p.cell_side_y, p.cells_y),
                     cell_coord(x.z, p.grid_lo_z, p.cell_side_z, p.cells_z));
}

fn cell_of(x: vec3<f64>) -> u32 {
    let c = cell_coords(x);
    return (c.z * p.cells_y + c.y) * p.cells_x + c.x;
}

fn radius_of(species: u32) -> f64 {
    return tables[SPECIES_WORDS * species];
}

// `Boundary::wrap`, the positions at the build, then the particle into its cell.
@compute @workgroup_size(64)
fn bin(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = particle_index(gid);
    if i >= p.n {
        return;
    }
    var x = load_pos(i);
    if p.periodic != 0u {
        let box_lo = vec2<f64>(p.box_lo_x, p.box_lo_y);
        let box_len = vec2<f64>(p.box_len_x, p.box_len_y);
        for (var k = 0; k < 2; k++) {
            let lo = box_lo[k];
            let len = box_len[k];
            let hi = lo + len;
            if x[k] < lo || x[k] >= hi {
                x[k] -= floor((x[k] - lo) / len) * len;
                if x[k] >= hi {
                    x[k] = lo;
                }
            }
        }
        store_pos(i, x);
    }
    store_built(i, x);
    let c = cell_of(x);
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
    let cell = vec3<i32>(cell_coords(xi));
    let cx = cell.x;
    let cy = cell.y;
    let cz = cell.z;
    let ri = radius_of(species_of[i]);
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
            if p.periodic == 0u && (y < 0 || y >= i32(p.cells_y)) {
                continue;
            }
            if y < 0 { y += i32(p.cells_y); iy = -1; }
            if y >= i32(p.cells_y) { y -= i32(p.cells_y); iy = 1; }
            for (var ox = -1; ox <= 1; ox++) {
                var x = cx + ox;
                var ix = 0;
                if p.periodic == 0u && (x < 0 || x >= i32(p.cells_x)) {
                    continue;
                }
                if x < 0 { x += i32(p.cells_x); ix = -1; }
                if x >= i32(p.cells_x) { x -= i32(p.cells_x); ix = 1; }
                let c = (u32(z) * p.cells_y + u32(y)) * p.cells_x + u32(x);
                let len = min(atomicLoad(&cell_count[c]), CELLCAP);
                let shift = vec3<f64>(f64(ix) * p.box_len_x, f64(iy) * p.box_len_y, 0.0lf);
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
                    let reach = ri + radius_of(species_of[j]) + p.search_reach;
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
    var old_h: array<f64, __MAXNCARRY__u>;
    for (var q = 0u; q < old_m; q++) {
        old_keys[q] = keys[base + q];
        for (var k = 0u; k < NS; k++) {
            old_h[CARRY * q + k] = h_state[NS * (base + q) + k];
        }
        old_h[CARRY * q + NS] = h_xi[3u * (base + q)];
        old_h[CARRY * q + NS + 1u] = h_xi[3u * (base + q) + 1u];
        old_h[CARRY * q + NS + 2u] = h_xi[3u * (base + q) + 2u];
        old_h[CARRY * q + NS + 3u] = h_radius[base + q];
    }
    var q = 0u;
    var carried: array<bool, MAXN>;
    for (var s = 0u; s < m; s++) {
        let key = found[s];
        while q < old_m && (old_keys[q] & ~ACTIVE) < key {
            q++;
        }
        if q < old_m && old_keys[q] == (key | ACTIVE) {
            carried[q] = true;
            keys[base + s] = key | ACTIVE;
            for (var k = 0u; k < NS; k++) {
                h_state[NS * (base + s) + k] = old_h[CARRY * q + k];
            }
            h_xi[3u * (base + s)] = old_h[CARRY * q + NS];
            h_xi[3u * (base + s) + 1u] = old_h[CARRY * q + NS + 1u];
            h_xi[3u * (base + s) + 2u] = old_h[CARRY * q + NS + 2u];
            h_radius[base + s] = old_h[CARRY * q + NS + 3u];
        } else {
            keys[base + s] = key;
        }
    }
    counts[i] = m;
    if BOOKED {
        // A touching pair the build dropped (a sphere moved by more than the skin) ends: its
        // plastic work is booked, half to each sphere.
        var dropped = 0.0lf;
        let si = species_of[i];
        for (var o = 0u; o < old_m; o++) {
            if (old_keys[o] & ACTIVE) != 0u && !carried[o] {
                let j = (old_keys[o] & ~ACTIVE) / 9u;
                let law = laws[si * p.species + species_of[j]];
                var state = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
                for (var w = 0u; w < NN; w++) {
                    state[w] = old_h[CARRY * o + w];
                }
                dropped += 0.5lf * plastic_work(law, state);
            }
        }
        books[BOOK_WORDS * i + B_PLASTIC] += dropped;
    }
}

// ---------------------------------------------------------------------------------------------
// Contact laws.

struct NormalOut {
    force: f64,
    radius: f64,
    stiffness: f64,
}

// `pow3_2` of the law crate.
fn pow3_2(d: f64) -> f64 {
    return d * sqrt(d);
}

// `x^{2/3}` for x > 0 (Rust's `powf(2/3)`; shaders have no f64 `pow`): the cube root by two
// Newton steps from the f32 root (relative error 1e-7, then 1e-14, then round-off), squared.
fn pow2_3(x: f64) -> f64 {
    if x <= 0.0lf {
        return 0.0lf;
    }
    // f32 holds no number below 1e-38: scale tiny arguments by 2^90 (the root by 2^30).
    var xs = x;
    var scale = 1.0lf;
    if x < 1e-30lf {
        xs = x * 1237940039285380274899124224.0lf;
        scale = 9.313225746154785e-10lf;
    }
    var y = f64(pow(f32(xs), 1.0f / 3.0f));
    y = y - (y * y * y - xs) / (3.0lf * y * y);
    y = y - (y * y * y - xs) / (3.0lf * y * y);
    y = y * scale;
    return y * y;
}

// `HertzLaw::update` (eq. 5); `state.x` is the largest overlap so far.
fn hertz_law(law: Law, state: ptr<function, vec3<f64>>, d: f64) -> NormalOut {
    var out = NormalOut(0.0lf, 0.0lf, 0.0lf);
    let sqrt_d = sqrt(d);
    if d <= 0.0lf {
        return out;
    }
    if d > (*state).x {
        (*state).x = d;
    }
    out.radius = law.sqrt_radius * sqrt_d;
    out.force = law.force_coefficient * d * sqrt_d;
    out.stiffness = 2.0lf * law.effective_modulus * out.radius;
    return out;
}

// `MdrLaw::update` (the closed form of docs/theory.md §4); `state.x` is the largest overlap.
fn mdr_law(law: Law, state: ptr<function, vec3<f64>>, d: f64) -> NormalOut {
    var out = NormalOut(0.0lf, 0.0lf, 0.0lf);
    if d <= 0.0lf {
        return out;
    }
    let loading = d >= (*state).x;
    (*state).x = max((*state).x, d);
    let s0 = (*state).x - law.yield_displacement;
    if d >= s0 {
        let sqrt_d = sqrt(d);
        let s = max(s0, 0.0lf);
        let sqrt_s = sqrt(s);
        out.radius = law.sqrt_radius * sqrt_d;
        var softening = 0.0lf;
        if loading {
            softening = law.plastic_fraction * sqrt_s;
        }
        out.force = law.force_coefficient * (d * sqrt_d - law.plastic_fraction * s * sqrt_s);
        out.stiffness = law.stiffness_coefficient * (sqrt_d - softening);
        return out;
    }
    let excess = d - law.plastic_fraction * s0;
    if excess <= 0.0lf {
        return out;
    }
    let sqrt_excess = sqrt(excess);
    out.radius = law.flat_radius_sqrt * sqrt_excess;
    out.force = law.flat_force_coefficient * excess * sqrt_excess;
    out.stiffness = 2.0lf * law.effective_modulus * out.radius;
    return out;
}

// `ThorntonLaw::update` with the 1997 unloading branch (docs/theory.md §6): `state` is the
// largest overlap, the unloading coefficient and the residual overlap.
fn thornton_law(law: Law, state: ptr<function, vec3<f64>>, d: f64) -> NormalOut {
    var out = NormalOut(0.0lf, 0.0lf, 0.0lf);
    if d <= 0.0lf {
        return out;
    }
    let e2 = 2.0lf * law.effective_modulus;
    if d >= (*state).x {
        (*state).x = d;
        let a = sqrt(law.effective_radius * d);
        if d <= law.yield_displacement {
            out.force = law.force_coefficient * pow3_2(d);
            out.radius = a;
            out.stiffness = e2 * a;
            return out;
        }
        // `loading_force` above the yield point: F_y + π p_y R (δ − δ_y).
        let force = law.yield_force
            + PI * law.yield_pressure * law.effective_radius * (d - law.yield_displacement);
        // R_p = 4 E* a³ / (3 F*), δ_p = δ* − (F* / ((4/3) E* √R_p))^{2/3}.
        let r_p = 4.0lf * law.effective_modulus * a * a * a / (3.0lf * force);
        let coefficient = 4.0lf / 3.0lf * law.effective_modulus * sqrt(r_p);
        (*state).y = coefficient;
        (*state).z = d - pow2_3(force / coefficient);
        out.force = force;
        out.radius = a;
        out.stiffness = PI * law.yield_pressure * law.effective_radius;
        return out;
    }
    if (*state).x <= law.yield_displacement {
        let a = sqrt(law.effective_radius * d);
        out.force = law.force_coefficient * pow3_2(d);
        out.radius = a;
        out.stiffness = e2 * a;
        return out;
    }
    let x = d - (*state).z;
    if x <= 0.0lf {
        return out;
    }
    let c = (*state).y;
    // a = √(R_p x), R_p = (3c / (4E*))².
    let q = 0.75lf * c / law.effective_modulus;
    let r_p = q * q;
    let a = sqrt(r_p * x);
    out.force = c * pow3_2(x);
    out.radius = a;
    out.stiffness = e2 * a;
    return out;
}

// The crater of the adhesive MDR law after loading to `max_overlap` (`AdhesiveMdrLaw::crater`).
struct Crater {
    inv_radius: f64,
    theta: f64,
    plastic_overlap: f64,
    volume_coefficient: f64,
    depth: f64,
    plastic_radius_sq: f64,
}

fn crater_of(law: Law, max_overlap: f64) -> Crater {
    let excess = max_overlap - law.yield_displacement;
    var s = 0.0lf;
    if excess > 0.0lf {
        s = excess;
    }
    let theta = law.hardening_ratio;
    let r = law.effective_radius;
    return Crater(
        1.0lf / r,
        theta,
        s,
        2.0lf / 3.0lf * (1.0lf - theta) * sqrt(r),
        (1.0lf - theta) * s,
        r * s,
    );
}

fn crater_height(c: Crater, a: f64) -> f64 {
    if a * a < c.plastic_radius_sq {
        return c.theta * a * a * c.inv_radius + c.depth;
    }
    return a * a * c.inv_radius;
}

fn crater_slope(c: Crater, a: f64) -> f64 {
    if a * a < c.plastic_radius_sq {
        return 2.0lf * c.theta * a * c.inv_radius;
    }
    return 2.0lf * a * c.inv_radius;
}

fn crater_integral(c: Crater, a: f64) -> f64 {
    let cube = a * a * a * c.inv_radius * (1.0lf / 3.0lf);
    if a * a <= c.plastic_radius_sq {
        return c.theta * cube + c.depth * a;
    }
    if c.plastic_overlap > 0.0lf {
        return cube + c.volume_coefficient * c.plastic_overlap * sqrt(c.plastic_overlap);
    }
    return cube;
}

// `φ(t) = h(t²) − c t − d` of `AdhesiveMdrLaw::retreat_by_halley`.
fn edge_phi(c: Crater, detach: f64, t: f64, d: f64) -> f64 {
    return crater_height(c, t * t) - detach * t - d;
}

// `edge_series` (docs/theory.md, eq. A12): `y/ε` with `y = u² − 1` of the largest root of
// `u⁴ − εu − 1 = 0`, to `ε⁸`: round-off for `ε ≤ 1/16`.
fn edge_series(eps: f64) -> f64 {
    let e2 = eps * eps;
    let high = 55.0lf / 131072.0lf + eps * (-9.0lf / 32768.0lf + eps * (1547.0lf / 16777216.0lf));
    return 0.5lf + e2 * (-1.0lf / 64.0lf + eps * (1.0lf / 128.0lf + eps * (-9.0lf / 4096.0lf + e2 * high)));
}

// `edge_fit` (docs/theory.md, eq. A12a): `y/ε` for `1/16 < ε ≤ 1/2`, the Chebyshev fit of
// degree 12 in `ε − 9/32` (`EDGE_FIT`, highest power first).
fn edge_fit(eps: f64) -> f64 {
    let x = eps - 0.28125lf;
    var sum = -1.992404867428227e-6lf;
    sum = sum * x + 2.3642759635774487e-6lf;
    sum = sum * x + 2.0106728254983943e-6lf;
    sum = sum * x + -1.838655713757549e-5lf;
    sum = sum * x + 5.514066179338563e-5lf;
    sum = sum * x + -1.010916017429161e-4lf;
    sum = sum * x + 6.442672025061706e-5lf;
    sum = sum * x + 3.599489725888206e-4lf;
    sum = sum * x + -1.8745341744308029e-3lf;
    sum = sum * x + 5.475940719746653e-3lf;
    sum = sum * x + -1.0045565279632239e-2lf;
    sum = sum * x + -7.127072868476349e-3lf;
    sum = sum * x + 0.49892426982073995lf;
    return sum;
}

// `edge_fit_wide` (docs/theory.md, eq. A12a): `y/ε` for `1/2 < ε ≤ 2`, the Chebyshev fit of
// degree 17 in `ε − 5/4` (`EDGE_FIT_WIDE`, highest power first).
fn edge_fit_wide(eps: f64) -> f64 {
    let x = eps - 1.25lf;
    var sum = 1.464374774178623e-10lf;
    sum = sum * x + -3.0523683423078364e-10lf;
    sum = sum * x + -5.975650824551518e-11lf;
    sum = sum * x + 1.912955072760476e-09lf;
    sum = sum * x + -9.590323676004934e-09lf;
    sum = sum * x + 3.630877074746764e-08lf;
    sum = sum * x + -1.1024783309362301e-07lf;
    sum = sum * x + 2.627001756711316e-07lf;
    sum = sum * x + -3.850603345854547e-07lf;
    sum = sum * x + -5.039958625627242e-07lf;
    sum = sum * x + 7.1441760035500145e-06lf;
    sum = sum * x + -3.7625473417398904e-05lf;
    sum = sum * x + 0.00015007887378059743lf;
    sum = sum * x + -0.0004955711165628972lf;
    sum = sum * x + 0.001293114127092354lf;
    sum = sum * x + -0.0015229623379989438lf;
    sum = sum * x + -0.016412805761664626lf;
    sum = sum * x + 0.48623040072786733lf;
    return sum;
}

// `AdhesiveMdrLaw::fitted_retreat`: `a_t ε (y/ε)` for `1/16 < ε ≤ 2` (`a_t³ ≥ (c/κ)²/4`);
// a negative result beyond.
fn fitted_retreat(k: f64, hold: f64, a_t: f64) -> f64 {
    let cube = a_t * a_t * a_t;
    let scale = k / sqrt(a_t);
    if cube >= 4.0lf * hold {
        return scale * edge_fit(scale / a_t);
    }
    if 4.0lf * cube >= hold {
        return scale * edge_fit_wide(scale / a_t);
    }
    return -1.0lf;
}

// `AdhesiveMdrLaw::edge_on_spheres_branch`: where springs touch on the flattened branch but
// the edge's root is not that branch's, the sphere's branch `h = x²/R` with its touching
// radius `√(R d)` in (A12); a negative result where that does not place the edge beyond `b`.
fn edge_on_spheres_branch(law: Law, c: Crater, previous: f64, d: f64) -> f64 {
    let k = law.detach_coefficient * law.effective_radius;
    let hold = k * k;
    let touching = sqrt(law.effective_radius * d);
    let cube = touching * touching * touching;
    var root: f64;
    if cube >= 256.0lf * hold {
        let scale = k / sqrt(touching);
        root = touching + scale * edge_series(scale / touching);
    } else {
        let retreat = fitted_retreat(k, hold, touching);
        if retreat < 0.0lf {
            return -1.0lf;
        }
        root = touching + retreat;
    }
    if root * root < c.plastic_radius_sq {
        return -1.0lf;
    }
    return min(root, previous);
}

// `AdhesiveMdrLaw::retreat_by_halley`: Halley's method from the right, for the cases the
// series does not cover; zero when the contact lets go.
fn retreat_by_halley(law: Law, c: Crater, previous: f64, d: f64, touching: f64) -> f64 {
    let k = law.detach_coefficient;
    var t = sqrt(previous);
    var value = edge_phi(c, k, t, d);
    if value <= 0.0lf {
        return previous;
    }
    if 2.0lf * t * crater_slope(c, t * t) - k <= 0.0lf {
        return 0.0lf;
    }
    let floor_t = sqrt(touching);
    for (var iteration = 0; iteration < 100; iteration++) {
        let edge_slope = crater_slope(c, t * t);
        let slope = 2.0lf * t * edge_slope - k;
        if slope <= 0.0lf {
            return 0.0lf;
        }
        let curvature = 6.0lf * edge_slope;
        let denominator = 2.0lf * slope * slope - value * curvature;
        var step: f64;
        if denominator > 0.0lf {
            step = 2.0lf * value * slope / denominator;
        } else {
            step = value / slope;
        }
        let next = max(t - step, floor_t);
        if t - next <= 1e-15lf * t {
            t = next;
            break;
        }
        t = next;
        value = edge_phi(c, k, t, d);
        if value <= 0.0lf {
            break;
        }
    }
    return max(t * t, touching);
}

// `AdhesiveMdrLaw::update` (docs/theory.md, "Adhesion: Heß's rule on the plastic springs"):
// `state` is the largest overlap and the attached radius (the adhesive work, a book, is not
// kept on the device). While the springs touch out to the attached edge the law is the MDR
// law itself; with stretched springs at the edge, the edge holds or retreats (eqs. A4, A5,
// A12) and the force is (A13) on the touching branch, (A3) otherwise.
fn adhesive_mdr_law(law: Law, state: ptr<function, vec3<f64>>, d: f64) -> NormalOut {
    var out = NormalOut(0.0lf, 0.0lf, 0.0lf);
    if law.detach_coefficient == 0.0lf {
        out = mdr_law(law, state, d);
        (*state).y = out.radius;
        return out;
    }
    var plain = vec3<f64>((*state).x, 0.0lf, 0.0lf);
    let touching = mdr_law(law, &plain, d);
    (*state).x = plain.x;
    let previous = (*state).y;
    let a_t = touching.radius;
    if a_t >= previous {
        (*state).y = a_t;
        return touching;
    }
    let c = crater_of(law, plain.x);
    let two_modulus = 2.0lf * law.effective_modulus;
    // `AdhesiveMdrLaw::branch`: the flattened branch where `d < s`, as `mdr_law` takes it.
    let s = plain.x - law.yield_displacement;
    let inner = d < s;
    var kappa = c.inv_radius;
    if inner {
        kappa = c.theta * c.inv_radius;
    }
    if a_t > 0.0lf {
        // `AdhesiveMdrLaw::unload_on_branch`: `ε = (c/κ) a_t^{−3/2}`; `ε ≤ 1/16` where
        // `a_t³ ≥ 256 (c/κ)²`, `ε ≤ 1/2` where `a_t³ ≥ 4 (c/κ)²`, `ε ≤ 2` where
        // `4 a_t³ ≥ (c/κ)²` (the bands of `Branch::series_radius`, `fitted_radius`,
        // `wide_radius`, up to the rounding of their cube roots).
        let k = law.detach_coefficient / kappa;
        let hold = k * k;
        let plastic_radius_sq = law.effective_radius * s;
        let cube = a_t * a_t * a_t;
        var root = 0.0lf;
        var placed = false;
        if cube >= 256.0lf * hold {
            // `series_retreat`: `a_t ε = (c/κ)/√a_t`.
            let scale = k / sqrt(a_t);
            root = a_t + scale * edge_series(scale / a_t);
            placed = true;
        } else {
            // The edge on the touching radius's branch holds while
            // `(a² − a_t²)² ≤ (c/κ)² a` (A5 squared).
            let square_gap = (previous - a_t) * (previous + a_t);
            if square_gap * square_gap <= hold * previous
                && !(inner && previous * previous >= plastic_radius_sq) {
                let annulus = previous - a_t;
                out.force = touching.force
                    - 2.0lf / 3.0lf * law.effective_modulus * kappa * annulus * annulus * (previous + 2.0lf * a_t);
                out.radius = previous;
                out.stiffness = two_modulus * previous;
                return out;
            }
            let retreat = fitted_retreat(k, hold, a_t);
            if retreat >= 0.0lf {
                root = a_t + retreat;
                placed = true;
            }
        }
        if placed && !(inner && root * root >= plastic_radius_sq) {
            var a = previous;
            if root < previous {
                a = root;
            }
            let annulus = a - a_t;
            (*state).y = a;
            out.force = touching.force
                - 2.0lf / 3.0lf * law.effective_modulus * kappa * annulus * annulus * (a + 2.0lf * a_t);
            out.radius = a;
            out.stiffness = two_modulus * a;
            return out;
        }
    }
    // `AdhesiveMdrLaw::held_edge`: the edge holds while `(h(a) − d)² ≤ c² a` (A5 squared),
    // with the force of (A3).
    let elongation = crater_height(c, previous) - d;
    if elongation * elongation <= law.detach_coefficient * law.detach_coefficient * previous {
        out.force = two_modulus * (previous * d - crater_integral(c, previous));
        out.radius = previous;
        out.stiffness = two_modulus * previous;
        return out;
    }
    // `AdhesiveMdrLaw::unload_by_iteration`.
    var a = -1.0lf;
    if a_t > 0.0lf && d < c.plastic_overlap {
        a = edge_on_spheres_branch(law, c, previous, d);
    }
    if a < 0.0lf {
        a = retreat_by_halley(law, c, previous, d, a_t);
    }
    (*state).y = a;
    if a == 0.0lf {
        return out;
    }
    out.force = two_modulus * (a * d - crater_integral(c, a));
    out.radius = a;
    out.stiffness = two_modulus * a;
    return out;
}

fn normal_law(law: Law, state: ptr<function, vec3<f64>>, d: f64) -> NormalOut {
    if p.law == LAW_HERTZ {
        return hertz_law(law, state, d);
    }
    if p.law == LAW_MDR {
        return mdr_law(law, state, d);
    }
    if p.law == LAW_THORNTON {
        return thornton_law(law, state, d);
    }
    return adhesive_mdr_law(law, state, d);
}

// ---------------------------------------------------------------------------------------------
// Work books (with `BOOKED`).

fn pow5_2(d: f64) -> f64 {
    return d * d * sqrt(d);
}

// `MdrLaw::loading_work`: `(8/15) E* √R [d^{5/2} − (1 − θ)(d − u_c)₊^{5/2}]` (docs/theory.md §4).
fn mdr_loading_work(law: Law, d: f64) -> f64 {
    if d <= 0.0lf {
        return 0.0lf;
    }
    let s = max(d - law.yield_displacement, 0.0lf);
    return 0.4lf * law.force_coefficient * (pow5_2(d) - law.plastic_fraction * pow5_2(s));
}

// `MdrLaw::stored_energy` at the largest overlap itself: the flattened part (Hertz with radius
// R/θ, from the residual depth `(1 − θ)s` to `s`) and the outer part (`s` to `d_max`).
fn mdr_stored_at_max(law: Law, max_overlap: f64) -> f64 {
    let d = max_overlap;
    let s = max_overlap - law.yield_displacement;
    if s <= 0.0lf {
        if d > 0.0lf {
            return 0.4lf * law.force_coefficient * pow5_2(d);
        }
        return 0.0lf;
    }
    let residual = law.plastic_fraction * s;
    if d <= residual {
        return 0.0lf;
    }
    var flat = 0.0lf;
    if law.hardening_ratio > 0.0lf {
        flat = 0.4lf * law.flat_force_coefficient * pow5_2(min(d, s) - residual);
    }
    var outer = 0.0lf;
    if d > s {
        outer = 0.4lf * law.force_coefficient * (pow5_2(d) - pow5_2(s))
            - law.plastic_fraction * law.force_coefficient * pow3_2(s) * (d - s);
    }
    return flat + outer;
}

// `ThorntonLaw::loading_work`: Hertz to `δ_y`, then the linear plastic branch.
fn thornton_loading_work(law: Law, d: f64) -> f64 {
    if d <= law.yield_displacement {
        return 0.4lf * law.force_coefficient * pow5_2(max(d, 0.0lf));
    }
    let x = d - law.yield_displacement;
    return 0.4lf * law.force_coefficient * pow5_2(law.yield_displacement)
        + law.yield_force * x
        + 0.5lf * PI * law.yield_pressure * law.effective_radius * x * x;
}

// `NormalLaw::dissipated_work` of a history (`state`: the normal law's words) less its
// adhesive work, which the adhesive law books as it happens: `W(d_max) − U(d_max)`, the loading
// work less the energy stored at the largest overlap (zero for Hertz).
fn plastic_work(law: Law, state: vec3<f64>) -> f64 {
    if p.law == LAW_HERTZ {
        return 0.0lf;
    }
    let d = state.x;
    if p.law == LAW_THORNTON {
        // `ThorntonLaw::elastic_energy` at `d_max` on the 1997 unloading branch.
        var stored = 0.4lf * law.force_coefficient * pow5_2(max(d, 0.0lf));
        if d > law.yield_displacement {
            stored = 0.4lf * state.y * pow5_2(max(d - state.z, 0.0lf));
        }
        return max(thornton_loading_work(law, d) - stored, 0.0lf);
    }
    return max(mdr_loading_work(law, d) - mdr_stored_at_max(law, d), 0.0lf);
}

// `AdhesiveMdrLaw::annulus_work`: `π Δγ (outer² − inner²)`, with `π Δγ = E* c² / 2` from the
// detach coefficient `c = √(2π Δγ / E*)`.
fn annulus_work(law: Law, outer: f64, inner: f64) -> f64 {
    return 0.5lf * law.effective_modulus * law.detach_coefficient * law.detach_coefficient
        * (outer * outer - inner * inner);
}

// `AdhesiveMdrLaw::edge_overlap`: `δ(a) = h(a) − c √a`, the overlap at which the edge at `a`
// holds (A5).
fn edge_overlap(law: Law, c: Crater, a: f64) -> f64 {
    return crater_height(c, a) - law.detach_coefficient * sqrt(a);
}

// `Crater::spring_energy`: `E* ∫_{−a}^{a} (d − h)² dx / 2`, the energy of the attached springs
// (A6).
fn spring_energy(law: Law, c: Crater, d: f64, a: f64) -> f64 {
    let r = law.effective_radius;
    let inner = min(a, sqrt(c.plastic_radius_sq));
    let e = d - c.depth;
    let k = c.theta / r;
    let inner3 = inner * inner * inner;
    var integral = e * e * inner - 2.0lf / 3.0lf * e * k * inner3
        + k * k * (inner3 * inner * inner) / 5.0lf;
    if a > inner {
        let a3 = a * a * a;
        let pa = d * d * a - 2.0lf / 3.0lf * d * a3 / r + a3 * a * a / (5.0lf * r * r);
        let pi = d * d * inner - 2.0lf / 3.0lf * d * inner3 / r
            + inner3 * inner * inner / (5.0lf * r * r);
        integral += pa - pi;
    }
    return law.effective_modulus * integral;
}

// `AdhesiveMdrLaw::let_go_work` (eq. A6): the edge retreats to the weakest edge `a*` (A7: the
// stationary points `(cR/4)^{2/3}` and `(cR/(4θ))^{2/3}` of `δ` on either branch, the plastic
// radius, or the edge itself), then the springs inside it let go with the energy they hold at
// `δ(a*)`.
fn let_go_work(law: Law, c: Crater, previous: f64) -> f64 {
    let b_sq = c.plastic_radius_sq;
    var best = previous;
    var best_overlap = edge_overlap(law, c, previous);
    let outer = pow2_3(law.detach_coefficient * law.effective_radius / 4.0lf);
    if outer * outer >= b_sq && outer <= previous {
        let o = edge_overlap(law, c, outer);
        if o < best_overlap {
            best = outer;
            best_overlap = o;
        }
    }
    if b_sq > 0.0lf && b_sq < previous * previous {
        let b = sqrt(b_sq);
        let o = edge_overlap(law, c, b);
        if o < best_overlap {
            best = b;
            best_overlap = o;
        }
    }
    if c.theta > 0.0lf {
        let inner = pow2_3(law.detach_coefficient * law.effective_radius / (4.0lf * c.theta));
        if inner * inner < b_sq && inner <= previous {
            let o = edge_overlap(law, c, inner);
            if o < best_overlap {
                best = inner;
                best_overlap = o;
            }
        }
    }
    return annulus_work(law, previous, best) + spring_energy(law, c, best_overlap, best);
}

// The adhesive work of one update of the adhesive law (`AdhesiveMdrState::adhesive_work`'s
// increment): the annulus the attached edge left from `previous` to the new attached radius
// `state.y`, or the whole neck's energy when it lets go (the radius drops to zero).
fn book_adhesive_work(law: Law, previous: f64, state: vec3<f64>) {
    if !BOOKED || p.law != LAW_ADHESIVE_MDR || law.detach_coefficient == 0.0lf {
        return;
    }
    let a = state.y;
    if a >= previous {
        return;
    }
    if a > 0.0lf {
        book(B_ADHESIVE, annulus_work(law, previous, a));
    } else {
        book(B_ADHESIVE, let_go_work(law, crater_of(law, state.x), previous));
    }
}

// The energy a Mindlin spring of displacement `xi` held at contact radius `radius`, released
// when its contact opens (`MindlinLaw::stiffness_energy_change` to a zero radius: the energy
// gained is minus `½ k_t(a) |ξ|²`, `k_t = 2 G* a`).
fn book_released_tangential_spring(law: Law, xi: vec3<f64>, radius: f64) {
    book(B_TANGENTIAL_STIFFNESS, -(0.5lf * (2.0lf * law.shear_modulus * radius) * dot3(xi, xi)));
}

// Add this pass's works to particle `i`'s books.
fn store_books(i: u32) {
    if BOOKED {
        for (var w = 0u; w < CONTACT_BOOK_WORDS; w++) {
            books[BOOK_WORDS * i + w] += booked[w];
        }
    }
}

// `NormalLaw::holds`: an adhesive contact with attached springs holds apart.
fn holds(law: Law, h: History) -> bool {
    return p.law == LAW_ADHESIVE_MDR && law.detach_coefficient > 0.0lf && h.normal.y > 0.0lf;
}

struct History {
    normal: vec3<f64>,
    xi: vec3<f64>,
    radius: f64,
    torque: vec3<f64>,
    rolling_stiffness: f64,
}

fn default_history() -> History {
    let zero = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    return History(zero, zero, 0.0lf, zero, 0.0lf);
}

// The slot `k`'s history (`k` = particle · MAXN + slot).
fn load_slot(k: u32) -> History {
    var h = default_history();
    for (var w = 0u; w < NN; w++) {
        h.normal[w] = h_state[NS * k + w];
    }
    h.xi = vec3<f64>(h_xi[3u * k], h_xi[3u * k + 1u], h_xi[3u * k + 2u]);
    h.radius = h_radius[k];
    if ROLLING {
        let r = NS * k + NN;
        h.torque = vec3<f64>(h_state[r], h_state[r + 1u], h_state[r + 2u]);
        h.rolling_stiffness = h_state[r + 3u];
    }
    return h;
}

fn store_slot(k: u32, h: History) {
    for (var w = 0u; w < NN; w++) {
        h_state[NS * k + w] = h.normal[w];
    }
    h_xi[3u * k] = h.xi.x;
    h_xi[3u * k + 1u] = h.xi.y;
    h_xi[3u * k + 2u] = h.xi.z;
    h_radius[k] = h.radius;
    if ROLLING {
        let r = NS * k + NN;
        h_state[r] = h.torque.x;
        h_state[r + 1u] = h.torque.y;
        h_state[r + 2u] = h.torque.z;
        h_state[r + 3u] = h.rolling_stiffness;
    }
}

// The history of wall slot `i` (particle · walls + wall): active, the normal state, ξ, a, the
// rolling state.
fn load_wall(i: u32) -> History {
    let f = FS * i;
    var h = default_history();
    for (var w = 0u; w < NN; w++) {
        h.normal[w] = wall_hist[f + 1u + w];
    }
    let t = f + 1u + NN;
    h.xi = vec3<f64>(wall_hist[t], wall_hist[t + 1u], wall_hist[t + 2u]);
    h.radius = wall_hist[t + 3u];
    if ROLLING {
        h.torque = vec3<f64>(wall_hist[t + 4u], wall_hist[t + 5u], wall_hist[t + 6u]);
        h.rolling_stiffness = wall_hist[t + 7u];
    }
    return h;
}

fn store_wall(i: u32, touching: bool, h: History) {
    let f = FS * i;
    wall_hist[f] = select(0.0lf, 1.0lf, touching);
    for (var w = 0u; w < NN; w++) {
        wall_hist[f + 1u + w] = h.normal[w];
    }
    let t = f + 1u + NN;
    wall_hist[t] = h.xi.x;
    wall_hist[t + 1u] = h.xi.y;
    wall_hist[t + 2u] = h.xi.z;
    wall_hist[t + 3u] = h.radius;
    if ROLLING {
        wall_hist[t + 4u] = h.torque.x;
        wall_hist[t + 5u] = h.torque.y;
        wall_hist[t + 6u] = h.torque.z;
        wall_hist[t + 7u] = h.rolling_stiffness;
    }
}

// What `ContactLaw::update` returns that the pair kernel uses.
struct ContactOut {
    force: vec3<f64>,
    normal_force: f64,
    stiffness: f64,
}

// `ContactLaw::update` with `MindlinLaw::update` (displacement form, rescaled on unloading) and
// `HertzianViscousLaw` or `StiffnessViscousLaw`: the force on body 1.
fn contact_update(law: Law, h: ptr<function, History>, overlap: f64, n: vec3<f64>,
                  rv: vec3<f64>) -> ContactOut {
    let zero = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    var normal_state = (*h).normal;
    let attached = normal_state.y;
    let normal = normal_law(law, &normal_state, overlap);
    (*h).normal = normal_state;
    book_adhesive_work(law, attached, normal_state);
    if normal.force <= 0.0lf && normal.radius <= 0.0lf {
        book_released_tangential_spring(law, (*h).xi, (*h).radius);
        (*h).xi = zero;
        (*h).radius = 0.0lf;
        return ContactOut(zero, 0.0lf, 0.0lf);
    }
    let normal_speed = dot3(rv, n);
    let approach_rate = -normal_speed;
    // `DampingLaw::normal_coefficient`: Tsuji's `η √(m k_n)` with the normal law's tangent
    // stiffness of this step (at any overlap the law holds the contact at, a held neck's
    // included), or the Hertzian `m γ_n √R √δ` (zero without damping).
    var dashpot = 0.0lf;
    if STIFFNESS_DAMPING {
        dashpot = law.stiffness_eta * sqrt(law.reduced_mass * normal.stiffness);
    } else if overlap > 0.0lf {
        dashpot = law.dashpot * sqrt(overlap);
    }
    let damping = dashpot * approach_rate;
    let normal_force = max(normal.force + damping, min(normal.force, 0.0lf));
    // Both dashpots' work of this step (`ContactLaw::update`), booked once below.
    var damping_power = (normal_force - normal.force) * approach_rate;
    // Mindlin, with the Coulomb cap on the total normal force plus twice the pull-off force.
    let a = normal.radius;
    let cap_force = normal_force + 2.0lf * law.pull_off;
    var t_force = zero;
    var sliding = false;
    if a <= 0.0lf || cap_force <= 0.0lf {
        book_released_tangential_spring(law, (*h).xi, (*h).radius);
        (*h).xi = zero;
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
            // `MindlinLaw::carried_energy_change`: `½ k |ξ|² ratio² − ½ k_t(a_prev) |ξ|²`.
            let before = 0.5lf * (2.0lf * law.shear_modulus * previous) * old_len2;
            book(B_TANGENTIAL_STIFFNESS, 0.5lf * k * old_len2 * ratio * ratio - before);
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
            // Gross slip: `μ F_N` times the slip length.
            book(B_FRICTION, cap * (len * (1.0lf - keep)));
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
            damping_power += eta_t * dot3(v_t, v_t);
        }
    }
    book(B_DAMPING, damping_power * p.dt);
    return ContactOut(force, normal_force, normal.stiffness);
}

// `EpsdRollingLaw::update` (Ai et al. 2011, type C): the rolling torque on body 1.
fn rolling_update(law: Law, h: ptr<function, History>, n: vec3<f64>, increment: vec3<f64>,
                  normal_force: f64, normal_stiffness: f64) -> vec3<f64> {
    let zero = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    if normal_force <= 0.0lf {
        // The released spring's energy is dissipated (`EpsdRollingState::elastic_energy`).
        if (*h).rolling_stiffness > 0.0lf {
            book(B_ROLLING, 0.5lf * dot3((*h).torque, (*h).torque) / (*h).rolling_stiffness);
        }
        (*h).torque = zero;
        (*h).rolling_stiffness = 0.0lf;
        return zero;
    }
    var torque = (*h).torque;
    let old_len2 = dot3(torque, torque);
    if old_len2 > 0.0lf {
        torque = torque - n * dot3(n, torque);
        let new_len2 = dot3(torque, torque);
        if new_len2 > 0.0lf {
            torque = torque * sqrt(old_len2 / new_len2);
        }
    }
    let rotation = increment - n * dot3(n, increment);
    let stiffness = law.rolling_stiffness_ratio * normal_stiffness;
    // `EpsdRollingState::stiffness_energy_change`: `½|M|² (1/k_r − 1/k_r,prev)`.
    let previous_stiffness = (*h).rolling_stiffness;
    if previous_stiffness > 0.0lf && stiffness > 0.0lf {
        book(B_ROLLING_STIFFNESS,
             0.5lf * old_len2 * (1.0lf / stiffness - 1.0lf / previous_stiffness));
    }
    torque = torque + rotation * (-stiffness);
    let cap = law.rolling_arm * normal_force;
    let magnitude2 = dot3(torque, torque);
    if magnitude2 > cap * cap {
        let magnitude = sqrt(magnitude2);
        // The excess rotation `(|M_trial| − cap)/k_r` is plastic and dissipates `cap` times it.
        let excess = magnitude - cap;
        torque = torque * (cap / magnitude);
        if stiffness > 0.0lf {
            book(B_ROLLING, cap * excess / stiffness);
        } else {
            book(B_ROLLING, cap * sqrt(dot3(rotation, rotation)));
        }
    }
    (*h).torque = torque;
    (*h).rolling_stiffness = stiffness;
    return torque;
}

// `evaluate_pair`: the contact law, then the rolling law on the relative rotation; the force on
// body 1 and the rolling torque on body 1 (body 2 receives their negatives).
struct PairOut {
    force: vec3<f64>,
    rolling_torque: vec3<f64>,
}

fn pair_wrench(law: Law, h: ptr<function, History>, overlap: f64, n: vec3<f64>, rv: vec3<f64>,
               w1: vec3<f64>, w2: vec3<f64>) -> PairOut {
    let out = contact_update(law, h, overlap, n, rv);
    var roll = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    if ROLLING {
        roll = rolling_update(law, h, n, (w1 - w2) * p.dt, out.normal_force, out.stiffness);
    }
    return PairOut(out.force, roll);
}

// ---------------------------------------------------------------------------------------------
// Wall contacts.

// The contact of a sphere with a wall: its overlap (negative while apart), the unit normal from
// the wall towards the sphere, the contact point (mid-overlap), and whether it has a normal (a
// centre on a surface of revolution has none: no contact, as on the CPU path).
struct WallContact {
    overlap: f64,
    normal: vec3<f64>,
    point: vec3<f64>,
    defined: bool,
}

// `sphere_half_space_signed`: the plane through `o` with outward normal `n`.
fn plane_contact(k: u32, x: vec3<f64>, r: f64) -> WallContact {
    let n = WALL_NORMAL[k];
    let o = WALL_POINT[k];
    let signed = dot3(n, x - o);
    let overlap = r - signed;
    return WallContact(overlap, n, x - n * (signed + 0.5lf * overlap), true);
}

// `v / s` component by component (nalgebra's division of a vector by a scalar).
fn divide3(v: vec3<f64>, s: f64) -> vec3<f64> {
    return vec3<f64>(v.x / s, v.y / s, v.z / s);
}

// `SurfaceOfRevolution::nearest` and `::sphere_contact_signed` (mdr-rapier's geometry.rs, which
// derives it): the point of the surface nearest to the centre lies in the meridional half-plane
// through it, so the distance is the planar distance from `(ρ, a)` (the centre's distance from
// the axis and its axial position) to the profile polyline; a profile vertex gives the contact
// with the rim it sweeps. The pose is the collider's, `WALL_ORIGIN` without rotation (a surface
// turning about its own axis keeps its place).
fn revolution_contact(k: u32, x: vec3<f64>, r: f64) -> WallContact {
    let local = x - WALL_ORIGIN[k];
    let axis = WALL_AXIS[k];
    let rel = local - WALL_CENTER[k];
    let a = dot3(rel, axis);
    let radial = rel - axis * a;
    let rho = sqrt(dot3(radial, radial));
    var e: vec3<f64>;
    if rho > 0.0lf {
        e = divide3(radial, rho);
    } else {
        // On the axis every meridional half-plane is nearest: any direction across it.
        var t = vec3<f64>(0.0lf, 1.0lf, 0.0lf);
        if abs(axis.x) < 0.9lf {
            t = vec3<f64>(1.0lf, 0.0lf, 0.0lf);
        }
        let u = t - axis * dot3(t, axis);
        e = divide3(u, sqrt(dot3(u, u)));
    }
    var best2 = 0.0lf;
    var best_r = 0.0lf;
    var best_a = 0.0lf;
    var first = true;
    for (var q = WALL_PROFILE_START[k]; q + 1u < WALL_PROFILE_END[k]; q++) {
        let p0 = PROFILE[q];
        let p1 = PROFILE[q + 1u];
        let dr = p1.x - p0.x;
        let da = p1.y - p0.y;
        let len2 = dr * dr + da * da;
        var t = 0.0lf;
        if len2 > 0.0lf {
            t = clamp(((rho - p0.x) * dr + (a - p0.y) * da) / len2, 0.0lf, 1.0lf);
        }
        let qr = p0.x + t * dr;
        let qa = p0.y + t * da;
        let d2 = (rho - qr) * (rho - qr) + (a - qa) * (a - qa);
        if first || d2 < best2 {
            first = false;
            best2 = d2;
            best_r = qr;
            best_a = qa;
        }
    }
    let nearest = (WALL_CENTER[k] + e * best_r) + axis * best_a;
    let dist = sqrt(best2);
    if dist == 0.0lf {
        return WallContact(r, axis, x, false);
    }
    let normal = divide3(local - nearest, dist);
    let overlap = r - dist;
    let surface = x - normal * dist;
    return WallContact(overlap, normal, surface - normal * (0.5lf * overlap), true);
}

// parry's `Aabb::do_project_local_point` (non-solid) on the cuboid `[-h, h]` and mdr-rapier's
// `sphere_shape_signed` (geometry.rs), in their order: the CPU path's contact of a sphere with a
// box's slab (a cuboid collider at the translation `WALL_ORIGIN`, no rotation, whose transforms
// are exact). Outside, the centre is clamped onto the cuboid (a face, an edge or a corner);
// inside, it goes to the nearest face along one axis (the first of x, y, z with the least depth),
// and the overlap is the radius plus the depth. The axis's sign is `copysign(1, c)` on the CPU,
// which takes −1 for a coordinate −0.0; here +1 (no f64 sign bit in WGSL): the two differ only
// for a centre exactly on the slab's mid-plane, `−0.0` against `+0.0`.
fn cuboid_contact(k: u32, x: vec3<f64>, r: f64) -> WallContact {
    let zero = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    let h = WALL_HALF[k];
    let local = x - WALL_ORIGIN[k];
    let shift = max(-h - local, zero) - max(local - h, zero);
    var inside = false;
    var projected = local + shift;
    if all(shift == zero) {
        inside = true;
        // The box's centre is `(−h + h) · 0.5 = 0`: `local` is the centred point.
        let sign = select(vec3<f64>(1.0lf), vec3<f64>(-1.0lf), local < zero);
        let diff = h - sign * local;
        var step = zero;
        if diff.x <= diff.y && diff.x <= diff.z {
            step.x = diff.x * sign.x;
        } else if diff.y <= diff.x && diff.y <= diff.z {
            step.y = diff.y * sign.y;
        } else {
            step.z = diff.z * sign.z;
        }
        projected = local + step;
    }
    let p = projected + WALL_ORIGIN[k];
    let d = x - p;
    let dist = sqrt(dot3(d, d));
    if dist == 0.0lf {
        return WallContact(r, d, x, false);
    }
    var signed = dist;
    var normal = divide3(d, dist);
    if inside {
        signed = -dist;
        normal = divide3(-d, dist);
    }
    let overlap = r - signed;
    return WallContact(overlap, normal, p - normal * (0.5lf * overlap), true);
}

// The contact of a sphere (centre `x`, radius `r`) with wall `k`.
fn wall_contact(k: u32, x: vec3<f64>, r: f64) -> WallContact {
    if WALL_KIND[k] == WALL_REVOLUTION {
        return revolution_contact(k, x, r);
    }
    // `ANY_SLAB` is a constant: a system without a box (the bed) compiles the branch out.
    if ANY_SLAB && WALL_KIND[k] == WALL_SLAB {
        return cuboid_contact(k, x, r);
    }
    return plane_contact(k, x, r);
}

// ---------------------------------------------------------------------------------------------
// Forces: each particle gathers its own wrench (walls first, in order, then its neighbours in key
// order). A pair is always evaluated with its lower index as body 1, so both particles compute the
// same bits and get exactly opposite forces and identical histories.

@compute @workgroup_size(64)
fn forces(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = particle_index(gid);
    if i >= p.n {
        return;
    }
    let zero = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    let xi = load_pos(i);
    let vi = load_vel(i);
    let wi = load_angvel(i);
    let si = species_of[i];
    let ri = radius_of(si);
    var force = zero;
    var torque = zero;
    for (var w = 0u; w < CONTACT_BOOK_WORDS; w++) {
        booked[w] = 0.0lf;
    }
    book_share = 1.0lf;
    // Each wall (`wall_contact`: a plane, a slab or a surface of revolution); a held adhesive
    // contact goes on at its negative overlap. A removed wall acts no more: its contact ends.
    for (var k = 0u; k < WALLS; k++) {
        let slot = i * p.walls + k;
        let was_active = wall_hist[FS * slot] != 0.0lf;
        if WALL_STAGE[k] <= p.walls_removed {
            if was_active {
                let law = laws[p.species * p.species + si * p.walls + k];
                book(B_PLASTIC, plastic_work(law, load_wall(slot).normal));
                store_wall(slot, false, default_history());
            }
            continue;
        }
        let contact = wall_contact(k, xi, ri);
        let n = contact.normal;
        let overlap = contact.overlap;
        var h = load_wall(slot);
        let law = laws[p.species * p.species + si * p.walls + k];
        let held = was_active && holds(law, h);
        if !contact.defined || (overlap <= 0.0lf && !held) {
            if was_active {
                book(B_PLASTIC, plastic_work(law, h.normal));
                store_wall(slot, false, default_history());
            }
        } else {
            // The wall guard, at every step: the first step with a crossing and, of that step,
            // the largest slot (atomics over one pass give the same words in any order).
            if overlap > CROSSING * ri {
                let step = atomicLoad(&status[S_PASSES]) - 1u;
                atomicMin(&status[S_CROSSING_STEP], step);
                if atomicLoad(&status[S_CROSSING_STEP]) == step {
                    atomicMax(&status[S_CROSSING_SLOT], slot + 1u);
                }
            }
            let arm1 = contact.point - xi;
            // The wall's velocity at the contact point, `ω × (x − c)` (zero for a fixed wall):
            // `relative_velocity` of the CPU kernel with the wall as body 2.
            let w2 = WALL_OMEGA[k];
            let arm2 = contact.point - WALL_PIVOT[k];
            let rv = vi + (cross3(wi, arm1) - cross3(w2, arm2));
            let out = pair_wrench(law, &h, overlap, n, rv, wi, w2);
            // A turning wall's power on the sphere, its force times the wall's velocity at the
            // contact point (the CPU's `wall_power`).
            book(B_WALL_WORK, dot3(out.force, cross3(w2, arm2)) * p.dt);
            store_wall(slot, true, h);
            force = force + out.force;
            torque = torque + (cross3(arm1, out.force) + out.rolling_torque);
        }
    }
    let base = i * MAXN;
    let m = counts[i];
    book_share = 0.5lf;
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
        let x2 = load_pos(b2) + vec3<f64>(ix * p.box_len_x, iy * p.box_len_y, 0.0lf);
        let d = x1 - x2;
        let dist2 = dot3(d, d);
        let s1 = species_of[b1];
        let s2 = species_of[b2];
        let r1 = radius_of(s1);
        let r2 = radius_of(s2);
        let law = laws[s1 * p.species + s2];
        let reach = r1 + r2;
        let touch = !(dist2 >= reach * reach || dist2 == 0.0lf);
        let was_active = (key & ACTIVE) != 0u;
        var h = default_history();
        if was_active {
            h = load_slot(base + s);
        }
        // A held adhesive contact goes on at its negative overlap until its law lets go.
        let held = was_active && dist2 != 0.0lf && holds(law, h);
        if !(touch || held) {
            // Separated: inactive, the history left as it is (reset when it touches again);
            // the contact's plastic work is booked.
            if was_active {
                book(B_PLASTIC, plastic_work(law, h.normal));
            }
            keys[base + s] = key & ~ACTIVE;
            continue;
        }
        let dist = sqrt(dist2);
        let overlap = reach - dist;
        let n = d * (1.0lf / dist);
        let lever1 = r1 - 0.5lf * overlap;
        let lever2 = r2 - 0.5lf * overlap;
        let w1 = load_angvel(b1);
        let w2 = load_angvel(b2);
        let rv = (load_vel(b1) - load_vel(b2)) - cross3(w1 * lever1 + w2 * lever2, n);
        let out = pair_wrench(law, &h, overlap, n, rv, w1, w2);
        keys[base + s] = key | ACTIVE;
        store_slot(base + s, h);
        let moment = cross3(n, out.force);
        if i == b1 {
            force = force + out.force;
            torque = torque + (moment * (-lever1) + out.rolling_torque);
        } else {
            force = force + (-out.force);
            torque = torque + (moment * (-lever2) - out.rolling_torque);
        }
    }
    store_wrench(2u * i, force);
    store_wrench(2u * i + 1u, torque);
    store_books(i);
}

// ---------------------------------------------------------------------------------------------
// Integration: the CPU stepper's step 4 (rapier's symplectic Euler with one solver iteration),
// the sink of the next step (`SINK`), and the rebuild decision of the next step (a particle
// moved more than half the skin, or a sphere jumped onto its parking spot).

// `Sink::apply` and `Sink::lost_energy` (mdr-sim's walls/sink.rs) for sphere `i` (mass `m`,
// radius `r`) at `x` moving with `v`, `w`, below the sink: it is held at rest on its spot, what
// it takes out of the run (kinetic, `I = (2/5) m r²` as the CPU run counts it, and
// gravitational above its spot) is booked, and a jump onto the spot requests a rebuild.
// Returns the spot.
fn park(i: u32, x: vec3<f64>, v: vec3<f64>, w: vec3<f64>, m: f64, r: f64) -> vec3<f64> {
    let at = SPECIES_WORDS * p.species + 3u * i;
    let spot = vec3<f64>(tables[at], tables[at + 1u], tables[at + 2u]);
    let moment = 0.4lf * m * r * r;
    let lost = 0.5lf * m * dot3(v, v) + 0.5lf * moment * dot3(w, w)
        + m * SINK_GRAVITY * dot3(SINK_UP, x - spot);
    if BOOKED {
        books[BOOK_WORDS * i + B_REMOVED] += lost;
    }
    let jump = x - spot;
    if dot3(jump, jump) > SINK_JUMP_DISTANCE * SINK_JUMP_DISTANCE {
        atomicOr(&status[S_REBUILD], 1u);
    }
    let zero = vec3<f64>(0.0lf, 0.0lf, 0.0lf);
    store_pos(i, spot);
    store_vel(i, zero);
    store_angvel(i, zero);
    return spot;
}

@compute @workgroup_size(64)
fn integrate(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = particle_index(gid);
    if i >= p.n {
        return;
    }
    let force = load_wrench(2u * i);
    let torque = load_wrench(2u * i + 1u);
    let t = SPECIES_WORDS * species_of[i];
    let mass = tables[t + 1u];
    let inv_mass = tables[t + 2u];
    let inv_inertia = tables[t + 3u];
    // rapier: force = user force + g · m; Δv = force · (1/m) · dt.
    let total = force + vec3<f64>(p.gravity_x * mass, p.gravity_y * mass, p.gravity_z * mass);
    let v = load_vel(i) + total * inv_mass * p.dt;
    let w = load_angvel(i) + torque * inv_inertia * p.dt;
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
    var moved = x;
    if SINK && dot3(x, SINK_UP) < SINK_HEIGHT {
        moved = park(i, x, v, w, mass, tables[t]);
    }
    let b = load_built(i);
    let e = moved - b;
    if sqrt(dot3(e, e)) > 0.5lf * p.skin {
        atomicOr(&status[S_REBUILD], 1u);
    }
}
