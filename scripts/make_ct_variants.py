#!/usr/bin/env python3
# Three smoothly warped copies of the bundled CT (wider, longer, a chin moved forward and down): patients of other
# proportions for facehex compare (docs/results.md). Needs python3-vtk9. Usage, from the repository root:
#   python3 scripts/make_ct_variants.py OUT_FOLDER && build/bin/facehex compare OUT_FOLDER/*.mha -o out/variants
import os, sys, vtk
r = vtk.vtkMetaImageReader(); r.SetFileName('resources/ct/headsq/headsq.mhd'); r.Update()
img = r.GetOutput()
b = img.GetBounds(); cx, cy, cz = (b[0]+b[1])/2, (b[2]+b[3])/2, (b[4]+b[5])/2
# name: (sx, sy, sz, extra landmark moves [(point, displacement)])
variants = {
  'wide':   (1.10, 1.00, 0.95, []),
  'long':   (0.94, 1.04, 1.10, []),
  'chin':   (1.00, 1.00, 1.00, [((cx, 175, 20), (0, 6, -6)), ((cx, 150, 45), (0, 3, 0))]),
}
for name, (sx, sy, sz, moves) in variants.items():
    src = vtk.vtkPoints(); dst = vtk.vtkPoints()
    # a coarse cage of fixed-ratio scaling about the centre, plus local moves
    for x in (b[0], cx, b[1]):
        for y in (b[2], cy, b[3]):
            for z in (b[4], cz, b[5]):
                # output point (x,y,z) samples input at the inverse-scaled point
                src.InsertNextPoint(x, y, z)
                dst.InsertNextPoint(cx + (x-cx)/sx, cy + (y-cy)/sy, cz + (z-cz)/sz)
    for (p, d) in moves:
        src.InsertNextPoint(*p); dst.InsertNextPoint(p[0]-d[0], p[1]-d[1], p[2]-d[2])
    tps = vtk.vtkThinPlateSplineTransform(); tps.SetSourceLandmarks(src); tps.SetTargetLandmarks(dst); tps.SetBasisToR()
    rs = vtk.vtkImageReslice(); rs.SetInputData(img); rs.SetResliceTransform(tps); rs.SetInterpolationModeToLinear()
    rs.SetOutputSpacing(img.GetSpacing()); rs.SetOutputOrigin(img.GetOrigin()); rs.SetOutputExtent(img.GetExtent())
    rs.SetBackgroundLevel(img.GetScalarRange()[0]); rs.Update()
    w = vtk.vtkMetaImageWriter(); w.SetFileName(os.path.join(sys.argv[1], name + '.mha')); w.SetInputData(rs.GetOutput()); w.SetCompression(False); w.Write()
    print(name, 'written')
