"""xper from Python: run a scene step by step, read its state as NumPy arrays, change it
between steps.

A :class:`Simulation` is the run ``xper run SCENE --out OUT`` makes, driven by the same
library (the run driver of ``xper-simulation``): the same frames, tables, checkpoints and
summary, bit for bit, whether the steps are taken by the command or from Python.

>>> import xper
>>> sim = xper.Simulation.from_file("scenes/drop", out="out/drop")
>>> sim.run(until=0.5)                       # s
>>> sim.bodies.position                      # (n, 2) in 2D, (n, 3) in 3D, m
>>> x = sim.view("bodies.position")          # the same, read in place: no copy, kept current
>>> sim.finish()["status"]
'stopped'

Errors are :class:`SceneError` (a scene, checkpoint or argument that cannot be run; the
message names the file, the place and the reason) and :class:`RunError` (a failed step, an
output that cannot be written), both :class:`XperError`.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _xper
from ._xper import RunError, SceneError, XperError, __version__
from .problems import CsrMatrix, Problem, SolveResult, read_problem, solve
from .scene import Scene

__all__ = ["Simulation", "Scene", "XperError", "SceneError", "RunError", "__version__", "solve",
           "read_problem", "Problem", "SolveResult", "CsrMatrix"]

PathLike = Union[str, "os.PathLike[str]"]


def _write_atomic(path: str, text: str) -> None:
    """Writes `text` to `path` through a temporary file renamed over it: a crash leaves the
    old file or the new one, never part of one."""
    partial = path + ".partial"
    with open(partial, "w", encoding="utf-8") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(partial, path)


class _Part:
    """The arrays of one part of the state (``bodies``, ``contacts``, ``world``) as
    attributes: ``sim.bodies.velocity`` reads ``bodies.velocity``; assigning a writable one
    writes it into the state for the next step."""

    def __init__(self, sim: "Simulation", part: str) -> None:
        object.__setattr__(self, "_sim", sim)
        object.__setattr__(self, "_part", part)

    def _names(self) -> List[str]:
        prefix = self._part + "."
        return [a["name"][len(prefix):] for a in self._sim.array_info()
                if a["name"].startswith(prefix)]

    def __getattr__(self, name: str) -> np.ndarray:
        if name.startswith("_") or name not in self._names():
            raise AttributeError(f"{self._part} has no array {name!r}; it has: "
                                 f"{', '.join(self._names())}")
        return self._sim.array(f"{self._part}.{name}")

    def __setattr__(self, name: str, values: Any) -> None:
        self._sim.set_array(f"{self._part}.{name}", values)

    def __dir__(self) -> List[str]:
        return self._names()

    def __repr__(self) -> str:
        return f"<xper {self._part}: {', '.join(self._names())}>"


class Simulation:
    """A scene being run, with its outputs in ``out``.

    ``Simulation(scene, out)`` reads the scene file (or ``DIR/scene.toml``), builds its
    simulation and writes the first frame, as ``xper run`` does; with ``resume=True`` it
    continues from the checkpoint in ``out`` instead (one written by ``xper run`` or by
    Python). ``progress=True`` shows the progress bar. ``max_memory`` (bytes) bounds the
    memory estimate ``xper check`` prints; the memory available by default.
    """

    def __init__(self, scene: PathLike, out: PathLike, *, resume: bool = False,
                 progress: bool = False, max_memory: Optional[float] = None) -> None:
        self._sim = _xper.Simulation(os.fspath(scene), os.fspath(out), resume, progress,
                                     max_memory)

    @classmethod
    def from_file(cls, scene: PathLike, out: PathLike, **options: Any) -> "Simulation":
        """The run of the scene file ``scene`` (or ``scene/scene.toml``)."""
        return cls(scene, out, **options)

    @classmethod
    def from_toml(cls, text: str, out: PathLike, **options: Any) -> "Simulation":
        """The run of a scene given as TOML text. The text is saved as ``out/scene.toml``
        (relative paths in it, such as a mesh file, are taken from ``out``), so that
        ``xper run out/scene.toml --out out --resume`` continues it."""
        os.makedirs(out, exist_ok=True)
        path = os.path.join(os.fspath(out), "scene.toml")
        _write_atomic(path, text)
        return cls(path, out, **options)

    @classmethod
    def from_scene(cls, scene: "Scene", out: PathLike, **options: Any) -> "Simulation":
        """The run of a scene built with :class:`xper.Scene` (saved as ``out/scene.toml``)."""
        return cls.from_toml(scene.to_toml(), out, **options)

    # Stepping.

    def step(self, n: int = 1) -> None:
        """Advances ``n`` steps, each followed by the frames and checkpoints the scene's
        ``[output]`` asks for. Reaching the scene's end finishes the run; a failed step
        finishes it and raises :class:`RunError`."""
        if int(n) != n or n < 0:
            raise SceneError(f"step: n must be a whole number >= 0, not {n!r}")
        self._sim.step(int(n))

    def run(self, until: Optional[float] = None, every: int = 1,
            callback: Optional[Callable[["Simulation"], Any]] = None) -> None:
        """Steps until the simulated time reaches ``until`` (s; the scene's end when
        ``None``), calling ``callback(sim)`` after every ``every``-th step. A callback may
        read and set the state; an exception it raises stops the loop and propagates."""
        if int(every) != every or every < 1:
            raise SceneError(f"run: every must be a whole number >= 1, not {every!r}")
        while not self.is_finished:
            if until is not None and self.time >= until - 1e-9 * abs(until):
                break
            self._sim.step(1)
            if callback is not None and self.step_index % every == 0:
                callback(self)

    def finish(self) -> Dict[str, Any]:
        """Ends the run now: the last checkpoint, ``summary.json`` and the plots (status
        ``completed`` at the scene's end, ``stopped`` before it). Returns the summary."""
        return self._sim.finish()

    def write_frame(self) -> None:
        """Writes a frame of the current state now (``frames/``, listed in ``result.pvd``)."""
        self._sim.write_frame()

    def write_checkpoint(self) -> None:
        """Writes the tables and ``checkpoint.bin`` now; a resume continues from here."""
        self._sim.write_checkpoint()

    def save(self) -> str:
        """Saves the run as it stands in its output directory (tables, then
        ``checkpoint.bin``, as ``xper run`` writes them) and returns the directory, which
        :meth:`load` or ``xper run SCENE --out DIR --resume`` continue from."""
        self._sim.write_checkpoint()
        return self.out

    @classmethod
    def load(cls, out: PathLike, scene: Optional[PathLike] = None,
             **options: Any) -> "Simulation":
        """Continues the run saved in the output directory ``out`` (by :meth:`save`, a
        scheduled checkpoint or ``xper run``). ``scene``: the scene file it was run from;
        when ``None``, ``out/scene.toml``, written first from the text the checkpoint keeps
        if it is not there (relative paths in it are then taken from ``out``)."""
        if scene is None:
            scene = os.path.join(os.fspath(out), "scene.toml")
            if not os.path.exists(scene):
                _write_atomic(scene, _xper.checkpoint_scene(os.fspath(out)))
        return cls(scene, out, resume=True, **options)

    def __enter__(self) -> "Simulation":
        return self

    def __exit__(self, *exc: Any) -> None:
        if not self.is_finished:
            self.finish()

    # State.

    @property
    def time(self) -> float:
        """Simulated time (s)."""
        return self._sim.time

    @property
    def step_index(self) -> int:
        """Steps done."""
        return self._sim.step_index

    @property
    def steps(self) -> int:
        """Steps the scene asks for."""
        return self._sim.steps

    @property
    def is_complete(self) -> bool:
        """Whether the scene's end is reached."""
        return self._sim.is_complete

    @property
    def is_finished(self) -> bool:
        """Whether the run is over (its end reached, a step failed or ``finish()``)."""
        return self._sim.is_finished

    @property
    def scene(self) -> str:
        """The scene file."""
        return os.fspath(self._sim.scene)

    @property
    def out(self) -> str:
        """The output directory."""
        return os.fspath(self._sim.out)

    @property
    def summary(self) -> Optional[Dict[str, Any]]:
        """``summary.json`` of the finished run, ``None`` before."""
        return self._sim.summary

    def array_info(self) -> List[Dict[str, Any]]:
        """Every array of the state: ``name``, ``shape`` (``n`` counts bodies or contacts),
        ``dtype``, ``unit``, ``writable``, ``view`` (whether :meth:`view` reads it in place)
        and ``about``."""
        return self._sim.array_info()

    def array(self, name: str) -> np.ndarray:
        """The array ``name`` (``array_info()`` lists them) of the current state: a new,
        read-only array (a copy, which the next steps leave as it is). The attributes of
        ``bodies``, ``contacts``, ``laws`` and ``world`` read it this way."""
        return self._sim.array(name)

    def view(self, name: str) -> np.ndarray:
        """The array ``name`` read in place: a read-only NumPy view of the simulation's
        own memory, no copy, whose values are the current ones after every step and write
        (``np.array(v)`` keeps a snapshot). Offered where the simulation keeps the array as
        contiguous float64 rows: the bodies' ``position``, ``velocity``,
        ``angular_velocity``, ``mass``, and in 2D ``orientation`` (``array_info()``'s
        ``view``); contacts are rebuilt every step and other arrays are computed, so those
        are read with :meth:`array`. A view keeps the simulation alive, and
        :meth:`add_bodies`, which may move the bodies' memory, raises while any view (or an
        array sliced from one) lives."""
        return self._sim.view(name)

    def set_array(self, name: str, values: Any) -> None:
        """Writes ``values`` (the shape ``array(name)`` has) into a writable array; the next
        step starts from them."""
        self._sim.set_array(name, np.ascontiguousarray(values, dtype=np.float64))

    def add_bodies(self, bodies: Sequence[Dict[str, Any]] = (),
                   walls: Sequence[Dict[str, Any]] = (),
                   materials: Sequence[Dict[str, Any]] = ()) -> np.ndarray:
        """Adds bodies between steps: ``bodies`` and ``walls`` are entries as ``[[bodies]]``
        and ``[[walls]]`` of a scene file (``Scene.add`` keywords), ``materials`` the
        ``[[materials]]`` they name. They are read and checked as a scene's (errors name
        ``added bodies``, the line, the field and the reason); their groups must be the
        scene's, whose laws apply. Their energy counts in the budget's initial energy.
        Refused while a :meth:`view` lives. Returns their indices in the bodies' arrays."""
        from .scene import Scene
        dim = self.bodies.position.shape[1]
        s = Scene(name="added", dt=1.0, duration=1.0, **({"dimension": 3} if dim == 3 else {}))
        for m in materials:
            s.add("materials", **m)
        for b in bodies:
            s.add("bodies", **b)
        for w in walls:
            s.add("walls", **w)
        return np.array(self._sim.add_bodies(s.to_toml()), dtype=np.int64)

    @property
    def bodies(self) -> _Part:
        """Bodies' arrays: ``id``, ``group``, ``position``, ``orientation``, ``velocity``,
        ``angular_velocity``, ``radius``, ``mass``, ``imposed_velocity``, ``force``."""
        return _Part(self, "bodies")

    @property
    def contacts(self) -> _Part:
        """Contacts' arrays: ``bodies``, ``point``, ``normal``, ``normal_impulse``,
        ``tangential_impulse``, ``gap``, ``status``."""
        return _Part(self, "contacts")

    @property
    def laws(self) -> _Part:
        """Laws' arrays: ``groups``, ``friction``, ``restitution``."""
        return _Part(self, "laws")

    @property
    def cell(self) -> _Part:
        """The periodic cell's arrays, in a scene with ``[cell]``: ``origin``, ``edges``,
        ``gradient``, ``wraps``."""
        return _Part(self, "cell")

    @property
    def group_names(self) -> List[str]:
        """Group names, in the order ``bodies.group`` and ``laws.groups`` index them."""
        return self._sim.group_names

    @property
    def world(self) -> _Part:
        """The world's arrays: ``gravity``, ``time``."""
        return _Part(self, "world")

    def tables(self) -> Dict[str, Dict[str, np.ndarray]]:
        """Every table of the run (``series.csv``, ...) as NumPy columns."""
        return self._sim.tables()

    @property
    def series(self) -> Dict[str, np.ndarray]:
        """``series.csv`` so far: one NumPy column per name, one row per step."""
        return self._sim.tables()["series.csv"]

    @property
    def report(self) -> Dict[str, float]:
        """The last step's row of ``series.csv`` (sweeps, residual, energies, ...), empty
        before the first step."""
        return self._sim.report()

    def __repr__(self) -> str:
        return (f"<xper.Simulation {self.scene}: step {self.step_index} of {self.steps}, "
                f"t = {self.time:.6g} s, outputs in {self.out}>")
