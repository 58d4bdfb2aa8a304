#!/usr/bin/python3
"""An SDS run's surface with its rock, as a `sessile render` scene.

    /usr/bin/python3 tools/sds/rock_scene.py RUN OUT_DIR [--frame N]

Reads RUN/sds/model.sds (its `rock = x y z radius` line) and the surface
PLY of frame N (default: RUN/sds/final.ply), and writes OUT_DIR/meshes.ply
(the organism, then the rock as a UV sphere) and OUT_DIR/scene.json (the
organism sand-coloured, the rock grey; docs/render.md, "Scenes"), which
`sessile render OUT_DIR/scene.json -o PICTURE.png` draws.  The rock is drawn
from its centre and radius, not the run's obstacle mesh (an icosphere of
level 4, or the symmetric start's sphere): the same sphere to the eye.
Needs Debian's python3-vtk9.
"""
import argparse
import json
import os
import sys

import vtk


def rock_of(model_path):
    with open(model_path, encoding="utf-8") as f:
        for line in f:
            words = line.split("#", 1)[0].split()
            if len(words) == 6 and words[0] == "rock" and words[1] == "=":
                return [float(w) for w in words[2:]]
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run")
    ap.add_argument("out")
    ap.add_argument("--frame", type=int, default=None, help="frame number (default: the final surface)")
    a = ap.parse_args()
    sds = os.path.join(a.run, "sds")
    rock = rock_of(os.path.join(sds, "model.sds"))
    if rock is None:
        sys.exit("rock_scene: %s has no rock line" % os.path.join(sds, "model.sds"))
    ply = os.path.join(sds, "final.ply" if a.frame is None else "frame_%04d.ply" % a.frame)
    if not os.path.isfile(ply):
        sys.exit("rock_scene: no %s" % ply)
    rd = vtk.vtkPLYReader()
    rd.SetFileName(ply)
    rd.Update()
    body = vtk.vtkTriangleFilter()
    body.SetInputData(rd.GetOutput())
    body.Update()
    sph = vtk.vtkSphereSource()
    sph.SetCenter(*rock[:3])
    sph.SetRadius(rock[3])
    sph.SetThetaResolution(96)
    sph.SetPhiResolution(48)
    sph.Update()
    b, r = body.GetOutput(), sph.GetOutput()
    app = vtk.vtkAppendPolyData()
    app.AddInputData(b)
    app.AddInputData(r)
    app.Update()
    merged = vtk.vtkPolyData()
    merged.SetPoints(app.GetOutput().GetPoints())
    merged.SetPolys(app.GetOutput().GetPolys())
    os.makedirs(a.out, exist_ok=True)
    w = vtk.vtkPLYWriter()
    w.SetFileName(os.path.join(a.out, "meshes.ply"))
    w.SetInputData(merged)
    w.SetFileTypeToBinary()
    if not w.Write():
        sys.exit("rock_scene: cannot write %s" % os.path.join(a.out, "meshes.ply"))
    nb, nbf = b.GetNumberOfPoints(), b.GetNumberOfPolys()
    ident = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    scene = {
        "format": "sessile render scene", "version": 1, "mesh": "meshes.ply",
        "parts": [[0, nb, 0, nbf], [nb, r.GetNumberOfPoints(), nbf, r.GetNumberOfPolys()]],
        "instances": [{"part": 0, "rgb": [214, 190, 140], "matrix": ident},
                      {"part": 1, "rgb": [120, 120, 125], "matrix": ident}],
    }
    with open(os.path.join(a.out, "scene.json"), "w", encoding="utf-8") as f:
        json.dump(scene, f)
        f.write("\n")
    print("rock_scene: %s: %d body vertices, rock at %s radius %g" % (a.out, nb, rock[:3], rock[3]))


if __name__ == "__main__":
    main()
