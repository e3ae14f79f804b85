//! The plot font: DejaVu Sans (Bitstream Vera licence, `assets/DejaVuSans-LICENSE.txt` of this
//! crate), embedded in the binary so that plots are laid out the same on every machine, with or
//! without installed fonts.

use plotters::style::{register_font, FontStyle};
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Register the embedded font as plotters' `sans-serif` family (once per process; later calls
/// do nothing). Call it before drawing text.
pub fn register_plot_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The bytes are a valid TrueType font shipped with this crate; were they not, plotters
        // would report the missing font when drawing text, as an error of that plot.
        let _ = register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

#[cfg(test)]
mod tests {
    use plotters::prelude::*;

    /// Text is laid out with the embedded font: a bitmap with a caption draws without a font
    /// error even where the machine has no fonts.
    #[test]
    fn text_draws_with_the_embedded_font() {
        super::register_plot_font();
        let mut pixels = vec![255u8; 200 * 100 * 3];
        {
            let root = BitMapBackend::with_buffer(&mut pixels, (200, 100)).into_drawing_area();
            root.draw_text(
                "MDR",
                &("sans-serif", 40).into_font().color(&BLACK),
                (10, 10),
            )
            .unwrap();
            root.present().unwrap();
        }
        assert!(pixels.iter().any(|&p| p < 128), "no glyph was drawn");
    }
}
