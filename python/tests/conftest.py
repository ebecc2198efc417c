"""Shared fixtures: where the built CLI, the repository and OpenCV's sample data are."""

import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("NEOPIPE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BUILD_DIR = pathlib.Path(os.environ.get("NEOPIPE_BUILD_DIR", SOURCE_DIR / "build"))
CLI = pathlib.Path(os.environ.get("NEOPIPE_CLI", BUILD_DIR / "apps" / "neopipe"))
OPENCV_DATA = pathlib.Path("/usr/share/doc/opencv-doc/examples/data")


@pytest.fixture(scope="session")
def cli():
    """Runs the built `neopipe` program: cli(*args) -> CompletedProcess (text)."""
    if not CLI.exists():
        pytest.skip(f"{CLI}: the neopipe program is not built")

    def run(*args, check=True):
        return subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True, check=check)

    return run


@pytest.fixture(scope="session")
def opencv_data():
    if not OPENCV_DATA.is_dir():
        pytest.skip(f"{OPENCV_DATA}: install opencv-doc for OpenCV's sample images")
    return OPENCV_DATA


@pytest.fixture(scope="session")
def examples():
    return SOURCE_DIR / "examples"


def cli_error(completed, command):
    """The message of the CLI's one error line, "neopipe COMMAND: error: MESSAGE"."""
    prefix = f"neopipe {command}: error: "
    lines = [l for l in completed.stderr.splitlines() if l.startswith(prefix)]
    assert lines, completed.stderr
    return lines[-1][len(prefix):]
