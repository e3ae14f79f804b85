use mdr_contact::normal::{thornton_restitution, NormalModel, Thornton};
use mdr_contact::ContactPair;
use mdr_impact::*;
fn main() {
    let pair = ContactPair::paper_fig2();
    let vy = Impact::paper(1.0).yield_speed().unwrap();
    println!("vy = {vy}");
    for v in [0.1, 0.3, 1.0, 3.0, 10.0, 100.0] {
        let e = Impact::paper(v).route(Route::Energy).run().unwrap();
        let t = Impact::paper(v)
            .route(Route::TimeIntegration)
            .run()
            .unwrap();
        println!(
            "{v}: energy e={} tc={} dmax={} | time e={} tc={} dmax={} F {} {}",
            e.normal_restitution,
            e.contact_time,
            e.max_overlap,
            t.normal_restitution,
            t.contact_time,
            t.max_overlap,
            e.peak_force,
            t.peak_force
        );
    }
    let th = Thornton::new(1.0e9).unwrap();
    let vty = th.bind(&pair).unwrap().yield_speed(pair.reduced_mass());
    for r in [1.5, 3.0, 10.0] {
        let o = Impact::new(pair, NormalSpec::Thornton(th), r * vty)
            .run()
            .unwrap();
        println!(
            "thornton v/vy={r}: {} vs {}",
            o.normal_restitution,
            thornton_restitution(r)
        );
    }
    for a in [10.0, 30.0, 60.0, 80.0] {
        let o = Impact::paper(1.0)
            .angle_degrees(a)
            .friction(0.2)
            .run()
            .unwrap();
        println!("angle {a}: {:?}", o);
    }
    let t0 = std::time::Instant::now();
    let speeds = log_spaced(0.01, 100.0, 100000);
    let out = Sweep::speeds(Impact::paper(1.0), &speeds).run().unwrap();
    println!("{} closed in {:?}", out.len(), t0.elapsed());
}
