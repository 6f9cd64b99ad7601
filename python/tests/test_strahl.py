"""The Python package end to end: arrays out of every kind of method, against the command
line's report and an independent method; errors, threads, cancellation and progress."""

import _thread
import json
import os
import signal
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import strahl

ROOT = Path(__file__).resolve().parents[2]
CLI = Path(os.environ.get("STRAHL_BIN", ROOT / "target" / "release" / "strahl"))


def test_a_solve_gives_one_row_per_surface_in_watts_and_lux():
    scene = strahl.load("cornell")
    assert scene.name == "cornell"
    assert "floor" in scene.objects
    result = scene.solve("hierarchical")
    assert result.names == scene.objects
    n = len(result.names)
    assert result.absorbed_w.shape == (n, 3)
    assert result.incident_w.shape == (n, 3)
    assert result.illuminance_lux.shape == (n,)
    assert np.isfinite(result.absorbed_w).all() and (result.absorbed_w >= 0).all()
    # The rows add up to the report's total, and lux is 683 × the luminance of E.
    total = np.array(result.report["totals"]["absorbed_power"])
    assert np.allclose(result.absorbed_w.sum(axis=0), total, rtol=1e-12)
    y = result.irradiance_w_m2 @ np.array([0.2126, 0.7152, 0.0722])
    assert np.allclose(result.illuminance_lux, 683.0 * y, rtol=1e-9)


def test_python_gives_the_command_lines_report(tmp_path):
    if not CLI.exists():
        pytest.skip(f"no command line at {CLI} (cargo build --release)")
    report = tmp_path / "r.json"
    subprocess.run(
        [CLI, "solve", "cornell", "--solver", "hierarchical", "-q", "--report", report],
        check=True,
    )
    by_cli = json.loads(report.read_text())
    by_python = strahl.load("cornell").solve("hierarchical").report
    assert by_python["objects"] == by_cli["objects"]
    assert by_python["totals"] == by_cli["totals"]


def test_the_arrays_are_the_reports_columns():
    result = strahl.load("cornell").solve("hierarchical", per_face=True)
    rows = result.report["objects"]
    assert result.names == [r["name"] for r in rows]
    np.testing.assert_array_equal(result.absorbed_w, [r["absorbed_power"] for r in rows])
    np.testing.assert_array_equal(result.illuminance_lux, [r["illuminance_lux"] for r in rows])
    np.testing.assert_array_equal(result.faces, [-1 if r.get("face") is None else r["face"] for r in rows])
    # Standard errors only where the final gather at the surfaces gathered: NaN elsewhere.
    sigma = [r.get("incident_power_standard_error") or [np.nan] * 3 for r in rows]
    np.testing.assert_array_equal(result.incident_w_sigma, sigma)
    assert np.isnan(result.incident_w_sigma).any() and not np.isnan(result.incident_w_sigma).all()
    with pytest.raises(ValueError, match="not a strahl report"):
        strahl._strahl.report_columns('{"objects": []}')


def test_radiosity_and_the_light_model_agree_surface_by_surface():
    scene = strahl.load("cornell")
    radiosity = scene.solve("hierarchical")
    photons = scene.solve("light-trace", photons=400_000, seed=3)
    a, b = radiosity.absorbed_w.sum(axis=1), photons.absorbed_w.sum(axis=1)
    # The lamp absorbs almost nothing; the rest within 3 % (the light model's 3σ at 4·10⁵
    # photons is about 1–2 % on the dimmest of them).
    big = a > 0.01 * a.sum()
    assert np.all(np.abs(b[big] / a[big] - 1) < 0.03), (a, b)


def test_a_render_is_a_height_by_width_by_3_radiance_array():
    image = strahl.load("cornell").render("pathtrace", width=64, height=48, samples_per_pixel=4)
    assert image.shape == (48, 64, 3) and image.dtype == np.float32
    assert np.isfinite(image).all()
    left, right = image[24, 13], image[24, 51]
    assert left[0] > 2 * left[1], left  # the red wall
    assert right[1] > 2 * right[0], right  # the green wall


def test_bad_input_raises_with_the_located_message(tmp_path):
    scene = tmp_path / "broken.toml"
    scene.write_text("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov = 'wide'\n")
    with pytest.raises(ValueError, match=r"broken\.toml:4:.*camera\.fov"):
        strahl.load(str(scene))
    with pytest.raises(ValueError, match="missing.toml. is neither a file nor a built-in scene"):
        strahl.load(str(tmp_path / "missing.toml"))
    cornell = strahl.load("cornell")
    with pytest.raises(ValueError, match="unknown method 'nonsense'.*hierarchical"):
        cornell.solve("nonsense")
    with pytest.raises(ValueError, match=r"hierarchical takes no setting 'photons' \(its settings: seed, surface-gather"):
        cornell.solve("hierarchical", photons=10)
    with pytest.raises(ValueError, match=r"oracle 'best' is not one of: lischinski"):
        cornell.solve("hierarchical", oracle="best")
    with pytest.raises(ValueError, match="clustering must be true or false"):
        cornell.solve("hierarchical", clustering=1)
    with pytest.raises(ValueError, match="min-area must lie between"):
        cornell.solve("hierarchical", min_area=2.0)
    with pytest.raises(ValueError, match="spp must be at least 1"):
        cornell.render("pathtrace", width=8, height=8, samples_per_pixel=0)
    with pytest.raises(ValueError, match="use render"):
        cornell.solve("pathtrace")
    with pytest.raises(ValueError):
        cornell.solve("light-trace", photons=0)


def test_two_threads_solve_at_once_and_get_what_one_gets():
    scene = strahl.load("canopy:300")
    alone = scene.solve("light-trace", photons=200_000, threads=1).absorbed_w
    results = [None, None]

    def solve(k):
        results[k] = scene.solve("light-trace", photons=200_000, threads=1).absorbed_w

    threads = [threading.Thread(target=solve, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert np.array_equal(r, alone)


def test_ctrl_c_raises_keyboard_interrupt_within_a_second():
    scene = strahl.load("canopy:3000")
    # Python's own Ctrl-C handler, also where the process started with SIGINT ignored (a
    # background job): interrupt_main acts only through it.
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        timer = threading.Timer(0.5, _thread.interrupt_main)
        started = time.monotonic()
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            # Some twenty seconds of work, should the interrupt not come.
            scene.solve("light-trace", photons=2 * 10**8)
        assert time.monotonic() - started < 2.5
    finally:
        signal.signal(signal.SIGINT, before)


def test_progress_is_reported_by_phase():
    seen = []
    strahl.load("cornell").solve("hierarchical", progress=lambda *p: seen.append(p))
    phases = {phase for phase, _, _ in seen}
    assert "solving" in phases or "linking" in phases, seen
    assert all(done >= 0 and total >= 0 for _, done, total in seen)


def _sheet(y, size=1.0):
    """A horizontal square of side `size` at height y, as two triangles."""
    v = np.array([[0, y, 0], [size, y, 0], [size, y, size], [0, y, size]], dtype=float)
    return v, np.array([[0, 2, 1], [0, 3, 2]])


def test_a_scene_from_arrays_under_a_sky_receives_pi_times_the_radiance():
    # One black square under a uniform sky of radiance L = 1/π: its top receives E = πL = 1
    # W/m² from the whole sky, its bottom nothing (the sky is all around, but an open sheet's
    # underside sees the sky below too: E = 1 there as well, 2 W on 1 m² in all).
    v, t = _sheet(0.0)
    scene = strahl.from_arrays(v, t, [0, 0], ["sheet"], 0.0, sky=1 / np.pi)
    for method in ["hierarchical", "light-trace"]:
        result = scene.solve(method, photons=200_000) if method == "light-trace" else scene.solve(method)
        assert result.names == ["sheet"]
        assert np.allclose(result.area_m2, [1.0])
        assert np.allclose(result.absorbed_w, 2.0, rtol=0.02), (method, result.absorbed_w)


def test_a_translucent_leaf_passes_light_to_the_one_below_it():
    # A translucent sheet (ρ = 0.1, τ = 0.4) above a black one, lit by a vertical sun of
    # 1 W/m² (no sky): the upper absorbs 1 − ρ − τ = 0.5 W; the lower receives the 0.4 W
    # the upper sends down, diffusely, less what escapes at the sides (a share set by the
    # gap: 1 m sheets 0.1 m apart keep most), and absorbs all it receives.
    top_v, top_t = _sheet(0.1)
    low_v, low_t = _sheet(0.0)
    vertices = np.vstack([top_v, low_v])
    triangles = np.vstack([top_t, low_t + 4])
    scene = strahl.from_arrays(
        vertices, triangles, [0, 0, 1, 1], ["upper", "lower"], [0.1, 0.0],
        translucency=[0.4, 0.0], sun=([0, -1, 0], 1.0),
    )
    hierarchical = scene.solve("hierarchical").absorbed_w.mean(axis=1)
    photons = scene.solve("light-trace", photons=400_000).absorbed_w.mean(axis=1)
    assert abs(hierarchical[0] - 0.5) < 0.01, hierarchical
    assert 0.3 < hierarchical[1] < 0.4, hierarchical
    assert np.allclose(hierarchical, photons, rtol=0.02), (hierarchical, photons)


def test_per_face_reports_every_triangle_and_bad_arrays_are_refused():
    v, t = _sheet(0.0)
    scene = strahl.from_arrays(v, t, [0, 0], ["leaf"], 0.2, sun=([0, -1, 0], 1.0), per_face=True)
    result = scene.solve("hierarchical")
    assert len(result.names) == 2
    # Each triangle absorbs (1 − ρ) × 0.5 m² × 1 W/m².
    assert np.allclose(result.absorbed_w, 0.4, rtol=1e-3), result.absorbed_w
    with pytest.raises(ValueError, match="triangle 1 names vertex"):
        strahl.from_arrays(v, [[0, 1, 2], [0, 1, 9]], [0, 0], ["x"], 0.5)
    with pytest.raises(ValueError, match="object 3 of 1"):
        strahl.from_arrays(v, t, [0, 3], ["x"], 0.5)
    with pytest.raises(ValueError, match="add up to at most 1"):
        strahl.from_arrays(v, t, [0, 0], ["x"], 0.7, translucency=0.5)
    with pytest.raises(ValueError, match="sky's radiance must be finite and not negative"):
        strahl.from_arrays(v, t, [0, 0], ["x"], 0.5, sky=float("nan"))
    with pytest.raises(ValueError, match="sun's irradiance must be finite and not negative"):
        strahl.from_arrays(v, t, [0, 0], ["x"], 0.5, sun=([0, -1, 0], -1.0))
    with pytest.raises(ValueError, match="direction must not be zero"):
        strahl.from_arrays(v, t, [0, 0], ["x"], 0.5, sun=([0, 0, 0], 1.0))
    with pytest.raises(ValueError, match="vertices: shape"):
        strahl.from_arrays(v[:, :2], t, [0, 0], ["x"], 0.5)


def test_sensors_come_as_arrays(tmp_path):
    # The furnace: a closed box emitting L = 2 on both sides with ρ = 0.5; at its centre a
    # sensor reads E = πL/(1 − ρ) = 4π W/m², 683·4π lux.
    scene = tmp_path / "furnace.toml"
    scene.write_text(
        "[materials.glow]\ndiffuse = 0.5\nemission = 2.0\ntwo_sided = true\n\n"
        '[[objects]]\nname = "box"\ntype = "box"\nmaterial = "glow"\n'
        "min = [0, 0, 0]\nmax = [1, 1, 1]\n\n"
        '[[sensors]]\nname = "middle"\nposition = [0.5, 0.5, 0.5]\nnormal = [0, -1, 0]\n'
    )
    result = strahl.load(str(scene)).solve("matrix")
    assert result.sensor_names == ["middle"]
    assert np.allclose(result.sensor_irradiance_w_m2, 4 * np.pi, rtol=1e-3)
    assert np.allclose(result.sensor_lux, 683 * 4 * np.pi, rtol=1e-3)
    assert strahl.load("cornell").solve("hierarchical").sensor_lux.shape == (0,)


def test_every_setting_is_a_keyword_and_gives_what_the_command_line_gives(tmp_path):
    assert strahl.settings("light-trace") == ["seed", "photons", "max_bounces"]
    assert "mesh_size" in strahl.settings("hierarchical")
    assert {"width", "height", "spp", "depth", "time_limit"} <= set(strahl.settings("pathtrace"))
    report = tmp_path / "r.json"
    flags = ["--error", "1e-3", "--min-area", "1e-4", "--link-samples", "4", "--no-clustering",
             "--max-rounds", "5", "--oracle", "bfa", "--surface-gather", "0.02", "--mesh-size", "levels:1"]
    subprocess.run(
        [CLI, "solve", "cornell", "--solver", "hierarchical", "-q", "--report", report, *flags],
        check=True,
    )
    by_cli = json.loads(report.read_text())["objects"]
    by_python = strahl.load("cornell").solve(
        "hierarchical", error=1e-3, min_area=1e-4, link_samples=4, clustering=False,
        max_rounds=5, oracle="bfa", surface_gather=0.02, mesh_size="levels:1",
    ).report["objects"]
    default = strahl.load("cornell").solve("hierarchical").report["objects"]
    key = lambda rows: [(r["name"], r["absorbed_power"]) for r in rows]
    assert key(by_python) == key(by_cli)
    assert key(by_python) != key(default)
    # numpy's bools (from masks and comparisons) are switches as Python's are.
    by_numpy = strahl.load("cornell").solve(
        "hierarchical", error=np.float64(1e-3), min_area=1e-4, link_samples=np.int64(4),
        clustering=np.False_, max_rounds=5, oracle="bfa", surface_gather=0.02,
        mesh_size="levels:1",
    ).report["objects"]
    assert key(by_numpy) == key(by_cli)


def test_per_triangle_results_of_whole_objects_sum_to_the_objects():
    v, t = _sheet(0.0)
    # Two leaves of two triangles each, the upper one lit by the sun, the lower one in its
    # shade and the sky's light.
    below = v + np.array([0.0, -0.5, 0.0])
    scene = strahl.from_arrays(
        np.vstack([v, below]), np.vstack([t, t + 4]), [0, 0, 1, 1], ["upper", "lower"], 0.3,
        translucency=0.2, sun=([0.3, -1, 0.1], 1.0), sky=0.05,
    )
    whole = scene.solve("light-trace", photons=200_000, seed=4)
    faces = scene.solve("light-trace", photons=200_000, seed=4, per_face=True)
    assert faces.names == ["upper", "upper", "lower", "lower"]
    assert list(faces.faces) == [0, 1, 0, 1]
    assert list(whole.faces) == [-1, -1]
    # The same photons: each object's triangles add up to the object.
    summed = faces.by_object()
    assert summed.names == whole.names
    assert np.allclose(summed.absorbed_w, whole.absorbed_w, rtol=1e-12, atol=0)
    assert np.allclose(summed.illuminance_lux, whole.illuminance_lux, rtol=1e-12)
    assert np.allclose(summed.area_m2, [1.0, 1.0])
    assert np.all(np.isnan(summed.lux_sigma)) and np.all(whole.lux_sigma > 0)
    # Rows of no area have no mean: NaN, never infinite.
    from dataclasses import replace

    flat = replace(faces, area_m2=np.array([0.0, 0.0, 0.5, 0.5])).by_object()
    assert np.all(np.isnan(flat.irradiance_w_m2[0])) and np.isnan(flat.illuminance_lux[0])
    assert np.all(np.isfinite(flat.irradiance_w_m2[1]))
    # Direct and indirect light are told apart, and add up to the whole.
    assert np.allclose(whole.direct_lux + whole.indirect_lux, whole.illuminance_lux, rtol=1e-9)
    assert np.all(faces.incident_w_sigma > 0)
    # Hierarchical radiosity per triangle agrees with the light model.
    by_radiosity = scene.solve("hierarchical", per_face=True)
    sigma = faces.incident_w_sigma.mean(axis=1)
    assert np.all(np.abs(by_radiosity.incident_w.mean(axis=1) - faces.incident_w.mean(axis=1)) < 4 * sigma + 0.01 * faces.incident_w.mean(axis=1))


def test_render_settings_reach_the_image():
    cornell = strahl.load("cornell")
    full = cornell.render("pathtrace", width=24, height=18, samples_per_pixel=4)
    direct = cornell.render("pathtrace", width=24, height=18, samples_per_pixel=4, depth=1)
    # One scattering event at most: no light reflected between the walls.
    assert direct.mean() < 0.9 * full.mean()
    flat = cornell.render("radiosity", width=24, height=18, shading="flat", error=1e-3)
    smooth = cornell.render("radiosity", width=24, height=18, error=1e-3)
    assert flat.shape == smooth.shape == (18, 24, 3) and not np.array_equal(flat, smooth)


def test_reports_and_meshes_are_written_as_the_command_line_writes_them(tmp_path):
    cornell = strahl.load("cornell")
    result = cornell.solve("hierarchical", export=tmp_path / "box.glb")
    assert (tmp_path / "box.glb").read_bytes()[:4] == b"glTF"
    result.write_report(tmp_path / "r.csv")
    result.write_report(tmp_path / "r.json")
    by_cli = tmp_path / "cli.csv"
    subprocess.run([CLI, "solve", "cornell", "--solver", "hierarchical", "-q", "--report", by_cli], check=True)
    assert (tmp_path / "r.csv").read_text() == by_cli.read_text()
    assert json.loads((tmp_path / "r.json").read_text()) == result.report
    with pytest.raises(ValueError, match="makes none"):
        cornell.solve("light-trace", photons=1000, export=tmp_path / "x.glb")
    with pytest.raises(ValueError):
        cornell.solve("hierarchical", export=tmp_path / "x.obj")


def test_a_leaf_under_a_cie_sky_and_the_sun_of_a_date_and_place():
    import datetime

    # NREL's published example: Golden, Colorado, 2003-10-17 12:30:30 at UTC−7.
    sun = strahl.sun_position(
        datetime.datetime(2003, 10, 17, 12, 30, 30), -7, 39.742476, -105.1786,
        elevation_m=1830.14, pressure_mbar=820, temperature_c=11, delta_t_s=67,
    )
    assert abs(sun.zenith_deg - 50.11162) < 1e-4 and abs(sun.azimuth_deg - 194.34024) < 1e-4
    assert abs(np.linalg.norm(sun.direction) - 1) < 1e-12
    assert abs(np.degrees(np.arccos(sun.direction[1])) - sun.zenith_deg) < 1e-9
    # South of west a little (azimuth 194°): −z is north, +x east.
    assert sun.direction[2] > 0 and sun.direction[0] < 0
    # An open black sheet under the CIE clear sky receives the diffuse horizontal irradiance
    # on its top (nothing from below the horizon), and the sun's beam times cos(zenith).
    v, t = _sheet(0.0)
    scene = strahl.from_arrays(
        v, t, [0, 0], ["sheet"], 0.0,
        sun=(-sun.direction, 800.0), cie_sky=(12, sun.direction, 110.0),
    )
    expected = 110.0 + 800.0 * sun.direction[1]
    for method in ["hierarchical", "light-trace"]:
        result = scene.solve(method, photons=400_000) if method == "light-trace" else scene.solve(method)
        assert np.allclose(result.incident_w, expected, rtol=0.01), (method, result.incident_w, expected)
    with pytest.raises(ValueError, match="type must be 1 to 15"):
        strahl.from_arrays(v, t, [0, 0], ["x"], 0.5, cie_sky=(16, [0, 1, 0], 100.0))
    with pytest.raises(ValueError, match="above the horizon"):
        strahl.from_arrays(v, t, [0, 0], ["x"], 0.5, cie_sky=(1, [0, -1, 0], 100.0))
