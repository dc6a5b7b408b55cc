//! Drawing that the `rocking` command, the work-precision study and the Python package need: the
//! embedded font (DejaVu Sans, see assets/DejaVuSans-LICENSE.txt, so no system font is needed),
//! [`chart`] (a figure's page, axes, lines, markers and legend), [`text`]
//! (subscripts, tick labels, titles wrapped between items), [`colour`] and [`style`] (a palette
//! that stays distinct for colour-blind readers and in greyscale, measured), [`export`] (one SVG
//! turned into PNG and PDF), [`animation`], the animated GIF of a run, and [`figure`], every
//! figure the command and Python draw (runs against τ, spectra, boundaries, IDA and fragility),
//! with [`figure_file`], the figure files that gather their runs and sweeps.
//!
//! It owns how things look; it must not compute results: it draws what a run or a study gives
//! (a figure file loads its runs and sweeps through `rocking-study`).

pub mod animation;
pub mod chart;
pub mod colour;
mod error;
pub mod export;
pub mod figure;
pub mod figure_file;
pub mod style;
pub mod text;

pub use error::FigureError;

use std::sync::Once;

use plotters::style::{register_font, FontStyle};

pub(crate) static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// Registers the embedded font as "sans-serif" (once per process).
pub fn register() {
    REGISTER.call_once(|| {
        // The font is bundled and known to be valid; a failure leaves text unrendered only.
        let _ = register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// `text` broken into lines of at most `chars` characters at spaces (a longer word stays whole).
pub fn wrap(text: &str, chars: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if line.chars().count() + 1 + word.chars().count() <= chars => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::wrap;

    #[test]
    fn a_long_legend_wraps_at_spaces_and_keeps_every_word() {
        let text = "overturned after one impact, with the rigid column's boundary dashed";
        let lines = wrap(text, 30);
        assert!(lines.len() >= 2, "{lines:?}");
        assert!(lines.iter().all(|l| l.chars().count() <= 30), "{lines:?}");
        assert_eq!(lines.join(" "), text);
    }
}
