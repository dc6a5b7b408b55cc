//! What a panel marks: markers, points at data coordinates, lines in their style's dash.

use super::*;

/// A marker's polygon, filled or outlined.
fn polygon<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    pts: Vec<(i32, i32)>,
    style: ShapeStyle,
    filled: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    if filled {
        area.draw(&Polygon::new(pts, style))
    } else {
        let mut closed = pts.clone();
        closed.push(pts[0]);
        area.draw(&PathElement::new(closed, style))
    }
}

/// Draws `marker` of `size` pixels at `at` (filled or open).
pub fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    marker: Marker,
    at: (i32, i32),
    size: i32,
    colour: RGBColor,
    filled: bool,
) -> Result<(), String> {
    let style = if filled {
        colour.filled()
    } else {
        colour.stroke_width(2)
    };
    let (x, y) = at;
    let s = size;
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    match marker {
        Marker::Circle => area.draw(&Circle::new(at, s, style)).map_err(e),
        Marker::Square => area
            .draw(&Rectangle::new([(x - s, y - s), (x + s, y + s)], style))
            .map_err(e),
        Marker::Triangle => {
            let pts = vec![(x, y - s - 1), (x - s - 1, y + s), (x + s + 1, y + s)];
            polygon(area, pts, style, filled).map_err(e)
        }
        Marker::TriangleDown => {
            let pts = vec![(x, y + s + 1), (x - s - 1, y - s), (x + s + 1, y - s)];
            polygon(area, pts, style, filled).map_err(e)
        }
        Marker::Diamond => {
            let s = s + 1;
            let pts = vec![(x, y - s), (x + s, y), (x, y + s), (x - s, y)];
            polygon(area, pts, style, filled).map_err(e)
        }
        Marker::Pentagon => {
            let r = f64::from(s) + 1.0;
            let pts = (0..5)
                .map(|k| {
                    let a = std::f64::consts::TAU * f64::from(k) / 5.0;
                    (
                        x + (r * a.sin()).round() as i32,
                        y - (r * a.cos()).round() as i32,
                    )
                })
                .collect();
            polygon(area, pts, style, filled).map_err(e)
        }
        Marker::Plus => {
            let style = colour.stroke_width(2);
            let s = s + 1;
            area.draw(&PathElement::new(vec![(x - s, y), (x + s, y)], style))
                .map_err(e)?;
            area.draw(&PathElement::new(vec![(x, y - s), (x, y + s)], style))
                .map_err(e)
        }
        Marker::Asterisk => {
            let style = colour.stroke_width(1);
            let s = s + 1;
            for (dx, dy) in [
                (s, 0),
                (0, s),
                (s * 2 / 3, s * 2 / 3),
                (s * 2 / 3, -s * 2 / 3),
            ] {
                area.draw(&PathElement::new(
                    vec![(x - dx, y - dy), (x + dx, y + dy)],
                    style,
                ))
                .map_err(e)?;
            }
            Ok(())
        }
        Marker::Cross => {
            let style = colour.stroke_width(2);
            area.draw(&PathElement::new(
                vec![(x - s, y - s), (x + s, y + s)],
                style,
            ))
            .map_err(e)?;
            area.draw(&PathElement::new(
                vec![(x - s, y + s), (x + s, y - s)],
                style,
            ))
            .map_err(e)
        }
    }
}

/// The pixel of the data point `p` of a chart, in its plotting area's pixels.
pub fn pixel(chart: &Chart<'_, '_>, p: (f64, f64)) -> (i32, i32) {
    let area = chart.plotting_area().strip_coord_spec();
    let (px, py) = chart.backend_coord(&p);
    let (bx, by) = area.get_base_pixel();
    (px - bx, py - by)
}

/// Draws `marker` at the data point `p` of a chart.
pub fn mark_at(
    chart: &Chart<'_, '_>,
    m: Marker,
    p: (f64, f64),
    size: i32,
    colour: RGBColor,
    filled: bool,
) -> Result<(), String> {
    let area = chart.plotting_area().strip_coord_spec();
    marker(&area, m, pixel(chart, p), size, colour, filled)
}

/// Draws a polyline in `style` on a chart (dashed when the style is).
pub fn styled_line(
    chart: &mut Chart<'_, '_>,
    points: Vec<(f64, f64)>,
    line: &LineStyle,
    colour: RGBColor,
    width: u32,
) -> Result<(), String> {
    if points.len() < 2 {
        return Ok(());
    }
    match line.dash {
        None => chart
            .draw_series(std::iter::once(PathElement::new(
                points,
                colour.stroke_width(width),
            )))
            .map(|_| ())
            .map_err(fail),
        Some((size, gap)) => chart
            .draw_series(std::iter::once(DashedPathElement::new(
                points,
                size,
                gap,
                colour.stroke_width(width),
            )))
            .map(|_| ())
            .map_err(fail),
    }
}
