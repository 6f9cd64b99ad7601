#!/usr/bin/env python3
"""Writes the Grynberg & Ward conference room as a strahl scene whose surfaces are reported
one by one, for checking hierarchical radiosity against the light model per surface.

    scripts/conference-room.py path/to/conference.obj OUT_DIR

OUT_DIR gets floor.obj, ceiling.obj, walls.obj, tables.obj, furniture.obj and room.toml: the
model scaled by 0.003 to metres (its copyright.txt), one grey material (ρ = 0.6), four
Lambertian downlights of 3000 lm 5 cm under the ceiling, and a 7 × 4 grid of sensors facing
up 0.75 m above the floor. The triangles are sorted by where they lie: horizontal ones at
the floor's and the ceiling's heights, vertical ones within reach of the room's outer
planes (the walls with their windows and fittings), the table tops (facing up, 0.49–0.56 m
high), and everything else as furniture. Then, for example:

    strahl solve OUT_DIR/room.toml --solver light-trace --photons 200000000 --report lt.json
    strahl solve OUT_DIR/room.toml --solver hierarchical --report hr.json
"""

import math
import os
import sys

SCALE = 0.003
GROUPS = ["floor", "ceiling", "walls", "tables", "furniture"]

SCENE_HEAD = """# Grynberg & Ward conference room (written by scripts/conference-room.py), metres,
# one grey material, four downlights of 3000 lm, a work plane of sensors 0.75 m high.
[materials.grey]
diffuse = 0.6
"""

LIGHTS = [(-1.0, -1.5), (2.5, -1.5), (-1.0, 0.8), (2.5, 0.8)]

SENSORS = """
[[sensors]]
name = "work-plane"
position = [-2.5, 0.75, -2.8]
edge_u = [7.0, 0, 0]
edge_v = [0, 0, 4.4]
count = [7, 4]
"""


def group_of(points):
    """The group a triangle with corners `points` (metres) belongs to."""
    (a, b, c) = points[:3]
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n))
    n = [x / length for x in n] if length > 0 else [0.0, 0.0, 0.0]
    cx, cy, cz = (sum(p[i] for p in points) / len(points) for i in range(3))
    if abs(n[1]) > 0.99 and cy < 0.01:
        return "floor"
    if abs(n[1]) > 0.99 and cy > 1.94:
        return "ceiling"
    if abs(n[1]) < 0.1 and (cx > 4.9 or cx < -2.8 or cz > 1.75 or cz < -3.0):
        return "walls"
    if n[1] > 0.99 and 0.49 < cy < 0.56:
        return "tables"
    return "furniture"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    source, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    vertices, faces = [], {g: [] for g in GROUPS}
    with open(source) as f:
        for line in f:
            if line.startswith("v "):
                vertices.append([float(x) * SCALE for x in line.split()[1:4]])
            elif line.startswith("f "):
                face = [int(x.split("/")[0]) - 1 for x in line.split()[1:]]
                faces[group_of([vertices[i] for i in face])].append(face)
    for group, group_faces in faces.items():
        used = sorted({i for face in group_faces for i in face})
        index = {i: k + 1 for k, i in enumerate(used)}
        with open(os.path.join(out, group + ".obj"), "w") as f:
            for i in used:
                f.write("v %.6f %.6f %.6f\n" % tuple(vertices[i]))
            for face in group_faces:
                f.write("f " + " ".join(str(index[i]) for i in face) + "\n")
        print(f"{group}: {len(group_faces)} triangles")
    with open(os.path.join(out, "room.toml"), "w") as f:
        f.write(SCENE_HEAD)
        for group in GROUPS:
            f.write(f'\n[[objects]]\nname = "{group}"\ntype = "mesh"\n')
            f.write(f'file = "{group}.obj"\nmaterial = "grey"\n')
        for x, z in LIGHTS:
            f.write(f'\n[[lights]]\ntype = "lambertian"\nposition = [{x}, 1.90, {z}]\n')
            f.write("direction = [0, -1, 0]\nflux_lm = 3000\n")
        f.write(SENSORS)


if __name__ == "__main__":
    main()
