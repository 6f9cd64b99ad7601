"""Splits a Wavefront OBJ into one OBJ per group of triangles, for scene scripts that report a
large model surface by surface (imported by conference-room.py and sibenik.py)."""

import math
import os


def normal_and_centre(points):
    """The unit normal (zero for a degenerate face) and the centroid of a face's corners."""
    (a, b, c) = points[:3]
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n))
    n = [x / length for x in n] if length > 0 else [0.0, 0.0, 0.0]
    centre = [sum(p[i] for p in points) / len(points) for i in range(3)]
    return n, centre


def split(source, out, scale, groups, group_of):
    """Reads `source`, scales its vertices by `scale`, sorts every face into one of `groups` by
    `group_of(normal, centre)` (scaled units) and writes OUT/<group>.obj for each."""
    os.makedirs(out, exist_ok=True)
    vertices, faces = [], {g: [] for g in groups}
    with open(source) as f:
        for line in f:
            if line.startswith("v "):
                vertices.append([float(x) * scale for x in line.split()[1:4]])
            elif line.startswith("f "):
                face = [int(x.split("/")[0]) - 1 for x in line.split()[1:]]
                normal, centre = normal_and_centre([vertices[i] for i in face])
                faces[group_of(normal, centre)].append(face)
    for group, group_faces in faces.items():
        used = sorted({i for face in group_faces for i in face})
        index = {i: k + 1 for k, i in enumerate(used)}
        with open(os.path.join(out, group + ".obj"), "w") as f:
            for i in used:
                f.write("v %.6f %.6f %.6f\n" % tuple(vertices[i]))
            for face in group_faces:
                f.write("f " + " ".join(str(index[i]) for i in face) + "\n")
        print(f"{group}: {len(group_faces)} triangles")


def object_entries(groups, material):
    """The scene file's `[[objects]]` entries of the OBJ files `split` wrote for `groups`,
    each of the material `material`."""
    return "".join(
        f'\n[[objects]]\nname = "{g}"\ntype = "mesh"\nfile = "{g}.obj"\nmaterial = "{material}"\n'
        for g in groups
    )
