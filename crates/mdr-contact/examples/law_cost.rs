//! Evaluates a normal law over the overlap sequence of `benches/law.rs` (8 impacts, peaks
//! 0.3–12 u_c, 128 half-sine samples each, a fresh history per impact) a given number of times:
//! a deterministic workload for instruction counts, where wall-clock timings are too noisy.
//!
//! ```text
//! cargo build --release -p mdr-contact --example law_cost
//! valgrind --tool=cachegrind --cache-sim=no target/release/examples/law_cost adhesive 1000
//! ```
//!
//! The instructions per evaluation are the difference between two repeat counts divided by
//! 1,024 times the difference of the counts (the setup cancels). Laws: `hertz`, `mdr`,
//! `adhesive` (the adhesive MDR closed form with Δγ = 1 J/m², as in the bench).

use mdr_contact::prelude::*;
use std::hint::black_box;

const SAMPLES_PER_IMPACT: usize = 128;
const PEAKS_OVER_YIELD: [f64; 8] = [0.3, 0.8, 1.5, 2.5, 4.0, 6.0, 9.0, 12.0];

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

fn repeat<L: NormalLaw>(law: &L, impacts: &[Vec<f64>], repeats: usize) -> f64 {
    (0..repeats).map(|_| run(law, black_box(impacts))).sum()
}

fn main() {
    let mut args = std::env::args().skip(1);
    let usage = "usage: law_cost hertz|mdr|adhesive REPEATS";
    let law = args.next().expect(usage);
    let repeats: usize = args.next().and_then(|n| n.parse().ok()).expect(usage);
    let pair = ContactPair::paper_fig2();
    let mdr = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let sequence = impacts(mdr.yield_overlap());
    let total = match law.as_str() {
        "hertz" => repeat(&Hertz.bind(&pair).unwrap(), &sequence, repeats),
        "mdr" => repeat(&mdr, &sequence, repeats),
        "adhesive" => repeat(
            &AdhesiveMdr::new(MdrElastoPlastic::paper(), 1.0)
                .unwrap()
                .bind(&pair)
                .unwrap(),
            &sequence,
            repeats,
        ),
        other => panic!("unknown law {other}; {usage}"),
    };
    println!("{law}: {repeats} × 1024 evaluations, summed force {total:e} N");
}
