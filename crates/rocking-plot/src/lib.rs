//! Drawing that both the `rocking` command and the Python package need: the embedded font
//! (DejaVu Sans, see assets/DejaVuSans-LICENSE.txt, so no system font is needed), text wrapping
//! for titles and legends, and [`animation`], the animated GIF of a run.
//!
//! It owns how things look; it must not compute results (it draws what a run or a study gives).

pub mod animation;

use std::sync::Once;

use plotters::style::{register_font, FontStyle};

static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
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
    fn a_long_title_wraps_at_spaces_and_keeps_every_word() {
        let title = "Fig. 8: γ_mb = γ_mc = 2, α = 0.1, ω_n/p = 2.5: rocking spectrum";
        let lines = wrap(title, 30);
        assert!(lines.len() >= 2, "{lines:?}");
        assert!(lines.iter().all(|l| l.chars().count() <= 30), "{lines:?}");
        assert_eq!(lines.join(" "), title);
    }
}
