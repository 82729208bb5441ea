"""Writes the VTK fixtures of this folder with VTK itself (Debian python3-vtk9), so the readers
are tested on files as VTK 9 writes them: a legacy file whose cell arrays are a FIELD block with
METADATA, and two uncompressed VTU files (inline base64 with UInt64 headers, raw appended data
with UInt32 headers). Run from this folder: /usr/bin/python3 make_vtk_fixtures.py"""
import numpy as np
import vtk
from vtk.util import numpy_support as ns


def grid():
    points = vtk.vtkPoints()
    for p in [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1), (2, 2, 2)]:
        points.InsertNextPoint(*p)
    g = vtk.vtkUnstructuredGrid()
    g.SetPoints(points)
    for cell_type, ids in [(10, (0, 1, 2, 3)), (5, (1, 2, 5)), (10, (1, 2, 3, 4))]:
        id_list = vtk.vtkIdList()
        for i in ids:
            id_list.InsertNextId(i)
        g.InsertNextCell(cell_type, id_list)
    region = ns.numpy_to_vtk(np.array([3, 9, 5], dtype=np.int32))
    region.SetName("region")
    g.GetCellData().AddArray(region)
    material = ns.numpy_to_vtk(np.array([1, 1, 2], dtype=np.int64))
    material.SetName("material")
    g.GetCellData().AddArray(material)
    stress = ns.numpy_to_vtk(np.arange(18, dtype=float).reshape(3, 6))
    stress.SetName("stress")
    stress.SetComponentName(0, "XX")
    g.GetCellData().AddArray(stress)
    displacement = ns.numpy_to_vtk(np.arange(18, dtype=float).reshape(6, 3))
    displacement.SetName("displacement")
    g.GetPointData().SetVectors(displacement)
    return g


g = grid()
legacy = vtk.vtkUnstructuredGridWriter()
legacy.SetInputData(g)
legacy.SetFileName("vtk9_field.vtk")
legacy.Write()
xml = vtk.vtkXMLUnstructuredGridWriter()
xml.SetInputData(g)
xml.SetCompressorTypeToNone()
xml.SetFileName("vtk9_base64.vtu")
xml.SetDataModeToBinary()
xml.SetHeaderTypeToUInt64()
xml.Write()
xml.SetFileName("vtk9_raw.vtu")
xml.SetDataModeToAppended()
xml.EncodeAppendedDataOff()
xml.SetHeaderTypeToUInt32()
xml.Write()
