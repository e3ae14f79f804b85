//! Run the Chung & Ooi tests at CI resolution, print the checks and optionally write the
//! figures: `cargo run -p mdr-verify --example verify_quick [N|all] [PLOT_DIR]`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let numbers: Vec<u8> = match args.next().as_deref() {
        Some("all") | None => (1..=8).collect(),
        Some(n) => vec![n.parse()?],
    };
    let plot_dir = args.next().map(std::path::PathBuf::from);
    for n in numbers {
        let report = mdr_verify::chung_ooi::run(n, mdr_verify::Resolution::ci())?;
        print!("{report}");
        if let Some(dir) = &plot_dir {
            for figure in &report.figures {
                println!(
                    "  figure: {}",
                    mdr_verify::plot::write_svg(figure, dir)?.display()
                );
            }
        }
    }
    Ok(())
}
