//! A spectrum's cost split into steps x cost per step (issue 45): plans the spectrum exactly as
//! `rocking spectrum` does (`Plan::spectrum`, the same cells, summary-only runs that stop when
//! the class is known), runs its cells one after the other on one thread, and prints the cells,
//! the solver's accepted and rejected steps summed over them (the runs' own counters), the CPU
//! time of the loop and the time per step.
//!
//! `cargo run --release -p rocking-study --example spectrum_steps -- SCENE [--set K=V]... [--axis SPEC]...`
//! (the scene's `[sweep] axes` without --axis; e.g. scenes/spectra/fig8.toml --set
//! structure.model=cantilever_modes3). Under callgrind (`--toggle-collect='*driver::simulate*'`)
//! it gives instructions per step of a whole spectrum.

use std::path::PathBuf;
use std::time::Instant;

use rocking_study::plan::{Base, Plan};

fn main() {
    let mut args = std::env::args().skip(1);
    let scene = PathBuf::from(
        args.next()
            .expect("usage: spectrum_steps SCENE [--set K=V]... [--axis SPEC]..."),
    );
    let (mut sets, mut axes) = (Vec::new(), Vec::new());
    while let Some(flag) = args.next() {
        let value = args
            .next()
            .unwrap_or_else(|| panic!("{flag} needs a value"));
        match flag.as_str() {
            "--set" => sets.push(value),
            "--axis" => axes.push(value),
            other => panic!("unknown flag {other}: give --set or --axis"),
        }
    }
    let base = Base::load(&scene, &sets).unwrap_or_else(|e| panic!("{e}"));
    let plan = Plan::spectrum(base, &axes).unwrap_or_else(|e| panic!("{e}"));
    let cells = plan.sweep.len();
    let (mut steps, mut rejected, mut failed) = (0u64, 0u64, 0usize);
    let start = Instant::now();
    for i in 0..cells {
        match plan.run_cell(&plan.sweep.values(i)) {
            Ok(run) => {
                steps += run.summary.solver_stats.steps;
                rejected += run.summary.solver_stats.rejected_steps;
            }
            Err(_) => failed += 1,
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "{} {sets:?}: {cells} cells ({failed} without a result), {steps} steps ({rejected} \
         rejected), {:.1} steps per cell, {seconds:.3} s, {:.3} µs per step",
        scene.display(),
        steps as f64 / cells as f64,
        1e6 * seconds / steps.max(1) as f64
    );
}
