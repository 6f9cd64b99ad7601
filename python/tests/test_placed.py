"""Objects placed many times from arrays (`placements`): one object per placement, named
`name[i]`, sharing the triangles; the light on every copy equals that on the same copies
handed over as triangles of their own, within the photons' noise; bad placements raise
ValueError."""

import numpy as np
import pytest

import strahl


def _plant():
    """Four blades around the y axis, each two triangles, leaning out: 8 triangles."""
    vertices, triangles = [], []
    for k in range(4):
        a = k * np.pi / 2 + 0.3
        out, side = np.array([np.cos(a), 0, np.sin(a)]), np.array([-np.sin(a), 0, np.cos(a)]) * 0.05
        base = len(vertices)
        vertices += [-side, side, out * 0.3 + [0, 0.4, 0] + side, out * 0.3 + [0, 0.4, 0] - side]
        triangles += [[base, base + 1, base + 2], [base, base + 2, base + 3]]
    return np.array(vertices), np.array(triangles)


def _matrices(n):
    """n placements on a row, each turned about y and scaled, as (n, 3, 4) matrices."""
    out = []
    for i in range(n):
        c, s, k = np.cos(0.7 * i), np.sin(0.7 * i), 0.8 + 0.05 * i
        out.append([[k * c, 0, k * s, 0.5 * i], [0, k, 0, 0], [-k * s, 0, k * c, 0.3 * (i % 2)]])
    return np.array(out)


GROUND = (np.array([[-1, 0, -1], [4, 0, -1], [4, 0, 2], [-1, 0, 2]], dtype=float), np.array([[0, 2, 1], [0, 3, 2]]))
LIGHTS = dict(sun=([0.4, -0.7, 0.3], 600.0), sky=20.0)


def test_placed_copies_receive_the_light_of_copies_of_their_own():
    plant, blades = _plant()
    matrices = _matrices(6)
    ground, quad = GROUND
    placed = strahl.from_arrays(
        np.vstack([ground, plant]), np.vstack([quad, blades + 4]), [0, 0] + [1] * 8,
        ["ground", "plant"], [0.2, 0.3], translucency=[0.0, 0.1],
        placements={"plant": matrices}, **LIGHTS,
    )
    # The same copies, their triangles moved into place here.
    vertices, triangles, ids = [ground], [quad], [0, 0]
    for i, m in enumerate(matrices):
        vertices.append(plant @ m[:, :3].T + m[:, 3])
        triangles.append(blades + 4 + 16 * i)
        ids += [i + 1] * 8
    names = ["ground"] + [f"plant[{i}]" for i in range(6)]
    copied = strahl.from_arrays(
        np.vstack(vertices), np.vstack(triangles), ids, names,
        [0.2] + [0.3] * 6, translucency=[0.0] + [0.1] * 6, **LIGHTS,
    )
    a = placed.solve("light-trace", photons=300_000, seed=2)
    b = copied.solve("light-trace", photons=300_000, seed=2)
    assert a.names == names
    assert np.allclose(a.area_m2, b.area_m2, rtol=1e-5)
    sigma = np.hypot(a.incident_w_sigma, b.incident_w_sigma)
    assert np.all(np.abs(a.incident_w - b.incident_w) <= 4 * sigma + 1e-9), (a.incident_w, b.incident_w)


def test_bad_placements_raise_value_error():
    plant, blades = _plant()
    place = lambda placements: strahl.from_arrays(plant, blades, [0] * 8, ["plant"], 0.3, placements=placements)
    with pytest.raises(ValueError, match="no object named"):
        place({"tree": _matrices(2)})
    with pytest.raises(ValueError, match="expected \\(p, 3, 4\\)"):
        place({"plant": np.zeros((2, 3))})
    with pytest.raises(ValueError, match="not finite and invertible"):
        place({"plant": np.zeros((2, 3, 4))})
