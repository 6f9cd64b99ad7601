"""Type stub of the extension module (python/src/lib.rs); use it through `strahl`."""

from typing import Any, Callable, Optional, Tuple

Progress = Optional[Callable[[str, int, int], None]]

class Scene:
    @property
    def name(self) -> str: ...
    @property
    def objects(self) -> list[str]: ...
    @property
    def periodic(self) -> Optional[Tuple[float, float, float, float]]:
        """The plot (x0, x1, z0, z1), scene units, a periodic scene repeats in x and z; None
        for a scene that is not periodic."""
    def solve(
        self,
        method: str,
        *,
        seed: int = 0,
        threads: int = 0,
        settings: list[Tuple[str, Any]] = [],
        per_face: bool = False,
        diffuse_only: bool = False,
        export: Optional[str] = None,
        progress: Progress = None,
    ) -> str:
        """The report as JSON (the `strahl solve --report` file)."""
    def batch(
        self,
        method: str,
        index: int,
        count: int,
        *,
        seed: int = 0,
        threads: int = 0,
        settings: list[Tuple[str, Any]] = [],
        per_face: bool = False,
        diffuse_only: bool = False,
        progress: Progress = None,
    ) -> str:
        """Batch `index` of `count` of the run, as JSON for `merge_light`."""
    def merge_light(self, partials: list[str], *, per_face: bool = False, diffuse_only: bool = False) -> str:
        """The report (JSON) of the whole run from all its batches."""
    def merge_render(self, partials: list[str]) -> Tuple[int, int, bytes]:
        """Width, height and linear radiance (f32 RGB) of the render from all its batches."""
    @staticmethod
    def setting_names(method: str) -> list[str]:
        """The settings `method` takes, by the command line's names (`seed` first)."""
    def render(
        self,
        method: str,
        *,
        seed: int = 0,
        threads: int = 0,
        settings: list[Tuple[str, Any]] = [],
        progress: Progress = None,
    ) -> Tuple[int, int, bytes]:
        """Width, height and linear radiance as little-endian f32 RGB, rows from the top."""

def load(name: str) -> Scene: ...
def scene_from_arrays(
    name: str,
    vertices: bytes,
    triangles: bytes,
    object_ids: bytes,
    names: list[str],
    reflectance: bytes,
    translucency: bytes,
    per_face: bool,
    sun: Optional[Tuple[Tuple[float, float, float], Tuple[float, float, float]]],
    sky: Optional[Tuple[float, float, float]],
    cie_sky: Optional[Tuple[int, Tuple[float, float, float], Tuple[float, float, float]]] = None,
    periodic: Optional[Tuple[float, float, float, float]] = None,
    placements: list[Tuple[int, bytes]] = ...,
) -> Scene:
    """`periodic`: the plot (x0, x1, z0, z1), scene units, repeated without end in x and z
    (y up); ValueError unless both ranges are finite with x0 < x1 and z0 < z1. `placements`:
    per placed object its index and little-endian `f32` 3 × 4 row-major matrices, one per
    copy."""
def sun_position(
    year: int, month: int, day: int, hour: int, minute: int, second: float,
    utc_offset_hours: float, latitude_deg: float, longitude_deg: float,
    elevation_m: float = 0.0, pressure_mbar: float = 1013.25, temperature_c: float = 15.0,
    delta_t_s: float = 69.0,
) -> Tuple[float, float, Tuple[float, float, float], float]: ...
def write_report(report: str, path: str) -> None: ...

def report_columns(json: str) -> dict:
    """The report ``json`` as columns: the objects' ``names`` and their figures as
    little-endian float64 bytes (NaN where the report has none; ``incident_power``,
    ``absorbed_power``, ``irradiance``, ``direct_power``, ``incident_power_standard_error``
    three numbers a row, ``area``, ``face``, ``illuminance_lux``, ``direct_illuminance_lux``,
    ``indirect_illuminance_lux``, ``illuminance_standard_error_lux`` one), ``sensors``,
    ``bands`` and ``states`` (a dict each) and ``red_far_red`` (or None)."""
