#!/usr/bin/python3
"""Writes the meshes and the neighbour lists tests/sim/mesh/test_mesh.cpp
checks figgen's against: Ready's lists as VTK itself makes them
(ready_neighbours.py, Debian's python3-vtk9), for every kind of
neighbourhood, on small meshes of every cell type figgen reads: patches of
three of Ready's own meshes (Penrose rhombs and a bunny's triangles as
VTK_POLYGON, FCC3333's polyhedra) and small meshes of each fixed type.

    /usr/bin/python3 tests/sim/mesh/make_fixtures.py READY/Patterns

Each mesh is NAME.vtu (VTK's writer, binary, zlib); expected.json holds,
for each mesh and kind, {"max_neighbors", "indices", "weights"}.
"""
import json
import math
import os
import sys

import vtkmodules.all as vtk

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import ready_neighbours  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def centre(grid, c):
    ids = vtk.vtkIdList()
    grid.GetCellPoints(c, ids)
    n = ids.GetNumberOfIds()
    return [sum(grid.GetPoint(ids.GetId(i))[k] for i in range(n)) / n for k in range(3)]


def patch(path, count, about=None):
    """The `count` cells nearest cell `about` (default: the one with the most vertex neighbours)."""
    grid = ready_neighbours.read_mesh(path)
    if about is None:
        lists = ready_neighbours.neighbours(grid, 'vertex')
        m = lists['max_neighbors']
        about = max(range(grid.GetNumberOfCells()),
                    key=lambda c: sum(1 for w in lists['weights'][c * m:(c + 1) * m] if w > 0))
    x = centre(grid, about)
    nearest = sorted(range(grid.GetNumberOfCells()), key=lambda c: (math.dist(centre(grid, c), x), c))[:count]
    ids = vtk.vtkIdList()
    for c in sorted(nearest):
        ids.InsertNextId(c)
    extract = vtk.vtkExtractCells()
    extract.SetInputData(grid)
    extract.SetCellList(ids)
    extract.Update()
    out = extract.GetOutput()
    # Only the chemicals: VTK's bookkeeping arrays are not Ready's.
    out.GetCellData().RemoveArray('vtkOriginalCellIds')
    out.GetPointData().RemoveArray('vtkOriginalPointIds')
    return out


def lattice(nx, ny, nz):
    points = vtk.vtkPoints()
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                points.InsertNextPoint(x, y, z)
    return points, lambda x, y, z: x + nx * (y + ny * z)


def fixed(kind):
    """A few cells of one fixed type, sharing points, edges and faces."""
    grid = vtk.vtkUnstructuredGrid()
    if kind in ('triangles', 'quads'):
        points, at = lattice(4, 4, 1)
        grid.SetPoints(points)
        for y in range(3):
            for x in range(3):
                a, b, c, d = at(x, y, 0), at(x + 1, y, 0), at(x + 1, y + 1, 0), at(x, y + 1, 0)
                if kind == 'quads':
                    grid.InsertNextCell(vtk.VTK_QUAD, 4, [a, b, c, d])
                elif (x + y) % 2:
                    grid.InsertNextCell(vtk.VTK_TRIANGLE, 3, [a, b, c])
                    grid.InsertNextCell(vtk.VTK_TRIANGLE, 3, [a, c, d])
                else:
                    grid.InsertNextCell(vtk.VTK_TRIANGLE, 3, [a, b, d])
                    grid.InsertNextCell(vtk.VTK_TRIANGLE, 3, [b, c, d])
    elif kind in ('voxels', 'hexahedra', 'pyramids'):
        points, at = lattice(3, 3, 3)
        grid.SetPoints(points)
        for z in range(2):
            for y in range(2):
                for x in range(2):
                    v = [at(x + i, y + j, z + k) for k in (0, 1) for j in (0, 1) for i in (0, 1)]
                    h = [v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]]
                    if kind == 'voxels':
                        grid.InsertNextCell(vtk.VTK_VOXEL, 8, v)
                    elif kind == 'hexahedra':
                        grid.InsertNextCell(vtk.VTK_HEXAHEDRON, 8, h)
                    elif (x, y, z) in ((0, 0, 0), (1, 0, 0)):
                        # six pyramids about the cube's centre, one on each face
                        middle = grid.GetPoints().InsertNextPoint(x + 0.5, y + 0.5, z + 0.5)
                        for f in ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)):
                            grid.InsertNextCell(vtk.VTK_PYRAMID, 5, [h[i] for i in f] + [middle])
    elif kind == 'tetra':
        voxels = fixed('voxels')
        tetra = vtk.vtkDataSetTriangleFilter()
        tetra.SetInputData(voxels)
        tetra.Update()
        grid.DeepCopy(tetra.GetOutput())
    elif kind == 'wedges':
        points, at = lattice(3, 3, 3)
        grid.SetPoints(points)
        for z in range(2):
            for y in range(2):
                for x in range(2):
                    a, b, c, d = at(x, y, z), at(x + 1, y, z), at(x + 1, y + 1, z), at(x, y + 1, z)
                    up = at(0, 0, 1)
                    for t in ((a, b, c), (a, c, d)):
                        grid.InsertNextCell(vtk.VTK_WEDGE, 6, list(t) + [p + up for p in t])
    a = vtk.vtkFloatArray()
    a.SetName('a')
    a.SetNumberOfTuples(grid.GetNumberOfCells())
    a.Fill(0.5)
    grid.GetCellData().AddArray(a)
    return grid


def main(patterns):
    meshes = {
        'penrose': patch(os.path.join(patterns, 'CellularAutomata/PenroseTilings/life.vtu'), 100, about=1500),
        'bunny': patch(os.path.join(patterns, 'GrayScott1984/bunny.vtu'), 80),
        'fcc': patch(os.path.join(patterns, 'CellularAutomata/FCC3333/random.vtu'), 40, about=6750),
    }
    for kind in ('triangles', 'quads', 'tetra', 'voxels', 'hexahedra', 'wedges', 'pyramids'):
        meshes[kind] = fixed(kind)
    expected = {}
    for name, grid in meshes.items():
        path = os.path.join(HERE, name + '.vtu')
        writer = vtk.vtkXMLUnstructuredGridWriter()
        writer.SetInputData(grid)
        writer.SetFileName(path)
        writer.SetDataModeToBinary()
        writer.Write()
        again = ready_neighbours.read_mesh(path)  # the lists of the file as the test reads it
        expected[name] = {k: ready_neighbours.neighbours(again, k) for k in ('vertex', 'edge', 'face')}
        for k, v in expected[name].items():
            del v['cells']
    with open(os.path.join(HERE, 'expected.json'), 'w') as out:
        json.dump(expected, out, separators=(',', ':'))
        out.write('\n')


if __name__ == '__main__':
    main(sys.argv[1])
