#!/usr/bin/env python3
# A CT turned about the vertical axis through its volume's centre, as a head turned in the scanner, with --pitch
# about the lateral axis, as a head pitched (nodding) in it, or with --roll about the front-to-back axis, as a head
# tilted towards a shoulder (same grid, so the field of view cuts what turns out of it), and hand-placed landmarks
# turned with it: known answers for the head turn, pitch and roll (docs/benchmarks.md). Needs python3-vtk9. Usage:
#   python3 scripts/turn_ct.py [--pitch|--roll] CT.mha|.mhd DEGREES OUT.mha [LANDMARKS.json OUT_LANDMARKS.json]
# DEGREES > 0 turns the face from +y towards -x (counter-clockwise seen from above); with --pitch, raises the chin
# (the face from +y towards +z); with --roll, tilts the top of the head towards +x.
import json, math, sys, vtk
args = [a for a in sys.argv[1:] if a not in ("--pitch", "--roll")]
pitch, roll = "--pitch" in sys.argv[1:], "--roll" in sys.argv[1:]
src, degrees, dst = args[0], float(args[1]), args[2]
r = vtk.vtkMetaImageReader(); r.SetFileName(src); r.Update(); img = r.GetOutput()
b = img.GetBounds(); c = ((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2)
# vtkImageReslice samples the input at T(output point): T turns by -degrees, so the content turns by +degrees.
t = vtk.vtkTransform(); t.Translate(*c)
if pitch:
    t.RotateX(-degrees)
elif roll:
    t.RotateY(-degrees)
else:
    t.RotateZ(-degrees)
t.Translate(-c[0], -c[1], -c[2])
rs = vtk.vtkImageReslice(); rs.SetInputData(img); rs.SetResliceTransform(t); rs.SetInterpolationModeToLinear()
rs.SetOutputSpacing(img.GetSpacing()); rs.SetOutputOrigin(img.GetOrigin()); rs.SetOutputExtent(img.GetExtent())
rs.SetBackgroundLevel(img.GetScalarRange()[0]); rs.Update()
w = vtk.vtkMetaImageWriter(); w.SetFileName(dst); w.SetInputData(rs.GetOutput()); w.SetCompression(False); w.Write()
if len(args) > 4:
    a = math.radians(degrees)
    doc = json.load(open(args[3]))
    # The plane the rotation turns in: (x, y) about z, (y, z) about x, (z, x) about y.
    u, v = (1, 2) if pitch else (2, 0) if roll else (0, 1)
    for l in doc["landmarks"]:
        p = list(l["position"])
        du, dv = p[u] - c[u], p[v] - c[v]
        p[u], p[v] = c[u] + math.cos(a) * du - math.sin(a) * dv, c[v] + math.sin(a) * du + math.cos(a) * dv
        l["position"] = p
    json.dump(doc, open(args[4], "w"), indent=1)
