"""Memory and time of a mesh placed many times (docs/PERFORMANCE.md, "Placed meshes"): a
plant of 16 leaves (each a 4 × 2 grid of quads, 256 triangles in all) placed N times at random
on a square plot at about 16 plants per m², lit by a sun and a sky; `strahl solve` with the
light model and 10⁶ photons on two threads, and `strahl info` (the world alone), whole
process, peak memory by GNU time. For comparison the same plants with every triangle copied
into place (one OBJ of all plants) for the smaller N. Usage:

    python3 scripts/placed-meshes.py [STRAHL] [N,N,...] [COPIED_N,...]
"""

import math
import os
import random
import subprocess
import sys
import tempfile

STRAHL = sys.argv[1] if len(sys.argv) > 1 else "target/release/strahl"
PLACED = [int(n) for n in (sys.argv[2] if len(sys.argv) > 2 else "1000,10000,100000").split(",")]
COPIED = [int(n) for n in (sys.argv[3] if len(sys.argv) > 3 else "1000,10000").split(",")]


def plant():
    """Vertices and quads of one plant: 16 leaves around a stem, each 4 × 2 quads."""
    vertices, quads = [], []
    for k in range(16):
        a = 2.4 * k
        h = 0.05 + 0.03 * k
        out = (math.cos(a), 0.0, math.sin(a))
        side = (-math.sin(a) * 0.02, 0.0, math.cos(a) * 0.02)
        base = len(vertices)
        for i in range(5):
            s = i / 4 * 0.15
            for j in (-1, 0, 1):
                vertices.append((out[0] * s + side[0] * j, h + 0.3 * s - s * s, out[2] * s + side[2] * j))
        for i in range(4):
            for j in range(2):
                v = base + i * 3 + j
                quads.append((v, v + 1, v + 4, v + 3))
    return vertices, quads


def placements(n, seed=1):
    rng = random.Random(seed)
    side = math.sqrt(n / 16.0)
    return [(rng.uniform(0, side), 0.0, rng.uniform(0, side), rng.uniform(0, 360), rng.uniform(0.8, 1.2)) for _ in range(n)], side


HEAD = """[materials.leaf]
diffuse = 0.1
translucency = 0.05

[materials.soil]
diffuse = 0.15

[[lights]]
type = "directional"
direction = [0.4, -0.8, 0.3]
irradiance = 800

[[lights]]
type = "sky"
radiance = 30

[[objects]]
type = "quad"
name = "soil"
material = "soil"
vertices = [[0, 0, {s}], [{s}, 0, {s}], [{s}, 0, 0], [0, 0, 0]]
"""


def write_obj(path, parts):
    with open(path, "w") as f:
        offset = 0
        for vertices, quads in parts:
            for v in vertices:
                f.write("v %.6f %.6f %.6f\n" % v)
            for q in quads:
                f.write("f %d %d %d %d\n" % tuple(i + 1 + offset for i in q))
            offset += len(vertices)


def moved(vertices, place):
    x, y, z, degrees, scale = place
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    return [(x + scale * (c * vx + s * vz), y + scale * vy, z + scale * (-s * vx + c * vz)) for vx, vy, vz in vertices]


def timed(args):
    """Seconds and peak memory (MB) of running `args`, by GNU time."""
    out = subprocess.run(["/usr/bin/time", "-f", "%e %M", *args], capture_output=True, text=True, check=True)
    seconds, kb = out.stderr.split()[-2:]
    return float(seconds), int(kb) / 1024


def measure(what, n, triangles, scene, side, mesh_fields):
    """Writes `scene` (the soil of a plot `side` wide and one mesh object with
    `mesh_fields`), then prints the world's cost (`strahl info`) and the solve's."""
    with open(scene, "w") as f:
        f.write(HEAD.format(s=side))
        f.write(f'\n[[objects]]\ntype = "mesh"\nname = "plant"\nmaterial = "leaf"\n{mesh_fields}\n')
    info = timed([STRAHL, "info", scene])
    solve = timed([STRAHL, "solve", scene, "--photons", "1000000", "--threads", "2", "-q", "--report", scene + ".json"])
    print(f"{what} {n:>7} plants ({n * triangles:>10} triangles): info {info[0]:6.2f} s {info[1]:8.1f} MB, "
          f"solve {solve[0]:6.2f} s {solve[1]:8.1f} MB")


def main():
    vertices, quads = plant()
    triangles = 2 * len(quads)
    with tempfile.TemporaryDirectory() as d:
        write_obj(os.path.join(d, "plant.obj"), [(vertices, quads)])
        for n in PLACED:
            rows, side = placements(n)
            with open(os.path.join(d, f"p{n}.csv"), "w") as f:
                f.write("x,y,z,degrees,scale\n")
                f.writelines("%.4f,%.4f,%.4f,%.2f,%.3f\n" % r for r in rows)
            fields = f'file = "plant.obj"\nplacements = "p{n}.csv"'
            measure("placed", n, triangles, os.path.join(d, f"placed{n}.toml"), side, fields)
        for n in COPIED:
            rows, side = placements(n)
            write_obj(os.path.join(d, f"all{n}.obj"), [(moved(vertices, r), quads) for r in rows])
            measure("copied", n, triangles, os.path.join(d, f"copied{n}.toml"), side, f'file = "all{n}.obj"')


if __name__ == "__main__":
    main()
