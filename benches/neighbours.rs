//! Cost of one neighbour-list build of the neighbour-list path (binning, the search of the 27
//! cells around each sphere, the sorted pair list and its per-particle indexes, and the
//! carry-over of the live contact histories), on 20,736
//! spheres of radius 2 mm packed as a jittered face-centred cubic lattice (12 neighbours within
//! the skin, 6 listed pairs per sphere, about half of them touching): in open space (a hopper or a
//! column) and in a box periodic in x and y (a bed); and in open space with every sphere moved by
//! up to ±30 % of its radius per axis (`open_disordered`: which stencil points are partners is
//! then as irregular as in a poured packing, where a lattice repeats one pattern). The skin is 0.1 d, the scenes'
//! default; each pair carries a 72-byte history (the size of a scene's with the MDR law and no
//! rolling resistance), live where the spheres touch, so the carry-over moves what a scene's
//! does.
//!
//! Run: `cargo bench --bench neighbours -- --warm-up-time 1 --measurement-time 5`

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mdr_contact::nalgebra::Vector3;
use mdr_rapier::neighbour_list::neighbours::{NeighbourBuilder, PairList};
use mdr_rapier::neighbour_list::Boundary;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const RADIUS: f64 = 0.002;
/// Cubic cells of the lattice (4 spheres each).
const CELLS: [usize; 3] = [18, 18, 16];
/// Side of a cubic cell: nearest neighbours 2 r apart before the jitter.
const SIDE: f64 = std::f64::consts::SQRT_2 * 2.0 * RADIUS;

/// A scene's history size (MDR, Mindlin and the work books; no rolling resistance).
type History = [f64; 9];

/// Jittered FCC lattice, each sphere moved by up to ±`jitter` (a fraction of r) per axis.
fn lattice(jitter: f64) -> (Vec<Vector3<f64>>, Vec<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let basis = [
        [0.0, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        [0.5, 0.0, 0.5],
        [0.0, 0.5, 0.5],
    ];
    let mut x = Vec::new();
    for k in 0..CELLS[2] {
        for j in 0..CELLS[1] {
            for i in 0..CELLS[0] {
                for b in basis {
                    let mut jitter = || rng.random_range(-jitter..jitter) * RADIUS;
                    x.push(Vector3::new(
                        (i as f64 + b[0] + 0.25) * SIDE + jitter(),
                        (j as f64 + b[1] + 0.25) * SIDE + jitter(),
                        (k as f64 + b[2] + 0.25) * SIDE + jitter(),
                    ));
                }
            }
        }
    }
    let r = vec![RADIUS; x.len()];
    (x, r)
}

fn build(c: &mut Criterion) {
    let skin = 0.2 * RADIUS;
    let side = |n: usize| n as f64 * SIDE;
    // ±0.5 % of d, and ±30 % of r.
    let cases = [
        ("open", Boundary::Open, 0.01),
        (
            "periodic_xy",
            Boundary::periodic_xy((0.0, side(CELLS[0])), (0.0, side(CELLS[1]))).unwrap(),
            0.01,
        ),
        ("open_disordered", Boundary::Open, 0.3),
    ];
    let mut group = c.benchmark_group("neighbour_build");
    for (name, boundary, jitter) in cases {
        let (x, r) = lattice(jitter);
        group.throughput(Throughput::Elements(x.len() as u64));
        let mut builder = NeighbourBuilder::default();
        let (mut old, mut list) = (PairList::<History>::default(), PairList::default());
        builder.build(&boundary, &x, &r, skin, &mut old, &mut list);
        // Live histories where the spheres touch.
        let offsets = boundary.offsets();
        for p in 0..list.len() {
            let (i, j) = (list.i[p] as usize, list.j[p] as usize);
            let xj = x[j] + offsets[list.image[p] as usize].position;
            list.active[p] = (x[i] - xj).norm() < r[i] + r[j];
            list.history[p] = [p as f64; 9];
        }
        group.bench_function(name, |b| {
            b.iter(|| {
                std::mem::swap(&mut old, &mut list);
                builder.build(&boundary, &x, &r, skin, &mut old, &mut list);
                list.len()
            })
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    // Criterion's plot backend needs a system font, which the build machine may not have.
    config = Criterion::default().without_plots();
    targets = build
}
criterion_main!(benches);
