#!/usr/bin/env python3
# A CT cropped to a box of its voxels and resampled to other voxel spacings, linear between the voxels, in the same
# physical frame: for measuring how the segmentation and the landmarks hold on finer and coarser scans than the ones at
# hand (docs/benchmarks.md, "Finer and coarser voxels"). Needs python3-vtk9. Usage:
#   python3 scripts/resample_ct.py CT.mha|.mhd I0,I1,J0,J1,K0,K1|all SX,SY,SZ OUT.mha
# I0..K1: the first and last voxel index kept along x, y and z; SX,SY,SZ: the new spacing in mm.
import sys

import vtk

if len(sys.argv) != 5:
    sys.exit("usage: resample_ct.py CT I0,I1,J0,J1,K0,K1|all SX,SY,SZ OUT.mha")
src, box, spacing, dst = sys.argv[1:]
reader = vtk.vtkMetaImageReader()
reader.SetFileName(src)
reader.Update()
if reader.GetErrorCode() != 0 or reader.GetOutput().GetNumberOfPoints() == 0:
    sys.exit(f"resample_ct.py: cannot read {src}")
voi = vtk.vtkExtractVOI()
voi.SetInputConnection(reader.GetOutputPort())
voi.SetVOI(*(reader.GetOutput().GetExtent() if box == "all" else [int(v) for v in box.split(",")]))
resample = vtk.vtkImageResample()
resample.SetInputConnection(voi.GetOutputPort())
for axis, s in enumerate(float(v) for v in spacing.split(",")):
    resample.SetAxisOutputSpacing(axis, s)
resample.SetInterpolationModeToLinear()
writer = vtk.vtkMetaImageWriter()
writer.SetInputConnection(resample.GetOutputPort())
writer.SetFileName(dst)
writer.SetCompression(True)
writer.Write()
if writer.GetErrorCode() != 0:
    sys.exit(f"resample_ct.py: cannot write {dst}")
