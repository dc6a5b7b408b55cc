//! Panels of `rocking ida`: the IDA curves (the intensity against max θ/α, one line per record,
//! overturned analyses in a column of their own) and the fitted fragility curve with its
//! bootstrap band and the empirical points it was fitted to.

use std::path::{Path, PathBuf};

use crate::chart::{axes, fail, mark_at, rgb, styled_line, Area, LegendItem};
use crate::style::{self, LineStyle};
use crate::text::tick;
use crate::FigureError;
use plotters::prelude::*;
use rocking_fragility::Bootstrap;
use rocking_scene::labels;

use super::{Figure, Panel};

/// One record's IDA curve: (max θ/α, IM, overturned) per analysis, by increasing IM.
pub type Points = Vec<(f64, f64, bool)>;

/// The records' lines (thin, one style: 61 records cannot each have a colour of their own).
const RECORD: LineStyle = style::LINES[0];
/// The overturned analyses' marker.
const OVERTURNED: LineStyle = style::LINES[1];

/// The IDA curves of a record suite.
pub struct IdaPanel {
    /// Per record: its name and its curve.
    pub curves: Vec<(String, Points)>,
    /// The intensity measure's axis label.
    pub im_label: String,
    /// Multiple stripes (every record at the same intensities) rather than hunt-and-fill IDA.
    pub stripes: bool,
}

impl IdaPanel {
    pub(super) fn legend(&self) -> Vec<LegendItem> {
        vec![
            LegendItem::Line(
                LineStyle {
                    dash: None,
                    ..RECORD
                },
                format!("one record's analyses ({} records)", self.curves.len()),
            ),
            LegendItem::Mark(
                OVERTURNED.marker,
                OVERTURNED.colour,
                true,
                "overturned (in the grey column)".to_string(),
            ),
        ]
    }

    pub(super) fn draw(&self, area: &Area<'_>) -> Result<(), String> {
        let points = || self.curves.iter().flat_map(|c| c.1.iter());
        let y_hi = (points().map(|p| p.1).fold(0.0, f64::max) * 1.05).max(1e-9);
        // The responses (at least 0 to 1), then a column for the overturned analyses.
        let x_top = points().filter(|p| !p.2).map(|p| p.0).fold(1.0, f64::max) * 1.05;
        let (column, collapse_x) = ((x_top, x_top * 1.1), x_top * 1.05);
        let mut chart = axes(
            area,
            None,
            (0.0, column.1),
            (0.0, y_hi),
            (labels::MAX_THETA_OVER_ALPHA, &self.im_label),
            true,
        )?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(column.0, 0.0), (column.1, y_hi)],
                RGBColor(235, 235, 235).filled(),
            )))
            .map_err(fail)?;
        let line = rgb(RECORD.colour).mix(0.6);
        for (_, pts) in &self.curves {
            let xy: Vec<(f64, f64)> = pts
                .iter()
                .map(|&(r, im, c)| (if c { collapse_x } else { r }, im))
                .collect();
            // The curve up to its first overturned analysis.
            let end = pts.iter().position(|p| p.2).map_or(xy.len(), |i| i + 1);
            chart
                .draw_series(std::iter::once(PathElement::new(
                    xy[..end].to_vec(),
                    line.stroke_width(1),
                )))
                .map_err(fail)?;
            for (&q, &(_, _, overturned)) in xy.iter().zip(pts) {
                if overturned {
                    mark_at(
                        &chart,
                        OVERTURNED.marker,
                        q,
                        4,
                        rgb(OVERTURNED.colour),
                        true,
                    )?;
                } else {
                    chart
                        .draw_series(std::iter::once(Circle::new(q, 2, line.filled())))
                        .map_err(fail)?;
                }
            }
        }
        Ok(())
    }
}

/// A fitted lognormal fragility curve with its bootstrap band and the points it was fitted to.
pub struct FitPanel {
    pub fit: Bootstrap,
    /// (IM, probability): the capacities' plotting positions or the stripes' fractions.
    pub empirical: Vec<(f64, f64)>,
    /// What the empirical points are, for the legend.
    pub empirical_label: String,
    pub im_label: String,
    /// The unit of the IM, for the legend's median.
    pub unit: String,
}

/// The fit's line and the band's fill.
const FIT: LineStyle = style::LINES[0];
const POINTS: LineStyle = style::BLACK;

impl FitPanel {
    pub(super) fn legend(&self) -> Vec<LegendItem> {
        let e = &self.fit.estimate;
        vec![
            LegendItem::Line(
                LineStyle { dash: None, ..FIT },
                format!(
                    "lognormal fit: median {} {}, β = {}",
                    tick((e.theta * 1e3).round() / 1e3),
                    self.unit,
                    tick((e.beta * 1e3).round() / 1e3)
                ),
            ),
            LegendItem::Fill(
                band_colour(),
                format!(
                    "{} % bootstrap band ({} resamples)",
                    tick((self.fit.level * 100.0 * 10.0).round() / 10.0),
                    self.fit.fits.len()
                ),
            ),
            LegendItem::Mark(
                POINTS.marker,
                POINTS.colour,
                true,
                self.empirical_label.clone(),
            ),
        ]
    }

    pub(super) fn draw(&self, area: &Area<'_>) -> Result<(), String> {
        let x_hi = self.empirical.iter().map(|p| p.0).fold(0.0, f64::max) * 1.2;
        let x_hi = x_hi.max(1e-9);
        let mut chart = axes(
            area,
            None,
            (0.0, x_hi),
            (0.0, 1.02),
            (&self.im_label, "P(overturning | IM)"),
            true,
        )?;
        let xs: Vec<f64> = (1..=200).map(|i| x_hi * i as f64 / 200.0).collect();
        let band: Vec<(f64, f64)> = xs
            .iter()
            .map(|&x| self.fit.band(x))
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        let mut poly: Vec<(f64, f64)> = xs.iter().zip(&band).map(|(&x, b)| (x, b.0)).collect();
        poly.extend(xs.iter().zip(&band).rev().map(|(&x, b)| (x, b.1)));
        chart
            .draw_series(std::iter::once(Polygon::new(
                poly,
                rgb(band_colour()).filled(),
            )))
            .map_err(fail)?;
        let curve: Vec<(f64, f64)> = xs
            .iter()
            .map(|&x| (x, self.fit.estimate.probability(x)))
            .collect();
        styled_line(
            &mut chart,
            curve,
            &LineStyle { dash: None, ..FIT },
            rgb(FIT.colour),
            2,
        )?;
        for &p in &self.empirical {
            mark_at(&chart, POINTS.marker, p, 4, rgb(POINTS.colour), true)?;
        }
        Ok(())
    }
}

/// The band: the fit's colour, light.
fn band_colour() -> [u8; 3] {
    let c = FIT.colour;
    c.map(|v| (255.0 - 0.22 * (255.0 - f64::from(v))).round() as u8)
}

/// `ida.svg`, `.png`, `.pdf` (the curves) and `fragility-fit.svg`, `.png`, `.pdf` (the fit, when
/// there is one).
pub fn ida_plots(
    ida: IdaPanel,
    fit: Option<FitPanel>,
    dir: &Path,
) -> Result<Vec<PathBuf>, FigureError> {
    let records = ida.curves.len();
    let (title, scaled) = if ida.stripes {
        (
            format!("Multiple-stripe analyses of {records} records"),
            "scaled to each stripe's intensity",
        )
    } else {
        (
            format!("IDA curves of {records} records"),
            "scaled up until the column overturns",
        )
    };
    let curves = Figure {
        title,
        caption: Some(format!(
            "Each line: one record {scaled}; a point: one analysis. An overturned analysis \
             has no {} and is drawn in the grey column.",
            labels::MAX_THETA_OVER_ALPHA
        )),
        columns: 1,
        panel: (760, 520),
        panels: vec![Panel::Ida(ida)],
        colour_top: None,
        print: None,
    };
    let mut written = curves.write(dir, "ida")?;
    let Some(fit) = fit else {
        return Ok(written);
    };
    let fit = Figure {
        title: format!("Fragility: probability of overturning, {records} records"),
        caption: None,
        columns: 1,
        panel: (760, 520),
        panels: vec![Panel::Fit(fit)],
        colour_top: None,
        print: None,
    };
    written.extend(fit.write(dir, "fragility-fit")?);
    Ok(written)
}
