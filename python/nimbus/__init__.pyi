# Type stubs of the package nimbus (python/nimbus/__init__.py): what each call takes and returns.
import os
from typing import Any, Callable, Iterable, Literal, Mapping, Optional, Sequence, Union

import numpy
import numpy.typing

__version__: str
VOXEL_SIZE_RANGE_M: tuple[float, float]  # metres: the voxel sizes a Volume may have (generate's too)

_Path = Union[str, os.PathLike[str]]
_Vec3 = Sequence[float]

class Volume:
    """A density volume (or a float grid read from a file): voxels, their place in the world (metres)
    and the file's metadata."""

    @property
    def density(self) -> numpy.typing.NDArray[numpy.float32]:
        """float32 [x, y, z], a writable view of the volume's voxels (Fortran order, no copy): a
        density, or a read grid's values as its file holds them."""
    @property
    def origin(self) -> tuple[int, int, int]:
        """Index of density[0, 0, 0]; its centre is at origin * voxel_size metres."""
    @property
    def voxel_size(self) -> Union[float, tuple[float, float, float]]:
        """Metres per voxel edge (a 3-tuple when the voxels are not cubes)."""
    @property
    def index_to_world(self) -> Optional[list[tuple[float, float, float, float]]]:
        """4x4 rows taking (i, j, k, 1) to world metres; None for a frustum transform."""
    @property
    def linear(self) -> bool: ...
    @property
    def grid(self) -> str:
        """The grid's name: "density", or the one read from a file ("noise")."""
    @property
    def up_axis(self) -> Literal["z", "y"]: ...
    @property
    def metadata(self) -> dict[str, Union[str, float, int]]: ...
    @property
    def extra_grids(self) -> list[str]: ...
    def write(self, path: _Path, *, half_float: bool = ...) -> None:
        """Write an OpenVDB fog volume atomically, as `nimbus generate` does."""
    @staticmethod
    def from_array(array: numpy.typing.ArrayLike, voxel_size: float, origin: Sequence[int] = ..., *,
                   up_axis: Literal["z", "y"] = ...) -> "Volume":
        """A volume from user densities indexed [x, y, z] (finite, >= 0)."""

def presets() -> list[str]: ...
def preset(name: str) -> dict[str, Any]: ...
def plan(preset: str, *, seed: Optional[int] = ..., voxel_size: Optional[float] = ..., res: Optional[int] = ...,
         time: float = ..., overrides: Optional[Mapping[str, Any]] = ..., params_file: Optional[_Path] = ...,
         coverage_map: Any = ..., size: float = ...) -> dict[str, Any]: ...
def generate(preset: str, *, seed: Optional[int] = ..., voxel_size: Optional[float] = ..., res: Optional[int] = ...,
             time: float = ..., overrides: Optional[Mapping[str, Any]] = ..., params_file: Optional[_Path] = ...,
             coverage_map: Any = ..., size: float = ...,
             progress: Optional[Callable[[float], Any]] = ...) -> Volume: ...
def read(path: _Path, *, grid: Optional[str] = ...) -> Volume: ...
def render(volumes_or_paths: Union[Volume, _Path, Iterable[Union[Volume, _Path]]], *, scene: str = ...,
           eye: Optional[_Vec3] = ..., look_at: Optional[_Vec3] = ..., up: Optional[_Vec3] = ...,
           fov: Optional[float] = ..., res: Optional[Sequence[int]] = ..., sun: Optional[_Vec3] = ...,
           # the one table of render settings (render_settings.hpp), in its order
           slices: int = ..., light_res: int = ..., max_lights: int = ..., blur: float = ...,
           repeat_to: Optional[float] = ..., cloud_shadow_res: int = ..., cloud_extinction: Optional[float] = ...,
           multiple: Optional[int] = ..., ms_grid: int = ..., ms_photons: int = ..., ms_lobes: int = ...,
           ms_diffusion_depth: float = ..., ms_similarity_depth: float = ..., ms_occlusion: float = ...,
           ms_contribution: float = ..., ms_eccentricity: float = ...,
           **options: Any) -> numpy.typing.NDArray[numpy.float32]:
    """(height, width, 4) float32: linear, premultiplied RGBA, row 0 at the top."""
def write_image(path: _Path, image: numpy.typing.ArrayLike, *, preview: Optional[_Path] = ...,
                exposure: Optional[float] = ..., metadata: Optional[Mapping[str, str]] = ...) -> None: ...
def read_image(path: _Path) -> tuple[numpy.typing.NDArray[numpy.float32], dict[str, str]]:
    """((height, width, 4) float32 RGBA, row 0 at the top; the header's text attributes)."""
def noise(kind: Literal["value", "gradient", "wavelet", "worley"], shape: Sequence[int], *, frequency: float = ...,
          fractal: Literal["none", "fbm", "turbulence", "ridged"] = ..., octaves: int = ..., seed: int = ...,
          time: Optional[float] = ..., lacunarity: float = ..., gain: float = ..., period: int = ...,
          projected: bool = ..., spacing: Optional[float] = ...) -> numpy.typing.NDArray[numpy.float32]: ...
