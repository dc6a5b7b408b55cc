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

/// A figure at its printed size: `width_mm` wide (the SVG's and the PDF's width), the PNG at
/// `dpi` pixels per inch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Print {
    pub width_mm: f64,
    pub dpi: f64,
}

/// usvg's pixels per inch: a length in mm becomes mm / 25.4 × 96 of its pixels.
const USVG_DPI: f64 = 96.0;

/// The SVG, PNG and PDF of a figure that plotters drew at its printed size (in units of
/// 1/[`crate::chart::UNITS_PER_MM`] mm): the SVG's `width` and `height` in mm over its
/// viewBox, no subscript below [`crate::chart::PRINT_MIN_PT`], the PDF page of that size and
/// the PNG at `print.dpi`.
pub fn export_print(plotters_svg: &str, print: Print) -> Result<Exported, String> {
    let min_sub = crate::chart::points(crate::chart::PRINT_MIN_PT);
    let svg = crate::style::hatch_svg(&crate::text::finish_svg_min(plotters_svg, min_sub));
    let svg = physical_size(&svg)?;
    let options = usvg::Options {
        font_family: FAMILY.to_string(),
        fontdb: fonts(),
        dpi: USVG_DPI as f32,
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(&svg, &options).map_err(|e| format!("SVG: {e}"))?;
    let scale = (print.dpi / USVG_DPI) as f32;
    let size = tree.size();
    let (w, h) = (
        (size.width() * scale).round() as u32,
        (size.height() * scale).round() as u32,
    );
    let mut pixmap =
        tiny_skia::Pixmap::new(w, h).ok_or_else(|| format!("PNG: a {w} × {h} image"))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    let png = pixmap.encode_png().map_err(|e| format!("PNG: {e}"))?;
    let pdf = svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions {
            dpi: USVG_DPI as f32,
        },
    )
    .map_err(|e| format!("PDF: {e}"))?;
    Ok(Exported {
        svg,
        png,
        pdf: ordered_resources(&pdf),
    })
}

/// The SVG with its root's `width` and `height` (plotters writes the viewBox's units) in mm.
fn physical_size(svg: &str) -> Result<String, String> {
    let start = svg.find("<svg").ok_or("SVG: no <svg> element")?;
    let end = start + svg[start..].find('>').ok_or("SVG: an unclosed <svg>")?;
    let tag = &svg[start..end];
    let mut out = tag.to_string();
    for name in ["width", "height"] {
        let key = format!(" {name}=\"");
        let from = out.find(&key).ok_or(format!("SVG: no {name}"))? + key.len();
        let len = out[from..].find('"').ok_or(format!("SVG: {name}"))?;
        let units: f64 = out[from..from + len]
            .parse()
            .map_err(|_| format!("SVG: {name}"))?;
        let mm = units / crate::chart::UNITS_PER_MM;
        out.replace_range(from..from + len, &format!("{}mm", crate::text::tick(mm)));
    }
    Ok(format!("{}{out}{}", &svg[..start], &svg[end..]))
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
    Ok(Exported {
        svg,
        png,
        pdf: ordered_resources(&pdf),
    })
}

/// The PDF with each resource dictionary's entries in the order of their names. svg2pdf 0.13
/// writes them in a `HashMap`'s order, which changes from call to call (the hatching patterns of
/// one figure came out in a new order each time); it names them in drawing order (`/po0`,
/// `/po1`, ...) and writes one entry a line, so sorting each run of entry lines by name restores
/// one order. Lines are only permuted: every byte offset (the cross-reference table) stays right.
/// Stream data is skipped by its `/Length`.
fn ordered_resources(pdf: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(pdf.len());
    let mut run: Vec<&[u8]> = Vec::new();
    let flush = |out: &mut Vec<u8>, run: &mut Vec<&[u8]>| {
        run.sort_by_key(|line| resource_name(line));
        for line in run.drain(..) {
            out.extend_from_slice(line);
        }
    };
    let mut length = 0usize;
    let mut at = 0;
    while at < pdf.len() {
        let end = pdf[at..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(pdf.len(), |k| at + k + 1);
        let line = &pdf[at..end];
        if resource_name(line).is_some() {
            run.push(line);
            at = end;
            continue;
        }
        flush(&mut out, &mut run);
        out.extend_from_slice(line);
        let text = line.trim_ascii();
        if let Some(n) = text.strip_prefix(b"/Length ") {
            length = std::str::from_utf8(n)
                .ok()
                .and_then(|n| n.parse().ok())
                .unwrap_or(0);
        }
        at = end;
        if text == b"stream" {
            let data_end = (at + length).min(pdf.len());
            out.extend_from_slice(&pdf[at..data_end]);
            at = data_end;
        }
    }
    flush(&mut out, &mut run);
    out
}

/// The name of a resource dictionary entry line (`/po12 19 0 R`, `/cs0 [/ICCBased 6 0 R]`) as
/// its letters and number, else `None`.
fn resource_name(line: &[u8]) -> Option<(&[u8], u64)> {
    let text = line.trim_ascii().strip_prefix(b"/")?;
    let letters = text.iter().take_while(|b| b.is_ascii_lowercase()).count();
    let digits = text[letters..]
        .iter()
        .take_while(|b| b.is_ascii_digit())
        .count();
    let rest = &text[letters + digits..];
    let reference = rest.ends_with(b" 0 R") || rest.ends_with(b" 0 R]");
    if letters == 0 || digits == 0 || !rest.starts_with(b" ") || !reference {
        return None;
    }
    let number = std::str::from_utf8(&text[letters..letters + digits])
        .ok()?
        .parse()
        .ok()?;
    Some((&text[..letters], number))
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

    #[test]
    fn a_hatched_figure_gives_the_same_pdf_bytes_every_time() {
        // Cells of the three hatched classes: one pattern resource per cell in the PDF.
        let mut svg = String::from(
            "<svg width=\"400\" height=\"40\" viewBox=\"0 0 400 40\" \
             xmlns=\"http://www.w3.org/2000/svg\">\n",
        );
        let hatched = crate::style::CLASSES.iter().filter(|c| c.hatch.is_some());
        for (k, c) in hatched.cycle().take(12).enumerate() {
            let [r, g, b] = c.fill;
            svg.push_str(&format!(
                "<rect x=\"{}\" y=\"0\" width=\"30\" height=\"40\" \
                 fill=\"#{r:02X}{g:02X}{b:02X}\"/>\n",
                k * 32
            ));
        }
        svg.push_str("</svg>\n");
        let first = export(&svg).unwrap().pdf;
        assert!(
            String::from_utf8_lossy(&first).matches("/po").count() >= 12,
            "a pattern per cell"
        );
        for _ in 0..5 {
            assert!(export(&svg).unwrap().pdf == first, "the PDF bytes differ");
        }
        // Entry lines are only reordered, so the cross-reference offsets still point at objects.
        let find = |from: usize, what: &[u8]| {
            first[from..]
                .windows(what.len())
                .position(|w| w == what)
                .map(|k| from + k)
        };
        let number = |from: usize| -> usize {
            let digits = first[from..]
                .iter()
                .take_while(|b| b.is_ascii_digit())
                .count();
            std::str::from_utf8(&first[from..from + digits])
                .unwrap()
                .parse()
                .unwrap()
        };
        let start = find(0, b"startxref\n").unwrap();
        let xref = number(start + 10);
        assert!(first[xref..].starts_with(b"xref\n0 "));
        // "xref", "0 N", the free entry, then one 20-byte entry per object.
        let mut entry = find(xref, b" 65535 f\r\n").unwrap() + 10;
        let mut objects = 0;
        while first[entry..].starts_with(b"0") && first[entry + 17] == b'n' {
            let offset = number(entry);
            let n = number(offset);
            assert!(
                first[offset..].starts_with(format!("{n} 0 obj").as_bytes()),
                "offset {offset} is not an object"
            );
            objects += 1;
            entry += 20;
        }
        assert!(objects > 12, "{objects} objects");
    }
}
