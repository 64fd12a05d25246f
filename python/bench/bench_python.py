"""Benchmarks of the Python module (figures, not tests): what stepping from Python costs
against `xper run`, and how long reading a million bodies' positions takes (a copy, and a view
in place). Saves bench-results/python.json; `xper bench --report-only` puts it in BENCHMARKS.md.

Run from the repository's root, with the module installed and the release binary built
(`cargo build --release -p xper-cli`):

    python python/bench/bench_python.py [--rounds 2] [--steps 1500]
"""

import argparse
import json
import os
import platform
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
import xper

ROOT = Path(__file__).resolve().parents[2]


def machine():
    cpu = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores, {platform.system()} (Python {platform.python_version()})"


def cut(scene, steps, tmp):
    text = (ROOT / "scenes" / scene / "scene.toml").read_text()
    lines = [ln for ln in text.splitlines()
             if not ln.startswith(("steps", "duration", "dump_problems"))]
    at = lines.index("[scene]") + 1
    lines.insert(at, f"steps = {steps}")
    path = Path(tmp) / f"{scene}.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def cli_run(xper_bin, scene, out):
    start = time.perf_counter()
    subprocess.run([xper_bin, "run", str(scene), "--out", str(out), "--quiet"], check=True)
    wall = time.perf_counter() - start
    stepping = json.loads((out / "summary.json").read_text())["wall_time_s"]
    return wall, stepping


def python_run(scene, out, steps):
    start = time.perf_counter()
    sim = xper.Simulation.from_file(scene, out=out)
    for _ in range(steps):
        sim.step(1)
    summary = sim.finish()
    return time.perf_counter() - start, summary["wall_time_s"]


def reading(scene_name, repeats):
    """Seconds per read of the positions as a copy (`sim.bodies.position`) and as a view in
    place (`sim.view`), alternated."""
    with tempfile.TemporaryDirectory() as tmp:
        sim = xper.Simulation.from_file(cut(scene_name, 1, tmp), out=Path(tmp) / "out")
        n = len(sim.bodies.id)
        copies, views = [], []
        for _ in range(repeats):
            start = time.perf_counter()
            p = sim.bodies.position
            copies.append(time.perf_counter() - start)
            start = time.perf_counter()
            v = sim.view("bodies.position")
            views.append(time.perf_counter() - start)
            assert np.array_equal(p, v)
            del v
        assert p.shape == (n, 2)
        sim.finish()
    return n, copies, views


def call_cost(calls):
    """Seconds per call of `step(0)` (the call into the module, its checks, no step) and
    of reading `time`: what a script pays per call beyond the work asked."""
    with tempfile.TemporaryDirectory() as tmp:
        sim = xper.Simulation.from_file(ROOT / "scenes" / "drop", out=Path(tmp) / "out")
        start = time.perf_counter()
        for _ in range(calls):
            sim.step(0)
        step0 = (time.perf_counter() - start) / calls
        start = time.perf_counter()
        for _ in range(calls):
            sim.time
        read = (time.perf_counter() - start) / calls
        sim.finish()
    return step0, read


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--steps", type=int, default=1500)
    ap.add_argument("--scene", default="box10k")
    ap.add_argument("--million", default="box1m", help="the scene of a million bodies")
    ap.add_argument("--xper", default=str(ROOT / "target" / "release" / "xper"))
    ap.add_argument("--json", default=str(ROOT / "bench-results" / "python.json"))
    ap.add_argument("--keep-runs", action="store_true",
                    help="keep the whole runs of the existing JSON; measure the rest again")
    a = ap.parse_args()
    rows = []
    if a.keep_runs:
        rows = json.loads(Path(a.json).read_text())["runs"]
        a.rounds = 0
    with tempfile.TemporaryDirectory() as tmp:
        scene = cut(a.scene, a.steps, tmp)
        for r in range(a.rounds):
            # Alternated in one sitting: the command, then Python, each round.
            for how in ("cli", "python"):
                out = Path(tmp) / f"{how}{r}"
                shutil.rmtree(out, ignore_errors=True)
                if how == "cli":
                    wall, stepping = cli_run(a.xper, scene, out)
                else:
                    wall, stepping = python_run(scene, out, a.steps)
                rows.append({"round": r, "how": how, "wall_s": wall, "stepping_s": stepping})
                print(f"round {r}: {how:6} {wall:8.2f} s in all, {stepping:8.2f} s in the steps "
                      f"(summary.json)")
    cli = [x for x in rows if x["how"] == "cli"]
    py = [x for x in rows if x["how"] == "python"]
    overhead = float(np.mean([p["wall_s"] / c["wall_s"] - 1 for c, p in zip(cli, py)]))
    print(f"Python's overhead over `xper run` on {a.scene} ({a.steps} calls of step(1)): "
          f"{100 * overhead:+.2f} % (mean of {len(cli)} alternated pairs, whole runs)")
    step0, read = call_cost(100_000)
    print(f"a call of step(0): {1e6 * step0:.2f} us; reading sim.time: {1e6 * read:.2f} us; "
          f"{a.steps} calls of step(1) pay {1e3 * a.steps * step0:.2f} ms for the calls")
    n, times, views = reading(a.million, 20)
    median_ms = 1e3 * float(np.median(times))
    view_ms = 1e3 * float(np.median(views))
    print(f"reading the positions of {n:,} bodies: median {median_ms:.2f} ms over 20 reads "
          f"(min {1e3 * min(times):.2f}, max {1e3 * max(times):.2f}); in place: median "
          f"{1e3 * view_ms:.1f} us")
    result = {
        "machine": machine(),
        "scene": a.scene,
        "steps": a.steps,
        "runs": rows,
        "overhead": overhead,
        "call_seconds": step0,
        "time_read_seconds": read,
        "reading": {"scene": a.million, "bodies": n, "seconds": times,
                    "median_ms": median_ms, "view_seconds": views, "view_median_ms": view_ms},
    }
    path = Path(a.json)
    partial = path.with_suffix(".json.partial")
    partial.write_text(json.dumps(result, indent=1) + "\n")
    os.replace(partial, path)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
