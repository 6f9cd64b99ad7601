#!/usr/bin/env python3
"""Writes Dabrovic's Šibenik cathedral as a strahl scene whose surfaces are reported group by
group, for checking hierarchical radiosity against the light model per surface.

    scripts/sibenik.py path/to/sibenik.obj OUT_DIR

The model (geometry only, in metres: the nave runs along x from -20 m, its floor at
y = -15.3 m and its vault at 4 m) has no lights and no materials. OUT_DIR gets floor.obj,
vaults.obj, walls.obj, other.obj and cathedral.toml: one grey material (ρ = 0.6), four
Lambertian pendant lamps of 5000 lm down the nave, two of 1500 lm in each aisle and one of
5000 lm under the dome, and an 8 × 3 grid of sensors facing up 0.75 m above the nave's floor.
The groups: horizontal faces facing up below y = -13 m (the floors), faces turned down (vaults,
arches, the undersides of cornices), vertical faces (walls, piers) and everything else. Then:

    strahl solve OUT_DIR/cathedral.toml --solver light-trace --photons 20000000 --report lt.json
    strahl solve OUT_DIR/cathedral.toml --solver hierarchical --report hr.json
"""

import os
import sys

from split_obj import object_entries, split

GROUPS = ["floor", "vaults", "walls", "other"]

SCENE_HEAD = """# Šibenik cathedral by Marko Dabrovic (RNA studio), holes corrected by Kenzie Lamar,
# written by scripts/sibenik.py: metres, one grey material, nine pendant lamps, sensors
# 0.75 m above the nave's floor. Research and testing only (no licence stated).
[materials.grey]
diffuse = 0.6
"""

# (x, y, z, lumen) of each Lambertian lamp facing down.
LAMPS = [
    (-16.0, -4.0, 0.0, 5000),
    (-11.0, -4.0, 0.0, 5000),
    (-6.0, -4.0, 0.0, 5000),
    (-1.0, -4.0, 0.0, 5000),
    (-14.0, -9.5, -6.0, 1500),
    (-6.0, -9.5, -6.0, 1500),
    (-14.0, -9.5, 6.0, 1500),
    (-6.0, -9.5, 6.0, 1500),
    (8.0, 0.0, 0.0, 5000),
]

SENSORS = """
[[sensors]]
name = "nave"
position = [-18.0, -14.55, -3.0]
edge_u = [20.0, 0, 0]
edge_v = [0, 0, 6.0]
count = [8, 3]
"""


def group_of(n, centre):
    """The group of a triangle with unit normal `n` and centroid `centre` (metres)."""
    if n[1] > 0.99 and centre[1] < -13.0:
        return "floor"
    if n[1] < -0.1:
        return "vaults"
    if abs(n[1]) < 0.1:
        return "walls"
    return "other"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    source, out = sys.argv[1], sys.argv[2]
    split(source, out, 1.0, GROUPS, group_of)
    with open(os.path.join(out, "cathedral.toml"), "w") as f:
        f.write(SCENE_HEAD)
        f.write(object_entries(GROUPS, "grey"))
        for x, y, z, lumen in LAMPS:
            f.write(f'\n[[lights]]\ntype = "lambertian"\nposition = [{x}, {y}, {z}]\n')
            f.write(f"direction = [0, -1, 0]\nflux_lm = {lumen}\n")
        f.write(SENSORS)


if __name__ == "__main__":
    main()
