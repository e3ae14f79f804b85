//! Subcommands of the `mdr-dem` program, one module per command group.

pub mod bench;
pub mod impact;
pub mod sim;
pub mod sim_ring;
pub mod sim_run;
pub mod verify;
