# A CT's voxels as a numpy array and back, for the scripts that make variants of a CT (noisy_ct.py, strap_ct.py,
# open_mouth_ct.py). Needs python3-vtk9 and numpy.
import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy


def read(path):
    """The image (its grid: GetDimensions, GetSpacing, GetOrigin) and its voxels, indexed [z, y, x], as stored."""
    reader = vtk.vtkMetaImageReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    nx, ny, nz = image.GetDimensions()
    return image, vtk_to_numpy(image.GetPointData().GetScalars()).reshape(nz, ny, nx)


def write_like(image, values, path, compress=False):
    """`values` ([z, y, x]) on `image`'s grid in its voxel type (rounded and clamped to an integer type) to `path`."""
    scalars = image.GetPointData().GetScalars()
    dtype = vtk_to_numpy(scalars).dtype
    if np.issubdtype(dtype, np.integer):
        info = np.iinfo(dtype)
        values = np.clip(np.round(values), info.min, info.max)
    out = vtk.vtkImageData()
    out.CopyStructure(image)
    array = numpy_to_vtk(np.ascontiguousarray(values, dtype=dtype).ravel(), deep=1, array_type=scalars.GetDataType())
    array.SetName(scalars.GetName() or "scalars")
    out.GetPointData().SetScalars(array)
    writer = vtk.vtkMetaImageWriter()
    writer.SetFileName(path)
    writer.SetInputData(out)
    writer.SetCompression(compress)
    writer.Write()
