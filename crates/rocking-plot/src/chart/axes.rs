//! A panel's axes: linear ticks by [`tick`], or powers of ten, labels with subscripts; the
//! print frame with its letter.

use super::*;

/// A panel's chart with its axes: ticks by [`tick`], labels with subscripts, an optional title.
pub fn axes<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
    grid: bool,
) -> Result<Chart<'a, 'b>, String> {
    let linear = |v: &f64| tick(*v);
    frame(area, title, x, y, labels, grid, &linear)
}

/// A log-log panel's chart: its coordinates are the log10 of the values (`x` and `y` are such
/// ranges), its ticks the powers of ten (10⁻⁵), unlabelled between them.
pub fn log_axes<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
) -> Result<Chart<'a, 'b>, String> {
    let powers = |v: &f64| {
        let k = v.round();
        if (v - k).abs() < 1e-9 {
            power_of_ten(k as i32)
        } else {
            String::new()
        }
    };
    frame(area, title, x, y, labels, true, &powers)
}

fn frame<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
    grid: bool,
    ticks: &dyn Fn(&f64) -> String,
) -> Result<Chart<'a, 'b>, String> {
    let t = current();
    if t.print {
        return print_frame(area, title, x, y, labels, grid, ticks, &t);
    }
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(10)
        .margin_right(18)
        .x_label_area_size(52)
        .y_label_area_size(72);
    if let Some(t) = title {
        builder.caption(rich(t), ("sans-serif", PANEL_TITLE));
    }
    let mut chart = builder
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(fail)?;
    let (xl, yl) = (rich(labels.0), rich(labels.1));
    let mut mesh = chart.configure_mesh();
    if grid {
        mesh.light_line_style(RGBColor(236, 236, 236))
            .bold_line_style(RGBColor(222, 222, 222));
    } else {
        mesh.disable_mesh();
    }
    mesh.x_desc(xl)
        .y_desc(yl)
        .x_labels(7)
        .y_labels(7)
        .x_label_formatter(ticks)
        .y_label_formatter(ticks)
        .label_style(("sans-serif", TICKS))
        .axis_desc_style(("sans-serif", AXIS))
        .draw()
        .map_err(fail)?;
    Ok(chart)
}

/// A panel's frame at print size: the letter above its top-left corner, tick labels and axis
/// labels in points, axis labels only where no row or column shares them, no minor grid (a dense
/// one prints as a grey tint), as many ticks as fit.
#[allow(clippy::too_many_arguments)]
fn print_frame<'a, 'b>(
    area: &'a Area<'b>,
    title: Option<&str>,
    x: (f64, f64),
    y: (f64, f64),
    labels: (&str, &str),
    grid: bool,
    ticks: &dyn Fn(&f64) -> String,
    t: &Type,
) -> Result<Chart<'a, 'b>, String> {
    let panel = PANEL.with(|p| p.borrow().clone());
    let (xa, ya) = print_label_areas(t, panel.hide_x_label, panel.hide_y_label);
    if let Some(letter) = &panel.letter {
        let style = ("sans-serif", t.letter)
            .into_font()
            .into_text_style(area)
            .pos(Pos::new(HPos::Left, VPos::Top));
        area.draw_text(letter, &style, (0, 0)).map_err(fail)?;
    }
    let (w, h) = area.dim_in_pixel();
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(PRINT_MARGIN)
        .margin_top(t.line(t.letter))
        .margin_right(PRINT_MARGIN_RIGHT)
        .x_label_area_size(xa)
        .y_label_area_size(ya);
    if let Some(title) = title.filter(|_| !panel.hide_title) {
        builder.caption(rich(title), ("sans-serif", t.panel_title));
    }
    let mut chart = builder
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(fail)?;
    let mut mesh = chart.configure_mesh();
    if grid {
        mesh.max_light_lines(0)
            .bold_line_style(RGBColor(226, 226, 226));
    } else {
        mesh.disable_mesh();
    }
    if !panel.hide_x_label {
        mesh.x_desc(rich(labels.0));
    }
    if !panel.hide_y_label {
        mesh.y_desc(rich(labels.1));
    }
    // A tick label every 12 mm across and 7 mm down at most.
    let fit = |len: u32, per_mm: f64| {
        ((f64::from(len) / (per_mm * UNITS_PER_MM)).floor() as usize).clamp(3, 7)
    };
    mesh.x_labels(fit(w.saturating_sub(ya), 12.0))
        .y_labels(fit(h.saturating_sub(xa), 7.0))
        .x_label_formatter(ticks)
        .y_label_formatter(ticks)
        .label_style(("sans-serif", t.ticks))
        .axis_desc_style(("sans-serif", t.axis))
        .draw()
        .map_err(fail)?;
    Ok(chart)
}
