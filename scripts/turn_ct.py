#!/usr/bin/env python3
# A CT turned about the vertical axis through its volume's centre, as a head turned in the scanner (same grid, so the
# field of view cuts what turns out of it), and hand-placed landmarks turned with it: known answers for the head turn
# (docs/benchmarks.md). Needs python3-vtk9. Usage:
#   python3 scripts/turn_ct.py CT.mha|.mhd DEGREES OUT.mha [LANDMARKS.json OUT_LANDMARKS.json]
# DEGREES > 0 turns the face from +y towards -x (counter-clockwise seen from above).
import json, math, sys, vtk
src, degrees, dst = sys.argv[1], float(sys.argv[2]), sys.argv[3]
r = vtk.vtkMetaImageReader(); r.SetFileName(src); r.Update(); img = r.GetOutput()
b = img.GetBounds(); c = ((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2)
# vtkImageReslice samples the input at T(output point): T turns by -degrees, so the content turns by +degrees.
t = vtk.vtkTransform(); t.Translate(*c); t.RotateZ(-degrees); t.Translate(-c[0], -c[1], -c[2])
rs = vtk.vtkImageReslice(); rs.SetInputData(img); rs.SetResliceTransform(t); rs.SetInterpolationModeToLinear()
rs.SetOutputSpacing(img.GetSpacing()); rs.SetOutputOrigin(img.GetOrigin()); rs.SetOutputExtent(img.GetExtent())
rs.SetBackgroundLevel(img.GetScalarRange()[0]); rs.Update()
w = vtk.vtkMetaImageWriter(); w.SetFileName(dst); w.SetInputData(rs.GetOutput()); w.SetCompression(False); w.Write()
if len(sys.argv) > 5:
    a = math.radians(degrees)
    doc = json.load(open(sys.argv[4]))
    for l in doc["landmarks"]:
        x, y, z = l["position"]
        dx, dy = x - c[0], y - c[1]
        l["position"] = [c[0] + math.cos(a) * dx - math.sin(a) * dy, c[1] + math.sin(a) * dx + math.cos(a) * dy, z]
    json.dump(doc, open(sys.argv[5], "w"), indent=1)
