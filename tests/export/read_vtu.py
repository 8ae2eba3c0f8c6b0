#!/usr/bin/env python3
"""Reads a .vtu file with VTK's own XML reader and prints what it found, one item a line:
   points N / cells N / types t1 t2 ... / array NAME COMPONENTS TUPLES v0 v1 ...
Exit 77 when VTK's Python bindings are missing (the calling test skips), 1 when the file does
not read."""
import sys

try:
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    from vtkmodules.vtkCommonCore import vtkFileOutputWindow, vtkOutputWindow
except ImportError as e:
    print("vtk missing: %s" % e)
    sys.exit(77)


class Errors:
    count = 0


def main(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.AddObserver("ErrorEvent", lambda *a: setattr(Errors, "count", Errors.count + 1))
    reader.Update()
    grid = reader.GetOutput()
    if Errors.count or grid is None or grid.GetNumberOfCells() == 0:
        print("vtk could not read %s" % path)
        return 1
    print("points %d" % grid.GetNumberOfPoints())
    print("cells %d" % grid.GetNumberOfCells())
    print("types " + " ".join(str(grid.GetCellType(i)) for i in range(grid.GetNumberOfCells())))
    data = grid.GetCellData()
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        values = []
        for t in range(a.GetNumberOfTuples()):
            values.extend(repr(v) for v in a.GetTuple(t))
        print("array %s %d %d %s" % (a.GetName(), a.GetNumberOfComponents(), a.GetNumberOfTuples(),
                                     " ".join(values)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
