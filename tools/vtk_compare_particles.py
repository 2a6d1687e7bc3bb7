#!/usr/bin/env python3
"""Reads two particle outputs (.pvtu) with VTK, the library ParaView reads
them with, and compares them point by point (matched by id): the number of
points and cells, the arrays and their values. Used to check that the
several pieces per file of scarp's particle output
(doc/performance/memory.md, "Memory") read as one data set, against a run
written with one piece per rank.

    /usr/bin/python3 tools/vtk_compare_particles.py A/particles_00001.pvtu B/particles_00001.pvtu

Needs VTK's Python bindings (Debian: python3-vtk9), which scarp itself does
not need; exits 1 if the two differ.
"""
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def load(path):
    reader = vtk.vtkXMLPUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    data = grid.GetPointData()
    arrays = {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i))
              for i in range(data.GetNumberOfArrays())}
    arrays["(points)"] = vtk_to_numpy(grid.GetPoints().GetData())
    return grid.GetNumberOfPoints(), grid.GetNumberOfCells(), arrays


def main():
    (na, ca, a), (nb, cb, b) = load(sys.argv[1]), load(sys.argv[2])
    print("points %d / %d, cells %d / %d, arrays %d / %d" %
          (na, nb, ca, cb, len(a), len(b)))
    same = na == nb and ca == cb and sorted(a) == sorted(b) and na > 0
    if same:
        oa, ob = np.argsort(a["id"]), np.argsort(b["id"])
        worst = max(float(np.abs(a[k][oa] - b[k][ob]).max()) for k in a)
        print("largest difference of any array at any point: %g" % worst)
        same = worst == 0.
    print("same" if same else "DIFFERENT")
    sys.exit(0 if same else 1)


if __name__ == "__main__":
    main()
