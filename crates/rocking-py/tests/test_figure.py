"""`rocking.figure` against `rocking figure`: the same figure file gives the same bytes.

The command is found as in test_rocking.py (ROCKING_CLI, else target/debug/rocking).
"""

import os
import subprocess
from pathlib import Path

import pytest

import rocking

REPO = Path(__file__).resolve().parents[3]
CLI = os.environ.get("ROCKING_CLI", str(REPO / "target" / "debug" / "rocking"))
PAPER = REPO / "scenes" / "paper"


@pytest.mark.parametrize(
    "name, cells",
    [("fig3", None), ("fig8-alpha01", 4)],
    ids=["runs", "spectra-4-cells"],
)
def test_a_figure_from_python_is_the_command_s_figure_byte_for_byte(tmp_path, name, cells):
    figure_file = PAPER / f"{name}.toml"
    out = tmp_path / "cli"
    args = [CLI, "figure", str(figure_file), "--out", str(out), "--cache", str(tmp_path / "c1")]
    if cells is not None:
        args += ["--cells", str(cells)]
    done = subprocess.run(args, capture_output=True, text=True, cwd=REPO)
    assert done.returncode == 0, done.stderr

    files = rocking.figure(figure_file, cache=tmp_path / "c2", cells=cells)
    assert sorted(files) == ["caption.md", "pdf", "png", "svg"]
    for ext, data in files.items():
        written = (out / f"{name}.{ext}").read_bytes()
        assert data == written, f"{name}.{ext}: {len(data)} bytes from Python, {len(written)} from the command"
    assert files["svg"].startswith(b"<svg") and files["png"][:4] == b"\x89PNG"
    assert files["pdf"][:5] == b"%PDF-"


def test_a_draft_keeps_its_caption_inside_and_writes_no_caption_file(tmp_path):
    files = rocking.figure(PAPER / "fig3.toml", cache=tmp_path / "c", draft=True)
    assert sorted(files) == ["pdf", "png", "svg"]


def test_a_figure_file_that_does_not_exist_is_a_value_error_naming_it(tmp_path):
    with pytest.raises(ValueError, match="nope.toml"):
        rocking.figure(tmp_path / "nope.toml", cache=tmp_path / "c")
