"""Renders a frame of a 3D xper run to a PNG with VTK (offscreen; on a machine without a
display run it under `xvfb-run -a`): spheres as glyphs of their radius, polyhedra as surfaces,
walls translucent.

    xvfb-run -a python3 tools/render3d.py OUT_DIR STEP IMAGE.png [--camera x y z fx fy fz]

OUT_DIR is the `--out` of `xper run`, STEP the step of a written frame. Needs the `vtk`
Python module (Debian: python3-vtk9).
"""

import sys

import vtk


def reader(out, part, step):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(f"{out}/frames/{part}_{step:08d}.vtu")
    r.Update()
    return r.GetOutput()


def main(argv):
    if len(argv) not in (4, 11) or (len(argv) == 11 and argv[4] != "--camera"):
        sys.exit(__doc__)
    out, step, image = argv[1], int(argv[2]), argv[3]
    camera = [float(x) for x in argv[5:11]] if len(argv) == 11 else None
    ren = vtk.vtkRenderer()
    ren.SetBackground(1, 1, 1)
    spheres = reader(out, "spheres", step)
    spheres.GetPointData().SetActiveScalars("radius")
    ball = vtk.vtkSphereSource()
    ball.SetThetaResolution(16)
    ball.SetPhiResolution(12)
    glyphs = vtk.vtkGlyph3D()
    glyphs.SetInputData(spheres)
    glyphs.SetSourceConnection(ball.GetOutputPort())
    glyphs.SetScaleModeToScaleByScalar()
    glyphs.SetScaleFactor(2.0)  # the source's radius is 0.5
    parts = [(glyphs, (0.3, 0.5, 0.8), 1.0)]
    for name, color, opacity in [("polyhedra", (0.8, 0.4, 0.2), 1.0), ("walls", (0.6, 0.6, 0.6), 0.2)]:
        parts.append((reader(out, name, step), color, opacity))
    for source, color, opacity in parts:
        mapper = vtk.vtkDataSetMapper() if not hasattr(source, "GetOutputPort") else vtk.vtkPolyDataMapper()
        if hasattr(source, "GetOutputPort"):
            mapper.SetInputConnection(source.GetOutputPort())
        else:
            mapper.SetInputData(source)
        mapper.ScalarVisibilityOff()
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(*color)
        actor.GetProperty().SetOpacity(opacity)
        ren.AddActor(actor)
    cam = ren.GetActiveCamera()
    if camera:
        cam.SetPosition(*camera[:3])
        cam.SetFocalPoint(*camera[3:])
        cam.SetViewUp(0, 0, 1)
        ren.ResetCameraClippingRange()
    else:
        ren.ResetCamera()
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.AddRenderer(ren)
    win.SetSize(700, 600)
    win.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(win)
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(image)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


if __name__ == "__main__":
    main(sys.argv)
