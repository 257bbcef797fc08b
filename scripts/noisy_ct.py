#!/usr/bin/env python3
# A CT with Gaussian noise of SIGMA file units added to every voxel, drawn from SEED: white, or correlated within each
# slice by PASSES passes of a 3 x 3 box (as a reconstruction kernel correlates a scanner's noise), scaled to SIGMA.
# Values are rounded and clamped to the file's integer type. For measuring how the segmentation handles a low-dose or
# cone-beam CT's noise (docs/benchmarks.md, "Noisy CTs"). Needs python3-vtk9 and numpy. Usage:
#   python3 scripts/noisy_ct.py CT.mha|.mhd SIGMA SEED PASSES OUT.mha
import sys

import numpy as np

import ct_image

if len(sys.argv) != 6:
    sys.exit("usage: noisy_ct.py CT SIGMA SEED PASSES OUT.mha")
src, sigma, seed, passes, dst = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
image, original = ct_image.read(src)
noise = np.random.default_rng(seed).normal(0.0, 1.0, original.shape).astype(np.float32)
for _ in range(passes):
    noise = sum(np.roll(np.roll(noise, a, 1), b, 2) for a in (-1, 0, 1) for b in (-1, 0, 1)) / 9
noise *= sigma / noise.std()
ct_image.write_like(image, original.astype(np.float32) + noise, dst)
