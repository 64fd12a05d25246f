"""Scenes built in Python: the TOML format of ``xper run``, section by section, with the same
names and the same defaults, and checked by the same reader (a bad value raises
:class:`xper.SceneError` naming the field and the reason).

>>> s = Scene(name="drop", dt=1e-3, duration=1.0, gravity=[0.0, -9.81])
>>> s.section("output", frame_every=10)
>>> s.add("materials", name="water_like", density=1000.0)
>>> s.add("laws", between=["ball", "ground"], kind="signorini_coulomb", friction=0.3)
>>> s.add("bodies", shape="disk", center=[0.0, 0.55], radius=0.05,
...       material="water_like", group="ball")
>>> s.add("walls", from_=[-0.5, 0.0], to=[0.5, 0.0], group="ground")
>>> sim = Simulation.from_scene(s, out="out/drop")

A keyword that Python reserves takes a trailing underscore (``from_`` is ``from``).
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from typing import Any, Dict, List

from . import _xper


def _key(name: str) -> str:
    name = name[:-1] if name.endswith("_") else name
    if name.replace("_", "").replace("-", "").isalnum():
        return name
    return json.dumps(name)


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        text = repr(v)
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if hasattr(v, "tolist"):                       # NumPy arrays and scalars
        return _value(v.tolist())
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(f"a scene value must be a number, string, bool, list or dict, not "
                    f"{type(v).__name__} ({v!r})")


class Scene:
    """A scene file under construction: ``[scene]`` from the keywords given here,
    other tables with :meth:`section`, arrays of tables (``[[bodies]]``, ...) with
    :meth:`add`."""

    def __init__(self, **scene: Any) -> None:
        self._sections: Dict[str, Dict[str, Any]] = {"scene": dict(scene)}
        self._arrays: Dict[str, List[Dict[str, Any]]] = {}

    def section(self, name: str, /, **fields: Any) -> "Scene":
        """Sets fields of the table ``[name]`` (``solver``, ``output``, ``fluid``, ``mesh``,
        ...); returns the scene."""
        self._sections.setdefault(name, {}).update(fields)
        return self

    def add(self, name: str, /, **fields: Any) -> "Scene":
        """Appends one ``[[name]]`` entry (``materials``, ``laws``, ``bodies``, ``walls``,
        ``generators``, ...); returns the scene."""
        self._arrays.setdefault(name, []).append(dict(fields))
        return self

    def to_toml(self) -> str:
        """The scene file's text."""
        out = ["# Written by xper.Scene."]
        for name, fields in self._sections.items():
            out.append(f"\n[{_key(name)}]")
            out += [f"{_key(k)} = {_value(v)}" for k, v in fields.items()]
        for name, entries in self._arrays.items():
            for fields in entries:
                out.append(f"\n[[{_key(name)}]]")
                out += [f"{_key(k)} = {_value(v)}" for k, v in fields.items()]
        return "\n".join(out) + "\n"

    def check(self) -> str:
        """Reads the scene as ``xper check`` does, without running it: returns its kind
        (``rigid``, ``rigid3d``, ``fluid`` or ``fracture``) or raises
        :class:`xper.SceneError`, whose message gives the line in :meth:`to_toml`'s text,
        the field and the reason."""
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "scene.toml")
            with open(path, "w", encoding="utf-8") as f:
                f.write(self.to_toml())
            return _xper.scene_kind(path)

    def __repr__(self) -> str:
        counts = ", ".join(f"{len(v)} {k}" for k, v in self._arrays.items())
        return f"<xper.Scene {self._sections['scene'].get('name', '?')}: {counts}>"
