//! The game-style example, run as a test: every body stays where a game expects it.

#[path = "../examples/game_world.rs"]
mod game_world;

#[test]
fn the_game_world_example_keeps_every_body_in_play() {
    let s = game_world::run(300).unwrap();
    // Crates and rock stand on the floor (rapier's contacts, to its allowance).
    assert!(s.lowest_surface_body > -0.02, "{s:?}");
    // No MDR sphere fell through the floor or the crates.
    assert!(s.lowest_sphere > 0.07, "{s:?}");
    // The user's ball rests on the ledge (top at 0.85 m); the ghost fell through to the floor.
    assert!((s.plain_balls[0] - 0.95).abs() < 0.02, "{s:?}");
    assert!(s.plain_balls[1] < 0.15, "{s:?}");
    assert!(s.law_impacts >= 12, "{s:?}");
    assert!(s.rapier_pairs >= 3, "{s:?}");
    assert!(s.collisions_started >= 12, "{s:?}");
}
