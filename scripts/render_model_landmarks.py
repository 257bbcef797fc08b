#!/usr/bin/env python3
# Renders a labelled patient tet model (its boundary coloured by side: skin beige, top cut red, bottom cut green,
# posterior cut blue, bone grey) with the landmarks found on it (blue found, orange estimated) and, when given, the
# reference landmarks placed by hand (small black), for docs/img. A landmark at most SLIT_DEPTH behind the surface
# seen from the camera (the eye corners and the stomion, read in the CT's slits, which the model's skin bridges) is
# drawn over it. Needs python3-vtk9 and a display (xvfb-run).
# Usage, from the repository root:
#   build/bin/facehex segment CT -o /tmp/model.vtu --write-landmarks /tmp/landmarks.json
#   xvfb-run -a python3 scripts/render_model_landmarks.py /tmp/model.vtu /tmp/landmarks.json front|side|cuts OUT.png \
#     TITLE [REFERENCE.json]
import json, sys
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy as v2n, numpy_to_vtk as n2v

from window_png import write_png

model_file, landmarks_file, view, out, title = sys.argv[1:6]
reference_file = sys.argv[6] if len(sys.argv) > 6 else None

reader = vtk.vtkXMLUnstructuredGridReader()
reader.SetFileName(model_file)
reader.Update()
surface_filter = vtk.vtkGeometryFilter()
surface_filter.SetInputData(reader.GetOutput())
surface_filter.Update()
surface = surface_filter.GetOutput()
mask = v2n(surface.GetPointData().GetArray('side_mask')).astype(int).ravel()

# A triangle's side: the one all three of its vertices lie on (core/mesh/sides.h: u0 u1 v0 v1 w0 w1 = bits 0-5).
side_colours = {0: (0.2, 0.35, 0.9), 1: (0.2, 0.35, 0.9), 2: (0.2, 0.7, 0.3), 3: (0.85, 0.2, 0.2),
                4: (0.6, 0.6, 0.6), 5: (0.93, 0.8, 0.7)}
colours = np.zeros((surface.GetNumberOfCells(), 3), dtype=np.uint8)
ids = vtk.vtkIdList()
for c in range(surface.GetNumberOfCells()):
    surface.GetCellPoints(c, ids)
    common = mask[ids.GetId(0)] & mask[ids.GetId(1)] & mask[ids.GetId(2)]
    side = next((s for s in (0, 1, 2, 3, 4, 5) if common & (1 << s)), 5)
    colours[c] = [int(255 * x) for x in side_colours[side]]
array = n2v(colours, deep=1)
array.SetName('side_colour')
surface.GetCellData().SetScalars(array)

window = vtk.vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetSize(1000, 900)
renderer = vtk.vtkRenderer()
renderer.SetBackground(1, 1, 1)
window.AddRenderer(renderer)
mapper = vtk.vtkPolyDataMapper()
mapper.SetInputData(surface)
mapper.SetScalarModeToUseCellData()
mapper.SetColorModeToDirectScalars()
actor = vtk.vtkActor()
actor.SetMapper(mapper)
renderer.AddActor(actor)


# Markers over the surface: a second layer drawn after the model, with the same camera.
overlay = vtk.vtkRenderer()
overlay.SetLayer(1)
overlay.SetActiveCamera(renderer.GetActiveCamera())
window.SetNumberOfLayers(2)
window.AddRenderer(overlay)
locator = vtk.vtkOBBTree()
locator.SetDataSet(surface)
locator.BuildLocator()
SLIT_DEPTH = 8.0  # mm: the model's skin lies up to about 5 mm in front of a closed slit's floor


def spheres(points, radius, colour):
    vtk_points = vtk.vtkPoints()
    for p in points:
        vtk_points.InsertNextPoint(*p)
    data = vtk.vtkPolyData()
    data.SetPoints(vtk_points)
    source = vtk.vtkSphereSource()
    source.SetRadius(radius)
    source.SetThetaResolution(16)
    source.SetPhiResolution(16)
    glyphs = vtk.vtkGlyph3D()
    glyphs.SetInputData(data)
    glyphs.SetSourceConnection(source.GetOutputPort())
    glyph_mapper = vtk.vtkPolyDataMapper()
    glyph_mapper.SetInputConnection(glyphs.GetOutputPort())
    glyph_mapper.ScalarVisibilityOff()
    glyph_actor = vtk.vtkActor()
    glyph_actor.SetMapper(glyph_mapper)
    glyph_actor.GetProperty().SetColor(*colour)
    return glyph_actor


def shown(points, radius, colour):
    """Each point in front of the surface, or at most SLIT_DEPTH behind it, drawn over it; the others hidden by it."""
    camera_at = np.array(renderer.GetActiveCamera().GetPosition())
    over, under = [], []
    for p in map(np.array, points):
        towards = (camera_at - p) / np.linalg.norm(camera_at - p)
        hits = vtk.vtkPoints()
        locator.IntersectWithLine(p + towards * SLIT_DEPTH, camera_at, hits, None)
        crossings = [np.array(hits.GetPoint(i)) for i in range(hits.GetNumberOfPoints())]
        (under if crossings else over).append(p)
    if over:
        overlay.AddActor(spheres(over, radius, colour))
    if under:
        renderer.AddActor(spheres(under, radius, colour))


bounds = surface.GetBounds()
centre = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2]
camera = renderer.GetActiveCamera()
camera.SetFocalPoint(*centre)
if view == 'front':
    camera.SetPosition(centre[0], centre[1] + 600, centre[2])
elif view == 'side':  # the profile, where most landmarks lie
    camera.SetPosition(centre[0] + 600, centre[1] + 150, centre[2])
else:  # 'cuts': from above and behind, where the cut sides and the bone side show
    camera.SetPosition(centre[0] + 600, centre[1] - 150, centre[2] + 250)
camera.SetViewUp(0, 0, 1)
renderer.ResetCamera()
camera.Zoom(1.3 if view != 'cuts' else 1.1)

found = json.load(open(landmarks_file))['landmarks']
shown([l['position'] for l in found if l['status'] != 'estimated'], 2.0, (0.1, 0.2, 0.9))
shown([l['position'] for l in found if l['status'] == 'estimated'], 2.0, (1.0, 0.55, 0.0))
if reference_file:
    shown([l['position'] for l in json.load(open(reference_file))['landmarks']], 1.0, (0, 0, 0))
text = vtk.vtkTextActor()
text.SetInput(title)
text.GetTextProperty().SetFontSize(18)
text.GetTextProperty().SetColor(0, 0, 0)
text.SetPosition(10, 10)
renderer.AddActor2D(text)
window.Render()
write_png(window, out)
