//! What every figure is drawn with, the `rocking` command's and the work-precision diagrams
//! alike: a [`Page`] (a title wrapped between items, panels in a grid, a legend column beside
//! them so that no legend covers data, and a caption under them that explains the marks), a
//! panel's axes ([`axes`]: tick labels by [`tick`], or powers of ten by [`log_axes`], axis
//! labels with subscripts), lines in their style's dash, markers, and the legend's entries.
//! plotters draws into an SVG string; [`crate::export`] makes the PNG and the PDF from it.

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontTransform;

use crate::style::{LineStyle, Marker};
use crate::text::{power_of_ten, rich, tick, wrap_items};

mod axes;
mod legend;
mod marks;
mod page;

pub use axes::{axes, log_axes};
pub use legend::{legend, legend_band, legend_band_height, LegendItem};
pub use marks::{mark_at, marker, pixel, styled_line};
pub(crate) use page::print_label_areas;
pub use page::{Page, PrintGeometry, PrintLayout};

/// The drawing area every panel and legend draws on.
pub type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;
/// A panel's chart: f64 axes (for a logarithmic axis, the log10 of the values).
pub type Chart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Font sizes (plotters' sizes: the SVG's are these / 1.24).
pub const TITLE: u32 = 22;
pub const PANEL_TITLE: u32 = 18;
pub const AXIS: u32 = 18;
pub const TICKS: u32 = 15;
pub const LEGEND: u32 = 15;
/// The width of the legend column.
pub const LEGEND_WIDTH: u32 = 280;

/// A figure at its printed size is drawn in units of 1/8 mm (the SVG's viewBox; its `width`
/// and `height` are in mm), so that a 175 mm double column is 1400 units wide.
pub const UNITS_PER_MM: f64 = 8.0;
/// plotters writes a font of size s as `font-size` s / 1.24 in the SVG.
const PLOTTERS_FONT: f64 = 1.24;

/// The drawing units of `pt` points at the printed size.
pub fn points(pt: f64) -> f64 {
    pt * 25.4 / 72.0 * UNITS_PER_MM
}

/// Type sizes at the printed size, in points: tick labels and legends 7 pt, axis labels and
/// column/row headers 8 pt, panel letters 9 pt; subscripts are never set below 6 pt.
pub const PRINT_TICKS_PT: f64 = 7.0;
pub const PRINT_LEGEND_PT: f64 = 7.0;
pub const PRINT_AXIS_PT: f64 = 8.0;
pub const PRINT_HEADER_PT: f64 = 8.0;
pub const PRINT_LETTER_PT: f64 = 9.0;
pub const PRINT_TITLE_PT: f64 = 9.0;
pub const PRINT_MIN_PT: f64 = 6.0;

/// A panel's margins at print size: the letter's line above, room for the last tick label on
/// the right.
const PRINT_MARGIN_RIGHT: u32 = 20;
const PRINT_MARGIN: u32 = 4;

/// The type sizes a figure is set in (plotters' sizes), and whether it is laid out for print.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Type {
    pub title: f64,
    pub panel_title: f64,
    pub axis: f64,
    pub ticks: f64,
    pub legend: f64,
    pub letter: f64,
    pub print: bool,
}

impl Type {
    /// The screen figures' sizes (pixels), as before print sizes existed.
    pub const SCREEN: Type = Type {
        title: TITLE as f64,
        panel_title: PANEL_TITLE as f64,
        axis: AXIS as f64,
        ticks: TICKS as f64,
        legend: LEGEND as f64,
        letter: PANEL_TITLE as f64,
        print: false,
    };

    /// The sizes at the printed width ([`UNITS_PER_MM`]): the `PRINT_*_PT` points, rounded up
    /// to whole plotters sizes (its tick labels are drawn at a whole size).
    pub fn print() -> Type {
        let f = |pt: f64| (points(pt) * PLOTTERS_FONT).ceil();
        Type {
            title: f(PRINT_TITLE_PT),
            panel_title: f(PRINT_HEADER_PT),
            axis: f(PRINT_AXIS_PT),
            ticks: f(PRINT_TICKS_PT),
            legend: f(PRINT_LEGEND_PT),
            letter: f(PRINT_LETTER_PT),
            print: true,
        }
    }

    /// The height of a line of text of plotters' size `size`, in this type's units.
    pub fn line(&self, size: f64) -> u32 {
        if self.print {
            (size / PLOTTERS_FONT * 1.25).ceil() as u32
        } else {
            line_height(size as u32)
        }
    }
}

/// What the panel about to be drawn shows besides its data at print size: its letter, and
/// whether it draws its own axis labels (not when its row or column shares one).
#[derive(Clone, Debug, Default)]
pub struct PanelText {
    pub letter: Option<String>,
    pub hide_x_label: bool,
    pub hide_y_label: bool,
    /// Its title is a column or row header of the figure.
    pub hide_title: bool,
}

thread_local! {
    static TYPE: std::cell::Cell<Type> = const { std::cell::Cell::new(Type::SCREEN) };
    static PANEL: std::cell::RefCell<PanelText> = std::cell::RefCell::new(PanelText::default());
}

/// The type sizes of the figure being drawn on this thread ([`Page::svg`] sets them).
pub fn current() -> Type {
    TYPE.with(|t| t.get())
}

/// Sets what the next panel's [`axes`] draws besides its data (its letter, shared labels).
pub fn set_panel(text: PanelText) {
    PANEL.with(|p| *p.borrow_mut() = text);
}

/// Sets the type for the duration of a drawing, and the screen's back after it.
struct TypeGuard;

impl TypeGuard {
    fn set(t: Type) -> TypeGuard {
        TYPE.with(|c| c.set(t));
        set_panel(PanelText::default());
        TypeGuard
    }
}

impl Drop for TypeGuard {
    fn drop(&mut self) {
        TYPE.with(|c| c.set(Type::SCREEN));
        set_panel(PanelText::default());
    }
}

pub fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// A drawing error as the message a figure's error carries.
pub fn fail<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// The height of a line of text of `size`.
pub fn line_height(size: u32) -> u32 {
    (size as f64 * 1.3) as u32
}

/// Lines of (rich) text from `y`, anchored at `x`.
pub fn text_lines(
    area: &Area<'_>,
    lines: &[String],
    size: u32,
    x: i32,
    y: i32,
    h: HPos,
) -> Result<(), String> {
    let style = ("sans-serif", size)
        .into_font()
        .into_text_style(area)
        .pos(Pos::new(h, VPos::Top));
    for (i, line) in lines.iter().enumerate() {
        let y = y + (i as u32 * line_height(size)) as i32;
        area.draw_text(&rich(line), &style, (x, y)).map_err(fail)?;
    }
    Ok(())
}
