//! The colour bar of a spectrum's survivors: the shaded scale with θ_cr/α marked on it, in the
//! legend column on screens or as a band beside the panels at print size.

use crate::text::{rich, tick};
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::chart::{fail, line_height, Area, Type, LEGEND, TICKS};

/// The colour bar of the shaded cells (`scale`: bottom to top, titled `label`) with `marks`
/// (θ_cr/α), at `y` in the legend column; returns the y below it.
pub(super) fn colour_bar(
    side: &Area<'_>,
    label: &str,
    scale: (f64, f64),
    marks: &[(f64, String)],
    y: i32,
) -> Result<i32, String> {
    let (bottom, top) = scale;
    let span = top - bottom;
    let height = 330;
    let (width, _) = side.dim_in_pixel();
    let area = side.clone().shrink((0, y), (width, height));
    area.draw(&Text::new(
        rich(label),
        (10, 4),
        ("sans-serif", LEGEND).into_font(),
    ))
    .map_err(fail)?;
    let bar = area.clone().shrink((10, 30), (34, height - 44));
    let mut chart = ChartBuilder::on(&bar)
        .set_label_area_size(LabelAreaPosition::Right, 0)
        .build_cartesian_2d(0.0..1.0, bottom..top)
        .map_err(fail)?;
    let steps = 120;
    chart
        .draw_series((0..steps).map(|k| {
            let (a, b) = (
                bottom + span * k as f64 / steps as f64,
                bottom + span * (k + 1) as f64 / steps as f64,
            );
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                ViridisRGB
                    .get_color_normalized((a + b) / 2.0, bottom, top)
                    .filled(),
            )
        }))
        .map_err(fail)?;
    // Ticks on the right of the bar.
    let font = ("sans-serif", TICKS)
        .into_font()
        .into_text_style(&area)
        .pos(Pos::new(HPos::Left, VPos::Center));
    let (_, bar_h) = bar.dim_in_pixel();
    let to_y = |v: f64| 30 + ((top - v) / span * bar_h as f64).round() as i32;
    for v in nice_ticks(bottom, top) {
        let py = to_y(v);
        area.draw(&PathElement::new(vec![(44, py), (50, py)], BLACK))
            .map_err(fail)?;
        area.draw_text(&tick(v), &font, (54, py)).map_err(fail)?;
    }
    // Marks from the top down; a label too close to the one above moves below it.
    let mut shown: Vec<&(f64, String)> = marks
        .iter()
        .filter(|m| (bottom..=top).contains(&m.0))
        .collect();
    shown.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut last_text = i32::MIN / 2;
    for (v, text) in shown {
        let py = to_y(*v);
        let ty = py.max(last_text + line_height(LEGEND) as i32);
        last_text = ty;
        area.draw(&PathElement::new(
            vec![(6, py), (48, py)],
            BLACK.stroke_width(3),
        ))
        .map_err(fail)?;
        area.draw(&PathElement::new(
            vec![(10, py), (44, py)],
            WHITE.stroke_width(1),
        ))
        .map_err(fail)?;
        area.draw_text(&rich(text), &font, (84, ty)).map_err(fail)?;
    }
    Ok(y + height)
}

/// The width of the colour bar's block at the left of a print figure's legend band (50 mm).
pub(super) const PRINT_BAR_WIDTH: u32 = 400;

/// The height of [`colour_bar_band`] with `marks` marks.
pub(super) fn colour_bar_band_height(marks: usize) -> u32 {
    let t = Type::print();
    let line = t.line(t.legend);
    4 + t.line(t.axis) + 4 + PRINT_BAR + 4 + t.line(t.ticks) + marks as u32 * line + 6
}

/// The bar's thickness at print size (3 mm).
const PRINT_BAR: u32 = 24;

/// The colour bar at print size, across the top-left of the legend band: its title (in axis-label
/// type), the bar,
/// its ticks under it, and each mark (θ_cr/α) as a line across the bar, labelled under the
/// ticks from the mark rightwards (one line per mark).
pub(super) fn colour_bar_band(
    area: &Area<'_>,
    label: &str,
    scale: (f64, f64),
    marks: &[(f64, String)],
) -> Result<(), String> {
    let t = Type::print();
    let (bottom, top) = scale;
    let span = top - bottom;
    let line = t.line(t.legend) as i32;
    let (width, _) = area.dim_in_pixel();
    let left = 12;
    let right = width as i32 - 40;
    let to_x = |v: f64| left + ((v - bottom) / span * f64::from(right - left)).round() as i32;
    let text = |size: f64, h: HPos| {
        ("sans-serif", size)
            .into_font()
            .into_text_style(area)
            .pos(Pos::new(h, VPos::Top))
    };
    // The title labels the colour axis: axis-label type.
    area.draw_text(&rich(label), &text(t.axis, HPos::Left), (left, 4))
        .map_err(fail)?;
    let y0 = 4 + t.line(t.axis) as i32 + 4;
    let y1 = y0 + PRINT_BAR as i32;
    let steps = 200;
    for k in 0..steps {
        let (a, b) = (
            left + (right - left) * k / steps,
            left + (right - left) * (k + 1) / steps,
        );
        let v = bottom + span * (f64::from(k) + 0.5) / f64::from(steps);
        area.draw(&Rectangle::new(
            [(a, y0), (b, y1)],
            ViridisRGB.get_color_normalized(v, bottom, top).filled(),
        ))
        .map_err(fail)?;
    }
    area.draw(&Rectangle::new([(left, y0), (right, y1)], BLACK))
        .map_err(fail)?;
    let ticks = text(t.ticks, HPos::Center);
    for v in nice_ticks(bottom, top) {
        let px = to_x(v);
        area.draw(&PathElement::new(vec![(px, y1), (px, y1 + 5)], BLACK))
            .map_err(fail)?;
        area.draw_text(&tick(v), &ticks, (px, y1 + 6))
            .map_err(fail)?;
    }
    let mut shown: Vec<&(f64, String)> = marks
        .iter()
        .filter(|m| (bottom..=top).contains(&m.0))
        .collect();
    shown.sort_by(|a, b| a.0.total_cmp(&b.0));
    let labels = text(t.legend, HPos::Left);
    let mut y = y1 + 6 + t.line(t.ticks) as i32;
    let char_w = 0.56 * t.legend / 1.24;
    for (v, label) in shown {
        let px = to_x(*v);
        area.draw(&PathElement::new(
            vec![(px, y0 - 3), (px, y1 + 3)],
            BLACK.stroke_width(3),
        ))
        .map_err(fail)?;
        area.draw(&PathElement::new(
            vec![(px, y0), (px, y1)],
            WHITE.stroke_width(1),
        ))
        .map_err(fail)?;
        let label = format!("↑ {label}");
        let w = (crate::text::plain(&rich(&label)).chars().count() as f64 * char_w) as i32;
        let x = (px - (char_w / 2.0) as i32)
            .min(width as i32 - w - 4)
            .max(0);
        area.draw_text(&rich(&label), &labels, (x, y))
            .map_err(fail)?;
        y += line;
    }
    Ok(())
}

/// About five round tick values from `bottom` to `top`.
fn nice_ticks(bottom: f64, top: f64) -> Vec<f64> {
    let raw = (top - bottom) / 5.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (bottom / step * (1.0 - 1e-9)).ceil() as i64;
    (first..)
        .map(|k| k as f64 * step)
        .take_while(|v| *v <= top * (1.0 + 1e-9) + 1e-12 * step)
        .collect()
}
