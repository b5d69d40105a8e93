#!/usr/bin/env python3
"""Open a checkpoint written by the tools with h5py and check it against docs/checkpoint.md:
root attributes, every documented dataset with its dtype kind, shape and units attribute."""
import sys

import h5py
import numpy as np


def main(path, expect_writer):
    with h5py.File(path, "r") as f:
        assert f.attrs["format"] == b"dem-checkpoint", f.attrs["format"]
        assert int(f.attrs["schema_version"]) == 4
        assert f.attrs["writer"].decode() == expect_writer, f.attrs["writer"]
        assert len(f.attrs["writer_version"]) > 0
        assert len(f.attrs["writer_commit"]) > 0  # git describe of the build, or "unknown"

        n = f["particles/id"].shape[0]
        m = f["materials/name"].shape[0]
        w = f["walls/name"].shape[0]
        npairs = f["pairs/materials"].shape[0]
        assert n > 0 and m > 0
        # path: (dtype kind, shape, units or None)
        spec = {
            "scene/text": ("S", (1,), None), "scene/path": ("S", (1,), None), "scene/walls": ("S", (1,), None),
            "scene/files": ("S", (f["scene/files"].shape[0],), None),
            "run/input_path": ("S", (1,), None), "run/input_seal": ("S", (1,), None),
            "state/time": ("f", (1,), "s"), "state/step": ("i", (1,), None), "state/dt": ("f", (1,), "s"),
            "state/gravity": ("f", (1, 3), "m/s^2"), "state/alpha_r": ("f", (1,), "1/s"),
            "state/alpha_theta": ("f", (1,), "1/s"), "state/periodic": ("i", (3,), None),
            "state/periodic_lo": ("f", (1, 3), "m"), "state/periodic_hi": ("f", (1, 3), "m"),
            "run/stage": ("S", (1,), None), "run/stage_start_step": ("i", (1,), None),
            "run/stage_steps": ("i", (1,), None), "run/stage_start_time": ("f", (1,), "s"),
            "particles/id": ("i", (n,), None), "particles/position": ("f", (n, 3), "m"),
            "particles/velocity": ("f", (n, 3), "m/s"), "particles/angular_velocity": ("f", (n, 3), "rad/s"),
            "particles/reference_position": ("f", (n, 3), "m"), "particles/image": ("i", (n, 3), None),
            "particles/radius": ("f", (n,), "m"),
            "particles/mass": ("f", (n,), "kg"), "particles/material": ("i", (n,), None),
            "particles/fixed": ("u", (n,), None),
            "materials/name": ("S", (m,), None), "materials/density": ("f", (m,), "kg/m^3"),
            "materials/kn": ("f", (m,), "N/m"), "materials/kt": ("f", (m,), "N/m"),
            "materials/friction_angle": ("f", (m,), "degree"), "materials/restitution": ("f", (m,), "1"),
            "materials/tangential_restitution": ("f", (m,), "1"), "materials/mixing": ("i", (4,), None),
            "materials/tensile_strength": ("f", (m,), "N"), "materials/cohesion": ("f", (m,), "N"),
            "materials/epsilon": ("f", (m,), "1"), "materials/law": ("i", (m,), None),
            "materials/tangential": ("i", (m,), None), "pairs/tangential": ("i", (npairs,), None),
            "materials/rolling": ("i", (m,), None), "pairs/rolling": ("i", (npairs,), None),
            "materials/rolling_friction": ("f", (m,), "1"), "pairs/rolling_friction": ("f", (npairs,), "1"),
            "materials/no_viscous_attraction": ("i", (m,), None),
            "materials/young_modulus": ("f", (m,), "Pa"), "materials/poisson_ratio": ("f", (m,), "1"),
            "pairs/young_modulus": ("f", (npairs,), "Pa"), "pairs/poisson_ratio": ("f", (npairs,), "1"),
            "pairs/materials": ("i", (npairs, 2), None), "pairs/law": ("i", (npairs,), None),
            "pairs/kn": ("f", (npairs,), "N/m"), "pairs/kt": ("f", (npairs,), "N/m"),
            "pairs/friction_angle": ("f", (npairs,), "degree"), "pairs/restitution": ("f", (npairs,), "1"),
            "pairs/tangential_restitution": ("f", (npairs,), "1"), "pairs/tensile_strength": ("f", (npairs,), "N"),
            "pairs/cohesion": ("f", (npairs,), "N"), "pairs/epsilon": ("f", (npairs,), "1"),
            "pairs/no_viscous_attraction": ("i", (npairs,), None),
            "walls/name": ("S", (w,), None), "walls/material": ("i", (w,), None),
            "walls/vertex_count": ("i", (w,), None), "walls/base_vertices": ("f", (w, 4, 3), "m"),
            "walls/vertices": ("f", (w, 4, 3), "m"), "walls/motion_table": ("i", (w,), None),
            "walls/motion_centre": ("f", (w, 3), "m"), "walls/motion_axis": ("f", (w, 3), "1"),
            "walls/motion_angular_speed": ("f", (w,), "rad/s"),
            "walls/motion_velocity": ("f", (w, 3), "m/s"), "walls/motion_direction": ("f", (w, 3), "1"),
            "walls/motion_frequency": ("f", (w,), "Hz"), "walls/motion_amplitude": ("f", (w,), "m"),
            "walls/motion_t0": ("f", (w,), "s"),
        }
        for name, (kind, shape, units) in spec.items():
            d = f[name]
            assert d.dtype.kind == kind, f"{name}: dtype {d.dtype}, expected kind {kind}"
            assert d.shape == shape, f"{name}: shape {d.shape}, expected {shape}"
            got = d.attrs.get("units")
            if units is None:
                assert got is None, f"{name}: unexpected units {got}"
            else:
                assert got is not None and got.decode() == units, f"{name}: units {got}, expected {units}"
            if d.size > 0:
                assert d.fletcher32, f"{name}: no Fletcher32 checksum"
        for name in ("contacts/pair_ids", "contacts/wall_ids"):
            assert f[name].dtype.kind == "i" and f[name].ndim == 2 and f[name].shape[1] == 2, name
        assert f["contacts/pair_spring"].shape == (f["contacts/pair_ids"].shape[0], 3)
        assert f["contacts/wall_spring"].shape == (f["contacts/wall_ids"].shape[0], 3)
        assert f["contacts/pair_spring"].attrs["units"] == b"N"
        for kind in ("pair", "wall"):
            assert f[f"contacts/{kind}_rolling"].shape == (f[f"contacts/{kind}_ids"].shape[0], 3)
            assert f[f"contacts/{kind}_rolling"].attrs["units"] == b"N m"
        assert f["contacts/pair_bonded"].shape == (f["contacts/pair_ids"].shape[0],)
        assert f["contacts/wall_bonded"].shape == (f["contacts/wall_ids"].shape[0],)
        assert f["contacts/pair_bonded"].dtype == np.uint8
        for name, units in (("run/frame_times", b"s"), ("run/servo_integral", b"m/s")):
            assert f[name].dtype.kind == "f" and f[name].ndim == 1 and f[name].attrs["units"] == units, name
        # Per [[stage.insert]] group: particles inserted and particle-events deferred (none outside run-stage).
        ins = f["run/insert_count"]
        assert ins.dtype.kind == "i" and ins.ndim == 1 and "units" not in ins.attrs, "run/insert_count"
        assert f["run/insert_deferred"].dtype.kind == "i" and f["run/insert_deferred"].shape == ins.shape, "run/insert_deferred"
        assert (ins[()] >= 0).all() and (f["run/insert_deferred"][()] >= 0).all()
        # Intact bonds when the stage began (the health log's broken count), -1 outside run-stage.
        sb = f["run/stage_start_bonds"]
        assert sb.dtype.kind == "i" and sb.shape == (1,) and "units" not in sb.attrs, "run/stage_start_bonds"
        assert sb[0] >= 0 if expect_writer == "run-stage" else sb[0] == -1, sb[0]

        # [stage.sink]: particles removed so far and their mass (0 without a sink).
        sc, sm = f["run/sink_count"], f["run/sink_mass"]
        assert sc.dtype.kind == "i" and sc.shape == (1,) and "units" not in sc.attrs and sc[0] >= 0, "run/sink_count"
        assert sm.dtype.kind == "f" and sm.shape == (1,) and sm.attrs["units"] == b"kg" and sm[0] >= 0, "run/sink_mass"

        # The input it started from: none for gen-primary, else the --in's seal.
        seal = f["run/input_seal"][0].decode()
        if expect_writer == "gen-primary":
            assert seal == "" and f["run/input_path"][0].decode() == "", seal
        else:
            assert seal.startswith("crc32=") and " size=" in seal and f["run/input_path"][0].decode(), seal
        for entry in f["scene/files"][:]:
            assert entry.decode().startswith("fnv1a64="), entry

        # Contents consistent with the scene the file carries.
        scene = f["scene/text"][0].decode()
        assert "[[material]]" in scene
        ids = f["particles/id"][:]
        assert len(np.unique(ids)) == n, "ids are unique"
        r = f["particles/radius"][:]
        rho = f["materials/density"][:][f["particles/material"][:]]
        assert np.allclose(f["particles/mass"][:], rho * 4 / 3 * np.pi * r**3, rtol=1e-12), "m = rho 4/3 pi a^3"
        pairs = f["contacts/pair_ids"][:]
        if len(pairs):
            assert np.all(pairs[:, 0] < pairs[:, 1]), "pair keys ordered id_i < id_j"
            assert np.all(np.isin(pairs, ids)), "pair keys are particle ids"
        assert f["state/dt"][0] > 0 and f["state/step"][0] > 0
    print(f"{path}: schema v4 ok ({n} particles, {m} materials, {w} walls)")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
