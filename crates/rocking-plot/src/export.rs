//! One figure, three files: plotters draws the SVG; its subscripts become tspans
//! ([`crate::text::finish_svg`]) and its hatched classes patterns ([`crate::style::hatch_svg`]);
//! usvg reads that SVG once with the embedded font (no system font is looked up, so every
//! machine draws the same pixels), resvg rasterises it to PNG and svg2pdf converts it to a PDF
//! with the text embedded (a subset of the font) and selectable.

use std::sync::{Arc, OnceLock};

use resvg::tiny_skia;
use svg2pdf::usvg;

/// The family the SVG names and the embedded font provides.
const FAMILY: &str = "DejaVu Sans";

/// A PDF page's pixels per inch: a 1040-pixel-wide figure is 7.2 inches, a journal's two-column
/// width.
const PDF_DPI: f32 = 144.0;

/// A figure as SVG (text), PNG and PDF bytes.
pub struct Exported {
    pub svg: String,
    pub png: Vec<u8>,
    pub pdf: Vec<u8>,
}

/// The font database: the embedded font only, standing for every generic family.
fn fonts() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(crate::FONT.to_vec());
        db.set_sans_serif_family(FAMILY);
        db.set_serif_family(FAMILY);
        db.set_monospace_family(FAMILY);
        Arc::new(db)
    })
    .clone()
}

/// The finished SVG of what plotters drew (subscripts and hatching in place).
pub fn finish(plotters_svg: &str) -> String {
    crate::style::hatch_svg(&crate::text::finish_svg(plotters_svg))
}

/// The SVG, PNG and PDF of what plotters drew into `plotters_svg`.
pub fn export(plotters_svg: &str) -> Result<Exported, String> {
    let svg = finish(plotters_svg);
    let options = usvg::Options {
        font_family: FAMILY.to_string(),
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(&svg, &options).map_err(|e| format!("SVG: {e}"))?;
    let size = tree.size().to_int_size();
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| format!("PNG: a {} × {} image", size.width(), size.height()))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    let png = pixmap.encode_png().map_err(|e| format!("PNG: {e}"))?;
    let pdf = svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions { dpi: PDF_DPI },
    )
    .map_err(|e| format!("PDF: {e}"))?;
    Ok(Exported { svg, png, pdf })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_svg_gives_a_png_of_its_size_and_a_pdf_with_the_text() {
        let svg = format!(
            "<svg width=\"120\" height=\"40\" viewBox=\"0 0 120 40\" \
             xmlns=\"http://www.w3.org/2000/svg\">\n<rect x=\"0\" y=\"0\" width=\"120\" \
             height=\"40\" fill=\"#FFFFFF\"/>\n<text x=\"10\" y=\"20\" font-family=\"sans-serif\" \
             font-size=\"14\" fill=\"#000000\">{}</text>\n</svg>\n",
            crate::text::rich("u/u_cr")
        );
        let out = export(&svg).unwrap();
        assert!(out.svg.contains("<tspan class=\"sub\""), "{}", out.svg);
        assert_eq!(&out.png[1..4], b"PNG");
        // Width and height in the IHDR chunk.
        let be = |k: usize| u32::from_be_bytes(out.png[k..k + 4].try_into().unwrap());
        assert_eq!((be(16), be(20)), (120, 40));
        assert!(out.pdf.starts_with(b"%PDF-"));
        // The font is embedded (a subset of DejaVu Sans) and nothing was drawn without it.
        let pdf = String::from_utf8_lossy(&out.pdf);
        assert!(pdf.contains("DejaVuSans"), "no embedded font");
        // The same input gives the same bytes.
        let again = export(&svg).unwrap();
        assert!(again.png == out.png && again.pdf == out.pdf);
    }
}
