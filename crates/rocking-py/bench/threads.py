"""Two Python threads, each running a single-threaded spectrum, against the same two spectra
one after the other: with the GIL released the two threads overlap (measured, not asserted).

    python crates/rocking-py/bench/threads.py
"""

import threading
import time

import rocking

SCENE = "scenes/spectra/fig8.toml"
AXES = ["excitation.omega_p_over_p=1:10:40", "excitation.amplitude=1:20:40"]


def one() -> None:
    rocking.spectrum(SCENE, axes=AXES, threads=1)


one()  # warm-up
start = time.perf_counter()
one()
one()
sequential = time.perf_counter() - start
start = time.perf_counter()
threads = [threading.Thread(target=one) for _ in range(2)]
for t in threads:
    t.start()
for t in threads:
    t.join()
parallel = time.perf_counter() - start
print(
    f"2 spectra of 1600 cells, 1 thread each: sequential {sequential:.2f} s, "
    f"two Python threads {parallel:.2f} s (speed-up {sequential / parallel:.2f})"
)
