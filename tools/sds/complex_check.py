"""The validity of an SDS complex read from a run's VTU frame (issue 13).

check(path) reads sds/frame_NNNN.vtu and returns a dict: X (cells' positions),
T (tets), vol (signed volumes), faces_over_2 (faces in more than two tets:
none in a valid complex), closed (every boundary edge once in each direction:
a closed, consistently oriented boundary).  Used by tests/sds/test_sds_cli.sh
and tests/sds/test_sds_models.sh."""
import collections

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def sides(t):
    """The four faces of tet t, each oriented outward."""
    return ((t[1], t[2], t[3]), (t[0], t[3], t[2]), (t[0], t[1], t[3]), (t[0], t[2], t[1]))


def check(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    X = vtk_to_numpy(g.GetPoints().GetData()).astype(float)
    T = vtk_to_numpy(g.GetCells().GetData()).reshape(-1, 5)[:, 1:]
    a, b, c, d = (X[T[:, k]] for k in range(4))
    vol = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6
    faces, edges = collections.Counter(), collections.Counter()
    for t in T:
        for f in sides(t):
            faces[tuple(sorted(f))] += 1
    for t in T:
        for f in sides(t):
            if faces[tuple(sorted(f))] == 1:
                for i in range(3):
                    edges[(f[i], f[(i + 1) % 3])] += 1
    closed = all(n == 1 and edges.get((e[1], e[0]), 0) == 1 for e, n in edges.items())
    return {"X": X, "T": T, "vol": vol, "faces_over_2": sum(n > 2 for n in faces.values()), "closed": closed}
