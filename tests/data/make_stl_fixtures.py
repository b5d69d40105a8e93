#!/usr/bin/python3
"""Writes the STL fixtures used by tests/data/mesh_walls.toml (run from anywhere; plain python3).

deflector.stl: ASCII, a tetrahedron (4 triangles) in millimetres.
baffle.stl:    binary, a 40 mm square (2 triangles) in millimetres, whose 80-byte header starts
               with "solid" as some exporters write it: readers must decide by the file size.
cube.stl:      ASCII, a closed 10 mm cube [0, 10]^3 (12 triangles, normals outward), for mesh
               regions (stage action remove, [[generation.cut]]).
cube_flipped.stl: the same cube with one triangle turned the other way (not consistently
               oriented: a mesh region must reject it).
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def normal(a, b, c):
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = sum(x * x for x in n) ** 0.5
    return [x / length for x in n]


def write_ascii(path, name, tris):
    with open(path, "w", newline="\n") as f:
        f.write("solid %s\n" % name)
        for t in tris:
            f.write("  facet normal %g %g %g\n    outer loop\n" % tuple(normal(*t)))
            for v in t:
                f.write("      vertex %g %g %g\n" % tuple(v))
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid %s\n" % name)


def write_binary(path, header, tris):
    with open(path, "wb") as f:
        f.write(header.encode().ljust(80, b"\0"))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<12fH", *normal(*t), *t[0], *t[1], *t[2], 0))


tip = (0, 0, 20)
base = [(-15, -10, 0), (15, -10, 0), (0, 15, 0)]
write_ascii(os.path.join(HERE, "deflector.stl"), "deflector",
            [(base[0], base[2], base[1]), (base[0], base[1], tip), (base[1], base[2], tip), (base[2], base[0], tip)])
sq = [(0, 0, 0), (40, 0, 0), (40, 0, 40), (0, 0, 40)]
write_binary(os.path.join(HERE, "baffle.stl"), "solid baffle (binary, despite this header)",
             [(sq[0], sq[1], sq[2]), (sq[0], sq[2], sq[3])])

# Cube corners by bits (x, y, z); each face as two triangles, counter-clockwise seen from outside.
c = [(10 * (k & 1), 10 * (k >> 1 & 1), 10 * (k >> 2 & 1)) for k in range(8)]
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
cube = []
for a, b, d, e in quads:
    cube += [(c[a], c[b], c[d]), (c[a], c[d], c[e])]
write_ascii(os.path.join(HERE, "cube.stl"), "cube", cube)
flipped = list(cube)
flipped[5] = (flipped[5][0], flipped[5][2], flipped[5][1])
write_ascii(os.path.join(HERE, "cube_flipped.stl"), "cube_flipped", flipped)
