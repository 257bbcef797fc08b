#!/usr/bin/env python3
# A CT as a scanner would have reconstructed it in a disc: the columns (along z) beyond RADIUS mm of (CX, CY) hold
# FILL in every slice, as a scanner fills what lies outside its field of view (docs/segmentation.md, the
# reconstruction disc; docs/benchmarks.md, "A round field of view"). Needs python3-vtk9. Usage:
#   python3 scripts/disc_ct.py CT.mha|.mhd CX,CY,RADIUS OUT.mha [FILL]
# FILL defaults to -3024, a common scanner fill; it must lie below every value of the CT.
import sys, vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
import numpy as np

src, spec, dst = sys.argv[1], sys.argv[2], sys.argv[3]
fill = float(sys.argv[4]) if len(sys.argv) > 4 else -3024.0
cx, cy, radius = (float(v) for v in spec.split(","))
r = vtk.vtkMetaImageReader(); r.SetFileName(src); r.Update(); img = r.GetOutput()
nx, ny, nz = img.GetDimensions(); sp = img.GetSpacing(); org = img.GetOrigin()
scalars = img.GetPointData().GetScalars()
values = vtk_to_numpy(scalars).reshape(nz, ny, nx).copy()
if fill >= values.min():
    sys.exit(f"error: the fill {fill} is not below the CT's lowest value {values.min()}")
x = org[0] + sp[0] * np.arange(nx); y = org[1] + sp[1] * np.arange(ny)
values[:, (x[None, :] - cx) ** 2 + (y[:, None] - cy) ** 2 > radius * radius] = fill
out = vtk.vtkImageData(); out.CopyStructure(img)
array = numpy_to_vtk(values.ravel(), deep=1, array_type=scalars.GetDataType()); array.SetName(scalars.GetName() or "scalars")
out.GetPointData().SetScalars(array)
w = vtk.vtkMetaImageWriter(); w.SetFileName(dst); w.SetInputData(out); w.SetCompression(True); w.Write()
