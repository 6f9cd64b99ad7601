#!/usr/bin/env python3
"""Writes strahl's built-in `cornell` scene as an MGF file (Materials and Geometry Format),
for radiosity programs that read MGF, such as RenderPark (see scripts/compare-renderpark.sh).

Usage: scripts/cornell-mgf.py [OUTPUT.mgf]      (without OUTPUT: to standard output)
       scripts/cornell-mgf.py --check           (prints the colour round trip, see below)

Geometry: the published Cornell box vertices (millimetres) of src/scene/builtin/cornell.rs,
in metres, face by face as strahl builds them: the red wall as two triangles (it is not
planar), the ceiling as four quads around the light's hole, the blocks as five quads each
(no bottoms), the light as one quad coplanar with the ceiling. Every face is listed
counter-clockwise seen from its front side (MGF's convention, and strahl's), so fronts face
into the room or out of the blocks and the light faces down. All materials are one-sided.
Each object is an MGF object (`o NAME`) with strahl's object name: floor, ceiling, back_wall,
red_wall, green_wall, short_block, tall_block, light.

Colours: MGF gives a colour as CIE xy chromaticity plus a luminous quantity: `rd Y` is the
diffuse reflectance's Y (0..1), `ed` the diffuse emittance in lm/m² (luminous exitance). A
reader turns xy + Y into CIE XYZ and then into its own RGB space, and divides the emittance by
a luminous efficacy to get W/m². RenderPark's RGB space (unless told otherwise on its command
line) has the nominal CRT primaries R (0.64, 0.33), G (0.29, 0.60), B (0.15, 0.06) and the
equal-energy white (1/3, 1/3), and its efficacy is 183.07 lm/W; its diffuse emitter of
emittance E W/m² has radiance E/π. The xy, Y and emittance below are computed from strahl's
linear RGB in that space, so that RenderPark's reflectances and emitted radiance are strahl's
(to float precision; `--check` prints the round trip). strahl's own RGB is linear Rec.709
(D65, white reflectance spectra adapted to it); a reader with other primaries would see
slightly different red and green walls, the neutral colours hardly change.
"""

import math
import sys

# strahl's Cornell colours, linear RGB, as strahl computes them from the measured spectra when
# the scene is built (src/scene/builtin/cornell.rs, `cornell::colors()`; printed from
# `strahl::scene::builtin::cornell::colors()` by a throwaway program against strahl at commit
# c21e38a, each f32 in its shortest round-trip form; the module documents them rounded to 3
# decimals). LIGHT is the emitted radiance, W·sr⁻¹·m⁻² (luminance 25); the light fixture also
# reflects diffusely with LIGHT_REFLECTANCE (grey).
WHITE = (0.7379998, 0.73609877, 0.7375886)
GREEN = (0.051920198, 0.39658567, 0.0864336)
RED = (0.5241579, 0.049799826, 0.050394855)
LIGHT = (36.55843, 23.437172, 6.4461756)
LIGHT_REFLECTANCE = 0.78

# RenderPark's default RGB space and luminous efficacy (see the module docstring).
PRIMARIES = ((0.640, 0.330), (0.290, 0.600), (0.150, 0.060))
WHITE_POINT = (1.0 / 3.0, 1.0 / 3.0)
EFFICACY_LM_PER_W = 183.07

# Published vertices, millimetres (as in src/scene/builtin/cornell.rs), each face
# counter-clockwise seen from its front side.
FLOOR = [[(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)]]
CEILING = [
    [(556.0, 548.8, 0.0), (556.0, 548.8, 227.0), (0.0, 548.8, 227.0), (0.0, 548.8, 0.0)],
    [(556.0, 548.8, 332.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 332.0)],
    [(213.0, 548.8, 227.0), (213.0, 548.8, 332.0), (0.0, 548.8, 332.0), (0.0, 548.8, 227.0)],
    [(556.0, 548.8, 227.0), (556.0, 548.8, 332.0), (343.0, 548.8, 332.0), (343.0, 548.8, 227.0)],
]
BACK_WALL = [[(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)]]
_RED_QUAD = [(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)]
RED_WALL = [[_RED_QUAD[0], _RED_QUAD[1], _RED_QUAD[2]], [_RED_QUAD[0], _RED_QUAD[2], _RED_QUAD[3]]]
GREEN_WALL = [[(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)]]
SHORT_BLOCK = [
    [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
    [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
    [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
    [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
    [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
]
TALL_BLOCK = [
    [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
    [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
    [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
    [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
    [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
]
LIGHT_QUAD = [[(343.0, 548.8, 227.0), (343.0, 548.8, 332.0), (213.0, 548.8, 332.0), (213.0, 548.8, 227.0)]]

# (object name, material, faces), in strahl's object order.
OBJECTS = [
    ("floor", "white", FLOOR),
    ("ceiling", "white", CEILING),
    ("back_wall", "white", BACK_WALL),
    ("red_wall", "red", RED_WALL),
    ("green_wall", "green", GREEN_WALL),
    ("short_block", "white", SHORT_BLOCK),
    ("tall_block", "white", TALL_BLOCK),
    ("light", "light", LIGHT_QUAD),
]


def rgb_to_xyz_matrix(primaries=PRIMARIES, white=WHITE_POINT):
    """The 3×3 matrix from linear RGB with these primaries and white (RGB 1,1,1 has Y = 1)
    to CIE XYZ: columns are the primaries' XYZ, scaled so that they add up to the white."""
    cols = [(x / y, 1.0, (1.0 - x - y) / y) for x, y in primaries]
    xw, yw = white
    w = (xw / yw, 1.0, (1.0 - xw - yw) / yw)
    m = [[cols[j][i] for j in range(3)] for i in range(3)]
    s = solve3(m, w)
    return [[m[i][j] * s[j] for j in range(3)] for i in range(3)]


def solve3(m, b):
    """Solves m·x = b for a 3×3 m (Cramer's rule)."""

    def det(a):
        return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
                - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
                + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))

    d = det(m)
    out = []
    for k in range(3):
        a = [row[:] for row in m]
        for i in range(3):
            a[i][k] = b[i]
        out.append(det(a) / d)
    return out


def mat_vec(m, v):
    return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]


def rgb_to_xy_y(rgb):
    """(x, y, Y) of a linear RGB colour in the reader's RGB space."""
    x_, y_, z_ = mat_vec(rgb_to_xyz_matrix(), rgb)
    s = x_ + y_ + z_
    return x_ / s, y_ / s, y_


def xy_y_to_rgb(x, y, lum):
    """The reader's side: CIE xy + Y to linear RGB."""
    xyz = [x / y * lum, lum, (1.0 - x - y) / y * lum]
    return solve3(rgb_to_xyz_matrix(), xyz)


def fmt(v):
    return f"{v:.9g}"


def materials():
    """MGF material definitions, and the RGB that a reader gets back from each."""
    lines, back = [], {}
    for name, rgb in (("white", WHITE), ("red", RED), ("green", GREEN)):
        x, y, lum = rgb_to_xy_y(rgb)
        lines += [f"m {name} =", "\tsides 1", "\tc", f"\t\tcxy {fmt(x)} {fmt(y)}", f"\trd {fmt(lum)}"]
        back[name] = (rgb, xy_y_to_rgb(float(fmt(x)), float(fmt(y)), float(fmt(lum))))
    # The light: emittance (exitance) π·L in lm/m², then the grey reflectance (the colour
    # context is reset to the default, equal-energy white, before `rd`).
    exitance = [math.pi * c for c in LIGHT]
    x, y, lum = rgb_to_xy_y(exitance)
    ed = lum * EFFICACY_LM_PER_W
    grey = (LIGHT_REFLECTANCE,) * 3
    gx, gy, glum = rgb_to_xy_y(grey)
    lines += [
        "m light =",
        "\tsides 1",
        "\tc",
        f"\t\tcxy {fmt(x)} {fmt(y)}",
        f"\ted {fmt(ed)}",
        "\tc",
        f"\trd {fmt(glum)}",
    ]
    radiance_back = [c / EFFICACY_LM_PER_W / math.pi
                     for c in xy_y_to_rgb(float(fmt(x)), float(fmt(y)), float(fmt(ed)))]
    back["light emitted radiance"] = (LIGHT, radiance_back)
    back["light reflectance"] = (grey, xy_y_to_rgb(gx, gy, glum))
    return lines, back


def mgf_text():
    out = [
        "# strahl's built-in `cornell` scene (the measured Cornell box), written by",
        "# scripts/cornell-mgf.py. Metres; faces counter-clockwise seen from the front;",
        "# colours for a reader whose RGB space has primaries R (0.64, 0.33), G (0.29, 0.60),",
        "# B (0.15, 0.06) and white (1/3, 1/3), emittance in lm/m^2 at 183.07 lm/W.",
        "# Light: emitted radiance (W/sr/m^2) " + " ".join(fmt(c) for c in LIGHT)
        + f", diffuse reflectance {LIGHT_REFLECTANCE}.",
    ]
    lines, _ = materials()
    out += lines
    for name, material, faces in OBJECTS:
        out.append(f"o {name}")
        out.append(f"m {material}")
        for f, face in enumerate(faces):
            names = []
            for k, (x, y, z) in enumerate(face):
                vname = f"{name}.{f}.{k}"
                names.append(vname)
                out.append(f"v {vname} =")
                out.append(f"\tp {x / 1000:.4f} {y / 1000:.4f} {z / 1000:.4f}")
            out.append("f " + " ".join(names))
        out.append("o")
    return "\n".join(out) + "\n"


def check():
    _, back = materials()
    worst = 0.0
    for name, (want, got) in back.items():
        rel = max(abs(g - w) / w for g, w in zip(got, want))
        worst = max(worst, rel)
        print(f"{name:24s} strahl {' '.join(f'{w:.7g}' for w in want):36s} "
              f"read back {' '.join(f'{g:.7g}' for g in got):36s} rel. diff {rel:.1e}")
    return worst < 1e-6


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip().split("\n\n")[1], file=sys.stderr)
        return 2
    if len(argv) == 2 and argv[1] == "--check":
        return 0 if check() else 1
    text = mgf_text()
    if len(argv) == 2:
        with open(argv[1], "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
