#!/usr/bin/python3
"""Ready's neighbour lists of a mesh, computed through VTK itself.

A line-by-line port of Ready's MeshRD::ComputeCellNeighbors (its
src/readybase/MeshRD.cpp) to Python, making the same calls on
vtkUnstructuredGrid as Ready does (GetCellPoints, GetCell, GetEdge, GetFace,
GetCellNeighbors) on Debian's VTK (python3-vtk9), so that what figgen's
sim/mesh/mesh.cpp computes without VTK can be checked against VTK's order.

    /usr/bin/python3 ready_neighbours.py MESH.vtu vertex|edge|face [OUT.json]

Writes (or prints) {"cells", "max_neighbors", "indices", "weights"}: the
padded arrays Ready hands its kernel, the weights as the floats Ready holds
(each the shortest decimal that reads back as that float).
"""
import json
import struct
import sys

import numpy
import vtkmodules.all as vtk


def f32(x):
    return struct.unpack('<f', struct.pack('<f', x))[0]


def neighbours(mesh, kind):
    if not mesh.IsHomogeneous():
        raise SystemExit('mixed cell types: Ready refuses them')
    pt_ids = vtk.vtkIdList()
    cell_ids = vtk.vtkIdList()
    edge_neighbours = {}  # IsEdgeNeighbor's answers, each cell's set computed once

    def ids(id_list):
        return [id_list.GetId(i) for i in range(id_list.GetNumberOfIds())]

    def is_edge_neighbour(c1, c2):
        if c1 not in edge_neighbours:
            found = set()
            cell = mesh.GetCell(c1)
            for e in range(cell.GetNumberOfEdges()):
                mesh.GetCellNeighbors(c1, cell.GetEdge(e).GetPointIds(), cell_ids)
                found.update(ids(cell_ids))
            edge_neighbours[c1] = found
        return c2 in edge_neighbours[c1]

    def add_if_new(found, n):
        if n not in found:
            found.append(n)

    lists = []
    max_neighbors = 0
    for c in range(mesh.GetNumberOfCells()):
        found = []
        mesh.GetCellPoints(c, pt_ids)
        points = ids(pt_ids)
        if kind == 'vertex':
            one = vtk.vtkIdList()
            one.SetNumberOfIds(1)
            while True:
                before = len(found)
                for p in points:
                    one.SetId(0, p)
                    mesh.GetCellNeighbors(c, one, cell_ids)
                    for n in ids(cell_ids):
                        if not found or is_edge_neighbour(found[-1], n):
                            add_if_new(found, n)
                if len(found) <= before:
                    break
            for p in points:
                one.SetId(0, p)
                mesh.GetCellNeighbors(c, one, cell_ids)
                for n in ids(cell_ids):
                    add_if_new(found, n)
        elif kind == 'edge':
            cell = mesh.GetCell(c)
            for e in range(cell.GetNumberOfEdges()):
                mesh.GetCellNeighbors(c, cell.GetEdge(e).GetPointIds(), cell_ids)
                for n in ids(cell_ids):
                    add_if_new(found, n)
        elif kind == 'face':
            cell = mesh.GetCell(c)
            for f in range(cell.GetNumberOfFaces()):
                mesh.GetCellNeighbors(c, cell.GetFace(f).GetPointIds(), cell_ids)
                for n in ids(cell_ids):
                    add_if_new(found, n)
        else:
            raise SystemExit('kind: vertex, edge or face')
        lists.append(found)
        max_neighbors = max(max_neighbors, len(found), 1)
    indices, weights = [], []
    for c, found in enumerate(lists):
        total = f32(0.0)
        for _ in found:
            total = f32(total + f32(1.0))
        total = max(total, f32(1e-5))
        w = f32(f32(1.0) / total)
        indices += found + [c] * (max_neighbors - len(found))
        weights += [w] * len(found) + [0.0] * (max_neighbors - len(found))
    # Each weight as the shortest decimal that reads back as its float.
    weights = [float(numpy.format_float_positional(numpy.float32(w))) for w in weights]
    return {'cells': mesh.GetNumberOfCells(), 'max_neighbors': max_neighbors, 'indices': indices, 'weights': weights}


def read_mesh(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode():
        raise SystemExit('VTK could not read ' + path)
    mesh = vtk.vtkUnstructuredGrid()
    mesh.DeepCopy(reader.GetOutput())  # as MeshRD::CopyFromMesh does
    return mesh


if __name__ == '__main__':
    result = neighbours(read_mesh(sys.argv[1]), sys.argv[2])
    text = json.dumps(result, separators=(',', ':'))
    if len(sys.argv) > 3:
        with open(sys.argv[3], 'w') as out:
            out.write(text)
    else:
        print(text)
