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

import os
import sys

from split_obj import object_entries, split

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


def group_of(n, centre):
    """The group of a triangle with unit normal `n` and centroid `centre` (metres)."""
    cx, cy, cz = centre
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
    split(source, out, SCALE, GROUPS, group_of)
    with open(os.path.join(out, "room.toml"), "w") as f:
        f.write(SCENE_HEAD)
        f.write(object_entries(GROUPS, "grey"))
        for x, z in LIGHTS:
            f.write(f'\n[[lights]]\ntype = "lambertian"\nposition = [{x}, 1.90, {z}]\n')
            f.write("direction = [0, -1, 0]\nflux_lm = 3000\n")
        f.write(SENSORS)


if __name__ == "__main__":
    main()
