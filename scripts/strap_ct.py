#!/usr/bin/env python3
# A CT with an object lying on the face's front, as a head strap or tape does: in each slice from Z0 to Z1 mm, the
# THICKNESS mm in front of each column's most anterior voxel above THRESHOLD (the skin, along +y) take VALUE (the
# object's density, e.g. 0 for a strap of soft tissue's). For measuring how objects on the skin move the landmarks
# (docs/benchmarks.md, "Objects on the skin"). Needs python3-vtk9. Usage:
#   python3 scripts/strap_ct.py CT.mha|.mhd Z0,Z1,THICKNESS,VALUE THRESHOLD OUT.mha
import sys

import numpy as np

import ct_image

if len(sys.argv) != 5:
    sys.exit(__doc__ or "usage: strap_ct.py CT Z0,Z1,THICKNESS,VALUE THRESHOLD OUT.mha")
src, spec, threshold, dst = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
z0, z1, thickness, value = (float(v) for v in spec.split(","))
image, stored = ct_image.read(src)
nz, ny, nx = stored.shape
spacing, origin = image.GetSpacing(), image.GetOrigin()
values = stored.copy()
layer = int(round(thickness / spacing[1]))
first = max(0, int(round((z0 - origin[2]) / spacing[2])))
last = min(nz - 1, int(round((z1 - origin[2]) / spacing[2])))
for k in range(first, last + 1):
    tissue = values[k] > threshold
    for i in np.flatnonzero(tissue.any(axis=0)):
        front = np.flatnonzero(tissue[:, i]).max()
        values[k, front + 1:min(ny, front + 1 + layer), i] = value
ct_image.write_like(image, values, dst, compress=True)
