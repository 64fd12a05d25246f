"""Shared helpers: the `xper` command the Python runs are compared with, and shipped scenes
cut to a few steps."""

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def xper_command():
    """The `xper` binary: $XPER_BIN, else the workspace's debug or release build."""
    candidates = [os.environ.get("XPER_BIN")] + [
        str(REPO / "target" / profile / "xper") for profile in ("debug", "release")
    ]
    for c in candidates:
        if c and os.path.isfile(c):
            return c
    pytest.fail("no xper binary: build it with `cargo build -p xper-cli` or set XPER_BIN")


def cut_scene(name, tmp_path, **edits):
    """Copies scenes/<name>/scene.toml into tmp_path with `key = value` lines replaced."""
    text = (REPO / "scenes" / name / "scene.toml").read_text()
    for key, value in edits.items():
        text, count = re.subn(rf"(?m)^{key}\s*=.*$", f"{key} = {value}", text)
        assert count == 1, f"{name}: no single line {key} = ..."
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return path


# The drop scene (scenes/drop): one disk above a wall.
G = 9.81        # m/s^2, the scenes' gravity
DT = 1e-3       # s, drop's time step
RHO = 1000.0    # kg/m^3, drop's disk
R = 0.05        # m, drop's disk
Y0 = 0.55       # m, drop's disk centre at rest


def drop(tmp_path, fresh, duration="2.0"):
    """A run of scenes/drop lasting `duration` s (outputs in a fresh directory)."""
    import xper
    return xper.Simulation.from_file(cut_scene("drop", tmp_path, duration=duration),
                                     out=fresh("drop"))


def run_cli(*args, ok=(0,)):
    """`xper ARGS...`; fails the test with its output when its exit code is not in `ok`."""
    done = subprocess.run([xper_command(), *map(str, args)], capture_output=True, text=True,
                          timeout=600)
    assert done.returncode in ok, f"xper {' '.join(map(str, args))}:\n{done.stderr}"
    return done


def without_timing(csv_text):
    """A table's text without its wall-clock columns (names ending in _time but `time`, or
    in _seconds): what two runs of the same scene agree on byte for byte."""
    lines = csv_text.splitlines()
    header = lines[0].split(",")
    keep = [not ((c.endswith("_time") and c != "time") or c.endswith("_seconds")) for c in header]
    return "\n".join(",".join(f for f, k in zip(line.split(","), keep) if k) for line in lines)


def same_outputs(a, b):
    """Asserts that output directories a and b hold the same series (timing aside), the
    same frames and the same checkpoint, byte for byte."""
    assert without_timing((a / "series.csv").read_text()) == without_timing(
        (b / "series.csv").read_text())
    frames_a = sorted(p.name for p in (a / "frames").iterdir())
    frames_b = sorted(p.name for p in (b / "frames").iterdir())
    assert frames_a == frames_b and frames_a
    for name in frames_a:
        assert (a / "frames" / name).read_bytes() == (b / "frames" / name).read_bytes(), name
    assert (a / "result.pvd").read_bytes() == (b / "result.pvd").read_bytes()
    assert (a / "checkpoint.bin").read_bytes() == (b / "checkpoint.bin").read_bytes()
    if (a / "problems").exists():
        problems = sorted(p.name for p in (a / "problems").iterdir())
        assert problems == sorted(p.name for p in (b / "problems").iterdir()) and problems
        for name in problems:
            assert (a / "problems" / name).read_bytes() == (b / "problems" / name).read_bytes()


@pytest.fixture
def fresh(tmp_path):
    """A new directory under the test's temporary directory."""
    count = [0]

    def make(name="out"):
        count[0] += 1
        path = tmp_path / f"{name}{count[0]}"
        shutil.rmtree(path, ignore_errors=True)
        return path

    return make
