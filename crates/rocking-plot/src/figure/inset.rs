//! An inset: a smaller chart in a corner of a history panel that shows a window of τ on its own
//! y range, where the panel's range (shared with its row, so that neighbours compare) flattens a
//! run's curve, as the stiff column's rotation in the paper's Fig. 5. The region it enlarges is
//! outlined on the panel; the inset draws the panel's runs and twins in their styles (without
//! impact marks), with tick labels at the panel's size and no axis labels (the panel's).

use plotters::prelude::*;

use super::clip::clip;
use crate::chart::{self, fail, styled_line, Chart};
use crate::style::LineStyle;
use crate::text::tick;

/// A line as a panel draws it: points, style, colour, width.
pub type Line = (Vec<(f64, f64)>, LineStyle, RGBColor, u32);

/// The corner of the panel's plotting area an inset sits in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Corner {
    TopRight,
    TopLeft,
    BottomRight,
    BottomLeft,
}

/// The corners by name, in the order of [`Corner`].
pub const CORNERS: [&str; 4] = ["top right", "top left", "bottom right", "bottom left"];

impl Corner {
    /// The corner named `name` (one of [`CORNERS`]).
    pub fn parse(name: &str) -> Option<Corner> {
        let all = [
            Corner::TopRight,
            Corner::TopLeft,
            Corner::BottomRight,
            Corner::BottomLeft,
        ];
        CORNERS.iter().position(|c| *c == name).map(|k| all[k])
    }
}

/// The fractions of the plotting area an inset's width and height may take.
pub const INSET_SIZE: (f64, f64) = (0.25, 0.8);

/// An inset of a history panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Inset {
    /// Its window of τ (default: the panel's).
    pub window: Option<(f64, f64)>,
    /// Its y range (default: the runs' values in its window, with a little room).
    pub range: Option<(f64, f64)>,
    pub corner: Corner,
    /// Its width and height as fractions of the panel's plotting area ([`INSET_SIZE`]).
    pub size: (f64, f64),
}

/// The grey of the inset's frame and of the outline of the region it enlarges.
const FRAME_GREY: RGBColor = RGBColor(110, 110, 110);
/// The inset's distance from the plotting area's edges, in drawing units (1/8 mm in print).
const GAP: u32 = 6;

/// Draws `inset` on the panel `chart`: the region `x` × `y` outlined on the panel, and the
/// `lines` on that region in the corner.
pub(super) fn draw(
    inset: &Inset,
    chart: &mut Chart<'_, '_>,
    x: (f64, f64),
    y: (f64, f64),
    lines: &[Line],
) -> Result<(), String> {
    // The region on the panel, where it lies within the panel's range.
    let (px, py) = (chart.x_range(), chart.y_range());
    let (rx0, rx1) = (x.0.max(px.start), x.1.min(px.end));
    let (ry0, ry1) = (y.0.max(py.start), y.1.min(py.end));
    if rx0 < rx1 && ry0 < ry1 {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(rx0, ry0), (rx1, ry1)],
                FRAME_GREY.stroke_width(1),
            )))
            .map_err(fail)?;
    }
    let plot = chart.plotting_area().strip_coord_spec();
    let (w, h) = plot.dim_in_pixel();
    let iw = (f64::from(w) * inset.size.0).round() as u32;
    let ih = (f64::from(h) * inset.size.1).round() as u32;
    let left = match inset.corner {
        Corner::TopRight | Corner::BottomRight => w.saturating_sub(iw + GAP),
        _ => GAP,
    };
    let top = match inset.corner {
        Corner::TopRight | Corner::TopLeft => GAP,
        _ => h.saturating_sub(ih + GAP),
    };
    let area = plot.shrink((left, top), (iw, ih));
    area.fill(&WHITE).map_err(fail)?;
    let (aw, ah) = area.dim_in_pixel();
    area.draw(&Rectangle::new(
        [(0, 0), (aw as i32 - 1, ah as i32 - 1)],
        FRAME_GREY.stroke_width(1),
    ))
    .map_err(fail)?;
    let t = chart::current();
    let (xa, ya) = chart::print_label_areas(&t, true, true);
    let mut c = ChartBuilder::on(&area)
        .margin(4)
        .margin_right(16)
        .x_label_area_size(xa)
        .y_label_area_size(ya)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(fail)?;
    let ticks = |v: &f64| tick(*v);
    c.configure_mesh()
        .disable_mesh()
        .x_labels(4)
        .y_labels(3)
        .x_label_formatter(&ticks)
        .y_label_formatter(&ticks)
        .label_style(("sans-serif", t.ticks))
        .draw()
        .map_err(fail)?;
    if y.0 < 0.0 && y.1 > 0.0 {
        c.draw_series(std::iter::once(PathElement::new(
            vec![(x.0, 0.0), (x.1, 0.0)],
            RGBColor(120, 120, 120).stroke_width(1),
        )))
        .map_err(fail)?;
    }
    for (points, style, colour, width) in lines {
        for piece in clip(points, (x, y)) {
            styled_line(&mut c, piece, style, *colour, *width)?;
        }
    }
    Ok(())
}
