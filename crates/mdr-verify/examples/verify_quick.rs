//! Run the Chung & Ooi tests at CI resolution and print the checks:
//! `cargo run -p mdr-verify --example verify_quick [N]`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let numbers: Vec<u8> = match std::env::args().nth(1) {
        Some(n) => vec![n.parse()?],
        None => (1..=8).collect(),
    };
    for n in numbers {
        let report = mdr_verify::chung_ooi::run(n, mdr_verify::Resolution::ci())?;
        print!("{report}");
    }
    Ok(())
}
