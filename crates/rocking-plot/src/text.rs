//! Text in the paper's notation on every output: labels are written as in the tables and the
//! terminal (`u_cr`, `ω_p/p`, `γ_mb`), and a figure draws `x_ab` as x with the subscript "ab".
//! plotters draws one run of text per call, so [`rich`] marks the subscripts with private-use
//! characters and [`finish_svg`] turns the marks into SVG `<tspan>`s (shifted by `dy`, smaller):
//! the PNG and the PDF are made from that SVG, so all three show the same subscripts. Also here:
//! tick labels without "-0" or a needless ".0", and titles that wrap only between items.

/// Opens a subscript (private use: no font draws it, no label contains it).
const SUB: char = '\u{E000}';
/// Closes it.
const END: char = '\u{E001}';

/// A subscript's size and its drop below the baseline, as fractions of the font size.
const SUB_SIZE: f64 = 0.72;
const SUB_DROP: f64 = 0.24;

/// `text` with each subscript marked: `_` after a letter or digit, followed by `{group}` or by
/// a run of letters and digits (`u_cr`, `ω_n/p`, `E_{ref}`). Any other `_` stays as it is.
pub fn rich(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len() + 8);
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let after_word = i > 0 && chars[i - 1].is_alphanumeric();
        if c == '_' && after_word && i + 1 < chars.len() {
            if chars[i + 1] == '{' {
                if let Some(len) = chars[i + 2..].iter().position(|&c| c == '}') {
                    out.push(SUB);
                    out.extend(&chars[i + 2..i + 2 + len]);
                    out.push(END);
                    i += len + 3;
                    continue;
                }
            } else if chars[i + 1].is_alphanumeric() {
                let len = chars[i + 1..]
                    .iter()
                    .take_while(|c| c.is_alphanumeric())
                    .count();
                out.push(SUB);
                out.extend(&chars[i + 1..i + 1 + len]);
                out.push(END);
                i += len + 1;
                continue;
            }
        }
        out.push(c);
        i += 1;
    }
    out
}

/// `text` as read: the subscript marks of [`rich`] removed (for width estimates).
pub fn plain(text: &str) -> String {
    text.chars().filter(|&c| c != SUB && c != END).collect()
}

/// The SVG that plotters wrote, with the subscript marks of every `<text>` element turned into
/// `<tspan class="sub">` (smaller, `dy` below the baseline) and the text after it back on the
/// baseline. Elements without marks are left byte for byte.
pub fn finish_svg(svg: &str) -> String {
    finish_svg_min(svg, 0.0)
}

/// [`finish_svg`] with no subscript smaller than `min_sub` (in the SVG's units), nor larger
/// than its text: a figure at its printed size keeps its subscripts at 6 pt or more.
pub fn finish_svg_min(svg: &str, min_sub: f64) -> String {
    if !svg.contains(SUB) {
        return svg.to_string();
    }
    let mut out = String::with_capacity(svg.len() + 1024);
    let mut rest = svg;
    while let Some(start) = rest.find("<text") {
        let Some(open_end) = rest[start..].find('>').map(|k| start + k + 1) else {
            break;
        };
        let Some(close) = rest[open_end..].find("</text>").map(|k| open_end + k) else {
            break;
        };
        out.push_str(&rest[..open_end]);
        let size = attribute(&rest[start..open_end], "font-size")
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(12.0);
        out.push_str(&tspans(&rest[open_end..close], size, min_sub));
        rest = &rest[close..];
    }
    out.push_str(rest);
    out
}

/// A subscript's size in a text of `size`: [`SUB_SIZE`] of it, at least `min_sub` (rounded up
/// to the two decimals the SVG carries, so that it reads back at least `min_sub`), at most `size`.
fn sub_size(size: f64, min_sub: f64) -> f64 {
    if min_sub <= 0.0 {
        return SUB_SIZE * size;
    }
    ((SUB_SIZE * size).max(min_sub) * 100.0)
        .ceil()
        .min(size * 100.0)
        / 100.0
}

/// The value of `name="..."` in an element's opening tag.
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let from = tag.find(&key)? + key.len();
    let len = tag[from..].find('"')?;
    Some(&tag[from..from + len])
}

/// The content of one `<text>` element with its marks as tspans.
fn tspans(content: &str, size: f64, min_sub: f64) -> String {
    if !content.contains(SUB) {
        return content.to_string();
    }
    let drop = SUB_DROP * size;
    let mut out = String::new();
    let mut lowered = false;
    let mut plain_run = String::new();
    let mut chars = content.chars();
    let flush = |out: &mut String, run: &mut String, lowered: &mut bool| {
        if run.is_empty() {
            return;
        }
        if *lowered {
            out.push_str(&format!("<tspan dy=\"{:.2}\">{run}</tspan>", -drop));
            *lowered = false;
        } else {
            out.push_str(run);
        }
        run.clear();
    };
    while let Some(c) = chars.next() {
        if c == SUB {
            flush(&mut out, &mut plain_run, &mut lowered);
            let sub: String = chars.by_ref().take_while(|&c| c != END).collect();
            // Two subscripts in a row: the second starts where the first is.
            let dy = if lowered { 0.0 } else { drop };
            out.push_str(&format!(
                "<tspan class=\"sub\" dy=\"{dy:.2}\" font-size=\"{:.2}\">{sub}</tspan>",
                sub_size(size, min_sub)
            ));
            lowered = true;
        } else {
            plain_run.push(c);
        }
    }
    flush(&mut out, &mut plain_run, &mut lowered);
    out
}

/// A tick label: at most six decimals with trailing zeros dropped ("20", not "20.0"), zero as
/// "0" whatever its sign, a true minus sign, and powers of ten (10⁻⁵) beyond 1e6 or below 1e-4.
pub fn tick(v: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    let a = v.abs();
    let body = if a < 5e-13 {
        return "0".into();
    } else if !(1e-4..1e6).contains(&a) {
        let s = format!("{a:.3e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        let e = superscript(e.parse::<i32>().unwrap_or(0));
        if m == "1" {
            format!("10{e}")
        } else {
            format!("{m}×10{e}")
        }
    } else {
        let s = format!("{a:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "0" {
            return "0".into();
        }
        s.to_string()
    };
    if v < 0.0 {
        format!("\u{2212}{body}")
    } else {
        body
    }
}

/// The tick label of 10^`e` on a logarithmic axis: "10⁻⁵", "10⁰", "10²".
pub fn power_of_ten(e: i32) -> String {
    format!("10{}", superscript(e))
}

/// An exponent in superscript digits (⁻¹²).
fn superscript(e: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits = e.unsigned_abs().to_string();
    let sign = if e < 0 { "⁻" } else { "" };
    sign.chars()
        .chain(digits.bytes().map(|d| DIGITS[(d - b'0') as usize]))
        .collect()
}

/// `text` broken into lines of at most `chars` characters between its items only: after ", ",
/// ": " or "; " outside brackets (an expression such as `a_p/(g tan α) = 1.3` is never cut); an
/// item longer than a line stays whole.
pub fn wrap_items(text: &str, chars: usize) -> Vec<String> {
    let mut items: Vec<String> = Vec::new();
    let mut depth = 0i32;
    let mut item = String::new();
    let mut it = text.chars().peekable();
    while let Some(c) = it.next() {
        item.push(c);
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' | ':' | ';' if depth <= 0 && it.peek() == Some(&' ') => {
                items.push(std::mem::take(&mut item));
                it.next();
            }
            _ => {}
        }
    }
    if !item.is_empty() {
        items.push(item);
    }
    let width = |s: &str| plain(s).chars().count();
    let mut lines: Vec<String> = Vec::new();
    for item in items {
        match lines.last_mut() {
            Some(line) if width(line) + 1 + width(&item) <= chars => {
                line.push(' ');
                line.push_str(&item);
            }
            _ => lines.push(item),
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subscripts_are_marked_after_a_letter_only() {
        assert_eq!(plain(&rich("u/u_cr")), "u/ucr");
        assert_eq!(rich("u/u_cr"), format!("u/u{SUB}cr{END}"));
        assert_eq!(rich("E_{ref}/2"), format!("E{SUB}ref{END}/2"));
        assert_eq!(rich("a_p/(g tan α)"), format!("a{SUB}p{END}/(g tan α)"));
        assert_eq!(
            rich("γ_mb = γ_mc = 2"),
            format!("γ{SUB}mb{END} = γ{SUB}mc{END} = 2")
        );
        // Not after a letter, or with nothing after it: left as written.
        assert_eq!(rich("_x a_ b"), "_x a_ b");
    }

    #[test]
    fn marks_become_tspans_and_the_baseline_comes_back() {
        let svg = format!(
            "<svg><text x=\"1\" font-size=\"10\">{}</text><text>plain_x</text></svg>",
            rich("γ_mb = γ_mc = 2")
        );
        let done = finish_svg(&svg);
        assert_eq!(
            done,
            "<svg><text x=\"1\" font-size=\"10\">γ<tspan class=\"sub\" dy=\"2.40\" \
             font-size=\"7.20\">mb</tspan><tspan dy=\"-2.40\"> = γ</tspan><tspan class=\"sub\" \
             dy=\"2.40\" font-size=\"7.20\">mc</tspan><tspan dy=\"-2.40\"> = 2</tspan></text>\
             <text>plain_x</text></svg>"
        );
        assert!(!done.contains(SUB) && !done.contains(END));
    }

    #[test]
    fn ticks_have_no_negative_zero_and_no_needless_decimals() {
        assert_eq!(tick(20.0), "20");
        assert_eq!(tick(-0.0), "0");
        assert_eq!(tick(-1e-17), "0");
        assert_eq!(tick(0.1 + 0.2), "0.3");
        assert_eq!(tick(-2.5), "\u{2212}2.5");
        assert_eq!(tick(2e-6), "2×10⁻⁶");
        assert_eq!(tick(1e7), "10⁷");
        assert_eq!(power_of_ten(-12), "10⁻¹²");
        assert_eq!(power_of_ten(0), "10⁰");
    }

    #[test]
    fn titles_wrap_between_items_only() {
        let title =
            "Fig. 3: ω_n/p = 11.9, α = 0.2, sine pulse ω_p/p = 5.1, a_p/(g tan α) = 1.30, VVEL";
        let lines = wrap_items(title, 40);
        assert!(lines.len() >= 2, "{lines:?}");
        assert_eq!(lines.join(" "), title);
        for l in &lines {
            assert!(
                l.ends_with(',') || l.ends_with(':') || l == lines.last().unwrap(),
                "{l}"
            );
        }
        assert!(lines.iter().any(|l| l.contains("a_p/(g tan α) = 1.30")));
    }
}
