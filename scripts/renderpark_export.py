"""What the RenderPark comparisons share: small vector helpers and the reading of RenderPark's
VRML export of a radiosity solution (compare-renderpark.sh, compare-renderpark-corpus.sh).

RenderPark writes its solution tone-mapped; with `-tonemapping Ward -ldmax 100
-brightness-adjust -16` the mapping is linear: display value = radiance x 2^-16 x 183.07 x
comp / 100, where comp (Ward's contrast-based scale factor) follows from the display's
adaptation luminance ldmax / 2 and the scene's, which RenderPark prints. Standard library
only.
"""

import re


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def newell(poly):
    """Area vector (normal x area) of a planar polygon."""
    n = (0.0, 0.0, 0.0)
    for i in range(len(poly)):
        c = cross(poly[i], poly[(i + 1) % len(poly)])
        n = (n[0] + c[0] / 2, n[1] + c[1] / 2, n[2] + c[2] / 2)
    return n


def adaptation_luminance(output):
    """The scene's adaptation luminance (cd/m^2) RenderPark printed in `output`, or None."""
    found = re.findall(r"adaptationLuminance\) *\.*: *([-0-9.eE+]+) cd", output)
    return float(found[-1]) if found else None


def display_scale(lwa):
    """Display value per unit of radiance in RenderPark's Ward export, for the scene's
    adaptation luminance `lwa` (cd/m^2)."""
    ldmax, bright, efficacy = 100.0, -16.0, 183.07
    comp = ((1.219 + (ldmax / 2) ** 0.4) / (1.219 + lwa ** 0.4)) ** 2.5
    return 2.0 ** bright * efficacy * comp / ldmax


def read_export(path):
    """(corner points, corner colours, face index list with -1 ends) of RenderPark's VRML
    export at `path`; raises ValueError when a part is missing."""
    text = open(path).read()

    def numbers(pattern):
        m = re.search(pattern + r"\s*\[([^\]]*)\]", text)
        if not m:
            raise ValueError(f"no {pattern} in the VRML export {path}")
        return m.group(1).replace(",", " ").split()

    points = [float(t) for t in numbers(r"\bpoint")]
    colors = [float(t) for t in numbers(r"color\s+Color\s*\{\s*color")]
    index = [int(t) for t in numbers(r"coordIndex")]
    P = [tuple(points[i:i + 3]) for i in range(0, len(points), 3)]
    C = [tuple(colors[i:i + 3]) for i in range(0, len(colors), 3)]
    return P, C, index


def elements(index):
    """The corner index lists of the faces of a VRML `coordIndex`."""
    face = []
    for i in index:
        if i >= 0:
            face.append(i)
        else:
            yield face
            face = []
