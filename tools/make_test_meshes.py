#!/usr/bin/env python3
"""Writes the small Gmsh meshes that the xper-mesh tests read.

Usage: python3 tools/make_test_meshes.py [--out DIR]
(default DIR: crates/xper-mesh/tests/data). Needs the `gmsh` Python package
(`pip install gmsh`). The outputs are committed; the tests also rerun this script when gmsh
is installed.

The geometry: the unit square [0, 1]^2 (m) with a rectangular inclusion
[0.3, 0.6] x [0.3, 0.5]; physical surfaces "matrix" (tag 1, area 0.94) and "inclusion"
(tag 2, area 0.06); physical lines "left", "right", "bottom", "top",
"inclusion_boundary"; physical point "origin" (the corner (0, 0)). Element size 0.1 m.

Files:
- square_inclusion_ascii.msh, square_inclusion_binary.msh: MSH 4.1, ASCII and binary.
- unnamed_groups.msh: same mesh, physical groups without names.
- no_groups.msh: same mesh, no physical group at all (every element saved).
- v22.msh: MSH 2.2 (rejected: convert with gmsh -format msh41).
- quads.msh: recombined into quadrangles (rejected).
- second_order.msh: 6-node triangles (rejected).
- nonplanar.msh: the square in the plane z = 1 (rejected).
- stray_line.msh: a physical line apart from the surfaces (its nodes are not nodes of
  triangles; rejected).
"""

import argparse
import os

import gmsh

H = 0.1


def square_with_inclusion(names=True, groups=True, z=0.0, stray_line=False):
    """Builds the geometry with the built-in kernel, so that every tag is known."""
    gmsh.model.add("square_inclusion")
    geo = gmsh.model.geo
    corners = [(0, 0), (1, 0), (1, 1), (0, 1)]
    inner = [(0.3, 0.3), (0.6, 0.3), (0.6, 0.5), (0.3, 0.5)]
    p = [geo.addPoint(x, y, z, H) for x, y in corners]
    q = [geo.addPoint(x, y, z, H) for x, y in inner]
    outer_lines = [geo.addLine(p[k], p[(k + 1) % 4]) for k in range(4)]
    inner_lines = [geo.addLine(q[k], q[(k + 1) % 4]) for k in range(4)]
    outer_loop = geo.addCurveLoop(outer_lines)
    inner_loop = geo.addCurveLoop(inner_lines)
    matrix = geo.addPlaneSurface([outer_loop, inner_loop])
    inclusion = geo.addPlaneSurface([inner_loop])
    stray = None
    if stray_line:
        a = geo.addPoint(2.0, 0.0, z, H)
        b = geo.addPoint(2.0, 1.0, z, H)
        stray = geo.addLine(a, b)
    geo.synchronize()
    if groups:
        def group(dim, tags, tag, name):
            gmsh.model.addPhysicalGroup(dim, tags, tag, name if names else "")

        group(2, [matrix], 1, "matrix")
        group(2, [inclusion], 2, "inclusion")
        bottom, right, top, left = outer_lines
        group(1, [left], 11, "left")
        group(1, [right], 12, "right")
        group(1, [bottom], 13, "bottom")
        group(1, [top], 14, "top")
        group(1, inner_lines, 15, "inclusion_boundary")
        group(0, [p[0]], 21, "origin")
        if stray is not None:
            group(1, [stray], 16, "stray")
    else:
        gmsh.option.setNumber("Mesh.SaveAll", 1)


def write(path, version=4.1, binary=False, recombine=False, order=1, **geometry):
    gmsh.clear()
    gmsh.option.setNumber("Mesh.SaveAll", 0)
    square_with_inclusion(**geometry)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.RecombineAll", 1 if recombine else 0)
    gmsh.model.mesh.generate(2)
    if order > 1:
        gmsh.model.mesh.setOrder(order)
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", 1 if binary else 0)
    gmsh.write(path)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(here, "..", "crates", "xper-mesh", "tests", "data")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=default, help="output directory")
    out = parser.parse_args().out
    os.makedirs(out, exist_ok=True)
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    try:
        path = lambda name: os.path.join(out, name)
        write(path("square_inclusion_ascii.msh"))
        write(path("square_inclusion_binary.msh"), binary=True)
        write(path("unnamed_groups.msh"), names=False)
        write(path("no_groups.msh"), groups=False)
        write(path("v22.msh"), version=2.2)
        write(path("quads.msh"), recombine=True)
        write(path("second_order.msh"), order=2)
        write(path("nonplanar.msh"), z=1.0)
        write(path("stray_line.msh"), stray_line=True)
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main()
