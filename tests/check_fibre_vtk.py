#!/usr/bin/env python3
"""Read the fibre frames run-stage wrote with VTK's own XML reader and check them against the
checkpoint: the .pvd lists existing frames with increasing times; the last frame holds one line per
segment, from tie point to tie point (particle position + tie offset, matched by id), with the
checkpoint's broken flags, zero tension where broken, and tension >= 0 everywhere."""
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader


def main(vtk_dir, stage, ckpt_path):
    pvd = os.path.join(vtk_dir, f"{stage}_fibres.pvd")
    sets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    times = [float(d.get("timestep")) for d in sets]
    assert len(sets) >= 2 and all(np.diff(times) > 0), f"{pvd}: times {times}"
    files = [os.path.join(vtk_dir, d.get("file")) for d in sets]
    assert all(os.path.isfile(f) for f in files), f"{pvd} lists missing files"
    r = vtkXMLPolyDataReader()
    r.SetFileName(files[-1])
    r.Update()
    poly = r.GetOutput()
    with h5py.File(ckpt_path, "r") as h:
        first = h["fibres/first_tie"][()]
        tie_id = h["fibres/tie_particle"][()]
        offset = h["fibres/tie_offset"][()]
        broken = h["fibres/segment_broken"][()]
        pos = dict(zip(h["particles/id"][()], h["particles/position"][()]))
    nseg = len(broken)
    assert poly.GetNumberOfLines() == nseg, (poly.GetNumberOfLines(), nseg)
    pts = vtk_to_numpy(poly.GetPoints().GetData())
    cd = poly.GetCellData()
    tension = vtk_to_numpy(cd.GetArray("tension"))
    vtk_broken = vtk_to_numpy(cd.GetArray("broken"))
    fibre = vtk_to_numpy(cd.GetArray("fibre"))
    assert np.array_equal(vtk_broken.astype(int), broken.astype(int)), "broken flags differ from the checkpoint"
    assert np.all(tension >= 0) and np.all(tension[broken == 1] == 0), "tension negative, or carried by a broken segment"
    s = 0
    for f in range(len(first) - 1):
        for t in range(first[f], first[f + 1] - 1):
            assert fibre[s] == f
            for end, tie in ((0, t), (1, t + 1)):
                expect = pos[tie_id[tie]] + offset[tie]
                assert np.allclose(pts[2 * s + end], expect, rtol=0, atol=1e-12), (s, end, pts[2 * s + end], expect)
            s += 1
    print(f"{files[-1]}: {nseg} segments, {int(broken.sum())} broken, largest tension {tension.max():.4g} N; {len(sets)} frames")


if __name__ == "__main__":
    main(*sys.argv[1:4])
