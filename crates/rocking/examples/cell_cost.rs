//! Cost of spectrum cells: a grid of sine pulses on the Fig-8 structure (γ_mb = γ_mc = 2,
//! ω_n/p = 5, α = 0.1, uplifted ζ = 0.01), τ up to the pulse plus 20, at a preset.
//!
//! `cargo run --release -p rocking --example cell_cost -- [n] [preset]`

use std::time::Instant;

use rocking::{simulate, DampingConvention, Dimensionless, Effects, Options, Preset, Structure};
use rocking_motion::SinePulse;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20);
    let preset = match args.get(2).map(String::as_str) {
        Some("fast") => Preset::Fast,
        Some("accurate") => Preset::Accurate,
        Some("reference") => Preset::Reference,
        _ => Preset::Default,
    };
    let d = Dimensionless {
        omega_n_over_p: 5.0,
        alpha: 0.1,
        gamma_mc: 2.0,
        gamma_mb: 2.0,
        gamma_ib: 1.0,
        zeta: 0.01,
        damping: DampingConvention::Uplifted,
    };
    let structure = Structure::from_dimensionless(&d, None).unwrap();
    let start = Instant::now();
    let (mut rhs, mut overturned, mut impacts) = (0u64, 0, 0u64);
    for i in 0..n {
        for j in 0..n {
            let wp = 1.0 + 9.0 * i as f64 / (n - 1) as f64;
            let amp = 1.0 + 19.0 * j as f64 / (n - 1) as f64;
            let pulse = SinePulse::new(amp * d.alpha.tan(), wp);
            let opts = Options {
                accuracy: preset.accuracy(),
                t_end: 2.0 * std::f64::consts::PI / wp + 20.0,
                ..Options::default()
            };
            let run = simulate(&structure, &pulse, &Effects::default(), &opts).unwrap();
            rhs += run.summary.solver_stats.rhs_evaluations;
            overturned += run.summary.overturned as usize;
            impacts += run.summary.impacts;
        }
    }
    let cells = (n * n) as f64;
    let el = start.elapsed().as_secs_f64();
    println!("{n}x{n} cells at {preset:?}: {:.3} s, {:.3} ms/cell, {:.0} RHS/cell, {:.1} ns/RHS (all-in), overturned {overturned}, impacts/cell {:.1}",
        el, 1e3 * el / cells, rhs as f64 / cells, 1e9 * el / rhs as f64, impacts as f64 / cells);
}
