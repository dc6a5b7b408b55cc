//! Every figure file of scenes/paper and scenes/forces drawn at its printed size (issue 46), on a
//! small grid: the SVG's physical width is the file's `width` (its viewBox in 1/8 mm), read back
//! from the SVG every text is set at 7 pt or more (tick labels, legends, headers), every axis
//! label at 8 pt or more, nothing (subscripts included) below 6 pt; a multi-panel figure carries
//! its letters (a), (b), ... once each; the title is not in the image but in NAME.caption.md; the
//! PNG is the file's resolution (600 dpi unless it says) of that width, the PDF page that width.
//! `--draft` keeps the title in the image and writes no caption file. Every panel's plotting
//! area, measured between its axis lines in the SVG, is at least 35 mm wide in print, and an inset
//! a figure file asks for is drawn with its own axes inside its panel's.

mod common;

use common::{bin, repo, tmp_path, FIGS_6_TO_8};
use std::path::{Path, PathBuf};

/// Points per mm.
const PT_PER_MM: f64 = 72.0 / 25.4;
/// Below these a figure fails (a rounding's tolerance: plotters writes sizes as f64 / 1.24).
const MIN_PT: f64 = 6.0 - 1e-6;
const TEXT_PT: f64 = 7.0 - 1e-6;
const AXIS_PT: f64 = 8.0 - 1e-6;
/// The narrowest a panel's plotting area may print (issue 46).
const MIN_PANEL_MM: f64 = 35.0;

/// A plotting area in the SVG's units: left, right, top, bottom.
type Rect = (f64, f64, f64, f64);

/// The plotting areas of an SVG: each y axis (a black vertical line) with the x axis (a black
/// horizontal line) that starts at its foot, as plotters draws every chart's axes.
fn plot_areas(svg: &str) -> Vec<Rect> {
    let lead =
        "<polyline fill=\"none\" opacity=\"1\" stroke=\"#000000\" stroke-width=\"1\" points=\"";
    let segments: Vec<[f64; 4]> = svg
        .split(lead)
        .skip(1)
        .filter_map(|rest| {
            let pts: Vec<f64> = rest
                .split('"')
                .next()?
                .split([' ', ','])
                .filter(|v| !v.is_empty())
                .map(|v| v.parse().ok())
                .collect::<Option<_>>()?;
            (pts.len() == 4).then(|| [pts[0], pts[1], pts[2], pts[3]])
        })
        .collect();
    let mut areas = Vec::new();
    for &[x, y0, x1, y1] in &segments {
        if x != x1 || (y1 - y0).abs() < 20.0 {
            continue;
        }
        let foot = y0.max(y1);
        for &[a, b, c, d] in &segments {
            if b == d && c - a > 20.0 && (a - x).abs() <= 2.0 && (b - foot).abs() <= 2.0 {
                areas.push((a, c + 1.0, y0.min(y1), foot));
            }
        }
    }
    areas
}

/// Whether `inner` lies inside `outer`.
fn inside(inner: &Rect, outer: &Rect) -> bool {
    inner != outer
        && inner.0 >= outer.0
        && inner.1 <= outer.1
        && inner.2 >= outer.2
        && inner.3 <= outer.3
}

fn ok(o: &std::process::Output) {
    assert!(
        o.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The value of `name="..."` in a tag.
fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let from = tag.find(&key)? + key.len();
    let len = tag[from..].find('"')?;
    Some(&tag[from..from + len])
}

/// One `<text>` element: its size, whether it is rotated (a y label or a row header), its text
/// with subscripts marked `_`, and its subscripts' sizes.
struct Text {
    size: f64,
    rotated: bool,
    text: String,
    subs: Vec<f64>,
}

fn texts(svg: &str) -> Vec<Text> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>'))
        .filter_map(|(tag, rest)| rest.split_once("</text>").map(|(body, _)| (tag, body)))
        .map(|(tag, body)| {
            let size: f64 = attr(tag, "font-size").unwrap().parse().unwrap();
            let mut text = String::new();
            let mut subs = Vec::new();
            for (k, part) in body.split("<tspan").enumerate() {
                if k == 0 {
                    text.push_str(part);
                    continue;
                }
                let (tag, rest) = part.split_once('>').unwrap();
                if tag.contains("class=\"sub\"") {
                    subs.push(attr(tag, "font-size").unwrap().parse().unwrap());
                    text.push('_');
                }
                text.push_str(&rest.replace("</tspan>", ""));
            }
            Text {
                size,
                rotated: tag.contains("rotate("),
                text: text.trim().to_string(),
                subs,
            }
        })
        .collect()
}

/// The figure files the test draws.
fn figure_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in ["scenes/paper", "scenes/forces"] {
        for e in std::fs::read_dir(repo().join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "toml") {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

/// The printed width a figure file states, in mm (default "double").
fn stated_width(spec: &toml::Value) -> f64 {
    match spec.get("width") {
        None => 175.0,
        Some(toml::Value::String(s)) if s == "double" => 175.0,
        Some(toml::Value::String(s)) if s == "single" => 85.0,
        Some(toml::Value::Float(v)) => *v,
        Some(toml::Value::Integer(v)) => *v as f64,
        Some(v) => panic!("width = {v}"),
    }
}

/// The axis labels a figure may show (every quantity's, the spectra's axes).
fn is_axis_label(t: &str) -> bool {
    t == "τ = p t"
        || t == "t (s)"
        || t == "ω_p/p"
        || t == "a_p/(g tan α)"
        || (t.contains('/') && !t.contains('=') && !t.contains(':') && t.len() < 40)
}

fn check(name: &str, dir: &Path, spec: &toml::Value) {
    let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap();
    let root = &svg[svg.find("<svg").unwrap()..];
    let root = &root[..root.find('>').unwrap()];
    let width_mm: f64 = attr(root, "width")
        .and_then(|w| w.strip_suffix("mm"))
        .unwrap_or_else(|| panic!("{name}: no width in mm: {root}"))
        .parse()
        .unwrap();
    let height_mm: f64 = attr(root, "height")
        .and_then(|w| w.strip_suffix("mm"))
        .unwrap()
        .parse()
        .unwrap();
    let stated = stated_width(spec);
    assert!(
        (width_mm - stated).abs() < 1e-9,
        "{name}: {width_mm} mm wide, the file says {stated} mm"
    );
    let view: Vec<f64> = attr(root, "viewBox")
        .unwrap()
        .split(' ')
        .map(|v| v.parse().unwrap())
        .collect();
    let mm_per_unit = width_mm / view[2];
    assert!(
        (view[3] * mm_per_unit - height_mm).abs() < 0.01,
        "{name}: the viewBox's aspect is not the page's"
    );
    let pt = |size: f64| size * mm_per_unit * PT_PER_MM;
    let all = texts(&svg);
    assert!(!all.is_empty(), "{name}: no text");
    let mut smallest = f64::INFINITY;
    for t in &all {
        let size = pt(t.size);
        smallest = smallest.min(size);
        assert!(
            size >= TEXT_PT,
            "{name}: `{}` at {size:.2} pt (< 7 pt)",
            t.text
        );
        for &s in &t.subs {
            smallest = smallest.min(pt(s));
            assert!(
                pt(s) >= MIN_PT,
                "{name}: a subscript of `{}` at {:.2} pt (< 6 pt)",
                t.text,
                pt(s)
            );
        }
        if t.rotated || is_axis_label(&t.text) {
            assert!(
                size >= AXIS_PT,
                "{name}: the axis label `{}` at {size:.2} pt (< 8 pt)",
                t.text
            );
        }
    }
    // Panels at least 35 mm wide; insets inside their panels.
    let panels = spec["panels"].as_array().unwrap();
    let areas = plot_areas(&svg);
    let (insets, outer): (Vec<Rect>, Vec<Rect>) = areas
        .iter()
        .partition(|a| areas.iter().any(|o| inside(a, o)));
    assert_eq!(
        outer.len(),
        panels.len(),
        "{name}: plotting areas {areas:?}"
    );
    let narrowest = outer
        .iter()
        .map(|a| (a.1 - a.0) * mm_per_unit)
        .fold(f64::INFINITY, f64::min);
    assert!(
        narrowest >= MIN_PANEL_MM,
        "{name}: a panel plots {narrowest:.1} mm wide (< {MIN_PANEL_MM} mm)"
    );
    let asked = panels.iter().filter(|p| p.get("inset").is_some()).count();
    assert_eq!(insets.len(), asked, "{name}: insets {insets:?}");
    eprintln!(
        "{name}: {width_mm} mm wide, smallest text {smallest:.2} pt, narrowest panel \
         {narrowest:.1} mm, {asked} insets"
    );
    // Letters: one per panel, in order, on a figure of more than one panel.
    let panels = panels.len();
    let letters: Vec<&str> = all
        .iter()
        .map(|t| t.text.as_str())
        .filter(|t| {
            t.len() >= 3
                && t.starts_with('(')
                && t.ends_with(')')
                && t[1..t.len() - 1].chars().all(|c| c.is_ascii_lowercase())
        })
        .collect();
    if panels > 1 {
        let expected: Vec<String> = (0..panels)
            .map(|k| format!("({})", (b'a' + k as u8) as char))
            .collect();
        assert_eq!(letters, expected, "{name}: panel letters");
    } else {
        assert!(letters.is_empty(), "{name}: one panel has no letter");
    }
    // No title inside the image; the caption beside it starts with it.
    let title = spec["title"].as_str().unwrap();
    let head = title.split(':').next().unwrap();
    for t in &all {
        let plain = t.text.replace('_', "");
        assert!(
            !plain.contains(head) && !title.replace('_', "").contains(&plain) || plain.len() < 12,
            "{name}: title text `{}` inside the image",
            t.text
        );
    }
    let caption = std::fs::read_to_string(dir.join(format!("{name}.caption.md"))).unwrap();
    assert!(
        caption.starts_with(&format!("**{}", title.trim_end_matches('.'))),
        "{name}: {caption}"
    );
    if panels > 1 {
        assert!(
            caption.contains("(a) "),
            "{name}: the letters in the caption"
        );
    }
    // The PNG: the stated resolution (600 dpi) of the same width; the PDF page that width.
    let dpi = spec
        .get("dpi")
        .and_then(toml::Value::as_integer)
        .unwrap_or(600) as f64;
    let png = std::fs::read(dir.join(format!("{name}.png"))).unwrap();
    let be = |k: usize| u32::from_be_bytes(png[k..k + 4].try_into().unwrap());
    let px = (width_mm / 25.4 * dpi).round() as u32;
    assert!(
        be(16).abs_diff(px) <= 1,
        "{name}: PNG {} px wide, {px} at {dpi} dpi",
        be(16)
    );
    let pdf = std::fs::read(dir.join(format!("{name}.pdf"))).unwrap();
    let pdf = String::from_utf8_lossy(&pdf);
    let media = pdf.split("/MediaBox [").nth(1).unwrap();
    let media: Vec<f64> = media
        .split(']')
        .next()
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(
        ((media[2] - media[0]) - width_mm * PT_PER_MM).abs() < 0.5,
        "{name}: PDF page {media:?} pt, {} pt wide expected",
        width_mm * PT_PER_MM
    );
}

/// Each figure file at its printed size, on a 4 × 4 grid of each sweep (the whole test ~1 min on
/// 2 cores).
#[test]
fn every_figure_file_is_drawn_at_its_printed_size_with_print_type_and_letters() {
    let out = tmp_path("print");
    let cache = tmp_path("print-cache");
    let files = figure_files();
    assert!(files.len() >= 9, "{files:?}");
    ok(&bin()
        .arg("figure")
        .args(&files)
        .args(["--cells", "4", "--quiet", "--out"])
        .arg(&out)
        .arg("--cache")
        .arg(&cache)
        .output()
        .unwrap());
    for f in &files {
        let spec: toml::Value = toml::from_str(&std::fs::read_to_string(f).unwrap()).unwrap();
        let name = f.file_stem().unwrap().to_string_lossy();
        check(&name, &out, &spec);
    }
    // The content each figure's argument needs (issue 46): the wind turbine in seconds with
    // the uplift moment ±W B marked; Fig. 5 with the fixed-base twins; Figs 6-8 with the rigid
    // column's boundary dashed on the flexible panels.
    let read = |name: &str| std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
    let turbine = texts(&read("turbine-elcentro"));
    assert!(
        turbine.iter().any(|t| t.text == "t (s)"),
        "turbine: no time in s"
    );
    assert!(
        !turbine.iter().any(|t| t.text == "τ = p t"),
        "turbine: τ left"
    );
    let fig5 = texts(&read("fig5"));
    assert!(
        fig5.iter().any(|t| t.text == "fixed-base twin"),
        "fig5: no twin"
    );
    // Fig. 5's inset lies in panel (b), the stiff column's rotation (top right).
    let areas = plot_areas(&read("fig5"));
    let (insets, outer): (Vec<Rect>, Vec<Rect>) = areas
        .iter()
        .partition(|a| areas.iter().any(|o| inside(a, o)));
    let top = outer.iter().map(|a| a.2).fold(f64::INFINITY, f64::min);
    let right = outer.iter().map(|a| a.0).fold(0.0, f64::max);
    let b = outer.iter().find(|a| a.2 == top && a.0 == right).unwrap();
    assert!(
        insets.len() == 1 && inside(&insets[0], b),
        "fig5: inset {insets:?} not in (b) {b:?}"
    );
    for name in FIGS_6_TO_8 {
        let svg = texts(&read(name));
        assert!(
            svg.iter().any(|t| t.text == "overturned | upright, rigid"),
            "{name}: no rigid boundary in the legend"
        );
    }
    // --draft: the title in the image, no caption file.
    let draft = tmp_path("print-draft");
    let fig3 = repo().join("scenes/paper/fig3.toml");
    ok(&bin()
        .arg("figure")
        .arg(&fig3)
        .args(["--draft", "--quiet", "--out"])
        .arg(&draft)
        .arg("--cache")
        .arg(&cache)
        .output()
        .unwrap());
    let svg = std::fs::read_to_string(draft.join("fig3.svg")).unwrap();
    assert!(texts(&svg).iter().any(|t| t.text.starts_with("Fig. 3:")));
    assert!(!draft.join("fig3.caption.md").exists());
    for d in [out, cache, draft] {
        let _ = std::fs::remove_dir_all(d);
    }
}

/// Figs 6-8 compare the γ families on one colour scale: the six files state the same
/// `colour_top`, draw the scenes' 100 × 100 cells (no `cells` cap), and overlay on every flexible
/// panel the rigid column of the same α (its `reference`); Fig. 9's small multiples use the
/// same sweeps (scene and overrides), so that the cache computes each once.
#[test]
fn figs_6_to_8_share_one_colour_scale_at_100_cells_with_the_rigid_boundary() {
    let mut tops = Vec::new();
    let mut sweeps_6_to_8 = std::collections::BTreeSet::new();
    for name in FIGS_6_TO_8 {
        let path = repo().join(format!("scenes/paper/{name}.toml"));
        let spec: toml::Value = toml::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        tops.push(
            spec.get("colour_top")
                .and_then(toml::Value::as_float)
                .unwrap_or_else(|| panic!("{name}: no colour_top")),
        );
        assert!(spec.get("cells").is_none(), "{name}: a cells cap");
        let sweeps = spec["sweeps"].as_table().unwrap();
        for (name_s, s) in sweeps {
            let axes = s.get("axes").map(|a| a.to_string()).unwrap_or_default();
            assert!(axes.is_empty(), "{name}.{name_s}: own axes {axes}");
            sweeps_6_to_8.insert((s["scene"].to_string(), s["set"].to_string()));
        }
        let panels = spec["panels"].as_array().unwrap();
        assert_eq!(panels.len(), 5, "{name}");
        for p in panels {
            let sweep = p["sweep"].as_str().unwrap();
            let reference = p.get("reference").and_then(toml::Value::as_str);
            if sweep.ends_with("rigid") {
                assert_eq!(reference, None, "{name}: {sweep}");
            } else {
                let alpha = &sweep[..3];
                assert_eq!(
                    reference,
                    Some(format!("{alpha}_wnrigid").as_str()),
                    "{name}: {sweep}"
                );
            }
        }
    }
    assert!(
        tops.windows(2).all(|w| w[0] == w[1]),
        "colour_top: {tops:?}"
    );
    assert_eq!(sweeps_6_to_8.len(), 30);
    let fig9: toml::Value =
        toml::from_str(&std::fs::read_to_string(repo().join("scenes/paper/fig9.toml")).unwrap())
            .unwrap();
    let fig9: std::collections::BTreeSet<_> = fig9["sweeps"]
        .as_table()
        .unwrap()
        .values()
        .map(|s| (s["scene"].to_string(), s["set"].to_string()))
        .collect();
    assert_eq!(fig9, sweeps_6_to_8, "fig9: not the sweeps of Figs 6-8");
    // The scenes' own axes: 100 × 100 cells.
    for family in ["fig6", "fig7", "fig8"] {
        let path = repo().join(format!("scenes/spectra/{family}.toml"));
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.contains(
                "\"excitation.omega_p_over_p=1:10:100\", \"excitation.amplitude=1:20:100\""
            ),
            "{family}: not 100 x 100"
        );
    }
}

/// A figure whose survivors exceed its stated `colour_top` says how many (drawn in its colour).
#[test]
fn survivors_above_colour_top_are_noted() {
    let dir = tmp_path("colour-top");
    std::fs::create_dir_all(&dir).unwrap();
    let fig = std::fs::read_to_string(repo().join("scenes/paper/fig8-alpha01.toml"))
        .unwrap()
        .replace("colour_top = ", "colour_top = 0.01 # was ")
        .replace(
            "../spectra/",
            &format!("{}/", repo().join("scenes/spectra").display()),
        );
    std::fs::write(dir.join("low.toml"), fig).unwrap();
    let o = bin()
        .arg("figure")
        .arg(dir.join("low.toml"))
        .args(["--cells", "3", "--quiet", "--out"])
        .arg(dir.join("out"))
        .arg("--cache")
        .arg(dir.join("cache"))
        .output()
        .unwrap();
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("shaded cells lie above colour_top = 0.01"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(dir);
}
