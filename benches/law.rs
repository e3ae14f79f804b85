//! Cost of one force evaluation of each contact law (issue 2): Hertz, the MDR closed form, the
//! MDR spring bed (1,000 springs) and the O(1) Mindlin tangential update.
//!
//! Every normal law runs the same realistic overlap sequence: 8 impacts (state reset between
//! them, as a new contact) with peak overlaps from 0.3 u_c to 12 u_c, 128 samples each of a
//! half-sine pulse, so the MDR law visits elastic loading, plastic loading, unloading above and
//! below `s`, and the residual crater. Criterion reports the time per sequence of 1,024
//! evaluations; `docs/performance.md` lists the time per evaluation.
//!
//! Run: `cargo bench --bench law -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, Criterion, Throughput};
use mdr_contact::nalgebra::Vector3;
use mdr_contact::normal::SpringBed;
use mdr_contact::prelude::*;
use std::hint::black_box;
use std::time::Instant;

const SAMPLES_PER_IMPACT: usize = 128;
const PEAKS_OVER_YIELD: [f64; 8] = [0.3, 0.8, 1.5, 2.5, 4.0, 6.0, 9.0, 12.0];

/// Overlaps of the 8 impacts, one `Vec` per impact.
fn impacts(yield_overlap: f64) -> Vec<Vec<f64>> {
    PEAKS_OVER_YIELD
        .iter()
        .map(|&peak| {
            (0..SAMPLES_PER_IMPACT)
                .map(|k| {
                    let phase = std::f64::consts::PI * (k as f64 + 0.5) / SAMPLES_PER_IMPACT as f64;
                    peak * yield_overlap * phase.sin()
                })
                .collect()
        })
        .collect()
}

fn evaluations() -> u64 {
    (PEAKS_OVER_YIELD.len() * SAMPLES_PER_IMPACT) as u64
}

/// Run `law` over every impact, a fresh history per impact; returns the summed force.
#[inline(never)]
fn run<L: NormalLaw>(law: &L, impacts: &[Vec<f64>]) -> f64 {
    let mut total = 0.0;
    for overlaps in impacts {
        let mut state = L::State::default();
        for &d in overlaps {
            total += law.update(&mut state, black_box(d)).force;
        }
    }
    total
}

fn normal_laws(c: &mut Criterion) {
    let pair = ContactPair::paper_fig2();
    let mdr = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let hertz = Hertz.bind(&pair).unwrap();
    let sequence = impacts(mdr.yield_overlap());
    let max_overlap = 12.0 * mdr.yield_overlap();
    let bed = SpringBed::sphere(&pair, &MdrElastoPlastic::paper(), 1000)
        .unwrap()
        .half_width(1.05 * (pair.effective_radius() * max_overlap).sqrt())
        .unwrap();
    // Sanity: the laws agree where they should (the bench measures the real thing).
    assert!((run(&bed, &sequence) / run(&mdr, &sequence) - 1.0).abs() < 1e-2);

    let mut group = c.benchmark_group("normal law, 1024 evaluations");
    group.throughput(Throughput::Elements(evaluations()));
    group.bench_function("hertz", |b| b.iter(|| run(&hertz, black_box(&sequence))));
    group.bench_function("mdr closed form", |b| {
        b.iter(|| run(&mdr, black_box(&sequence)))
    });
    group.bench_function("mdr spring bed, 1000 springs", |b| {
        b.iter(|| run(&bed, black_box(&sequence)))
    });
    group.finish();
}

fn tangential_law(c: &mut Criterion) {
    let pair = ContactPair::paper_fig2();
    let mdr = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let mindlin = Mindlin::new(0.3).unwrap().bind(&pair).unwrap();
    // Inputs of an oblique impact: the MDR normal response along the sequence, a slowly
    // rotating normal, a tangential displacement increment per step.
    let mut inputs = Vec::new();
    for overlaps in impacts(mdr.yield_overlap()) {
        let mut state = MdrState::default();
        for (k, &d) in overlaps.iter().enumerate() {
            let angle = 1e-3 * k as f64;
            inputs.push(TangentialInput {
                normal: Vector3::new(angle.sin(), 0.0, angle.cos()),
                displacement_increment: Vector3::new(2e-8, 5e-9, 1e-9),
                normal_response: mdr.update(&mut state, d),
            });
        }
    }
    let mut group = c.benchmark_group("tangential law, 1024 evaluations");
    group.throughput(Throughput::Elements(evaluations()));
    group.bench_function("mindlin O(1)", |b| {
        b.iter(|| {
            let mut state = MindlinState::default();
            let mut total = 0.0;
            for input in black_box(&inputs) {
                total += mindlin.update(&mut state, input).force.x;
            }
            total
        })
    });
    group.finish();
}

/// Interleaved timing of Hertz and the MDR closed form: on a shared, loaded machine the
/// criterion medians of two benchmarks taken one after the other can differ by ±30 % from load
/// changes alone, so the ratio is also measured as the minimum over 200 interleaved rounds of
/// 100 sequences each (the minimum is the run least disturbed by other processes).
fn interleaved_ratio() {
    let pair = ContactPair::paper_fig2();
    let mdr = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let hertz = Hertz.bind(&pair).unwrap();
    let sequence = impacts(mdr.yield_overlap());
    let (mut t_hertz, mut t_mdr) = (f64::INFINITY, f64::INFINITY);
    let time = |f: &dyn Fn() -> f64| {
        let start = Instant::now();
        for _ in 0..100 {
            black_box(f());
        }
        start.elapsed().as_secs_f64()
    };
    for _ in 0..200 {
        t_hertz = t_hertz.min(time(&|| run(&hertz, black_box(&sequence))));
        t_mdr = t_mdr.min(time(&|| run(&mdr, black_box(&sequence))));
    }
    let per_evaluation = 1e9 / (100 * evaluations()) as f64;
    println!(
        "interleaved minimum: hertz {:.2} ns, mdr closed form {:.2} ns per evaluation, \
         mdr/hertz = {:.2}",
        t_hertz * per_evaluation,
        t_mdr * per_evaluation,
        t_mdr / t_hertz
    );
}

criterion_group!(benches, normal_laws, tangential_law);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    interleaved_ratio();
}
