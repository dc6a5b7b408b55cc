//! Figures on what they draw, not on pixels: the labels in the SVG text of the time history, the
//! spectrum and the one-axis line plot (subscripts as tspans); every figure file of scenes/paper
//! drawn on small grids (overlays, one colour scale, no "-0" tick); a one-axis sweep writes its
//! line plot; the animated GIF
//! has the stated frame count and size, and its first and last frames show the base plate at the
//! simulated angles (read back from the drawn plate's pixels).

mod common;

use common::{bin, repo, tmp_path, FIGS_6_TO_8};
use std::path::{Path, PathBuf};

fn ok(o: &std::process::Output) {
    assert!(
        o.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The text of each <text> element (labels, not attributes), with its subscript tspans written
/// back in the labels' notation (`u<tspan class="sub" ...>cr</tspan>` reads `u_cr`).
fn texts(svg: &str) -> Vec<String> {
    texts_marking(svg, "_")
}

/// The text of each <text> element, each subscript preceded by `mark`.
fn texts_marking(svg: &str, mark: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').map(|(_, rest)| rest))
        .filter_map(|t| t.split_once("</text>").map(|(text, _)| text))
        .map(|t| {
            let mut out = String::new();
            for (k, part) in t.split("<tspan").enumerate() {
                if k == 0 {
                    out.push_str(part);
                    continue;
                }
                let (tag, rest) = part.split_once('>').unwrap();
                if tag.contains("class=\"sub\"") {
                    out.push_str(mark);
                }
                out.push_str(&rest.replace("</tspan>", ""));
            }
            out
        })
        .collect()
}

fn svg_text(path: &Path) -> String {
    texts(&std::fs::read_to_string(path).unwrap()).join("\n")
}

fn sweep(out: &Path, axes: &[&str]) {
    let mut c = bin();
    c.arg("spectrum")
        .arg(repo().join("scenes/spectra/fig8.toml"))
        .arg("--quiet")
        .arg("--out")
        .arg(out);
    for a in axes {
        c.arg("--axis").arg(a);
    }
    ok(&c.output().unwrap());
}

#[test]
fn the_spectrum_is_labelled_in_the_papers_notation() {
    let out = tmp_path("spectrum");
    sweep(
        &out,
        &[
            "excitation.omega_p_over_p=1:10:8",
            "excitation.amplitude=1:20:8",
        ],
    );
    let text = svg_text(&out.join("spectrum.svg"));
    for label in [
        "ω_p/p",
        "a_p/(g tan α)",
        "max |θ|/α",
        "overturned",
        "Fig. 8",
    ] {
        assert!(
            text.contains(label),
            "`{label}` is not in the SVG text:\n{text}"
        );
    }
    assert!(
        !text.contains("excitation."),
        "a raw key in the labels:\n{text}"
    );
    assert!(out.join("spectrum.png").is_file());
}

#[test]
fn a_one_axis_sweep_writes_its_line_plot() {
    let out = tmp_path("line");
    sweep(&out, &["excitation.amplitude=1:20:12"]);
    for f in ["line.png", "line.svg"] {
        assert!(out.join(f).is_file(), "{f} is missing");
    }
    let text = svg_text(&out.join("line.svg"));
    for label in ["a_p/(g tan α)", "max |θ|/α", "fraction overturned"] {
        assert!(
            text.contains(label),
            "`{label}` is not in the SVG text:\n{text}"
        );
    }
    // The fraction printed is the cells' own: from cells.csv.
    let csv = std::fs::read_to_string(out.join("cells.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    let over = rows.iter().filter(|r| r.contains(",overturned")).count();
    assert!(
        text.contains(&format!("fraction overturned = {over}/{}", rows.len())),
        "{text}"
    );
}

#[test]
fn the_time_history_is_labelled_in_the_papers_notation() {
    let out = tmp_path("history");
    ok(&bin()
        .arg("run")
        .arg(repo().join("scenes/fig3-vvel.toml"))
        .args(["--set", "output.plots=true", "--out"])
        .arg(&out)
        .output()
        .unwrap());
    let text = svg_text(&out.join("plot.svg"));
    for label in ["θ/α", "u/u_cr", "E/E_ref", "ü_g/(g tan α)", "τ = p t"] {
        assert!(
            text.contains(label),
            "`{label}` is not in the SVG text:\n{text}"
        );
    }
    // The caption explains the marks drawn: impacts, and no overturning arrow (the run stays up).
    assert!(text.contains("Markers on a line"), "{text}");
    assert!(!text.contains("overturns there"), "{text}");
}

/// The orientation (radians, clockwise on the screen) of the pixels of one colour, from their
/// second moments, and their count.
fn orientation(frame: &gif::Frame, palette: &[u8], rgb: [u8; 3]) -> (f64, usize) {
    let w = frame.width as usize;
    let pts: Vec<(f64, f64)> = frame
        .buffer
        .iter()
        .enumerate()
        .filter(|(_, &i)| palette[3 * i as usize..3 * i as usize + 3] == rgb)
        .map(|(k, _)| ((k % w) as f64, (k / w) as f64))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for (x, y) in &pts {
        sxx += (x - mx) * (x - mx);
        syy += (y - my) * (y - my);
        sxy += (x - mx) * (y - my);
    }
    (0.5 * (2.0 * sxy).atan2(sxx - syy), pts.len())
}

#[test]
fn the_animation_has_its_frames_and_size_and_shows_the_simulated_angles() {
    // An overturning run: the last frame lies far from the first.
    let out = tmp_path("animation");
    let o = bin()
        .arg("run")
        .arg(repo().join("scenes/fig10-overturns.toml"))
        .args([
            "--animate",
            "--set",
            "output.plots=false",
            "--set",
            "output.animation_frames=37",
            "--set",
            "output.animation_width=640",
            "--set",
            "output.animation_height=480",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    ok(&o);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("animation: 37 frames of 640 × 480 pixels"),
        "{stdout}"
    );
    // θ/α of the first and last history rows (the first and last frames).
    let csv = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let theta = |line: &str| -> f64 { line.split(',').nth(2).unwrap().parse().unwrap() };
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    let alpha = 0.1; // the scene's α
    let (first, last) = (theta(rows[0]) * alpha, theta(rows[rows.len() - 1]) * alpha);
    assert!(last.abs() > 1.0, "the run overturns: θ = {last}");

    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::Indexed);
    let file = std::fs::File::open(out.join("animation.gif")).unwrap();
    let mut dec = opts.read_info(file).unwrap();
    assert_eq!((dec.width(), dec.height()), (640, 480));
    let palette = dec.global_palette().unwrap().to_vec();
    let mut frames = Vec::new();
    while let Some(f) = dec.read_next_frame().unwrap() {
        assert_eq!((f.width, f.height), (640, 480));
        frames.push(f.clone());
    }
    assert_eq!(frames.len(), 37);
    // The base plate's colour (plot::animation::BASE).
    let base = [51, 51, 153];
    for (frame, theta) in [(&frames[0], first), (&frames[36], last)] {
        let (angle, pixels) = orientation(frame, &palette, base);
        assert!(pixels > 50, "the base plate is drawn ({pixels} pixels)");
        // The plate's axis is known up to a half turn; a few pixels' rounding on a plate of
        // about a hundred pixels gives about 0.03 rad.
        let d = (angle - theta).rem_euclid(std::f64::consts::PI);
        let d = d.min(std::f64::consts::PI - d);
        assert!(
            d < 0.03,
            "drawn {angle:.4} rad, simulated θ = {theta:.4} rad"
        );
    }
}

/// Runs `rocking spectrum` on the Fig-9 scene (`[sweep] reference = "rigid"`) with small axes.
fn fig9(out: &Path, extra: &[&str]) -> std::process::Output {
    let mut c = bin();
    c.arg("spectrum")
        .arg(repo().join("scenes/spectra/fig9.toml"))
        .arg("--quiet")
        .arg("--out")
        .arg(out)
        .args(extra);
    c.output().unwrap()
}

#[test]
fn the_rigid_reference_is_the_rigid_columns_own_spectrum_and_is_drawn() {
    let grid = [
        "--axis",
        "excitation.omega_p_over_p=2:6:4",
        "--axis",
        "excitation.amplitude=2:12:5",
    ];
    // Three axes (boundaries of two structures) with the reference beside them.
    let out = tmp_path("fig9-reference");
    let mut args = vec!["--axis", "structure.omega_n_over_p=2.5,10"];
    args.extend(grid);
    ok(&fig9(&out, &args));
    // The reference's cells are those of the rigid column's own spectrum over the figure's axes.
    let rigid = tmp_path("fig9-rigid");
    let mut args = vec!["--set", "effects.flexibility=false"];
    args.extend(grid);
    ok(&fig9(&rigid, &args));
    let reference = std::fs::read_to_string(out.join("reference.csv")).unwrap();
    assert_eq!(
        reference,
        std::fs::read_to_string(rigid.join("cells.csv")).unwrap(),
        "reference.csv differs from the rigid column's spectrum"
    );
    assert_eq!(reference.lines().count(), 1 + 4 * 5);
    assert!(reference.contains("overturned"), "{reference}");
    let text = svg_text(&out.join("spectrum.svg"));
    assert!(text.contains("rigid column"), "{text}");
    assert!(
        text.contains("ω_n/p = 2.5") && text.contains("ω_n/p = 10"),
        "{text}"
    );
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).unwrap()).unwrap();
    assert_eq!(meta["reference"]["name"], "rigid");
    assert_eq!(meta["reference"]["cells"], 20);
    // The two-axis spectrum of the rigid run (which names the reference too) draws it dashed on
    // its colour map, with a legend entry.
    // (The legend wraps its text over lines: compare with the whitespace normalised.)
    let text = svg_text(&rigid.join("spectrum.svg"));
    let words = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        words.contains("overturned | upright, rigid column"),
        "{text}"
    );
    let svg = std::fs::read_to_string(rigid.join("spectrum.svg")).unwrap();
    assert!(
        svg.matches("stroke=\"#000000\"").count() > 10,
        "no dashes drawn in black"
    );
    // Sharded and merged, the reference is run where the figure is drawn: the same bytes.
    let shards: Vec<PathBuf> = (0..2)
        .map(|k| tmp_path(&format!("fig9-shard{k}")))
        .collect();
    for (k, dir) in shards.iter().enumerate() {
        let shard = format!("{k}/2");
        let mut args = vec![
            "--axis",
            "structure.omega_n_over_p=2.5,10",
            "--shard",
            &shard,
        ];
        args.extend(grid);
        ok(&fig9(dir, &args));
    }
    let merged = tmp_path("fig9-merged");
    ok(&bin()
        .arg("merge")
        .arg(&merged)
        .args(&shards)
        .output()
        .unwrap());
    for f in [
        "cells.csv",
        "reference.csv",
        "meta.json",
        "spectrum.svg",
        "spectrum.png",
        "spectrum.pdf",
    ] {
        assert_eq!(
            std::fs::read(merged.join(f)).unwrap(),
            std::fs::read(out.join(f)).unwrap(),
            "merged {f} differs"
        );
    }
    for d in [out, rigid, merged].into_iter().chain(shards) {
        let _ = std::fs::remove_dir_all(d);
    }
}

#[test]
fn an_unknown_reference_is_refused_naming_the_key_and_the_choices() {
    let out = tmp_path("fig9-bad-reference");
    let o = fig9(&out, &["--set", "sweep.reference=\"elastic\""]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("fig9.toml") && err.contains("sweep.reference") && err.contains("\"rigid\""),
        "{err}"
    );
    assert!(!out.exists(), "nothing is written for a refused scene");
}

/// Every tick label and number of an SVG: none is a negative zero or ends in a needless ".0",
/// and no label shows a literal underscore (subscripts are drawn as such: read without a mark).
fn assert_clean_text(name: &str, svg: &str) {
    for t in texts_marking(svg, "") {
        let t = t.trim();
        assert!(
            !matches!(t, "-0" | "\u{2212}0" | "-0.0" | "\u{2212}0.0"),
            "{name}: a negative zero tick `{t}`"
        );
        let is_number = t
            .chars()
            .all(|c| c.is_ascii_digit() || c == '.' || c == '-' || c == '\u{2212}');
        assert!(
            !(is_number && t.contains('.') && t.ends_with('0')),
            "{name}: a needless trailing zero in `{t}`"
        );
        assert!(!t.contains('_'), "{name}: a literal underscore in `{t}`");
    }
}

/// `rocking figure` on every figure file of scenes/paper, on small grids (the test CI runs).
#[test]
fn every_paper_figure_is_drawn_and_shows_what_it_compares() {
    let out = tmp_path("paper");
    let cache = tmp_path("paper-cache");
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo().join("scenes/paper"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    // Figs 3-10, Figs 6-8 one file per slenderness α (issue 46), and Fig. 10's zoom.
    assert_eq!(files.len(), 12, "Figs 3-10: {files:?}");
    ok(&bin()
        .arg("figure")
        .args(&files)
        .args(["--cells", "6", "--quiet", "--out"])
        .arg(&out)
        .arg("--cache")
        .arg(&cache)
        .output()
        .unwrap());
    for f in &files {
        let stem = f.file_stem().unwrap().to_string_lossy();
        for ext in ["svg", "png", "pdf"] {
            assert!(out.join(format!("{stem}.{ext}")).is_file(), "{stem}.{ext}");
        }
        let svg = std::fs::read_to_string(out.join(format!("{stem}.svg"))).unwrap();
        assert_clean_text(&stem, &svg);
        assert!(std::fs::read(out.join(format!("{stem}.pdf")))
            .unwrap()
            .starts_with(b"%PDF"));
    }
    let text = |stem: &str| {
        let t = svg_text(&out.join(format!("{stem}.svg")));
        t.split_whitespace().collect::<Vec<_>>().join(" ")
    };
    // Fig. 3: one figure overlays both impact models, each in its own line colour.
    let fig3 = std::fs::read_to_string(out.join("fig3.svg")).unwrap();
    let t3 = text("fig3");
    for label in [
        "VVEL",
        "ADJex",
        "θ/α",
        "u/u_cr",
        "E_kin/E_ref",
        "ü_g/(g tan α)",
    ] {
        assert!(t3.contains(label), "fig3: `{label}` missing: {t3}");
    }
    // Both runs are drawn in the three overlaid panels: each impact of VVEL is marked in each of
    // them with its marker in its colour (circles), plus one in the legend; ADJex's, more than
    // 12, are ticks along each panel's bottom edge (a rug) in its colour, and its square is only
    // in the legend.
    let impacts = |scene: &str| {
        let o = bin()
            .arg("run")
            .arg(repo().join(scene))
            .args(["--json", "--out"])
            .arg(out.join(scene.replace('/', "-")))
            .output()
            .unwrap();
        ok(&o);
        let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        summary["impacts"].as_u64().unwrap() as usize
    };
    let marks = |element: &str, colour: &str| {
        fig3.split(element)
            .skip(1)
            .filter(|e| {
                e.split('>')
                    .next()
                    .unwrap()
                    .contains(&format!("fill=\"{colour}\""))
            })
            .count()
    };
    let (vvel, adjex) = (
        impacts("scenes/fig3-vvel.toml"),
        impacts("scenes/fig3-adjex.toml"),
    );
    assert!(
        vvel > 0 && vvel <= 12 && adjex > 12,
        "{vvel} and {adjex} impacts"
    );
    assert_eq!(
        marks("<circle", "#1B80C6"),
        1 + 3 * vvel,
        "fig3: VVEL's impacts"
    );
    assert_eq!(marks("<rect", "#AC2000"), 1, "fig3: ADJex's square");
    // A rug tick: a thin vertical two-point polyline in ADJex's colour (one per pixel column: two
    // impacts of ADJex's double impact may share one).
    let ticks = fig3
        .split("<polyline")
        .skip(1)
        .map(|e| e.split('>').next().unwrap())
        .filter(|e| e.contains("stroke=\"#AC2000\" stroke-width=\"1\""))
        .filter(|e| {
            let points: Vec<&str> = e
                .split("points=\"")
                .nth(1)
                .map_or("", |p| p.split('"').next().unwrap())
                .split_whitespace()
                .collect();
            points.len() == 2 && points[0].split(',').next() == points[1].split(',').next()
        })
        .count();
    assert!(
        (3 * (adjex - 3)..=3 * adjex).contains(&ticks),
        "fig3: {ticks} rug ticks for ADJex's {adjex} impacts in 3 panels"
    );
    // Figs 6-8, one file per slenderness: five panels (four stiffnesses and the rigid column) on
    // one colour scale, θ_cr/α marked once (one α per file).
    for stem in FIGS_6_TO_8 {
        let t = text(stem);
        assert_eq!(
            t.matches("survived: max |θ|/α").count(),
            1,
            "{stem}: one colour bar"
        );
        assert_eq!(t.matches("θ_cr/α =").count(), 1, "{stem}: θ_cr/α mark: {t}");
        // Five panels (letters (a)-(e)) in rows of three; the shared x label once per column.
        assert!(
            t.contains("(e)") && !t.contains("(f)"),
            "{stem}: five panels"
        );
        assert_eq!(
            t.matches("ω_p/p").count(),
            3,
            "{stem}: one x label per column"
        );
    }
    // Fig. 9: a line per structure and the rigid column, with the method stated.
    let t9 = text("fig9");
    for label in ["ω_n/p = 2.5", "ω_n/p = 20", "rigid column", "bisection"] {
        assert!(t9.contains(label), "fig9: `{label}` missing: {t9}");
    }
    // Fig. 10: three runs and the pulses in black.
    let t10 = text("fig10");
    for label in ["stiff", "14.5", "= 15", "/(u_cr ω_n)"] {
        assert!(t10.contains(label), "fig10: `{label}` missing: {t10}");
    }
    // Drawn again from the cache (another process): the same bytes.
    let again = tmp_path("paper-again");
    ok(&bin()
        .arg("figure")
        .args(&files)
        .args(["--cells", "6", "--quiet", "--out"])
        .arg(&again)
        .arg("--cache")
        .arg(&cache)
        .output()
        .unwrap());
    for f in &files {
        let stem = f.file_stem().unwrap().to_string_lossy();
        for ext in ["svg", "png", "pdf"] {
            let name = format!("{stem}.{ext}");
            assert!(
                std::fs::read(out.join(&name)).unwrap()
                    == std::fs::read(again.join(&name)).unwrap(),
                "{name} differs when drawn again"
            );
        }
    }
    for d in [out, cache, again] {
        let _ = std::fs::remove_dir_all(d);
    }
}

#[test]
fn a_bad_figure_file_is_refused_naming_the_file_and_the_field() {
    let dir = tmp_path("bad-figure");
    std::fs::create_dir_all(&dir).unwrap();
    let base = std::fs::read_to_string(repo().join("scenes/paper/fig3.toml"))
        .unwrap()
        .replace("../fig3", &format!("{}/scenes/fig3", repo().display()));
    for (edit, field) in [
        (base.replace("columns = 2", "columns = 20"), "columns"),
        (
            base.replace("style = \"red\"", "style = \"mauve\""),
            "runs.adjex.style",
        ),
        (
            base.replace("runs = [\"vvel\"]", "runs = [\"nope\"]"),
            "panels[3].runs",
        ),
        (base.replace("columns = 2", "colums = 2"), "colums"),
        (
            base.replace("\"u_over_ucr\"", "\"u_over_u\""),
            "panels[1].quantity",
        ),
        // A control character (issue 47, item 15): it failed when drawn, exit 1.
        (base.replacen("title = \"", "title = \"\\u0007", 1), "title"),
    ] {
        let file = dir.join("bad.toml");
        std::fs::write(&file, edit).unwrap();
        let o = bin()
            .arg("figure")
            .arg(&file)
            .arg("--out")
            .arg(dir.join("out"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{field}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("bad.toml") && err.contains(field),
            "{field}: {err}"
        );
        assert!(!dir.join("out/bad.svg").exists());
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// Two figure files of one name into one --out (issue 47, item 7: both were drawn as
/// `fig.*`, the first lost, and both listed): refused before anything is drawn, naming both.
#[test]
fn two_figure_files_of_one_name_are_refused_before_drawing() {
    let dir = tmp_path("same-name");
    for sub in ["a", "b"] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
        std::fs::copy(
            repo().join("scenes/paper/fig3.toml"),
            dir.join(sub).join("fig.toml"),
        )
        .unwrap();
    }
    let o = bin()
        .arg("figure")
        .arg(dir.join("a/fig.toml"))
        .arg(dir.join("b/fig.toml"))
        .args(["--cells", "2", "--quiet", "--out"])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("a/fig.toml") && err.contains("b/fig.toml") && err.contains("fig.svg"),
        "{err}"
    );
    assert!(!dir.join("out").exists(), "nothing drawn");
    let _ = std::fs::remove_dir_all(dir);
}
