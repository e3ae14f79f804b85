//! Experimental points of Kharaz, Gorham & Salman (2001) for Chung & Ooi's test 4.
//!
//! A. H. Kharaz, D. A. Gorham, A. D. Salman, "An experimental study of the elastic rebound of
//! spheres", Powder Technology 120, 281–291 (2001), doi:10.1016/S0032-5910(01)00283-2: 5 mm
//! aluminium oxide spheres on a thick soda-lime glass anvil at 3.9 m/s, impact angle measured
//! from the normal. No copy of the paper (or of Chung & Ooi's figures) was available here; the
//! points below are the digitisations published in two open-source DEM codes, copied as numbers
//! (not re-digitised), each with its repository, path and commit:
//!
//! - e_t, spin, rebound angle of the centre: Lethe (chaos-polymtl/lethe),
//!   `examples/dem/3d-oblique-wall-impact/oblique_wall_impact_postprocessing.py`, commit
//!   255b519263fbb22f758d40763a12290296d53200 (cited there to Kharaz et al. 2001).
//! - rebound angle of the contact point: Kratos Multiphysics (KratosMultiphysics/Kratos),
//!   `applications/DEMApplication/tests/DEM3D_chung_ooi_tests/test4_data/paper_data/benchmark4_graph3.dat`,
//!   section `#Experiment`, commit f678879c5465efeaae8328b72b3fea70897e4721 (Chung & Ooi's
//!   Fig. of test 4).
//!
//! Definitions (our sign convention, `collision` module): `e_t = v_t'/v_t` of the centre; spin
//! `ω'` (rad/s, forward rolling positive); rebound angle of the centre `atan(v_t'/v_n')`; rebound
//! angle of the contact point `atan((v_t' − R ω')/v_n')`, all angles in degrees from the normal.

/// `(impact angle °, e_t)` (Lethe's digitisation).
pub const TANGENTIAL_RESTITUTION: [(f64, f64); 8] = [
    (1.84, 0.79344),
    (3.703, 0.74533),
    (9.496, 0.67257),
    (20.012, 0.59691),
    (30.127, 0.68756),
    (39.382, 0.77148),
    (49.694, 0.84761),
    (60.02, 0.90142),
];

/// `(impact angle °, |ω'| rad/s)` (Lethe's digitisation).
pub const SPIN: [(f64, f64); 7] = [
    (6.143, 136.18),
    (10.991, 265.69),
    (21.251, 577.65),
    (31.157, 612.88),
    (39.143, 595.49),
    (50.348, 453.21),
    (60.328, 382.09),
];

/// `(impact angle °, rebound angle of the centre °)` (Lethe's digitisation).
pub const REBOUND_ANGLE_CENTRE: [(f64, f64); 9] = [
    (0.016, 0.074),
    (2.15, 1.733),
    (4.096, 2.962),
    (9.826, 6.518),
    (20.567, 12.208),
    (30.29, 21.67),
    (39.535, 32.613),
    (49.747, 45.125),
    (60.208, 57.474),
];

/// `(impact angle °, rebound angle of the contact point °)` (Kratos' digitisation).
pub const REBOUND_ANGLE_CONTACT: [(f64, f64); 11] = [
    (2.0997281572207847, 0.7703927492447065),
    (3.9434155319702846, 0.7703927492447065),
    (9.717622556290827, -1.0574018126888234),
    (20.309682809728216, -8.53474320241692),
    (30.160683905575503, -2.5528700906344426),
    (39.120476602752326, 9.909365558912384),
    (49.51201496648886, 30.015105740181262),
    (59.9037955064207, 49.95468277945619),
    (70.46025585915032, 66.90332326283988),
    (78.85965284042405, 78.86706948640483),
    (84.78158734387202, 85.6797583081571),
];
