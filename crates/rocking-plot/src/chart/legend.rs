//! The legend: its entries, drawn as a column beside the panels or as a band above them.

use super::*;

/// Something the legend column shows.
pub enum LegendItem {
    /// A line with its dash and marker.
    Line(LineStyle, String),
    /// A filled box (a class), hatched where the class is.
    Fill([u8; 3], String),
    /// A line without a marker (a boundary), solid or dashed.
    Rule([u8; 3], Option<(u32, u32)>, String),
    /// A marker alone, in a colour, filled or open.
    Mark(Marker, [u8; 3], bool, String),
    /// A heading.
    Heading(String),
}

impl LegendItem {
    /// What the entry shows: two entries with the same key are one.
    pub fn key(&self) -> String {
        match self {
            LegendItem::Line(s, t) => format!("line {} {t}", s.name),
            LegendItem::Fill(c, t) => format!("fill {c:?} {t}"),
            LegendItem::Rule(c, d, t) => format!("rule {c:?} {d:?} {t}"),
            LegendItem::Mark(m, c, f, t) => format!("mark {m:?} {c:?} {f} {t}"),
            LegendItem::Heading(t) => format!("heading {t}"),
        }
    }
}

/// Draws the legend column's entries from `top` down.
pub fn legend(area: &Area<'_>, top: i32, items: &[LegendItem]) -> Result<(), String> {
    let width = area.dim_in_pixel().0 as usize;
    let chars = (width.saturating_sub(56) as f64 / (0.55 * LEGEND as f64)) as usize;
    let font = ("sans-serif", LEGEND).into_font();
    let mut y = top;
    for item in items {
        let (text, indent) = match item {
            LegendItem::Heading(t) => (t.as_str(), 8),
            LegendItem::Line(_, t)
            | LegendItem::Fill(_, t)
            | LegendItem::Rule(_, _, t)
            | LegendItem::Mark(_, _, _, t) => (t.as_str(), 52),
        };
        let cy = y + 9;
        match item {
            LegendItem::Line(s, _) => {
                let points = vec![(8, cy), (44, cy)];
                let c = rgb(s.colour);
                match s.dash {
                    None => area.draw(&PathElement::new(points, c.stroke_width(2))),
                    Some((a, b)) => {
                        area.draw(&DashedPathElement::new(points, a, b, c.stroke_width(2)))
                    }
                }
                .map_err(fail)?;
                marker(area, s.marker, (26, cy), 4, c, true)?;
            }
            LegendItem::Fill(c, _) => {
                area.draw(&Rectangle::new([(12, y), (40, y + 18)], rgb(*c).filled()))
                    .map_err(fail)?;
                area.draw(&Rectangle::new([(12, y), (40, y + 18)], BLACK))
                    .map_err(fail)?;
            }
            LegendItem::Rule(c, dash, _) => {
                let points = vec![(8, cy), (44, cy)];
                let c = rgb(*c);
                match dash {
                    None => area.draw(&PathElement::new(points, c.stroke_width(2))),
                    Some((a, b)) => {
                        area.draw(&DashedPathElement::new(points, *a, *b, c.stroke_width(2)))
                    }
                }
                .map_err(fail)?;
            }
            LegendItem::Mark(m, c, filled, _) => marker(area, *m, (26, cy), 5, rgb(*c), *filled)?,
            LegendItem::Heading(_) => {}
        }
        // Between items first; an item longer than the column then between words.
        let lines: Vec<String> = wrap_items(text, chars.max(12))
            .into_iter()
            .flat_map(|l| crate::wrap(&l, chars.max(12)))
            .collect();
        for (k, l) in lines.iter().enumerate() {
            area.draw(&Text::new(
                rich(l),
                (indent, y + 1 + (line_height(LEGEND) * k as u32) as i32),
                font.clone(),
            ))
            .map_err(fail)?;
        }
        y += 8 + (line_height(LEGEND) * lines.len().max(1) as u32) as i32;
    }
    Ok(())
}

/// The sample of a legend entry at print size: 9 mm, long enough to show a dash pattern.
const BAND_SAMPLE: u32 = 72;

/// The legend above the panels at print size: the entries in reading order in as many columns
/// as fit unwrapped (at most six), each entry's text wrapped to its column where none fit.
/// Returns the column width and each row's entries' lines.
fn band_layout(width: u32, items: &[LegendItem]) -> (u32, Vec<Vec<Vec<String>>>) {
    let t = Type::print();
    let char_w = 0.56 * t.legend / PLOTTERS_FONT;
    let text = |item: &LegendItem| match item {
        LegendItem::Heading(s)
        | LegendItem::Line(_, s)
        | LegendItem::Fill(_, s)
        | LegendItem::Rule(_, _, s)
        | LegendItem::Mark(_, _, _, s) => crate::text::plain(&rich(s)),
    };
    let need = |item: &LegendItem| {
        let sample = match item {
            LegendItem::Heading(_) => 0,
            _ => BAND_SAMPLE,
        };
        sample + (text(item).chars().count() as f64 * char_w).ceil() as u32 + 16
    };
    let widest = items.iter().map(need).max().unwrap_or(0);
    let columns = (1..=items.len().clamp(1, 6))
        .rev()
        .find(|&k| widest <= width / k as u32)
        .unwrap_or(1);
    let col_w = width / columns as u32;
    let chars = ((col_w.saturating_sub(BAND_SAMPLE + 8)) as f64 / char_w).max(12.0) as usize;
    let rows = items
        .chunks(columns)
        .map(|row| {
            row.iter()
                .map(|item| {
                    let s = match item {
                        LegendItem::Heading(s)
                        | LegendItem::Line(_, s)
                        | LegendItem::Fill(_, s)
                        | LegendItem::Rule(_, _, s)
                        | LegendItem::Mark(_, _, _, s) => s,
                    };
                    wrap_items(s, chars)
                        .into_iter()
                        .flat_map(|l| crate::wrap(&l, chars))
                        .collect()
                })
                .collect()
        })
        .collect();
    (col_w, rows)
}

/// The height of the legend band at print size for `items` in `width` units.
pub fn legend_band_height(width: u32, items: &[LegendItem]) -> u32 {
    if items.is_empty() {
        return 0;
    }
    let t = Type::print();
    let (_, rows) = band_layout(width, items);
    rows.iter()
        .map(|row| row.iter().map(Vec::len).max().unwrap_or(1) as u32 * t.line(t.legend) + 6)
        .sum::<u32>()
        + 8
}

/// Draws the legend band at print size ([`legend_band_height`] tall).
pub fn legend_band(area: &Area<'_>, items: &[LegendItem]) -> Result<(), String> {
    let t = Type::print();
    let (width, _) = area.dim_in_pixel();
    let (col_w, rows) = band_layout(width, items);
    let line = t.line(t.legend) as i32;
    let font = ("sans-serif", t.legend)
        .into_font()
        .into_text_style(area)
        .pos(Pos::new(HPos::Left, VPos::Top));
    let mut y = 4;
    let mut k = 0;
    for row in rows {
        let mut tallest = 1;
        for (c, lines) in row.iter().enumerate() {
            let item = &items[k];
            k += 1;
            let x0 = c as i32 * col_w as i32;
            let cy = y + line / 2;
            let sample = vec![(x0 + 4, cy), (x0 + BAND_SAMPLE as i32 - 8, cy)];
            let mid = (x0 + (BAND_SAMPLE as i32 - 4) / 2, cy);
            let indent = match item {
                LegendItem::Heading(_) => 4,
                LegendItem::Line(s, _) => {
                    let c = rgb(s.colour);
                    match s.dash {
                        None => area.draw(&PathElement::new(sample, c.stroke_width(2))),
                        Some((a, b)) => {
                            area.draw(&DashedPathElement::new(sample, a, b, c.stroke_width(2)))
                        }
                    }
                    .map_err(fail)?;
                    marker(area, s.marker, mid, 5, c, true)?;
                    BAND_SAMPLE
                }
                LegendItem::Fill(c, _) => {
                    let bx = [
                        (x0 + 10, y + 1),
                        (x0 + BAND_SAMPLE as i32 - 14, y + line - 2),
                    ];
                    area.draw(&Rectangle::new(bx, rgb(*c).filled()))
                        .map_err(fail)?;
                    area.draw(&Rectangle::new(bx, BLACK)).map_err(fail)?;
                    BAND_SAMPLE
                }
                LegendItem::Rule(c, dash, _) => {
                    let c = rgb(*c);
                    match dash {
                        None => area.draw(&PathElement::new(sample, c.stroke_width(2))),
                        Some((a, b)) => {
                            area.draw(&DashedPathElement::new(sample, *a, *b, c.stroke_width(2)))
                        }
                    }
                    .map_err(fail)?;
                    BAND_SAMPLE
                }
                LegendItem::Mark(m, c, filled, _) => {
                    marker(area, *m, mid, 6, rgb(*c), *filled)?;
                    BAND_SAMPLE
                }
            };
            for (j, l) in lines.iter().enumerate() {
                area.draw_text(&rich(l), &font, (x0 + indent as i32, y + j as i32 * line))
                    .map_err(fail)?;
            }
            tallest = tallest.max(lines.len());
        }
        y += tallest as i32 * line + 6;
    }
    Ok(())
}
