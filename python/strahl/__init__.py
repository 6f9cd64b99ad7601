"""strahl: global illumination by radiosity and ray tracing, with the light every surface
receives and absorbs.

    >>> import strahl
    >>> scene = strahl.load("canopy:300")
    >>> result = scene.solve("hierarchical")
    >>> result.absorbed_w.shape            # one row per reported surface, R, G, B in watts
    (301, 3)

Units: lengths in scene units (metres for lux), powers in W, irradiance in W/m², illuminance
in lux (683 lm/W times the luminance), radiance in W/(sr·m²), linear Rec.709 RGB.
"""

from __future__ import annotations

import json
import uuid
from collections import OrderedDict
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Callable, NamedTuple, Optional

import numpy as np

from . import _strahl

__all__ = ["load", "from_arrays", "settings", "sun_position", "Scene", "Result", "Band", "State", "SunPosition"]


@dataclass(frozen=True)
class State:
    """One state of a scene's ``day`` light alone (its sun and sky at full strength), one row
    per reported surface as in :class:`Result`."""

    time: str
    """The state's clock time as the scene gives it."""
    incident_w: np.ndarray
    """Power arriving on each surface, W, shape (n, 3)."""
    absorbed_w: np.ndarray
    """Power absorbed by each surface, W, shape (n, 3)."""
    irradiance_w_m2: np.ndarray
    """Mean irradiance on each surface, W/m², shape (n, 3) (NaN where not known)."""


@dataclass(frozen=True)
class Band:
    """The light in one wavelength band of a scene with ``[[bands]]``, one row per reported
    surface (as in :class:`Result`) and per sensor."""

    name: str
    """The band's name."""
    from_nm: float
    """Shortest wavelength, nm."""
    to_nm: float
    """Longest wavelength, nm."""
    incident_w: np.ndarray
    """Power arriving on each surface in the band, W, shape (n,)."""
    absorbed_w: np.ndarray
    """Power absorbed by each surface in the band, W, shape (n,)."""
    irradiance_w_m2: np.ndarray
    """Mean irradiance in the band, W/m², shape (n,) (NaN where the area is not known)."""
    incident_umol_s: np.ndarray
    """Photon flux arriving, µmol/s, shape (n,)."""
    absorbed_umol_s: np.ndarray
    """Photon flux absorbed, µmol/s, shape (n,)."""
    photon_irradiance_umol_m2_s: np.ndarray
    """Mean photon irradiance, µmol m⁻² s⁻¹ (PPFD in a 400–700 nm band), shape (n,)."""
    incident_w_sigma: np.ndarray
    """Standard error of the incident power, W, shape (n,) (NaN where the method has none)."""
    sensor_irradiance_w_m2: np.ndarray
    """Irradiance at each sensor in the band, W/m², shape (s,)."""
    sensor_photon_irradiance_umol_m2_s: np.ndarray
    """Photon irradiance at each sensor, µmol m⁻² s⁻¹, shape (s,)."""


@dataclass(frozen=True)
class Result:
    """The light on every reported surface (one row per object, or per face of per-face
    objects, in scene order), from one method's run."""

    names: list
    """The surfaces' names."""
    area_m2: np.ndarray
    """Area of each surface, scene units² (NaN where the method does not know it)."""
    incident_w: np.ndarray
    """Power arriving on each surface, W, shape (n, 3)."""
    absorbed_w: np.ndarray
    """Power absorbed by each surface, W, shape (n, 3)."""
    irradiance_w_m2: np.ndarray
    """Mean irradiance on each surface, W/m², shape (n, 3) (NaN where not known)."""
    illuminance_lux: np.ndarray
    """Mean illuminance on each surface, lux, shape (n,) (NaN where not known)."""
    faces: np.ndarray
    """The face of its object each row reports (per-face objects, or ``per_face=True``; for
    a scene from arrays a face is a triangle, numbered as given), -1 for a whole object,
    shape (n,)."""
    direct_w: np.ndarray
    """Of the incident power, what came straight from the lights and the sky, W, shape (n, 3)
    (NaN where the method does not tell it apart)."""
    direct_lux: np.ndarray
    """Illuminance by direct light, lux, shape (n,) (NaN where not told apart)."""
    indirect_lux: np.ndarray
    """Illuminance by light reflected or sent on by other surfaces, lux, shape (n,) (NaN
    where not told apart)."""
    incident_w_sigma: np.ndarray
    """Standard error of the incident power, W, shape (n, 3) (Monte Carlo figures; NaN
    where the method has none)."""
    lux_sigma: np.ndarray
    """Standard error of the illuminance, lux, shape (n,) (NaN where none)."""
    sensor_names: list
    """The sensors' names (``name[i,j]`` for a point of a grid), in scene order."""
    sensor_lux: np.ndarray
    """Illuminance at each sensor, lux, shape (s,)."""
    sensor_irradiance_w_m2: np.ndarray
    """Irradiance at each sensor, W/m², shape (s, 3)."""
    _json: str = field(repr=False, compare=False)
    bands: dict = field(default_factory=dict)
    """For a scene with ``[[bands]]``: each band's :class:`Band` by its name, in the scene's
    order; empty otherwise."""
    red_far_red: Optional[np.ndarray] = None
    states: list = field(default_factory=list)
    """For a scene with a ``day`` light: each state alone, a :class:`State` each, in order
    (the other figures are the mean over them); empty otherwise."""
    """The red : far-red ratio of the photon irradiance per surface, shape (n,) (NaN where
    there is no far red), for scenes with bands named ``red`` and ``far-red``; else None."""

    @cached_property
    def report(self) -> dict:
        """The whole report, as `strahl solve --report FILE.json` writes it (read from its
        JSON when first asked for)."""
        return json.loads(self._json)

    def report_json(self) -> str:
        """The report as JSON text."""
        return json.dumps(self.report, indent=2)

    def write_report(self, path) -> None:
        """Writes the report as ``strahl solve --report PATH`` does: ``.json`` (the whole
        report) or ``.csv`` (one row per surface, the sensors in ``NAME.sensors.csv``)."""
        _strahl.write_report(self._json, str(path))

    def by_object(self) -> "Result":
        """The rows of each object (its faces, when reported per face) summed into one row
        per object name, in order of first appearance: powers add, irradiance and
        illuminance are the area-weighted means. Standard errors are NaN (a sum of faces'
        figures does not give the object's: the faces' errors are correlated); solve without
        ``per_face`` for them. Sensors are kept."""
        order = list(dict.fromkeys(self.names))
        index = {n: k for k, n in enumerate(order)}
        rows = np.array([index[n] for n in self.names], dtype=int)
        k = len(order)

        def total(values):
            out = np.zeros((k,) + values.shape[1:])
            np.add.at(out, rows, values)
            return out

        area = total(self.area_m2)
        known = area > 0  # a sum of no area (or of an unknown one) has no mean: NaN

        def per_area(values):
            shape = (k,) + (1,) * (values.ndim - 1)
            return np.divide(values, area.reshape(shape), out=np.full(values.shape, np.nan), where=known.reshape(shape))

        weighted = lambda values: per_area(total(values * self.area_m2.reshape((-1,) + (1,) * (values.ndim - 1))))
        return replace(
            self,
            names=order,
            area_m2=area,
            faces=np.full(k, -1),
            incident_w=total(self.incident_w),
            absorbed_w=total(self.absorbed_w),
            irradiance_w_m2=per_area(total(self.incident_w)),
            illuminance_lux=weighted(self.illuminance_lux),
            direct_w=total(self.direct_w),
            direct_lux=weighted(self.direct_lux),
            indirect_lux=weighted(self.indirect_lux),
            incident_w_sigma=np.full((k, 3), np.nan),
            lux_sigma=np.full(k, np.nan),
            bands={
                name: replace(
                    b,
                    incident_w=total(b.incident_w),
                    absorbed_w=total(b.absorbed_w),
                    irradiance_w_m2=per_area(total(b.incident_w)),
                    incident_umol_s=total(b.incident_umol_s),
                    absorbed_umol_s=total(b.absorbed_umol_s),
                    photon_irradiance_umol_m2_s=per_area(total(b.incident_umol_s)),
                    incident_w_sigma=np.full(k, np.nan),
                )
                for name, b in self.bands.items()
            },
            red_far_red=None if self.red_far_red is None else _ratio(self.bands, order, total),
            states=[
                replace(
                    st,
                    incident_w=total(st.incident_w),
                    absorbed_w=total(st.absorbed_w),
                    irradiance_w_m2=per_area(total(st.incident_w)),
                )
                for st in self.states
            ],
        )


def _ratio(bands: dict, order: list, total) -> np.ndarray:
    """The red : far-red ratio of the summed photon flux of bands named red and far-red."""
    pick = lambda names: next(b for n, b in bands.items() if n.lower() in names)
    red, far = total(pick({"red"}).incident_umol_s), total(pick({"far-red", "far_red"}).incident_umol_s)
    return np.divide(red, far, out=np.full(len(order), np.nan), where=far > 0)


def _result(report_json: str) -> Result:
    columns = _strahl.report_columns(report_json)

    def array(values, width=1):
        values = np.frombuffer(values, dtype="<f8")
        return values.reshape(-1, width) if width > 1 else values

    def band(b):
        return Band(
            name=b["name"],
            from_nm=b["from_nm"],
            to_nm=b["to_nm"],
            incident_w=array(b["incident_power"]),
            absorbed_w=array(b["absorbed_power"]),
            irradiance_w_m2=array(b["irradiance"]),
            incident_umol_s=array(b["incident_photons_umol_s"]),
            absorbed_umol_s=array(b["absorbed_photons_umol_s"]),
            photon_irradiance_umol_m2_s=array(b["photon_irradiance_umol_m2_s"]),
            incident_w_sigma=array(b["incident_power_standard_error"]),
            sensor_irradiance_w_m2=array(b["sensor_irradiance"]),
            sensor_photon_irradiance_umol_m2_s=array(b["sensor_photon_irradiance_umol_m2_s"]),
        )

    def state(st):
        return State(
            time=st["time"],
            incident_w=array(st["incident_power"], 3),
            absorbed_w=array(st["absorbed_power"], 3),
            irradiance_w_m2=array(st["irradiance"], 3),
        )

    sensors, ratio, faces = columns["sensors"], columns["red_far_red"], array(columns["face"])
    return Result(
        states=[state(st) for st in columns["states"]],
        bands={b["name"]: band(b) for b in columns["bands"]},
        red_far_red=None if ratio is None else array(ratio),
        sensor_names=sensors["names"],
        sensor_lux=array(sensors["illuminance_lux"]),
        sensor_irradiance_w_m2=array(sensors["irradiance"], 3),
        names=columns["names"],
        area_m2=array(columns["area"]),
        incident_w=array(columns["incident_power"], 3),
        absorbed_w=array(columns["absorbed_power"], 3),
        irradiance_w_m2=array(columns["irradiance"], 3),
        illuminance_lux=array(columns["illuminance_lux"]),
        faces=np.where(np.isnan(faces), -1, faces).astype(int),
        direct_w=array(columns["direct_power"], 3),
        direct_lux=array(columns["direct_illuminance_lux"]),
        indirect_lux=array(columns["indirect_illuminance_lux"]),
        incident_w_sigma=array(columns["incident_power_standard_error"], 3),
        lux_sigma=array(columns["illuminance_standard_error_lux"]),
        _json=report_json,
    )


class Scene:
    """A scene compiled for ray queries: open one with :func:`load` or build one with
    :func:`from_arrays`. It pickles as what it was made from (a name, or the arrays), so it
    travels to other processes — Dask workers — which compile it once each."""

    def __init__(self, compiled: _strahl.Scene, recipe: tuple):
        self._scene = compiled
        self._recipe = recipe
        self._token = uuid.uuid4().hex

    def __reduce__(self):
        return (_rebuilt, (self._recipe, self._token))

    @property
    def name(self) -> str:
        """The scene's name."""
        return self._scene.name

    @property
    def objects(self) -> list:
        """The objects' names, in scene order."""
        return self._scene.objects

    @property
    def periodic(self) -> Optional[tuple]:
        """The plot ``(x0, x1, z0, z1)`` (scene units, single precision) that a periodic
        scene repeats without end in x and z, or None for a scene that is not periodic."""
        return self._scene.periodic

    def solve(
        self,
        method: str = "hierarchical",
        *,
        seed: int = 0,
        threads: int = 0,
        per_face: bool = False,
        diffuse_only: bool = False,
        export=None,
        progress: Optional[Callable[[str, int, int], None]] = None,
        **settings,
    ) -> Result:
        """Runs a method that reports the light on every surface: ``light-trace`` (the light
        model), ``surface-trace`` (rays from points on every surface, each to a share of its
        own light: ``points=256``, or ``standard_error=0.03`` to add points where a surface
        needs them), ``matrix``, ``progressive``, ``hierarchical`` or
        ``hierarchical-shooting``.

        ``settings`` are the method's settings by the command line's names with ``_`` for
        ``-`` (``photons=10**7``, ``error=1e-5``, ``mesh_size="levels:2"``,
        ``oracle="lischinski"``, ``clustering=False``, ``surface_gather=0``; see
        :func:`settings` and ``strahl solve --help`` for each one's meaning and units); a
        setting the method does not take raises ValueError. ``per_face=True`` reports every
        face of every object on its own (a triangle, for a scene from arrays: per triangle
        results aligned with the input; :meth:`Result.by_object` sums them per object);
        ``diffuse_only=True`` drops the materials' specular, mirror and refracting lobes.
        ``export="room.glb"`` (``.gltf``, ``.ply``) also writes a radiosity solver's solution
        as a mesh with radiosity vertex colours; :meth:`Result.write_report` writes the report
        as JSON or CSV.
        ``threads=0`` uses every core; the GIL is released meanwhile. ``progress(phase,
        done, total)`` is called as the work goes. Ctrl-C raises KeyboardInterrupt within a
        second. Bad settings raise ValueError with the command line's message."""
        report = self._scene.solve(
            method,
            seed=seed,
            threads=threads,
            settings=_named(settings),
            per_face=per_face,
            diffuse_only=diffuse_only,
            export=None if export is None else str(export),
            progress=progress,
        )
        return _result(report)

    def render(
        self,
        method: str = "pathtrace",
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        samples_per_pixel: Optional[int] = None,
        seed: int = 0,
        threads: int = 0,
        progress: Optional[Callable[[str, int, int], None]] = None,
        **settings,
    ) -> np.ndarray:
        """Renders the scene's camera view: ``pathtrace``, ``raytrace``, ``radiosity`` or
        ``final-gather``, ``width`` × ``height`` pixels (the scene camera's where not given),
        ``samples_per_pixel`` (the command line's ``spp``) and the method's other
        ``settings`` by name as for :meth:`solve` (``depth=8``, ``time_limit=2.0`` seconds,
        ``shading="flat"``, ``error=1e-3`` for the radiosity solve behind an image). Returns
        the linear radiance, W/(sr·m²), as a float32 array of shape (height, width, 3), rows
        from the top."""
        named = dict(width=width, height=height, spp=samples_per_pixel, **settings)
        return _image(*self._scene.render(method, seed=seed, threads=threads, settings=_named(named), progress=progress))


def _image(width: int, height: int, pixels: bytes) -> np.ndarray:
    """Little-endian f32 RGB rows from the top as a (height, width, 3) array."""
    return np.frombuffer(pixels, dtype="<f4").reshape(height, width, 3).copy()


def _named(settings: dict) -> list:
    """Python keywords as the library's setting names (``mesh_size`` → ``mesh-size``)."""
    return [(name.replace("_", "-"), value) for name, value in settings.items()]


def settings(method: str) -> list:
    """The names of the settings ``method`` takes as keywords of :meth:`Scene.solve` or
    :meth:`Scene.render` (``seed`` first)."""
    return [n.replace("-", "_") for n in _strahl.Scene.setting_names(method)]


def load(name: str) -> Scene:
    """Opens a built-in scene by name (``cornell``, ``canopy:300``, ``blocks:216``,
    ``field:2000``, …) or a scene file (``.toml``, ``.obj``, ``.gltf``/``.glb``, ``.mgf``).
    A bad file raises ValueError naming the file, line and field."""
    return Scene(_strahl.load(name), ("load", name))


def _rgb_rows(values, count: int, what: str) -> np.ndarray:
    """`values` (a number, an RGB triple, or one of either per row) as `count` RGB rows."""
    a = np.asarray(values, dtype=float)
    if a.ndim == 0:
        a = np.full((count, 3), float(a))
    elif a.shape == (3,) and count != 3:
        a = np.tile(a, (count, 1))
    elif a.ndim == 1 and a.shape[0] == count:
        a = np.repeat(a[:, None], 3, axis=1)
    if a.shape != (count, 3):
        raise ValueError(f"{what}: shape {a.shape}, expected ({count}, 3), ({count},), (3,) or a number")
    return a


def from_arrays(
    vertices,
    triangles,
    object_ids,
    names,
    reflectance,
    *,
    translucency=0.0,
    sun=None,
    sky=None,
    cie_sky=None,
    periodic=None,
    placements=None,
    per_face: bool = False,
    name: str = "arrays",
) -> Scene:
    """A scene of triangles from arrays, as a plant model hands over its organs:
    ``vertices`` (n, 3) in scene units (metres for lux), ``triangles`` (m, 3) vertex
    indices, ``object_ids`` (m,) the object of each triangle (an index into ``names``), and
    per object a diffuse ``reflectance`` and ``translucency`` (light passing to the other
    side, diffusely; ρ + τ ≤ 1 per channel) — each a number, an RGB triple, or one of
    either per object. Lights: ``sun=(direction, irradiance)`` (the direction its light
    travels; W/m² on a surface facing it, a number or RGB) and ``sky=radiance``
    (W/(sr·m²); an open horizontal surface then receives π × radiance) or
    ``cie_sky=(sky_type, sun_direction, diffuse_horizontal)``, one of the 15 CIE standard
    general skies (1 overcast … 12 clear … 15), brighter toward the sun (the direction toward
    it, above the horizon: :func:`sun_position` gives it), scaled so that an open horizontal
    surface receives ``diffuse_horizontal`` W/m² (a number or RGB). With ``per_face``
    every triangle is reported on its own. Surfaces reflect and transmit on both sides.

    ``periodic=(x0, x1, z0, z1)`` (scene units, y up) makes the scene a field: the plot
    x ∈ [x0, x1], z ∈ [z0, z1] repeats without end in x and z, and light leaving through
    one side enters through the opposite one. Geometry may reach over the plot's sides (at
    most two periods): what lies beyond a side is seen through the opposite one; a ground is
    a quad covering the plot. Powers are then per plot. Only the light model
    (``light-trace``) takes every light in a periodic scene; the ray tracers and the
    radiosity solvers take sun and sky only (ValueError otherwise). The radiosity solvers
    solve the plot with the copies of what reaches into it, the light the field beyond it
    reflects coming by rays; ``periodic_margin=`` (scene units) adds copies in a margin
    around it. A plot with a range that is empty (x1 ≤ x0 or z1 ≤ z0) or
    not finite raises ValueError.

    ``placements={name: matrices}`` places an object many times: ``matrices`` of shape
    (p, 3, 4) or (p, 4, 4), each an affine map (row-major, ``[R | t]``) from the object's
    triangles as given to where a copy stands. The object becomes p objects named
    ``name[i]`` that share its triangles — kept once, not copied, where there are 8 or more —
    so a plant of 10³ triangles can stand 10⁵ times in a field."""
    vertices = np.ascontiguousarray(vertices, dtype="<f4")
    triangles = np.ascontiguousarray(triangles, dtype="<u4")
    object_ids = np.ascontiguousarray(object_ids, dtype="<u4")
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise ValueError(f"vertices: shape {vertices.shape}, expected (n, 3)")
    if triangles.ndim != 2 or triangles.shape[1] != 3:
        raise ValueError(f"triangles: shape {triangles.shape}, expected (m, 3)")
    names = [str(n) for n in names]
    k = len(names)
    rho = np.ascontiguousarray(_rgb_rows(reflectance, k, "reflectance"), dtype="<f4")
    tau = np.ascontiguousarray(_rgb_rows(translucency, k, "translucency"), dtype="<f4")
    rgb = lambda v: tuple(float(x) for x in np.broadcast_to(np.asarray(v, dtype=float), (3,)))
    sun_light = None if sun is None else (rgb(sun[0]), rgb(sun[1]))
    sky_light = None if sky is None else rgb(sky)
    cie_light = None if cie_sky is None else (int(cie_sky[0]), rgb(cie_sky[1]), rgb(cie_sky[2]))
    plot = None
    if periodic is not None:
        plot = tuple(float(x) for x in np.asarray(periodic, dtype=float).reshape(-1))
        if len(plot) != 4:
            raise ValueError(f"periodic: {len(plot)} numbers, expected four (x0, x1, z0, z1)")
    placed = []
    for placed_name, matrices in (placements or {}).items():
        if str(placed_name) not in names:
            raise ValueError(f"placements: no object named {placed_name!r}")
        m = np.asarray(matrices, dtype="<f4")
        if m.ndim != 3 or m.shape[1:] not in ((3, 4), (4, 4)):
            raise ValueError(f"placements[{placed_name!r}]: shape {m.shape}, expected (p, 3, 4) or (p, 4, 4)")
        if m.shape[1] == 4 and not np.allclose(m[:, 3], [0, 0, 0, 1]):
            raise ValueError(f"placements[{placed_name!r}]: the last row of a 4 × 4 matrix must be 0, 0, 0, 1")
        rows = np.ascontiguousarray(m[:, :3, :].reshape(-1, 12), dtype="<f4")
        placed.append((names.index(str(placed_name)), rows.tobytes()))
    given = (
        name,
        vertices.tobytes(),
        triangles.tobytes(),
        object_ids.tobytes(),
        names,
        rho.tobytes(),
        tau.tobytes(),
        per_face,
        sun_light,
        sky_light,
        cie_light,
        plot,
        placed,
    )
    return Scene(_strahl.scene_from_arrays(*given), ("arrays", given))


class SunPosition(NamedTuple):
    """Where the sun is (:func:`sun_position`)."""

    zenith_deg: float
    """Angle from straight up, degrees (above 90 at night)."""
    azimuth_deg: float
    """Clockwise from north, degrees."""
    direction: np.ndarray
    """Unit vector toward the sun in strahl's frame: y up, −z north, +x east."""
    distance_au: float
    """Earth–Sun distance, astronomical units."""


def sun_position(
    when,
    utc_offset_hours: float,
    latitude_deg: float,
    longitude_deg: float,
    *,
    elevation_m: float = 0.0,
    pressure_mbar: float = 1013.25,
    temperature_c: float = 15.0,
    delta_t_s: float = 69.0,
) -> SunPosition:
    """The sun seen from a site (degrees north and east) at the local time ``when`` (a
    ``datetime.datetime``, ``utc_offset_hours`` ahead of UTC), by NREL's Solar Position
    Algorithm (to 10⁻⁵° on NREL's published example). The direction toward the sun is the
    ``sun`` of a CIE sky; a directional sun travels along its negative."""
    second = when.second + when.microsecond / 1e6
    zenith, azimuth, direction, distance = _strahl.sun_position(
        when.year, when.month, when.day, when.hour, when.minute, second, utc_offset_hours,
        latitude_deg, longitude_deg, elevation_m, pressure_mbar, temperature_c, delta_t_s,
    )
    return SunPosition(zenith, azimuth, np.array(direction), distance)


# Scenes rebuilt from pickles in this process, by the token of the scene pickled: a worker
# that runs many tasks on one scene compiles it once.
_REBUILT: "OrderedDict[str, Scene]" = OrderedDict()
_REBUILT_KEPT = 4


def _rebuilt(recipe: tuple, token: str) -> Scene:
    """The scene `recipe` describes, compiled once per process for each `token`."""
    scene = _REBUILT.get(token)
    if scene is None:
        kind, given = recipe
        compiled = _strahl.load(given) if kind == "load" else _strahl.scene_from_arrays(*given)
        scene = Scene(compiled, recipe)
        scene._token = token
        _REBUILT[token] = scene
        while len(_REBUILT) > _REBUILT_KEPT:
            _REBUILT.popitem(last=False)
    _REBUILT.move_to_end(token)
    return scene
