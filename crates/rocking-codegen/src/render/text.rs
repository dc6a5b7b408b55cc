//! Rust source text: literals, identifiers, doc lines and the final whitespace tidy.

const RUST_KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut",
    "pub", "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type",
    "unsafe", "use", "where", "while", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "try", "typeof", "unsized", "virtual", "yield",
];

/// Strips trailing whitespace, collapses runs of blank lines and ends with one newline.
pub(super) fn tidy(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut blank = 0;
    for line in text.lines() {
        let line = line.trim_end();
        if line.is_empty() {
            blank += 1;
            if blank > 1 {
                continue;
            }
        } else {
            blank = 0;
        }
        out.push_str(line);
        out.push('\n');
    }
    while out.ends_with("\n\n") {
        out.pop();
    }
    out
}

/// Formats an `f64` as a Rust expression that evaluates to exactly that value:
/// the shortest round-trip representation, always with a `.` or an exponent
/// (`3.0`, `0.375`, `1e-20`, `-0.0`), or `f64::INFINITY`, `f64::NEG_INFINITY`, `f64::NAN`.
pub fn float_literal(v: f64) -> String {
    if v.is_nan() {
        return "f64::NAN".to_string();
    }
    if v.is_infinite() {
        return if v > 0.0 {
            "f64::INFINITY".to_string()
        } else {
            "f64::NEG_INFINITY".to_string()
        };
    }
    let s = format!("{v:?}");
    if s.contains(['.', 'e', 'E']) {
        s
    } else {
        format!("{s}.0")
    }
}

/// `snake_case` → `CamelCase` (`full` → `Full`, `rigid_base` → `RigidBase`).
pub fn camel_case(name: &str) -> String {
    let mut out = String::new();
    for part in name.split('_').filter(|p| !p.is_empty()) {
        let mut chars = part.chars();
        if let Some(c) = chars.next() {
            out.extend(c.to_uppercase());
            out.push_str(chars.as_str());
        }
    }
    out
}

pub(super) fn is_ident(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c == '_' || c.is_ascii_alphabetic())
        && chars.all(|c| c == '_' || c.is_ascii_alphanumeric())
        && s != "_"
        && !RUST_KEYWORDS.contains(&s)
}

pub(super) fn is_work_var_name(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some('w' | 'o')) && s.len() > 1 && chars.all(|c| c.is_ascii_digit())
}

pub(crate) fn str_lit(s: &str) -> String {
    format!("{s:?}")
}

/// Doc-comment lines (`prefix` + text) for a markdown block; blank lines kept.
pub(super) fn doc_lines(prefix: &str, text: &str) -> Vec<String> {
    let text = text.trim();
    if text.is_empty() {
        return Vec::new();
    }
    text.lines()
        .map(|l| {
            let l = l.trim_end();
            if l.is_empty() {
                prefix.to_string()
            } else {
                format!("{prefix} {l}")
            }
        })
        .collect()
}

/// Single-line text (no newlines), for list items and table cells.
pub(super) fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

pub(super) fn code_list(items: &[String]) -> String {
    if items.is_empty() {
        "(none)".to_string()
    } else {
        items
            .iter()
            .map(|e| format!("`{e}`"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// An array expression: on one line when short, else one element per line.
pub(super) fn array_lines(values: &[String]) -> Vec<String> {
    let one = format!("[{}]", values.join(", "));
    if one.len() <= 60 {
        vec![one]
    } else {
        let mut lines = vec!["[".to_string()];
        lines.extend(values.iter().map(|v| format!("    {v},")));
        lines.push("]".to_string());
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals() {
        assert_eq!(float_literal(0.375), "0.375");
        assert_eq!(float_literal(1e-20), "1e-20");
        assert_eq!(float_literal(1e300), "1e300");
        assert_eq!(float_literal(-0.0), "-0.0");
        assert_eq!(float_literal(3.0), "3.0");
        assert_eq!(float_literal(-2.5), "-2.5");
        assert_eq!(float_literal(0.1), "0.1");
        assert_eq!(float_literal(1e16), "1e16");
        assert_eq!(float_literal(f64::INFINITY), "f64::INFINITY");
        assert_eq!(float_literal(f64::NEG_INFINITY), "f64::NEG_INFINITY");
        assert_eq!(float_literal(f64::NAN), "f64::NAN");
        // Round trip through Rust's own parser.
        for v in [
            0.1,
            1.0 / 3.0,
            6.02214076e23,
            5e-324,
            f64::MAX,
            -1.7976931348623157e308,
        ] {
            let lit = float_literal(v);
            assert!(lit.contains(['.', 'e']), "{lit}");
            assert_eq!(lit.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{lit}");
        }
    }

    #[test]
    fn camel() {
        assert_eq!(camel_case("full"), "Full");
        assert_eq!(camel_case("rigid_base"), "RigidBase");
        assert_eq!(camel_case("p2_linear"), "P2Linear");
    }

    #[test]
    fn identifiers() {
        assert!(is_ident("theta_dot"));
        assert!(!is_ident("fn"));
        assert!(!is_ident("2x"));
        assert!(!is_ident("a-b"));
        assert!(is_work_var_name("w12"));
        assert!(is_work_var_name("o0"));
        assert!(!is_work_var_name("w"));
        assert!(!is_work_var_name("wx"));
    }
}
