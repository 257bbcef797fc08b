# The picture a rendered window shows, written as a PNG: the last step of the render scripts (render_*.py), which import
# it from beside them. Needs python3-vtk9.
import vtk


def write_png(window, path):
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
