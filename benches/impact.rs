//! Benchmarks of the single-impact validator: a 200-point e_n(v0) curve with the
//! discrete spring bed (2,000 springs, 2,000 steps per Hertz contact time; target < 2 s on the
//! 2-core reference machine) and the closed form's throughput (target ≥ 100,000 velocities/s).
//! Run: `cargo bench --bench impact`. Figures are recorded in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use mdr_impact::{log_spaced, Impact, Method, Sweep, DEFAULT_SPRINGS, DEFAULT_STEPS_PER_CONTACT};
use std::hint::black_box;

fn springs_curve(c: &mut Criterion) {
    let speeds = log_spaced(0.01, 30.0, 200);
    let template = Impact::paper(1.0)
        .method(Method::Springs {
            springs: DEFAULT_SPRINGS,
        })
        .steps_per_contact(DEFAULT_STEPS_PER_CONTACT);
    let sweep = Sweep::speeds(template, &speeds);
    let mut group = c.benchmark_group("impact_curve");
    group.sample_size(10);
    group.throughput(Throughput::Elements(speeds.len() as u64));
    group.bench_function("springs_2000_x_200_points", |b| {
        b.iter(|| black_box(sweep.run().unwrap()))
    });
    group.finish();
}

fn closed_form(c: &mut Criterion) {
    let speeds = log_spaced(0.01, 30.0, 10_000);
    let mut group = c.benchmark_group("impact_closed");
    group.throughput(Throughput::Elements(speeds.len() as u64));
    group.bench_function("energy_route_serial_10000", |b| {
        b.iter(|| {
            for &v in &speeds {
                black_box(Impact::paper(v).run().unwrap());
            }
        })
    });
    group.bench_function("energy_route_sweep_10000", |b| {
        b.iter_batched(
            || Sweep::speeds(Impact::paper(1.0), &speeds),
            |sweep| black_box(sweep.run().unwrap()),
            BatchSize::LargeInput,
        )
    });
    group.finish();
}

criterion_group! {
    name = benches;
    // Criterion's plot backend needs a system font, which the build machine may not have.
    config = Criterion::default().without_plots();
    targets = springs_curve, closed_form
}
criterion_main!(benches);
