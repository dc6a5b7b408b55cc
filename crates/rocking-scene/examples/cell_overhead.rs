//! Per-cell cost outside the simulation in a spectrum sweep: the time a cell spends setting its
//! axis values on the scene and building the setup (`knob::setup`, as `rocking spectrum` does),
//! against the time of its simulation, on a grid over the scene's two sweep axes.
//!
//! `cargo run --release -p rocking-scene --example cell_overhead -- [SCENE] [n]`
//! (default scenes/spectra/fig8.toml, n = 100: the Fig-8 spectrum's 100 × 100 cells).

use std::path::Path;
use std::time::Instant;

use rocking::History;
use rocking_scene::knob::{self, Knob, KnobValue};
use rocking_scene::scene;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = Path::new(
        args.get(1)
            .map_or("scenes/spectra/fig8.toml", String::as_str),
    );
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100);
    let sc = scene::load(path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let w = Knob::resolve(&sc, "excitation.omega_p_over_p").unwrap();
    let a = Knob::resolve(&sc, "excitation.amplitude").unwrap();
    let (mut t_setup, mut t_sim) = (0.0, 0.0);
    let mut impacts = 0u64;
    for i in 0..n {
        for j in 0..n {
            let t0 = Instant::now();
            let wp = 1.0 + 9.0 * i as f64 / (n - 1) as f64;
            let amp = 1.0 + 19.0 * j as f64 / (n - 1) as f64;
            let cell = [(&w, KnobValue::Number(wp)), (&a, KnobValue::Number(amp))];
            let mut m = knob::setup(&sc, &cell).unwrap();
            m.options.history = History::None;
            m.options.event_log = false;
            m.options.energy = false;
            m.options.stop_when_known = true;
            let t1 = Instant::now();
            let run =
                rocking::simulate(&m.structure, &m.excitation, &m.effects, &m.options).unwrap();
            let t2 = Instant::now();
            impacts += run.summary.impacts;
            t_setup += (t1 - t0).as_secs_f64();
            t_sim += (t2 - t1).as_secs_f64();
        }
    }
    let cells = (n * n) as f64;
    println!(
        "{}: {n}x{n} cells, setup {:.2} µs/cell, simulation {:.1} µs/cell, overhead {:.2} % of a cell (impacts {impacts})",
        path.display(),
        1e6 * t_setup / cells,
        1e6 * t_sim / cells,
        100.0 * t_setup / (t_setup + t_sim)
    );
}
