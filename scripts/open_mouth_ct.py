#!/usr/bin/env python3
# A CT with its mouth opened GAP mm, as a jaw opens about its joints, from the landmarks `facehex segment
# --write-landmarks` found on it (stomion, mouth corners, tragi): below the mouth line (a parabola in x through the
# stomion and the corners' height) everything moves down by GAP times how far forward of the tragi it lies (1 at the
# stomion's depth and in front of it); the band this stretches repeats the mouth line's slice, and between the corners
# (an ellipse as tall as the gap there) it is air to 12 mm behind the lips' front in each column, but for voxels at or
# above BONE (the teeth). For measuring how the segmentation handles an open mouth (docs/benchmarks.md, "An open
# mouth"). The CT must be upright in its voxel axes (+y anterior, +z superior). Needs python3-vtk9 and numpy. Usage:
#   python3 scripts/open_mouth_ct.py CT.mha|.mhd LANDMARKS.json BONE GAP OUT.mha
import json
import sys

import numpy as np

import ct_image

if len(sys.argv) != 6:
    sys.exit("usage: open_mouth_ct.py CT LANDMARKS.json BONE GAP OUT.mha")
src, marks, bone, gap, dst = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
points = {l["name"]: np.array(l["position"]) for l in json.load(open(marks))["landmarks"]}
stomion, right, left = points["stomion"], points["cheilion right"], points["cheilion left"]
tragus_y = 0.5 * (points["tragus right"][1] + points["tragus left"][1])
image, stored = ct_image.read(src)
nz, ny, nx = stored.shape
spacing, origin = image.GetSpacing(), image.GetOrigin()
volume = stored.astype(np.float32)
air = float(np.percentile(volume, 1))
x = origin[0] + spacing[0] * np.arange(nx)
y = origin[1] + spacing[1] * np.arange(ny)
z = origin[2] + spacing[2] * np.arange(nz)
centre, half_width = 0.5 * (right[0] + left[0]), 0.5 * (left[0] - right[0])
u = ((x - centre) / half_width)[None, None, :]
cut = stomion[2] + (0.5 * (right[2] + left[2]) - stomion[2]) * np.minimum(u * u, 1)
drop = (gap * np.clip((y - tragus_y) / (stomion[1] - tragus_y), 0, 1))[None, :, None]
Z = z[:, None, None]
source = np.where(Z >= cut, Z, np.where(Z < cut - drop, Z + drop, cut))
t = np.clip((source - origin[2]) / spacing[2], 0, nz - 1)
k0 = np.minimum(np.floor(t).astype(int), nz - 2)
f = t - k0
j = np.arange(ny)[None, :, None]
i = np.arange(nx)[None, None, :]
opened = volume[k0, j, i] * (1 - f) + volume[k0 + 1, j, i] * f
w = (Z - (cut - drop / 2)) / np.maximum(drop / 2, 1e-6)
# The lips' front in each column at the mouth line: the most anterior voxel above half way from air to bone.
line = np.clip(np.round((cut[0, 0] - origin[2]) / spacing[2]).astype(int), 0, nz - 1)
tissue = volume[line, :, np.arange(nx)] > 0.5 * (air + bone)  # [x, y]
lips = np.where(tissue.any(axis=1), y[ny - 1 - np.argmax(tissue[:, ::-1], axis=1)], -np.inf)
mouth = (u * u + w * w < 1) & (drop > 0.5) & (y[None, :, None] > lips[None, None, :] - 12) & (opened < bone)
opened[mouth] = air
ct_image.write_like(image, opened, dst)
