"""Wavelength bands from Python: the plant example's bands as numpy arrays (power, photons,
PPFD, R:FR), summed per object like the RGB figures, and a black square under a 5778 K sun
receiving the black body's share of the PAR band (Planck's fractional function, 0.366 659 4,
and 4.566 09 µmol per joule: tests/bands.rs derives both)."""

from pathlib import Path

import numpy as np
import pytest

import strahl
import strahl.distributed

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "plant-bands" / "plant.toml"

SQUARE = """
[[bands]]
name = "PAR"
from_nm = 400
to_nm = 700

[materials.black]
diffuse = 0
one_sided = true

[[objects]]
type = "quad"
name = "square"
material = "black"
vertices = [[0, 0, 1], [1, 0, 1], [1, 0, 0], [0, 0, 0]]

[[lights]]
type = "directional"
direction = [0, -1, 0]
irradiance = 1000
spectrum = { blackbody_k = 5778 }
"""


def test_the_plant_example_gives_every_leaf_its_bands():
    result = strahl.load(str(EXAMPLE)).solve("light-trace", photons=50_000)
    assert list(result.bands) == ["PAR", "red", "far-red", "NIR"]
    par, nir = result.bands["PAR"], result.bands["NIR"]
    n = len(result.names)
    assert par.incident_w.shape == (n,) and par.photon_irradiance_umol_m2_s.shape == (n,)
    leaves = [k for k, name in enumerate(result.names) if name.startswith("leaf")]
    assert len(leaves) == 9
    # Leaves absorb most of the PAR and little of the near infrared, as their spectra say.
    assert np.all(par.absorbed_w[leaves] > 0.8 * par.incident_w[leaves])
    assert np.all(nir.absorbed_w[leaves] < 0.3 * nir.incident_w[leaves])
    assert np.all(par.incident_w_sigma[leaves] > 0)
    assert result.red_far_red.shape == (n,) and np.all(result.red_far_red[leaves] > 0)
    summed = result.by_object()
    assert np.allclose(summed.bands["PAR"].absorbed_umol_s, par.absorbed_umol_s)


def test_a_scene_with_bands_is_not_split_into_batches():
    with pytest.raises(ValueError, match="not split into batches"):
        strahl.distributed.trace_batch(strahl.load(str(EXAMPLE)), 0, 2, photons=1000)


def test_a_black_square_receives_the_par_of_a_black_body(tmp_path):
    path = tmp_path / "square.toml"
    path.write_text(SQUARE)
    result = strahl.load(str(path)).solve("matrix")
    par = result.bands["PAR"]
    assert abs(par.incident_w[0] / (1000 * 0.366_659_443) - 1) < 1e-5
    assert abs(par.photon_irradiance_umol_m2_s[0] / (1000 * 0.366_659_443 * 4.566_089_469) - 1) < 1e-5
    assert result.red_far_red is None


DAY = """
[materials.black]
diffuse = 0

[[objects]]
type = "quad"
name = "plate"
material = "black"
vertices = [[0, 0, 1], [1, 0, 1], [1, 0, 0], [0, 0, 0]]

[[lights]]
type = "day"
sky_type = 12
date = "2026-06-21"
utc_offset_hours = 2
latitude_deg = 52.52
longitude_deg = 13.40
states = [
  { time = "02:30", direct_normal = 0, diffuse_horizontal = 0 },
  { time = "13:15", direct_normal = 800, diffuse_horizontal = 150 },
]
"""


def test_each_state_of_a_day_comes_back_alone(tmp_path):
    path = tmp_path / "day.toml"
    path.write_text(DAY)
    result = strahl.load(str(path)).solve("matrix")
    assert [s.time for s in result.states] == ["02:30", "13:15"]
    night, noon = result.states
    assert night.incident_w[0, 1] == 0
    # The day's figure is the mean of its two states (the solve is linear in the lights).
    assert abs(noon.incident_w[0, 1] / 2 / result.incident_w[0, 1] - 1) < 1e-6
    assert result.by_object().states[1].incident_w.shape == (1, 3)
