#!/usr/bin/python3
"""A close, front view of a CT's skin around some landmarks, with several readings of them drawn on it.

    xvfb-run -a python3 scripts/render_landmark_readings.py CT THRESHOLD XMIN XMAX ZMIN ZMAX OUT.png TITLE \
        LABEL=FILE.json [LABEL=FILE.json ...]

The skin is the iso-surface at THRESHOLD (the CT's units) of the volume blurred by one voxel, the view orthographic
along -y (the face looking to +y), with a 1 mm grid (5 mm lines bold, labelled) in x and z. Each FILE is a FaceHex
landmark file (core/face/landmark_file.h); its landmarks inside the window are drawn as discs of one colour per file
(in order: black, white, blue, orange), named in the legend by LABEL.
"""
import json
import math
import sys

import vtk

from window_png import write_png

COLOURS = [(0, 0, 0), (1, 1, 1), (0.1, 0.35, 1), (1, 0.55, 0)]


def main():
    if len(sys.argv) < 10:
        sys.exit(__doc__)
    ct, threshold = sys.argv[1], float(sys.argv[2])
    x0, x1, z0, z1 = map(float, sys.argv[3:7])
    out, title = sys.argv[7], sys.argv[8]
    readings = [arg.split("=", 1) for arg in sys.argv[9:]]

    reader = vtk.vtkMetaImageReader()
    reader.SetFileName(ct)
    reader.Update()
    image = reader.GetOutput()
    origin, spacing, dims = image.GetOrigin(), image.GetSpacing(), image.GetDimensions()
    voi = vtk.vtkExtractVOI()
    voi.SetInputData(image)
    index = lambda v, a: min(dims[a] - 1, max(0, int((v - origin[a]) / spacing[a])))
    voi.SetVOI(index(x0 - 10, 0), index(x1 + 10, 0), 0, dims[1] - 1, index(z0 - 10, 2), index(z1 + 10, 2))
    blur = vtk.vtkImageGaussianSmooth()
    blur.SetInputConnection(voi.GetOutputPort())
    blur.SetStandardDeviations(1, 1, 1)
    iso = vtk.vtkFlyingEdges3D()
    iso.SetInputConnection(blur.GetOutputPort())
    iso.SetValue(0, threshold)
    iso.Update()
    skin = iso.GetOutput()
    bounds = skin.GetBounds()
    y_front = bounds[3] + 5

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(skin)
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.93, 0.8, 0.7)
    renderer.AddActor(actor)

    # The grid, in front of the skin.
    points, thin, bold = vtk.vtkPoints(), vtk.vtkCellArray(), vtk.vtkCellArray()

    def segment(p, q, cells):
        cells.InsertNextCell(2)
        cells.InsertCellPoint(points.InsertNextPoint(p))
        cells.InsertCellPoint(points.InsertNextPoint(q))

    for x in range(math.ceil(x0), math.floor(x1) + 1):
        segment((x, y_front, z0), (x, y_front, z1), bold if x % 5 == 0 else thin)
    for z in range(math.ceil(z0), math.floor(z1) + 1):
        segment((x0, y_front, z), (x1, y_front, z), bold if z % 5 == 0 else thin)
    for cells, width, opacity in ((thin, 1, 0.25), (bold, 2, 0.6)):
        lines = vtk.vtkPolyData()
        lines.SetPoints(points)
        lines.SetLines(cells)
        line_mapper = vtk.vtkPolyDataMapper()
        line_mapper.SetInputData(lines)
        line_actor = vtk.vtkActor()
        line_actor.SetMapper(line_mapper)
        line_actor.GetProperty().SetColor(0.1, 0.1, 0.8)
        line_actor.GetProperty().SetLineWidth(width)
        line_actor.GetProperty().SetOpacity(opacity)
        renderer.AddActor(line_actor)

    def text(s, position, colour, size=16):
        label = vtk.vtkBillboardTextActor3D()
        label.SetInput(s)
        label.SetPosition(*position)
        label.GetTextProperty().SetColor(*colour)
        label.GetTextProperty().SetFontSize(size)
        renderer.AddActor(label)

    for x in range(math.ceil(x0 / 5) * 5, math.floor(x1) + 1, 5):
        text(str(x), (x, y_front, z0 + 0.3), (0.8, 0, 0))
    for z in range(math.ceil(z0 / 5) * 5, math.floor(z1) + 1, 5):
        text(str(z), (x1 - 1.5, y_front, z + 0.3), (0.8, 0, 0))

    width = 1200
    height = int(width * (z1 - z0) / (x1 - x0))
    # The readings: discs in front of the grid, and a legend.
    radius = (z1 - z0) / 60
    for k, (label, path) in enumerate(readings):
        colour = COLOURS[k % len(COLOURS)]
        for landmark in json.load(open(path))["landmarks"]:
            x, _, z = landmark["position"]
            if not (x0 <= x <= x1 and z0 <= z <= z1):
                continue
            disc = vtk.vtkRegularPolygonSource()
            disc.SetNumberOfSides(24)
            disc.SetRadius(radius)
            disc.SetCenter(x, y_front + 1 + k, z)
            disc.SetNormal(0, 1, 0)
            disc_mapper = vtk.vtkPolyDataMapper()
            disc_mapper.SetInputConnection(disc.GetOutputPort())
            disc_actor = vtk.vtkActor()
            disc_actor.SetMapper(disc_mapper)
            disc_actor.GetProperty().SetColor(*colour)
            disc_actor.GetProperty().EdgeVisibilityOn()
            disc_actor.GetProperty().SetEdgeColor(0.3, 0.3, 0.3)
            disc_actor.GetProperty().LightingOff()
            renderer.AddActor(disc_actor)
        legend = vtk.vtkTextActor()
        legend.SetInput("o " + label)
        legend.GetTextProperty().SetColor(*[c * 0.8 for c in colour] if colour != (1, 1, 1) else (0.5, 0.5, 0.5))
        legend.GetTextProperty().SetFontSize(18)
        legend.GetTextProperty().BoldOn()
        legend.GetTextProperty().SetBackgroundColor(1, 1, 1)
        legend.GetTextProperty().SetBackgroundOpacity(0.7)
        legend.SetPosition(10, height - 58 - 24 * k)
        renderer.AddActor2D(legend)
    heading = vtk.vtkTextActor()
    heading.SetInput(title)
    heading.GetTextProperty().SetColor(0, 0, 0)
    heading.GetTextProperty().SetFontSize(18)
    heading.GetTextProperty().SetBackgroundColor(1, 1, 1)
    heading.GetTextProperty().SetBackgroundOpacity(0.7)
    heading.SetPosition(10, height - 32)
    renderer.AddActor2D(heading)

    # Lit from above and from either side, so that a slit's or a fold's edge casts a shade.
    cx, cz = (x0 + x1) / 2, (z0 + z1) / 2
    renderer.AutomaticLightCreationOff()
    for lx, lz, intensity in ((0, 1, 0.8), (0.6, 0.3, 0.4), (-0.6, 0.3, 0.4)):
        light = vtk.vtkLight()
        light.SetLightTypeToSceneLight()
        light.PositionalOff()
        light.SetFocalPoint(cx, bounds[2], cz)
        light.SetPosition(cx + 300 * lx, bounds[3] + 150, cz + 300 * lz)
        light.SetIntensity(intensity)
        renderer.AddLight(light)
    camera = renderer.GetActiveCamera()
    camera.ParallelProjectionOn()
    camera.SetFocalPoint(cx, bounds[2], cz)
    camera.SetPosition(cx, bounds[3] + 500, cz)
    camera.SetViewUp(0, 0, 1)
    camera.SetParallelScale((z1 - z0) / 2)
    camera.SetClippingRange(1, 2000)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.AddRenderer(renderer)
    window.SetSize(width, height)
    window.Render()
    write_png(window, out)


if __name__ == "__main__":
    main()
