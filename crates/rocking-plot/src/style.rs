//! The figures' palette: the fill (and hatching) of a spectrum's classes, and the line styles of
//! the runs or structures a figure compares, each with its own colour, dash and marker so that
//! no line is told apart by colour alone. Every pair of class fills and every pair of line
//! colours stays at least [`DISTINCT`] apart (CIEDE2000) for normal vision, protanopia,
//! deuteranopia and tritanopia, and in greyscale (beyond four lines, [`DISTINCT_GREY`]): the
//! tests below measure it, and each overturned class's fill against every colour of the
//! survivors' scale (viridis) too. The paper calls the no-impact overturning area blue and the
//! one-impact area brown; so do these (a blue-violet, found with the several-impacts ochre by a
//! search of the RGB cube for the largest least difference from the scale and the other fills).

/// The least CIEDE2000 difference between two colours that must be told apart. A just
/// noticeable difference is about 1-2.3 ΔE₀₀ side by side (Sharma 2003); areas and thin lines of
/// a figure are compared across the page, not side by side, so the threshold is about five
/// times that: colours at 10 read as different categories at a glance.
pub const DISTINCT: f64 = 10.0;

/// The fill of a spectrum's class and the legend text.
#[derive(Clone, Copy, Debug)]
pub struct ClassStyle {
    pub fill: [u8; 3],
    /// Lines drawn over the fill (in `ink`), so that the class reads without its colour.
    pub hatch: Option<Hatch>,
    pub ink: [u8; 3],
    pub label: &'static str,
}

/// The direction of hatching lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hatch {
    /// `/`
    Rising,
    /// `\`
    Falling,
    /// `×`
    Cross,
    /// `|`
    Vertical,
}

pub const NO_UPLIFT: ClassStyle = ClassStyle {
    fill: [0xFD, 0xEF, 0xF3],
    hatch: None,
    ink: [0, 0, 0],
    label: "no uplift",
};
pub const OVERTURNED_NO_IMPACT: ClassStyle = ClassStyle {
    fill: [0xA8, 0xA0, 0xE8],
    hatch: Some(Hatch::Falling),
    ink: [0x0B, 0x35, 0x50],
    label: "overturned, no impact",
};
pub const OVERTURNED_ONE_IMPACT: ClassStyle = ClassStyle {
    fill: [0x5C, 0x3A, 0x15],
    hatch: Some(Hatch::Rising),
    ink: [0xE8, 0xD5, 0xB0],
    label: "overturned after one impact",
};
pub const OVERTURNED_IMPACTS: ClassStyle = ClassStyle {
    fill: [0xA0, 0x68, 0x00],
    hatch: Some(Hatch::Cross),
    ink: [0xFF, 0xFF, 0xFF],
    label: "overturned after impacts",
};
pub const FAILED: ClassStyle = ClassStyle {
    fill: [0, 0, 0],
    hatch: None,
    ink: [0xFF, 0xFF, 0xFF],
    label: "run failed (no result)",
};
/// The cells beyond the model (its mass matrix singular). No colour stays [`DISTINCT`] from the
/// five fills above for every vision (a search of the RGB cube finds at most 9.1), so this one
/// is the other cell without a result, [`FAILED`], told apart by its white vertical hatching
/// (the fill differs from black only so that the hatching, keyed by fill, can find it).
pub const BEYOND_MODEL: ClassStyle = ClassStyle {
    fill: [0x10, 0x10, 0x10],
    hatch: Some(Hatch::Vertical),
    ink: [0xFF, 0xFF, 0xFF],
    label: "beyond the model (M singular)",
};

/// A shaded cell whose run has no value of the quantity (the time of an event that did not
/// happen): white, crossed in grey so that greyscale tells it from the scale's light end (the
/// fill differs from the page's white only so that the hatching, keyed by fill, finds it).
pub const NO_VALUE: ClassStyle = ClassStyle {
    fill: [0xFF, 0xFF, 0xFD],
    hatch: Some(Hatch::Cross),
    ink: [0x90, 0x90, 0x90],
    label: "no value (no such event)",
};

/// Every class fill, for the test and the hatching patterns.
pub const CLASSES: [ClassStyle; 6] = [
    NO_UPLIFT,
    OVERTURNED_NO_IMPACT,
    OVERTURNED_ONE_IMPACT,
    OVERTURNED_IMPACTS,
    FAILED,
    BEYOND_MODEL,
];

/// The shape drawn along a line (every few points) and in its legend entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
    Cross,
    TriangleDown,
    Pentagon,
    Plus,
    Asterisk,
}

/// A line of a compared run or structure.
#[derive(Clone, Copy, Debug)]
pub struct LineStyle {
    pub name: &'static str,
    pub colour: [u8; 3],
    /// Dash and gap lengths (pixels); `None` for a solid line.
    pub dash: Option<(u32, u32)>,
    pub marker: Marker,
}

/// The lines a figure compares, in order of use (a figure file may name them: `style =
/// "red"`). The paper's Fig. 10 draws the stiff column red and the flexible ones blue and
/// green, and the ground motion black ([`BLACK`]). Eight, each with its own colour, dash and
/// marker: the first four (and black) stay [`DISTINCT`] in greyscale too; all eight do for
/// normal vision and the three dichromacies, and in greyscale at least [`DISTINCT_GREY`], where
/// the dash and the marker tell them apart.
pub const LINES: [LineStyle; 8] = [
    LineStyle {
        name: "blue",
        colour: [0x1B, 0x80, 0xC6],
        dash: None,
        marker: Marker::Circle,
    },
    LineStyle {
        name: "red",
        colour: [0xAC, 0x20, 0x00],
        dash: Some((12, 5)),
        marker: Marker::Square,
    },
    LineStyle {
        name: "green",
        colour: [0x1F, 0xBE, 0x5B],
        dash: Some((4, 4)),
        marker: Marker::Triangle,
    },
    LineStyle {
        name: "indigo",
        colour: [0x24, 0x25, 0x7B],
        dash: Some((18, 5)),
        marker: Marker::Diamond,
    },
    LineStyle {
        name: "pink",
        colour: [0xC3, 0x78, 0x96],
        dash: Some((2, 4)),
        marker: Marker::TriangleDown,
    },
    LineStyle {
        name: "teal",
        colour: [0x00, 0x78, 0x69],
        dash: Some((24, 6)),
        marker: Marker::Pentagon,
    },
    LineStyle {
        name: "wine",
        colour: [0x87, 0x0F, 0x4B],
        dash: Some((6, 2)),
        marker: Marker::Plus,
    },
    LineStyle {
        name: "plum",
        colour: [0x2D, 0x0F, 0x3C],
        dash: Some((10, 10)),
        marker: Marker::Asterisk,
    },
];

/// The least CIEDE2000 difference in greyscale between any two of the eight [`LINES`] and
/// black: nine greys on a page cannot all be [`DISTINCT`] (lightness is one dimension); the
/// dash and the marker carry the difference there.
pub const DISTINCT_GREY: f64 = 6.0;

/// The reference line (the rigid column) and the ground motion.
pub const BLACK: LineStyle = LineStyle {
    name: "black",
    colour: [0, 0, 0],
    dash: Some((8, 5)),
    marker: Marker::Cross,
};

/// The line style named `name` (`blue`, `red`, `green`, `indigo`, `pink`, `teal`, `wine`,
/// `plum`, `black`).
pub fn line_named(name: &str) -> Option<LineStyle> {
    LINES
        .iter()
        .chain(std::iter::once(&BLACK))
        .find(|l| l.name == name)
        .copied()
}

/// The names [`line_named`] knows, for messages.
pub fn line_names() -> Vec<&'static str> {
    LINES.iter().map(|l| l.name).chain([BLACK.name]).collect()
}

fn hex(c: [u8; 3]) -> String {
    format!("#{:02X}{:02X}{:02X}", c[0], c[1], c[2])
}

/// The SVG with every area filled in a hatched class's colour (`<rect>` and `<polygon>`, the
/// cells and their legend swatches) filled with that class's hatching pattern instead. The
/// patterns are in user space, so neighbouring cells continue each other's lines.
pub fn hatch_svg(svg: &str) -> String {
    let hatched: Vec<&ClassStyle> = CLASSES
        .iter()
        .chain([&NO_VALUE])
        .filter(|c| c.hatch.is_some())
        .collect();
    let fills: Vec<String> = hatched
        .iter()
        .map(|c| format!("fill=\"{}\"", hex(c.fill)))
        .collect();
    if !fills.iter().any(|f| svg.contains(f.as_str())) {
        return svg.to_string();
    }
    let mut defs = String::from("<defs>\n");
    for c in &hatched {
        let (angle, cross) = match c.hatch {
            Some(Hatch::Rising) => (45, false),
            Some(Hatch::Falling) => (-45, false),
            Some(Hatch::Vertical) => (0, false),
            _ => (45, true),
        };
        let (fill, ink) = (hex(c.fill), hex(c.ink));
        let id = &fill[1..];
        defs.push_str(&format!(
            "<pattern id=\"hatch-{id}\" width=\"7\" height=\"7\" patternUnits=\"userSpaceOnUse\" \
             patternTransform=\"rotate({angle})\"><rect width=\"7\" height=\"7\" fill=\"{fill}\"/>\
             <line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"7\" stroke=\"{ink}\" stroke-width=\"1.6\"/>"
        ));
        if cross {
            defs.push_str(&format!(
                "<line x1=\"0\" y1=\"0\" x2=\"7\" y2=\"0\" stroke=\"{ink}\" stroke-width=\"1.6\"/>"
            ));
        }
        defs.push_str("</pattern>\n");
    }
    defs.push_str("</defs>\n");
    let mut out = String::with_capacity(svg.len() + defs.len());
    let mut lines = svg.split_inclusive('\n');
    // The defs go after the opening <svg ...> tag (plotters writes it on its own line).
    for line in lines.by_ref() {
        out.push_str(line);
        if line.trim_start().starts_with("<svg") {
            out.push_str(&defs);
            break;
        }
    }
    for line in lines {
        let area =
            line.trim_start().starts_with("<rect") || line.trim_start().starts_with("<polygon");
        match fills
            .iter()
            .zip(&hatched)
            .find(|(f, _)| area && line.contains(f.as_str()))
        {
            Some((f, c)) => out.push_str(&line.replace(
                f.as_str(),
                &format!("fill=\"url(#hatch-{})\"", &hex(c.fill)[1..]),
            )),
            None => out.push_str(line),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::{closest_pair, Vision};

    /// The smallest difference of a set for each vision, printed (the numbers the docs quote)
    /// and checked against the threshold.
    fn assert_distinct(what: &str, colours: &[[u8; 3]], names: &[&str]) {
        for v in Vision::ALL {
            let (d, i, j) = closest_pair(colours, v);
            println!(
                "{what}: {v:?}: min ΔE00 = {d:.1} ({} / {})",
                names[i], names[j]
            );
            assert!(
                d >= DISTINCT,
                "{what}: {} and {} are {d:.1} apart for {v:?} (< {DISTINCT})",
                names[i],
                names[j]
            );
        }
    }

    #[test]
    fn class_fills_stay_distinct_for_every_vision_and_in_greyscale() {
        // Every class but the one told apart by its hatching alone.
        let coloured: Vec<&ClassStyle> = CLASSES
            .iter()
            .filter(|c| c.label != BEYOND_MODEL.label)
            .collect();
        let colours: Vec<[u8; 3]> = coloured.iter().map(|c| c.fill).collect();
        let names: Vec<&str> = coloured.iter().map(|c| c.label).collect();
        assert_distinct("classes", &colours, &names);
        // The hatched-only class: distinct by colour from all but the failed cells, and by a
        // hatching no other class has from those.
        let others: Vec<[u8; 3]> = CLASSES
            .iter()
            .filter(|c| c.label != BEYOND_MODEL.label && c.label != FAILED.label)
            .map(|c| c.fill)
            .collect();
        for v in Vision::ALL {
            for o in &others {
                let d = crate::colour::difference(BEYOND_MODEL.fill, *o, v);
                assert!(
                    d >= DISTINCT,
                    "{:?} vs {o:?}: {d:.1} for {v:?}",
                    BEYOND_MODEL.fill
                );
            }
        }
        assert!(BEYOND_MODEL.hatch.is_some());
        assert!(CLASSES
            .iter()
            .filter(|c| c.label != BEYOND_MODEL.label)
            .all(|c| c.hatch != BEYOND_MODEL.hatch));
    }

    /// The survivors' colour scale (viridis, as figure/spectrum.rs shades it), 256 samples.
    fn survivor_scale() -> Vec<[u8; 3]> {
        use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};
        (0..256)
            .map(|k| {
                let c = ViridisRGB.get_color_normalized(f64::from(k) / 255.0, 0.0, 1.0);
                [c.0, c.1, c.2]
            })
            .collect()
    }

    #[test]
    fn a_cell_without_a_value_stays_distinct_from_the_scale_and_the_overturned_classes() {
        // It is shaded among survivors and beside overturned cells; the no-uplift cells are
        // shaded too on such a panel, and the failed ones are black.
        let scale = survivor_scale();
        let overturned = [
            OVERTURNED_NO_IMPACT,
            OVERTURNED_ONE_IMPACT,
            OVERTURNED_IMPACTS,
        ];
        for v in Vision::ALL {
            let d = scale
                .iter()
                .chain(overturned.iter().map(|c| &c.fill))
                .map(|s| crate::colour::difference(NO_VALUE.fill, *s, v))
                .fold(f64::INFINITY, f64::min);
            println!("no value, {v:?}: min ΔE00 = {d:.1}");
            // In greyscale the scale's light end is near white: the grey crosses tell it.
            if v != Vision::Greyscale {
                assert!(d >= DISTINCT, "no value: {d:.1} for {v:?}");
            }
        }
        assert!(NO_VALUE.hatch.is_some());
        let svg = hatch_svg("<svg>\n<rect fill=\"#FFFFFD\"/>\n</svg>\n");
        assert!(svg.contains("<rect fill=\"url(#hatch-FFFFFD)\"/>"), "{svg}");
        for c in CLASSES {
            assert_ne!(c.fill, NO_VALUE.fill, "{}", c.label);
        }
    }

    #[test]
    fn class_fills_stay_distinct_from_the_survivor_scale() {
        // A spectrum puts the classes beside survivors of any shade: every filled class stays
        // DISTINCT from every colour of the scale for normal vision and the three dichromacies.
        let scale = survivor_scale();
        for c in CLASSES {
            for v in [
                Vision::Normal,
                Vision::Protanopia,
                Vision::Deuteranopia,
                Vision::Tritanopia,
            ] {
                let d = scale
                    .iter()
                    .map(|s| crate::colour::difference(c.fill, *s, v))
                    .fold(f64::INFINITY, f64::min);
                println!(
                    "{} against the survivors, {v:?}: min ΔE00 = {d:.1}",
                    c.label
                );
                assert!(
                    d >= DISTINCT,
                    "{}: {d:.1} from the scale for {v:?}",
                    c.label
                );
            }
            // In greyscale the scale runs through every lightness, so no fill can stay apart:
            // the overturned classes are told by their hatching there, the no-uplift cells by
            // the uplift line drawn between them and the survivors, the failed ones by their
            // black (the darkest viridis is still 9 ΔE00 lighter).
            let grey = scale
                .iter()
                .map(|s| crate::colour::difference(c.fill, *s, Vision::Greyscale))
                .fold(f64::INFINITY, f64::min);
            println!("{} against the survivors, greyscale: {grey:.1}", c.label);
            assert!(
                grey >= DISTINCT - 1.0
                    || c.hatch.is_some()
                    || c.label == NO_UPLIFT.label
                    || c.label == FAILED.label,
                "{}: {grey:.1} from the scale in greyscale and nothing else tells it apart",
                c.label
            );
        }
    }

    #[test]
    fn line_colours_stay_distinct_for_every_vision_and_in_greyscale() {
        // The first four and black, for every vision and in greyscale.
        let first: Vec<LineStyle> = LINES[..4].iter().copied().chain([BLACK]).collect();
        let colours: Vec<[u8; 3]> = first.iter().map(|l| l.colour).collect();
        let names: Vec<&str> = first.iter().map(|l| l.name).collect();
        assert_distinct("lines 1-4", &colours, &names);
        // All eight and black: a figure of eight runs (issue 47, item 21: the fifth run took
        // the first one's style).
        let mut colours: Vec<[u8; 3]> = LINES.iter().map(|l| l.colour).collect();
        colours.push(BLACK.colour);
        let names = line_names();
        assert!(LINES.len() >= 8, "at least eight runs apart");
        for v in Vision::ALL {
            let (d, i, j) = closest_pair(&colours, v);
            println!(
                "lines: {v:?}: min ΔE00 = {d:.1} ({} / {})",
                names[i], names[j]
            );
            let least = if v == Vision::Greyscale {
                DISTINCT_GREY
            } else {
                DISTINCT
            };
            assert!(
                d >= least,
                "{} and {} are {d:.1} apart for {v:?} (< {least})",
                names[i],
                names[j]
            );
        }
        // And every line stands out from the white page.
        for l in LINES {
            for v in Vision::ALL {
                let d = crate::colour::difference(l.colour, [255; 3], v);
                assert!(d >= 2.0 * DISTINCT, "{} on white: {d:.1} for {v:?}", l.name);
            }
        }
    }

    #[test]
    fn every_line_has_its_own_dash_and_marker() {
        let all: Vec<LineStyle> = LINES.iter().copied().chain([BLACK]).collect();
        for (i, a) in all.iter().enumerate() {
            for b in &all[i + 1..] {
                assert_ne!(a.marker, b.marker, "{} / {}", a.name, b.name);
                assert_ne!(a.dash, b.dash, "{} / {}", a.name, b.name);
            }
        }
    }

    #[test]
    fn hatched_fills_become_patterns_in_areas_only() {
        let fill = hex(OVERTURNED_ONE_IMPACT.fill);
        let svg = format!(
            "<svg width=\"10\">\n<rect x=\"0\" fill=\"{fill}\"/>\n<polyline stroke=\"{fill}\" fill=\"{fill}\"/>\n</svg>\n"
        );
        let out = hatch_svg(&svg);
        let id = &fill[1..];
        assert!(
            out.contains(&format!("<pattern id=\"hatch-{id}\"")),
            "{out}"
        );
        assert!(
            out.contains(&format!("<rect x=\"0\" fill=\"url(#hatch-{id})\"/>")),
            "{out}"
        );
        assert!(
            out.contains(&format!("<polyline stroke=\"{fill}\" fill=\"{fill}\"/>")),
            "{out}"
        );
    }
}
