#!/usr/bin/env python3
"""Read back every VTK file run-stage and post-macro wrote, with VTK's own XML readers, and check
them against the checkpoint: each .pvd lists existing frames with increasing times; the last
particle frame holds exactly the checkpoint's particles (ids, radii, positions, velocities); wall
frames hold one polygon per wall at the checkpoint's vertices; the displacement file matches
positions minus the reference checkpoint's positions, matched by id."""
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader


def read(reader_cls, path):
    r = reader_cls()
    r.SetFileName(path)
    r.Update()
    out = r.GetOutput()
    assert out is not None and out.GetNumberOfPoints() >= 0, path
    return out


def arr(data, name):
    a = data.GetPointData().GetArray(name)
    assert a is not None, f"missing point array {name}"
    return vtk_to_numpy(a)


def main(vtk_dir, stage, ckpt_path, ref_path, disp_path):
    frames = {}
    for kind in ("particles", "walls"):
        pvd = os.path.join(vtk_dir, f"{stage}_{kind}.pvd")
        sets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
        times = [float(d.get("timestep")) for d in sets]
        assert len(sets) >= 2 and all(np.diff(times) > 0), f"{pvd}: times {times}"
        files = [os.path.join(vtk_dir, d.get("file")) for d in sets]
        assert all(os.path.isfile(f) for f in files), f"{pvd} lists missing files"
        frames[kind] = (times, files)
    with h5py.File(ckpt_path, "r") as f, h5py.File(ref_path, "r") as g:
        ids = f["particles/id"][:]
        t = f["state/time"][0]
        assert frames["particles"][0][-1] == t, "last frame at the checkpoint time"
        for path in frames["particles"][1]:
            data = read(vtkXMLUnstructuredGridReader, path)
            assert data.GetNumberOfCells() == data.GetNumberOfPoints()
            for name in ("id", "radius", "velocity", "angular_velocity", "material", "displacement"):
                arr(data, name)
        last = read(vtkXMLUnstructuredGridReader, frames["particles"][1][-1])
        assert np.array_equal(arr(last, "id"), ids)
        assert np.array_equal(arr(last, "radius"), f["particles/radius"][:])
        assert np.array_equal(vtk_to_numpy(last.GetPoints().GetData()), f["particles/position"][:])
        assert np.array_equal(arr(last, "velocity"), f["particles/velocity"][:])
        assert np.array_equal(arr(last, "material"), f["particles/material"][:])
        walls = read(vtkXMLPolyDataReader, frames["walls"][1][-1])
        nw = f["walls/name"].shape[0]
        assert walls.GetNumberOfCells() == nw
        verts = f["walls/vertices"][:]
        counts = f["walls/vertex_count"][:]
        pts = vtk_to_numpy(walls.GetPoints().GetData())
        expected = np.concatenate([verts[w, : counts[w]] for w in range(nw)])
        assert np.allclose(pts, expected, rtol=0, atol=1e-15), "wall vertices at the checkpoint time"

        disp = read(vtkXMLUnstructuredGridReader, disp_path)
        ref = dict(zip(g["particles/id"][:], g["particles/position"][:]))
        u = arr(disp, "displacement")
        x = f["particles/position"][:]
        want = np.array([x[k] - ref[i] if i in ref else [np.nan] * 3 for k, i in enumerate(ids)])
        assert np.array_equal(np.isnan(u), np.isnan(want)) and np.allclose(u[~np.isnan(u)], want[~np.isnan(want)], rtol=0, atol=0)
    print(f"VTK ok: {len(frames['particles'][1])} particle frames, {len(frames['walls'][1])} wall frames, displacement of {len(ids)} particles")


if __name__ == "__main__":
    main(*sys.argv[1:])
