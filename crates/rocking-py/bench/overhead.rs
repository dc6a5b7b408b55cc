//! The Rust side of the Python overhead benchmark: the Fig. 3 scene loaded once, then simulated
//! and summarised N times through the same calls as `rocking run --json` and `Scene.run()`
//! (`rocking_study::report::simulate` and `summary_json`). Prints the mean time per run of the
//! fastest of 20 batches (the least disturbed on a shared machine).
//!
//! `cargo run --release -p rocking-py --example overhead -- scenes/fig3-vvel.toml 2000`

use std::path::PathBuf;
use std::time::Instant;

use rocking_scene::{scene, setup};
use rocking_study::report;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = PathBuf::from(args.next().unwrap_or("scenes/fig3-vvel.toml".into()));
    let n: usize = args.next().map_or(Ok(2000), |s| s.parse())?;
    let mut m = setup::build(&scene::load(&path, &[])?)?;
    if m.plots {
        m.options.event_log = true; // as `rocking run` and `Scene.run()` do
    }
    let mut checksum = 0.0;
    for _ in 0..n.div_ceil(10) {
        checksum += report::simulate(&m, &path)?
            .run
            .summary
            .max_theta_over_alpha; // warm-up
    }
    // The best of 20 batches: on a shared machine the minimum is the least disturbed.
    let batch = n.div_ceil(20);
    let mut best = f64::INFINITY;
    for _ in 0..20 {
        let start = Instant::now();
        for _ in 0..batch {
            let report = report::simulate(&m, &path)?;
            let summary = report::summary_json(&m, &path, &[], &report)?.to_string();
            checksum += summary.len() as f64;
        }
        best = best.min(start.elapsed().as_secs_f64() / batch as f64);
    }
    println!(
        "rust: {:.1} us per run (best batch of 20 x {batch} runs of {}; checksum {checksum:.3})",
        best * 1e6,
        path.display()
    );
    Ok(())
}
