#!/usr/bin/env python3
"""The CIE standard general sky (CIE S 011/E:2003, ISO 15469:2004) by a second implementation.

strahl's Rust test `sky::cie::reference` compares its relative luminances L/L_z with the
table src/sky/cie/reference.csv: 15 sky types x 4 Sun positions x 20 sky elements, angles in
degrees, azimuth clockwise from north. This script checks that table against a second
implementation: the `colour-science` package's `sky_luminance_distribution_CIE2003` where it
can be imported (it is in colour-science's development branch; release 0.4.7 does not have
it yet), and always a direct transcription of the standard's formulas below, with the
parameters of its Table 1.

Needs: Python 3 alone (colour-science optional: `pip install colour-science`).

Usage: scripts/check-cie-sky.py [--write]
  --write   regenerate the table from the transcription (then check it as usual)
Exit status 0 when every value agrees to 1e-12 relative, 1 otherwise.
"""

import csv
import math
import os
import sys

TABLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src", "sky", "cie",
                     "reference.csv")
TOLERANCE = 1e-12

# CIE S 011/E:2003 Table 1: type -> (a, b, c, d, e).
PARAMETERS = {
    1: (4.0, -0.70, 0.0, -1.0, 0.00),
    2: (4.0, -0.70, 2.0, -1.5, 0.15),
    3: (1.1, -0.8, 0.0, -1.0, 0.00),
    4: (1.1, -0.8, 2.0, -1.5, 0.15),
    5: (0.0, -1.0, 0.0, -1.0, 0.00),
    6: (0.0, -1.0, 2.0, -1.5, 0.15),
    7: (0.0, -1.0, 5.0, -2.5, 0.30),
    8: (0.0, -1.0, 10.0, -3.0, 0.45),
    9: (-1.0, -0.55, 2.0, -1.5, 0.15),
    10: (-1.0, -0.55, 5.0, -2.5, 0.30),
    11: (-1.0, -0.55, 10.0, -3.0, 0.45),
    12: (-1.0, -0.32, 10.0, -3.0, 0.45),
    13: (-1.0, -0.32, 16.0, -3.0, 0.30),
    14: (-1.0, -0.15, 16.0, -3.0, 0.30),
    15: (-1.0, -0.15, 24.0, -2.8, 0.15),
}

SUNS = [(0.0, 0.0), (35.0, 135.0), (62.0, 250.0), (80.0, 10.0)]
ELEMENTS = [(z, a) for z in (0.0, 25.0, 50.0, 75.0, 88.0) for a in (0.0, 90.0, 200.0, 300.0)]


def gradation(z, a, b):
    """phi(Z) = 1 + a exp(b / cos Z), 1 at the horizon; Z in radians."""
    if z >= math.pi / 2:
        return 1.0
    return 1.0 + a * math.exp(b / math.cos(z))


def indicatrix(chi, c, d, e):
    """f(chi) = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi; chi in radians."""
    return 1.0 + c * (math.exp(d * chi) - math.exp(d * math.pi / 2)) + e * math.cos(chi) ** 2


def transcription(sky, z, az, zs, azs):
    """L/L_z = f(chi) phi(Z) / (f(Z_s) phi(0)); angles in radians."""
    a, b, c, d, e = PARAMETERS[sky]
    cos_chi = math.cos(zs) * math.cos(z) + math.sin(zs) * math.sin(z) * math.cos(abs(az - azs))
    chi = math.acos(max(-1.0, min(1.0, cos_chi)))
    return (indicatrix(chi, c, d, e) * gradation(z, a, b)
            / (indicatrix(zs, c, d, e) * gradation(0.0, a, b)))


def colour_science():
    """colour-science's implementation, or None where it cannot be imported."""
    try:
        from colour.phenomena import sky_luminance_distribution_CIE2003
    except ImportError:
        return None

    def relative(sky, z, az, zs, azs):
        return float(sky_luminance_distribution_CIE2003(sky, z, az, zs, azs))

    return relative


def grid():
    for sky in range(1, 16):
        for zs, azs in SUNS:
            for z, az in ELEMENTS:
                yield sky, zs, azs, z, az


def write():
    with open(TABLE, "w", newline="") as f:
        out = csv.writer(f, lineterminator="\n")
        out.writerow(["type", "sun_zenith_deg", "sun_azimuth_deg", "zenith_deg", "azimuth_deg",
                      "relative_luminance"])
        for sky, zs, azs, z, az in grid():
            value = transcription(sky, *map(math.radians, (z, az, zs, azs)))
            out.writerow([sky, zs, azs, z, az, repr(value)])
    print(f"wrote {TABLE}")


def compare(name, implementation, rows):
    worst = 0.0
    for row in rows:
        sky = int(row["type"])
        z, az, zs, azs = (math.radians(float(row[k])) for k in
                          ("zenith_deg", "azimuth_deg", "sun_zenith_deg", "sun_azimuth_deg"))
        expected = float(row["relative_luminance"])
        value = implementation(sky, z, az, zs, azs)
        worst = max(worst, abs(value - expected) / abs(expected))
    ok = worst <= TOLERANCE
    print(f"{name}: {len(rows)} values, largest relative difference {worst:.2e} "
          f"({'ok' if ok else 'FAILED'})")
    return ok


def main():
    if "--write" in sys.argv[1:]:
        write()
    with open(TABLE, newline="") as f:
        rows = list(csv.DictReader(f))
    if len(rows) != 15 * len(SUNS) * len(ELEMENTS):
        print(f"{TABLE}: {len(rows)} rows, expected {15 * len(SUNS) * len(ELEMENTS)}")
        return 1
    ok = compare("transcription of the standard's formulas", transcription, rows)
    colour = colour_science()
    if colour is None:
        print("colour-science not importable: checked against the transcription only")
    else:
        ok = compare("colour-science sky_luminance_distribution_CIE2003", colour, rows) and ok
    print("1 passed, 0 failed" if ok else "0 passed, 1 failed")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
