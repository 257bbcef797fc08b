#!/usr/bin/env python3
# Renders the surface of a patient hex mesh coloured by one of its cell or point arrays (e.g. dihedral_change,
# moved_from_mapping of facehex run's patient_hex.vtu), for docs/img. Needs python3-vtk9 and a display (xvfb-run).
# Usage, from the repository root:
#   xvfb-run -a python3 scripts/render_cell_field.py OUT/patient_hex.vtu ARRAY MAX front|side OUT.png TITLE
import sys, vtk
from window_png import write_png
mesh, array, top, view, out, title = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4], sys.argv[5], sys.argv[6]
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(mesh); r.Update(); g = r.GetOutput()
on_cells = g.GetCellData().GetArray(array) is not None
if not on_cells and g.GetPointData().GetArray(array) is None:
    sys.exit(mesh + ': no cell or point array ' + array)
(g.GetCellData() if on_cells else g.GetPointData()).SetActiveScalars(array)
surface = vtk.vtkDataSetSurfaceFilter(); surface.SetInputData(g)
lut = vtk.vtkLookupTable(); lut.SetHueRange(0.66, 0.0); lut.Build()
mapper = vtk.vtkDataSetMapper(); mapper.SetInputConnection(surface.GetOutputPort()); mapper.SetScalarRange(0, top)
mapper.SetLookupTable(lut)
(mapper.SetScalarModeToUseCellData if on_cells else mapper.SetScalarModeToUsePointData)()
actor = vtk.vtkActor(); actor.SetMapper(mapper); actor.GetProperty().EdgeVisibilityOn()
actor.GetProperty().SetEdgeColor(0.2, 0.2, 0.2)
ren = vtk.vtkRenderer(); ren.AddActor(actor); ren.SetBackground(1, 1, 1)
bar = vtk.vtkScalarBarActor(); bar.SetLookupTable(lut); bar.SetNumberOfLabels(5); bar.SetWidth(0.08)
bar.GetLabelTextProperty().SetColor(0, 0, 0); bar.GetLabelTextProperty().ShadowOff(); ren.AddActor2D(bar)
text = vtk.vtkTextActor(); text.SetInput(title); text.GetTextProperty().SetColor(0, 0, 0)
text.GetTextProperty().SetFontSize(20); text.SetPosition(10, 10); ren.AddActor2D(text)
win = vtk.vtkRenderWindow(); win.SetOffScreenRendering(1); win.AddRenderer(ren); win.SetSize(900, 860)
b = g.GetBounds(); centre = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
cam = ren.GetActiveCamera(); cam.SetFocalPoint(*centre); cam.SetViewUp(0, 0, 1)
cam.SetPosition(centre[0], centre[1] + 500, centre[2]) if view == 'front' else cam.SetPosition(centre[0] + 500, centre[1], centre[2])
ren.ResetCamera(); cam.Zoom(1.1); win.Render()
write_png(win, out)
