"""Type stub of the extension module (python/src/lib.rs); use it through `strahl`."""

from typing import Callable, Optional, Tuple

Progress = Optional[Callable[[str, int, int], None]]

class Scene:
    @property
    def name(self) -> str: ...
    @property
    def objects(self) -> list[str]: ...
    def solve(
        self,
        method: str,
        *,
        seed: int = 0,
        threads: int = 0,
        photons: Optional[int] = None,
        error: Optional[float] = None,
        progress: Progress = None,
    ) -> str:
        """The report as JSON (the `strahl solve --report` file)."""
    def render(
        self,
        method: str,
        *,
        width: Optional[int] = None,
        height: Optional[int] = None,
        samples_per_pixel: Optional[int] = None,
        seed: int = 0,
        threads: int = 0,
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
) -> Scene: ...
def light_trace_batch(
    name: str, photons: int, seed: int, index: int, count: int, threads: int = 0
) -> str: ...
def merge_batches(name: str, partials: list[str]) -> str: ...
