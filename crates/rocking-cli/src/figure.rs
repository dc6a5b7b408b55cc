//! `rocking figure FIGURE.toml... [--out DIR]`: the figures of figure files
//! ([`rocking_plot::figure_file`]), drawn into `--out` as one output directory ([`OutDir`]).

use std::collections::BTreeMap;
use std::path::PathBuf;

use crate::error::CliError;
use crate::out_dir::{OutDir, FIGURE_OUT};
use rocking_plot::figure_file::{self, stem};
use rocking_scene::SceneError;

/// Options of the command.
pub struct Options {
    pub out: PathBuf,
    /// The title and caption drawn inside the image (for screens), no caption file.
    pub draft: bool,
    pub cache: PathBuf,
    pub cells: Option<usize>,
    pub quiet: bool,
}

/// `rocking figure`: every figure is drawn into a staging directory that replaces `--out` at
/// the end, under its lock ([`OutDir`]), keeping the figures of other files already there; two
/// files of one name would write the same outputs and are refused before anything is drawn.
pub fn figure(files: &[PathBuf], opts: &Options) -> Result<(), CliError> {
    let mut seen: BTreeMap<String, &PathBuf> = BTreeMap::new();
    for file in files {
        if let Some(first) = seen.insert(stem(file), file) {
            return Err(SceneError::input(format!(
                "{} and {}: both would be drawn as {}/{}.svg (.png, .pdf): draw them into \
                 different --out directories, or rename one",
                first.display(),
                file.display(),
                opts.out.display(),
                stem(file)
            ))
            .into());
        }
    }
    let specs = files
        .iter()
        .map(|f| figure_file::read(f))
        .collect::<Result<Vec<_>, _>>()?;
    let dir = OutDir::begin(&opts.out, FIGURE_OUT)?;
    let mut loader = figure_file::Loader::new(&opts.cache, opts.quiet);
    let mut listed = Vec::new();
    for (file, spec) in files.iter().zip(&specs) {
        let figure = figure_file::draw(file, spec, &mut loader, opts.cells, opts.draft)?;
        let written = figure.write(dir.path(), &stem(file))?;
        listed.push((file, written));
    }
    let listed: Vec<_> = listed
        .into_iter()
        .map(|(f, w)| (f, w.iter().map(|p| dir.final_path(p)).collect::<Vec<_>>()))
        .collect();
    dir.commit()?;
    for (file, written) in listed {
        out!("{}:", file.display());
        for p in written {
            out!("  {}", p.display());
        }
    }
    Ok(())
}
