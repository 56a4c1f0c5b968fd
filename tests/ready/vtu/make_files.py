#!/usr/bin/python3
"""Writes the VTU files the tests read (tests/ready/test_vtu.cpp): one small
Ready mesh in each encoding VTK's XML writer makes, with VTK's own writer
(Debian's python3-vtk9), and Ready's <RD> element put in after; and two
polyhedra, as Ready's FCC3333 patterns hold theirs.

    /usr/bin/python3 tests/ready/vtu/make_files.py

The mesh: 8 points, point i at (i % 4, i // 4, 0.125 i), and four polygons
(VTK_POLYGON, as Ready's meshes have them): 0 1 5 4 | 1 2 6 | 1 6 5 | 2 3 7 6.
Cell data, cell c: a = 0.25 c - 3, b = 1 / (c + 1) (Float32 or Float64) and
v = (c, -c, 0.5 c) (three components), which the tests compute again.
"""
import os
import vtkmodules.all as vtk
from vtkmodules.util.numpy_support import numpy_to_vtk
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
CELLS = [[0, 1, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7, 6]]
RD = b"""
  <RD format_version="6">
    <description>A test mesh: two chemicals that diffuse.</description>
    <rule name="Test rule" type="formula" neighborhood_type="edge">
      <param name="timestep">0.1</param>
      <param name="D">0.5</param>
      <formula number_of_chemicals="2">
        delta_a = D * laplacian_a;
        delta_b = D * laplacian_b;
      </formula>
    </rule>
    <initial_pattern_generator apply_when_loading="false" />
  </RD>
"""


def mesh(dtype):
    grid = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    points.SetDataType(vtk.VTK_DOUBLE if dtype == np.float64 else vtk.VTK_FLOAT)
    for i in range(8):
        points.InsertNextPoint(i % 4, i // 4, 0.125 * i)
    grid.SetPoints(points)
    for cell in CELLS:
        grid.InsertNextCell(vtk.VTK_POLYGON, len(cell), cell)
    c = np.arange(len(CELLS), dtype=np.float64)
    for name, values in (("a", 0.25 * c - 3), ("b", 1 / (c + 1)), ("v", np.stack([c, -c, 0.5 * c], axis=1))):
        array = numpy_to_vtk(values.astype(dtype), deep=True)
        array.SetName(name)
        grid.GetCellData().AddArray(array)
    return grid


def polyhedra():
    """Two unit cubes side by side as VTK_POLYHEDRON, sharing the face 1 2 6 5 (x = 1)."""
    grid = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    for z in (0, 1):
        for y, x in ((0, 0), (0, 1), (1, 1), (1, 0), (0, 2), (1, 2)):
            points.InsertNextPoint(x, y, z)
    grid.SetPoints(points)
    # points: bottom 0..5 (0 1 2 3 a square, 4 5 past it), top 6..11
    cubes = [[0, 1, 2, 3, 6, 7, 8, 9], [1, 4, 5, 2, 7, 10, 11, 8]]
    for b in cubes:
        faces = [[b[0], b[3], b[2], b[1]], [b[4], b[5], b[6], b[7]], [b[0], b[1], b[5], b[4]],
                 [b[1], b[2], b[6], b[5]], [b[2], b[3], b[7], b[6]], [b[3], b[0], b[4], b[7]]]
        stream = [len(faces)]
        for f in faces:
            stream += [len(f)] + f
        ids = vtk.vtkIdList()
        for v in stream:
            ids.InsertNextId(v)
        grid.InsertNextCell(vtk.VTK_POLYHEDRON, ids)
    a = numpy_to_vtk(np.array([0.5, 1.5], dtype=np.float32), deep=True)
    a.SetName("a")
    grid.GetCellData().AddArray(a)
    return grid


def write(name, grid, mode, compressed, header64, ids64=True, encode=True):
    writer = vtk.vtkXMLUnstructuredGridWriter()
    writer.SetInputData(grid)
    path = os.path.join(HERE, name)
    writer.SetFileName(path)
    {"ascii": writer.SetDataModeToAscii, "binary": writer.SetDataModeToBinary,
     "appended": writer.SetDataModeToAppended}[mode]()
    writer.SetEncodeAppendedData(encode)
    if compressed:
        writer.SetCompressorTypeToZLib()
        writer.SetBlockSize(64)  # several blocks for the larger arrays
    else:
        writer.SetCompressorTypeToNone()
    writer.SetHeaderTypeToUInt64() if header64 else writer.SetHeaderTypeToUInt32()
    writer.SetIdTypeToInt64() if ids64 else writer.SetIdTypeToInt32()
    writer.Write()
    data = open(path, "rb").read()
    at = data.index(b">", data.index(b"<VTKFile")) + 1
    open(path, "wb").write(data[:at] + RD + data[at:])


write("ascii-f32.vtu", mesh(np.float32), "ascii", False, False)
write("binary-f32-int32.vtu", mesh(np.float32), "binary", False, False, ids64=False)
write("binary-zlib-f64.vtu", mesh(np.float64), "binary", True, True)
write("binary-zlib-f32-uint32.vtu", mesh(np.float32), "binary", True, False)
write("appended-base64-f32.vtu", mesh(np.float32), "appended", False, True)
write("appended-base64-zlib-f64.vtu", mesh(np.float64), "appended", True, False, ids64=False)
write("appended-raw-f64-int32.vtu", mesh(np.float64), "appended", False, True, ids64=False, encode=False)
write("appended-raw-zlib-f32.vtu", mesh(np.float32), "appended", True, True, encode=False)
write("polyhedra-binary-zlib.vtu", polyhedra(), "binary", True, False)
write("polyhedra-ascii.vtu", polyhedra(), "ascii", False, False)
