#!/usr/bin/env python3
# A CT with Gaussian noise of SIGMA file units added to every voxel, drawn from SEED: white, or correlated within each
# slice by PASSES passes of a 3 x 3 box (as a reconstruction kernel correlates a scanner's noise), scaled to SIGMA.
# Values are rounded and clamped to the file's integer type. For measuring how the segmentation handles a low-dose or
# cone-beam CT's noise (docs/benchmarks.md, "Noisy CTs"). Needs python3-vtk9 and numpy. Usage:
#   python3 scripts/noisy_ct.py CT.mha|.mhd SIGMA SEED PASSES OUT.mha
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

if len(sys.argv) != 6:
    sys.exit("usage: noisy_ct.py CT SIGMA SEED PASSES OUT.mha")
src, sigma, seed, passes, dst = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
reader = vtk.vtkMetaImageReader()
reader.SetFileName(src)
reader.Update()
image = reader.GetOutput()
nx, ny, nz = image.GetDimensions()
scalars = image.GetPointData().GetScalars()
original = vtk_to_numpy(scalars)
noise = np.random.default_rng(seed).normal(0.0, 1.0, (nz, ny, nx)).astype(np.float32)
for _ in range(passes):
    noise = sum(np.roll(np.roll(noise, a, 1), b, 2) for a in (-1, 0, 1) for b in (-1, 0, 1)) / 9
noise *= sigma / noise.std()
values = original.astype(np.float32) + noise.ravel()
if np.issubdtype(original.dtype, np.integer):
    info = np.iinfo(original.dtype)
    values = np.clip(np.round(values), info.min, info.max)
out = vtk.vtkImageData()
out.CopyStructure(image)
array = numpy_to_vtk(values.astype(original.dtype), deep=1, array_type=scalars.GetDataType())
array.SetName(scalars.GetName() or "scalars")
out.GetPointData().SetScalars(array)
writer = vtk.vtkMetaImageWriter()
writer.SetFileName(dst)
writer.SetInputData(out)
writer.SetCompression(False)
writer.Write()
