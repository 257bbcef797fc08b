#!/usr/bin/env python3
# Renders a hex standard's side labels (point data side_mask) on its surface: skin (w1) pink, bone (w0) blue, the other
# sides grey, no side (walls of openings) yellow; seen from the front and below, the nose and the nostrils in the
# middle. Needs python3-vtk9 and a display (xvfb-run). Usage, from the repository root:
#   xvfb-run -a python3 scripts/render_side_labels.py resources/standards/artisynth-refface/standard.vtu OUT.png TITLE
import sys, vtk
import numpy as np
from vtk.util.numpy_support import vtk_to_numpy as v2n, numpy_to_vtk as n2v
from window_png import write_png
mesh, out, title = sys.argv[1:4]
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(mesh); r.Update(); g = r.GetOutput()
if g.GetPointData().GetArray('side_mask') is None:
    sys.exit(mesh + ': no point array side_mask')
mask = v2n(g.GetPointData().GetArray('side_mask')).astype(int)
category = np.where(mask & 32, 2, np.where(mask & 16, 1, np.where(mask > 0, 3, 0))).astype(float)
array = n2v(category); array.SetName('side'); g.GetPointData().AddArray(array); g.GetPointData().SetActiveScalars('side')
surface = vtk.vtkDataSetSurfaceFilter(); surface.SetInputData(g)
lut = vtk.vtkLookupTable(); lut.SetNumberOfTableValues(4); lut.Build()
for i, c in enumerate([(1, 0.9, 0.2), (0.3, 0.5, 1), (1, 0.6, 0.6), (0.5, 0.5, 0.5)]): lut.SetTableValue(i, *c, 1)
mapper = vtk.vtkDataSetMapper(); mapper.SetInputConnection(surface.GetOutputPort()); mapper.SetLookupTable(lut)
mapper.SetScalarRange(0, 3); mapper.InterpolateScalarsBeforeMappingOn()
actor = vtk.vtkActor(); actor.SetMapper(mapper); actor.GetProperty().EdgeVisibilityOn()
actor.GetProperty().SetEdgeColor(0.2, 0.2, 0.2)
ren = vtk.vtkRenderer(); ren.AddActor(actor); ren.SetBackground(1, 1, 1)
text = vtk.vtkTextActor(); text.SetInput(title); text.GetTextProperty().SetColor(0, 0, 0)
text.GetTextProperty().SetFontSize(20); text.SetPosition(10, 10); ren.AddActor2D(text)
win = vtk.vtkRenderWindow(); win.SetOffScreenRendering(1); win.AddRenderer(ren); win.SetSize(800, 700)
# The bundled standard's frame: +y anterior, +z superior, the nose tip near (0, 95, -58).
cam = ren.GetActiveCamera(); cam.SetFocalPoint(0, 80, -60); cam.SetPosition(0, 160, -160); cam.SetViewUp(0, 0.8, 0.6)
cam.SetViewAngle(22); win.Render()
write_png(win, out)
