#!/usr/bin/env bash
# The Python package (crates/rocking-py): build the abi3 wheel with a pinned maturin, install it
# into a NEW virtual environment (so nothing can come from the development tree), run pytest
# against the command's outputs and execute the example notebook headless.
#
# `--prepare` only creates the two environments (maturin; the test dependencies, without the
# wheel): .ci/run starts it in the background at its beginning, so the downloads (about 2 min,
# hardly any CPU) overlap the Rust build. Without it, this script prepares them itself.
set -euo pipefail
cd "$(dirname "$0")/.."

PY="${PYTHON:-python3}"
ROOT="$PWD/target/python-ci"
PREPARED="$ROOT/prepared"

prepare() {
    rm -rf "$ROOT"
    mkdir -p "$ROOT/wheels"
    echo "-- build venv with maturin; test venv with the test dependencies"
    "$PY" -m venv "$ROOT/build-venv"
    "$ROOT/build-venv/bin/pip" install --quiet --disable-pip-version-check maturin==1.16.0
    "$PY" -m venv "$ROOT/test-venv"
    "$ROOT/test-venv/bin/pip" install --quiet --disable-pip-version-check \
        pytest==9.2.0 numpy==2.4.6 pandas==3.1.1 matplotlib==3.11.2 \
        nbformat==5.11.1 nbclient==0.11.0 ipykernel==7.4.0
    touch "$PREPARED"
}

if [[ "${1:-}" == "--prepare" ]]; then
    prepare
    exit 0
fi
[[ -f "$PREPARED" ]] || prepare
rm -f "$PREPARED" "$ROOT"/wheels/*

# The wheel's Cargo profile: `release` by default (what users get from pip). .ci/run asks for
# `dev` (opt-level 0, no LTO): about 1 min to build instead of 6 to 8 for the release profile on
# 2 cores, and the tests still compare exactly with the command built at opt-level 3 (Rust
# neither reorders nor contracts floating point, so results do not depend on the opt-level).
# (`test` cannot be used: `cargo rustc --profile test` builds a test harness, not the module.)
PROFILE="${ROCKING_WHEEL_PROFILE:-release}"
echo "-- the wheel (profile $PROFILE)"
"$ROOT/build-venv/bin/maturin" build --profile "$PROFILE" --quiet \
    -m crates/rocking-py/Cargo.toml --out "$ROOT/wheels"
# The command the tests compare with: the one `cargo test --workspace` (the step before this one in
# .ci/run) built for its own tests, in the test profile (opt-level 3; no rebuild here). Rust does
# not reorder floating point, so it prints the release build's numbers; run alone, this builds it.
cargo test --workspace --no-run --quiet
export ROCKING_CLI="$PWD/target/debug/rocking"

echo "-- the wheel into the clean test venv"
"$ROOT/test-venv/bin/pip" install --quiet --disable-pip-version-check "$ROOT"/wheels/rocking-*.whl

echo "-- pytest (from outside the tree: the installed package is tested)"
set +e
TESTS="$PWD/crates/rocking-py/tests"
(cd "$ROOT" && "$ROOT/test-venv/bin/python" -m pytest -q -p no:cacheprovider "$TESTS")
status=$?
set -e
case $status in
  0) ;;
  5) echo "pytest collected no tests: that is a failure here" >&2; exit 1 ;;
  *) exit "$status" ;;
esac

echo "-- the example notebook, executed headless"
MPLBACKEND=Agg "$ROOT/test-venv/bin/python" - crates/rocking-py/examples/rocking.ipynb <<'PYEOF'
import sys
import nbformat
from nbclient import NotebookClient
path = sys.argv[1]
nb = nbformat.read(path, as_version=4)
client = NotebookClient(nb, timeout=600, kernel_name="python3",
                        resources={"metadata": {"path": "."}})
client.execute()
print(f"{path}: {sum(c.cell_type == 'code' for c in nb.cells)} code cells ran")
PYEOF
