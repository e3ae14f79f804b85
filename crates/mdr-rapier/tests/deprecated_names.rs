//! The former names of the neighbour-list path (`fast`, `FastForceStepper`, …) still name the
//! same items, so that programs written against them keep compiling, with a deprecation warning.
#![allow(deprecated)]

use mdr_contact::normal::Hertz;
use mdr_contact::tangential::Mindlin;
use mdr_rapier::neighbour_list as new;
use std::any::TypeId;

fn same<A: 'static, B: 'static>() -> bool {
    TypeId::of::<A>() == TypeId::of::<B>()
}

#[test]
fn former_names_are_the_renamed_items() {
    use mdr_rapier::fast as old;
    assert!(same::<
        old::FastForceStepper<Hertz>,
        new::NeighbourListStepper<Hertz>,
    >());
    assert!(same::<
        old::FastForceStepper<Hertz, Mindlin>,
        new::NeighbourListStepper<Hertz, Mindlin>,
    >());
    assert!(same::<old::FastStepReport, new::NeighbourListStepReport>());
    assert!(same::<old::FastListState<u8>, new::NeighbourListState<u8>>());
    assert!(same::<
        old::FastParticles,
        new::particles::NeighbourListParticles,
    >());
    assert!(same::<old::bed::Bed, new::bed::Bed>());
    assert!(same::<old::FastSurface, new::surfaces::NeighbourListSurface>());
    assert!(same::<new::FastSurface, new::surfaces::NeighbourListSurface>());
    assert!(!same::<
        old::FastForceStepper<Hertz>,
        new::NeighbourListStepper<Hertz, Mindlin>,
    >());
}
