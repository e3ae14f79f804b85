//! Every entry of the validator that takes an impact speed refuses one that is NaN, infinite or
//! not positive with an error naming `speed`, instead of answering `e_n = 1`.

use mdr_contact::ContactPair;
use mdr_impact::fit::{fit, predict, FitParameter, FitValues};
use mdr_impact::output::Measurement;
use mdr_impact::{Impact, ImpactError, Method, Route, Sweep};

const BAD_SPEEDS: [f64; 5] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1.0, 0.0];

fn assert_names_speed<T: std::fmt::Debug>(result: mdr_impact::Result<T>, speed: f64) {
    let error = result.expect_err(&format!("speed {speed} should have been refused"));
    assert_eq!(error.key(), Some("speed"), "{error}");
    assert!(error.to_string().contains("speed"), "{error}");
}

#[test]
fn impact_and_trace_refuse_a_bad_speed_on_every_route() {
    for v in BAD_SPEEDS {
        for route in [Route::Auto, Route::Energy, Route::TimeIntegration] {
            assert_names_speed(Impact::paper(v).route(route).run(), v);
        }
        assert_names_speed(Impact::paper(v).trace(), v);
        assert_names_speed(
            Impact::paper(v)
                .method(Method::Springs { springs: 50 })
                .run(),
            v,
        );
        assert_names_speed(Sweep::speeds(Impact::paper(1.0), &[1.0, v]).run(), v);
    }
}

#[test]
fn spring_bed_sizing_refuses_a_bad_speed() {
    for v in [f64::NAN, f64::INFINITY, -1.0] {
        let impact = Impact::paper(v);
        let model = mdr_contact::normal::MdrElastoPlastic::paper();
        assert_names_speed(impact.spring_bed(&model, 100), v);
    }
}

#[test]
fn predict_refuses_a_bad_speed() {
    let pair = ContactPair::paper_fig2();
    for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1.0] {
        assert_names_speed(predict(&pair, &FitValues::paper(), &[1.0, v]), v);
    }
    // A good speed still gives the energy route's value, and e_n = 1 at rest.
    let e = predict(&pair, &FitValues::paper(), &[0.0, 1.0]).unwrap();
    assert_eq!(e[0], FitValues::paper().scale);
    assert!(e[1] < e[0]);
}

#[test]
fn fit_refuses_a_bad_measured_speed() {
    let pair = ContactPair::paper_fig2();
    for v in BAD_SPEEDS {
        let mut data: Vec<Measurement> = [0.5, 1.0, 2.0, 4.0]
            .iter()
            .map(|&speed| Measurement {
                speed,
                restitution: 0.7,
            })
            .collect();
        data[2].speed = v;
        let result = fit(&pair, FitValues::paper(), &[FitParameter::Scale], &data);
        assert!(
            matches!(&result, Err(ImpactError::Invalid { key: "speed", .. })),
            "{result:?}"
        );
    }
}
