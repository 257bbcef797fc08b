#!/usr/bin/env python3
# Renders a standard hex mesh (surface coloured by VTK's hex scaled Jacobian) with its feature rows, for docs/img.
# Needs python3-vtk9 and a display (xvfb-run). Usage, from the repository root:
#   build/bin/facehex fields STANDARD.vtu --constraints CONSTRAINTS.json --standard-domain auxiliary -o /tmp/f.vtu
#   xvfb-run -a python3 scripts/render_standard.py STANDARD.vtu /tmp/f.vtu front|side|back OUT.png TITLE
# Feature rows: skin vertices fixed in u (blue) or v (red) that are not on that field's shape ends.
import vtk, sys
import numpy as np
from vtk.util.numpy_support import vtk_to_numpy as v2n, numpy_to_vtk as n2v
from window_png import write_png
hexf, fieldsf, view, out, title = sys.argv[1:6]
def read(f):
    r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(f); r.Update(); return r.GetOutput()
g = read(hexf); fg = read(fieldsf)
nhex = g.GetNumberOfPoints()
fixed = v2n(fg.GetPointData().GetArray('fixed_uvw'))[:nhex]
mask = v2n(fg.GetPointData().GetArray('side_mask'))[:nhex].astype(int)
P = v2n(g.GetPoints().GetData())
rw = vtk.vtkRenderWindow(); rw.SetOffScreenRendering(1); rw.SetSize(1000, 900)
ren = vtk.vtkRenderer(); ren.SetBackground(1, 1, 1); rw.AddRenderer(ren)
mq = vtk.vtkMeshQuality(); mq.SetInputData(g); mq.SetHexQualityMeasureToScaledJacobian(); mq.Update()
g2 = mq.GetOutput(); q = g2.GetCellData().GetArray('Quality'); q.SetName('scaled_jacobian_vtk')
gf = vtk.vtkGeometryFilter(); gf.SetInputData(g2); gf.Update()
surf = gf.GetOutput()
mp = vtk.vtkPolyDataMapper(); mp.SetInputData(surf)
if True:
    surf.GetCellData().SetActiveScalars('scaled_jacobian_vtk'); mp.SetScalarModeToUseCellData(); mp.SetScalarRange(0, 1)
    lut = vtk.vtkLookupTable(); lut.SetHueRange(0.0, 0.33); lut.SetSaturationRange(0.5, 0.5); lut.SetValueRange(1, 1); lut.Build(); mp.SetLookupTable(lut)
else:
    mp.ScalarVisibilityOff()
a = vtk.vtkActor(); a.SetMapper(mp); a.GetProperty().EdgeVisibilityOn(); a.GetProperty().SetEdgeColor(0.25, 0.25, 0.25)
a.GetProperty().SetColor(0.93, 0.8, 0.7); ren.AddActor(a)
# feature vertices: fixed in u off u0/u1, or fixed in v off v0/v1, on the boundary (w1 skin) shown as spheres
colors = {'u': (0.1, 0.2, 0.9), 'v': (0.85, 0.1, 0.1)}
for f, bits in ((0, 0b11), (1, 0b1100)):
    sel = np.where((fixed[:, f] > 0) & ((mask & bits) == 0) & ((mask & 0b100000) != 0))[0]
    pts = vtk.vtkPoints()
    for i in sel: pts.InsertNextPoint(*P[i])
    pd = vtk.vtkPolyData(); pd.SetPoints(pts)
    sp = vtk.vtkSphereSource(); sp.SetRadius(1.1); sp.SetThetaResolution(10); sp.SetPhiResolution(10)
    gl = vtk.vtkGlyph3D(); gl.SetInputData(pd); gl.SetSourceConnection(sp.GetOutputPort()); gl.Update()
    m2 = vtk.vtkPolyDataMapper(); m2.SetInputConnection(gl.GetOutputPort()); m2.ScalarVisibilityOff()
    a2 = vtk.vtkActor(); a2.SetMapper(m2); a2.GetProperty().SetColor(*colors['uv'[f]]); ren.AddActor(a2)
b = surf.GetBounds(); cc = [(b[0]+b[1])/2, (b[2]+b[3])/2, (b[4]+b[5])/2]
cam = ren.GetActiveCamera(); cam.SetFocalPoint(*cc)
up = (0, 0, 1)
if view == 'front': cam.SetPosition(cc[0], cc[1] + 600, cc[2])
elif view == 'side': cam.SetPosition(cc[0] + 600, cc[1] + 150, cc[2])
elif view == 'back': cam.SetPosition(cc[0], cc[1] - 600, cc[2])
cam.SetViewUp(*up); ren.ResetCamera(); cam.Zoom(1.2)
t = vtk.vtkTextActor(); t.SetInput(title); t.GetTextProperty().SetFontSize(18); t.GetTextProperty().SetColor(0, 0, 0); t.SetPosition(10, 10); ren.AddActor2D(t)
rw.Render()
write_png(rw, out)
