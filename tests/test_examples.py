"""Every gallery script runs off screen and writes its picture."""

import subprocess
import sys
from pathlib import Path

import pytest
import pyvista as pv

EXAMPLES = sorted((Path(__file__).parents[1] / "examples").glob("*.py"))


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_writes_its_picture(script, tmp_path):
    result = subprocess.run(
        [sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True, timeout=600
    )
    assert result.returncode == 0, result.stderr
    pictures = list(tmp_path.glob("*.png"))
    assert pictures, "the example saved no picture"
    for picture in pictures:
        assert pv.read(picture).n_points > 100_000
    assert result.stdout.strip(), "the example printed nothing (what ran, how exact)"
    assert "without shadows" not in result.stderr, result.stderr
