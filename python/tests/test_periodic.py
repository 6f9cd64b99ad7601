"""Periodic scenes from arrays: a plot repeated without end in x and z, lit through the
light model and radiosity across the plot's sides; bad plots refused; and carried through a
pickle (as to a Dask worker)."""

import pickle

import numpy as np
import pytest

import strahl

SUN = 10.0  # W/m², straight down
PLOT = (0.0, 2.0, 0.0, 2.0)  # x0, x1, z0, z1


def _field(periodic=PLOT, sun=SUN, sky=None):
    """A black 1 × 1 m leaf at height 1 centred on the plot's corner (0, 0) (three quarters
    of it beyond the plot's sides) over a black ground quad covering the 2 × 2 m plot, lit by
    a vertical sun of `sun` W/m² (and a uniform sky of radiance `sky`). The leaf is the
    highest geometry and the ground the lowest: light entering from above and below meets
    them first."""
    leaf = [[-0.5, 1.0, -0.5], [0.5, 1.0, -0.5], [0.5, 1.0, 0.5], [-0.5, 1.0, 0.5]]
    ground = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, 2.0], [0.0, 0.0, 2.0]]
    quad = np.array([[0, 2, 1], [0, 3, 2]])
    vertices, triangles, ids, names = leaf + ground, [quad, quad + 4], [0, 0, 1, 1], ["leaf", "ground"]
    return strahl.from_arrays(
        np.array(vertices, dtype=float),
        np.vstack(triangles),
        ids,
        names,
        0.0,
        sun=None if sun is None else ([0, -1, 0], sun),
        sky=sky,
        periodic=periodic,
    )


def _light(scene):
    return scene.solve("light-trace", photons=200_000, seed=5)


def _check_sun(result):
    """The sun brings 10 W/m² over the 4 m² plot: the leaf (1 m², all of it but a quarter
    seen through the plot's sides) receives 10 W, the ground the other 30 W, within 3σ."""
    incident = result.incident_w.mean(axis=1)[:2]
    sigma = result.incident_w_sigma.mean(axis=1)[:2]
    assert result.names[:2] == ["leaf", "ground"]
    assert np.all(sigma > 0), sigma
    expected = np.array([SUN * 1.0, SUN * 3.0])
    assert np.all(np.abs(incident - expected) <= 3 * sigma), (incident, sigma)


def test_the_light_model_follows_the_sun_across_the_plots_sides():
    scene = _field()
    assert scene.periodic == PLOT
    _check_sun(_light(scene))
    # Not periodic, the ground would lose only the quarter of the leaf's shadow over it.
    plain = _light(_field(periodic=None))
    assert plain.incident_w.mean(axis=1)[1] > SUN * 3.5, plain.incident_w


def test_the_surface_tracer_measures_every_surface_of_a_plot():
    # The sun's light is exact on every surface: the leaf's top takes 10 W/m² at every point,
    # the leaf's wrapped shadow is cut out of the ground across the plot's sides.
    result = _field().solve("surface-trace", points=16, seed=1)
    incident = result.incident_w.mean(axis=1)[:2]
    sigma = result.incident_w_sigma.mean(axis=1)[:2]
    assert np.all(np.abs(incident - [SUN, 3 * SUN]) < 1e-4) and np.all(sigma < 1e-6), (incident, sigma)
    with pytest.raises(ValueError, match="points"):
        _field().solve("surface-trace", points=0)
    # A standard error asked for: under a uniform sky of 1 W/m² as well, the ground's open
    # share of it varies under the leaf; it gets points until its error is there (3 W from
    # above through the gaps, 4 W from below, beside the sun's 30 W).
    result = _field(sky=1 / np.pi).solve("surface-trace", points=64, standard_error=0.005, seed=2)
    ground, sigma = result.incident_w[1].mean(), result.incident_w_sigma[1].mean()
    assert 0 < sigma <= 0.005 * ground and abs(ground - (3 * SUN + 7)) <= 3 * sigma, (ground, sigma)


def test_a_ground_at_the_bottom_of_all_geometry_stops_the_sky_from_below():
    # A uniform sky of radiance 1/π brings 1 W/m² down through the plot's top and 1 W/m² up
    # through its bottom: the leaf (top side: 1 W; its underside sees only the black ground)
    # 1 W, the ground 3 W from above and 4 W from below.
    result = _field(sun=None, sky=1 / np.pi).solve("light-trace", photons=400_000, seed=5)
    incident = result.incident_w.mean(axis=1)[:2]
    sigma = result.incident_w_sigma.mean(axis=1)[:2]
    assert np.all(np.abs(incident - [1.0, 7.0]) <= 3 * sigma + 1e-9), (incident, sigma)


def test_radiosity_solves_a_plot_with_copies_around_it():
    # The plot's own objects are reported, their light exact to 0.1 % (the leaf's four
    # quarters catch the sun through the plot's four corners); a margin of copies is a
    # setting, a negative one refused.
    for margin in ({}, {"periodic_margin": 0.25}):
        result = _field().solve("hierarchical", **margin)
        assert result.names == ["leaf", "ground"]
        incident = result.incident_w.mean(axis=1)
        assert np.allclose(incident, [SUN, 3 * SUN], rtol=1e-3), incident
    with pytest.raises(ValueError, match="periodic-margin"):
        _field().solve("hierarchical", periodic_margin=-1.0)


def test_a_bad_plot_is_refused():
    with pytest.raises(ValueError, match=r"periodic: the plot's x range must be"):
        _field(periodic=(0.0, 0.0, 0.0, 2.0))
    with pytest.raises(ValueError, match=r"z range"):
        _field(periodic=(0.0, 2.0, 0.0, float("nan")))
    with pytest.raises(ValueError, match="expected four"):
        _field(periodic=(0.0, 2.0, 0.0))


def test_a_periodic_scene_pickles_as_periodic():
    scene = _field()
    restored = pickle.loads(pickle.dumps(scene))
    # Rebuilt from its recipe, not the same compiled scene.
    assert restored is not scene and restored._scene is not scene._scene
    assert restored.periodic == PLOT
    a, b = _light(scene), _light(restored)
    assert np.array_equal(a.incident_w, b.incident_w), (a.incident_w, b.incident_w)
    assert a.incident_w[0, 0] == b.incident_w[0, 0] > 0


def test_a_scene_that_is_not_periodic_says_so():
    assert _field(periodic=None).periodic is None
    assert strahl.load("field:20").periodic is not None
