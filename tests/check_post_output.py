#!/usr/bin/env python3
"""Read back everything post-macro wrote, with VTK's own XML readers and numpy, and check it
against the checkpoints and against itself (docs/post.md):
- particles (.vtu): the checkpoint's particles, stress tensors (9 components) and pressure
  (-trace/3), coordination, displacement = position - reference position matched by id (NaN for
  particles not in the reference);
- force chains (.vtp): one line per contact; pair lines join two touching spheres, wall lines end
  on a wall; forces finite, |f|^2 = f_n^2 + f_t^2;
- grid (.vti): the requested origin, spacing and size; density >= 0; every array finite except
  displacement fields (NaN only where the fit is undefined);
- tables (.csv): the region averages equal the per-particle tensors of the .vtu summed over the
  particles whose centre is in the region, times their volumes, over the region's volume; the
  stress profile's slabs add up to the same; counts add up.
Usage: check_post_output.py OUTDIR CURRENT.h5 REFERENCE.h5 CELL REGION_LO(x,y,z) REGION_HI(x,y,z)"""
import csv
import sys

import h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader


def read(reader_cls, path):
    r = reader_cls()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def arr(data, name, cells=False):
    a = (data.GetCellData() if cells else data.GetPointData()).GetArray(name)
    assert a is not None, f"missing {'cell' if cells else 'point'} array {name}"
    return vtk_to_numpy(a)


def table(path):
    with open(path) as f:
        assert f.readline().startswith("# "), f"{path}: first line is a comment"
        rows = list(csv.DictReader(f))
    return rows


def tensor(row):
    return np.array([[float(row[f"s{a}{b}"]) for b in "xyz"] for a in "xyz"])


def main(out, cur_path, ref_path, cell, lo, hi):
    cell = float(cell)
    lo = np.array([float(v) for v in lo.split(",")])
    hi = np.array([float(v) for v in hi.split(",")])
    with h5py.File(cur_path, "r") as f, h5py.File(ref_path, "r") as g:
        ids = f["particles/id"][:]
        x = f["particles/position"][:]
        radius = f["particles/radius"][:]
        ref = dict(zip(g["particles/id"][:], g["particles/position"][:]))
        walls = f["walls/vertices"][:]
    n = len(ids)

    # Particles.
    p = read(vtkXMLUnstructuredGridReader, f"{out}/particles.vtu")
    assert np.array_equal(arr(p, "id"), ids)
    assert np.array_equal(vtk_to_numpy(p.GetPoints().GetData()), x)
    stress = arr(p, "stress").reshape(n, 3, 3)
    assert p.GetPointData().GetArray("stress").GetNumberOfComponents() == 9
    assert np.allclose(arr(p, "pressure"), -np.trace(stress, axis1=1, axis2=2) / 3, rtol=1e-12, atol=0)
    coord = arr(p, "coordination")
    assert coord.min() >= 0 and coord.sum() > 0
    u = arr(p, "displacement")
    want = np.array([x[k] - ref[i] if i in ref else [np.nan] * 3 for k, i in enumerate(ids)])
    assert np.array_equal(np.isnan(u), np.isnan(want)) and np.array_equal(u[~np.isnan(u)], want[~np.isnan(want)])

    # Force chains.
    c = read(vtkXMLPolyDataReader, f"{out}/chains.vtp")
    pts = vtk_to_numpy(c.GetPoints().GetData())
    lines = vtk_to_numpy(c.GetLines().GetConnectivityArray()).reshape(-1, 2)
    nl = len(lines)
    assert nl == c.GetNumberOfCells() and nl > 0
    wall = arr(c, "wall", True)
    fmag, fn, ft = arr(c, "force_magnitude", True), arr(c, "normal_force", True), arr(c, "tangential_force", True)
    force = arr(c, "force", True)
    assert np.all(np.isfinite(force)) and np.allclose(np.linalg.norm(force, axis=1), fmag, rtol=1e-12, atol=0)
    assert np.allclose(fmag**2, fn**2 + ft**2, rtol=1e-9, atol=1e-12 * fmag.max() ** 2)
    pair = wall < 0
    i, j = lines[pair, 0], lines[pair, 1]
    assert np.all(np.linalg.norm(x[j] - x[i], axis=1) < radius[i] + radius[j]), "pair lines join touching spheres"
    assert np.all(lines[~pair, 1] >= n), "wall lines end on points after the particles"
    wp = pts[lines[~pair, 1]]
    for k, w in zip(np.nonzero(~pair)[0], wall[~pair].astype(int)):
        v = walls[w][:3]
        normal = np.cross(v[1] - v[0], v[2] - v[0])
        assert abs(np.dot(pts[lines[k, 1]] - v[0], normal / np.linalg.norm(normal))) < 1e-12, "wall contact point on the wall's plane"
    assert len(wp) == np.count_nonzero(~pair)

    # Grid.
    im = read(vtkXMLImageDataReader, f"{out}/grid.vti")
    assert np.allclose(im.GetSpacing(), [cell] * 3) and np.allclose(im.GetOrigin(), lo)
    dims = np.array(im.GetDimensions())
    assert np.array_equal(dims, np.ceil((hi - lo) / cell - 1e-9).astype(int) + 1), f"grid dims {dims}"
    rho = arr(im, "density")
    assert rho.min() >= 0 and rho.max() > 0
    for name, comps in (("solid_fraction", 1), ("velocity", 3), ("stress", 9), ("pressure", 1)):
        a = arr(im, name)
        assert a.size == dims.prod() * comps and np.all(np.isfinite(a)), name
    disp = arr(im, "displacement")
    grad = arr(im, "displacement_gradient").reshape(-1, 3, 3)
    strain = arr(im, "strain").reshape(-1, 3, 3)
    ok = np.all(np.isfinite(disp), axis=1)
    assert ok.any(), "the displacement fit is defined somewhere"
    assert np.allclose(strain[ok], 0.5 * (grad[ok] + grad[ok].transpose(0, 2, 1)), rtol=1e-12, atol=1e-15)
    assert np.allclose(arr(im, "volumetric_strain")[ok], np.trace(strain[ok], axis1=1, axis2=2), rtol=1e-12, atol=1e-15)

    # Tables: region averages from the per-particle tensors.
    volume = 4.0 / 3.0 * np.pi * radius**3
    moment = stress * volume[:, None, None]
    rows = table(f"{out}/averages.csv")
    assert len(rows) == 2
    for r in rows:
        blo = np.array([float(r[k]) for k in ("x_lo", "y_lo", "z_lo")])
        bhi = np.array([float(r[k]) for k in ("x_hi", "y_hi", "z_hi")])
        inside = np.all((x >= blo) & (x <= bhi), axis=1)
        V = np.prod(bhi - blo)
        assert int(r["count"]) == inside.sum()
        want = moment[inside].sum(axis=0) / V
        got = tensor(r)
        assert np.allclose(got, want, rtol=1e-8, atol=1e-9 * np.abs(want).max()), f"region average\n{got}\n{want}"
        assert np.isclose(float(r["solid_fraction"]), volume[inside].sum() / V, rtol=1e-8)
    prof = table(f"{out}/stress_profile.csv")
    inside = np.all((x >= lo) & (x <= hi), axis=1)
    assert sum(int(r["count"]) for r in prof) == inside.sum()
    total = sum(tensor(r) * (float(r["z_hi"]) - float(r["z_lo"])) for r in prof) / (hi[2] - lo[2])
    want = moment[inside].sum(axis=0) / np.prod(hi - lo)
    assert np.allclose(total, want, rtol=1e-8, atol=1e-9 * np.abs(want).max()), "slabs add up to the region"
    print(f"post-macro outputs ok: {n} particles, {nl} contact lines ({np.count_nonzero(~pair)} on walls), grid {dims.tolist()}, "
          f"{ok.sum()} nodes with a displacement fit")


if __name__ == "__main__":
    main(*sys.argv[1:])
