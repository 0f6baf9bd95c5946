"""The package's static checks, run by the test command as CI runs it: mypy and ruff, clean."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).parents[1]


def _run(*command: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", *command], cwd=ROOT, capture_output=True, text=True, timeout=600
    )


def test_mypy_finds_no_type_errors_in_the_package(tmp_path):
    result = _run("mypy", "--cache-dir", str(tmp_path / "mypy"))
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Success: no issues found" in result.stdout


def test_ruff_finds_nothing_to_fix_or_reformat():
    paths = ["pvshadows", "tests", "examples", "docs"]
    lint = _run("ruff", "check", *paths)
    assert lint.returncode == 0, lint.stdout + lint.stderr
    layout = _run("ruff", "format", "--check", *paths)
    assert layout.returncode == 0, layout.stdout + layout.stderr
