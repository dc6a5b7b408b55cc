"""Python overhead per simulation against the Rust library, on the Fig. 3 scene.

    cargo run --release -p rocking-py --example overhead -- scenes/fig3-vvel.toml 2000
    python crates/rocking-py/bench/overhead.py scenes/fig3-vvel.toml 2000

Both load the scene once and then time N runs of simulate + summary (``Scene.run().summary``
here; ``report::simulate`` + ``summary_json`` there). Prints the mean time per run.
"""

import sys
import time

import rocking

path = sys.argv[1] if len(sys.argv) > 1 else "scenes/fig3-vvel.toml"
n = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
scene = rocking.load_scene(path)
for _ in range(n // 10):
    scene.run().summary  # warm-up
start = time.perf_counter()
checksum = 0.0
for _ in range(n):
    checksum += scene.run().summary.max_theta_over_alpha
per_run = (time.perf_counter() - start) / n
print(f"python: {per_run * 1e6:.1f} us per run ({n} runs of {path}; checksum {checksum:.3f})")
