# Type stubs for the package shadowref (python/shadowref/__init__.py): what editors complete.
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

Overrides = Union[None, str, Sequence[str], Mapping[str, Any]]
SceneSource = Union["Scene", str, os.PathLike[str], Mapping[str, Any]]

class SceneError(ValueError):
    """Bad input; str(error) is "file:line:col: message"."""
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    message: str
    def __init__(self, text: str) -> None: ...

class Scene:
    """A loaded scene with its overrides applied."""
    overrides: List[str]
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def method(self) -> str: ...
    @property
    def lights(self) -> List[str]: ...
    def with_overrides(self, overrides: Overrides) -> Scene: ...

def load(source: Union[str, os.PathLike[str], Mapping[str, Any]], overrides: Overrides = ...) -> Scene:
    """Loads a scene from a file path or a dict, with -D style overrides."""
    ...

def loads(text: str, name: str = ..., overrides: Overrides = ...) -> Scene:
    """Loads a scene from YAML text; `name` is the file name its errors give."""
    ...

class FragmentRecord:
    """One fragment that reached the watched pixel, in drawing order."""
    draw: int
    what: str
    front: bool
    depth: float
    stored_depth: float
    stencil_passed: bool
    depth_passed: bool
    stencil_before: int
    stencil_after: int
    color_before: Tuple[float, float, float, float]
    color_after: Tuple[float, float, float, float]

class Frame:
    """A rendered frame's buffers, read-only arrays indexed [y, x] with row 0 at the bottom."""
    width: int
    height: int
    threads: int
    method: str
    color: Optional[npt.NDArray[np.float32]]          # (height, width, 4)
    depth: Optional[npt.NDArray[np.float32]]          # (height, width), window depth
    eye_depth: Optional[npt.NDArray[np.float64]]      # (height, width), distance along the view axis
    stencil: Optional[npt.NDArray[np.uint8]]          # (height, width)
    accumulation: Optional[npt.NDArray[np.float32]]   # (height, width, 4)
    stencil_per_light: Dict[str, npt.NDArray[np.uint8]]
    visibility: Dict[str, npt.NDArray[np.float32]]
    shadow_maps: Dict[str, npt.NDArray[np.float32]]
    stats: Dict[str, int]
    pass_milliseconds: Dict[str, float]
    warnings: List[str]
    history: List[FragmentRecord]
    def write(self, path: Union[str, os.PathLike[str]]) -> None:
        """Writes .png or .exr as `shadowref render -o` does."""
        ...

def render(scene: SceneSource, method: Optional[str] = ..., pipeline: str = ..., threads: int = ...,
           size: Optional[Sequence[int]] = ..., overrides: Overrides = ..., history: Optional[Sequence[int]] = ...,
           stencil_per_light: bool = ..., visibility: bool = ..., shadow_maps: bool = ...) -> Frame:
    """Renders one frame (pipeline "fast" or "reference"; threads 0: one per CPU); releases the GIL."""
    ...

class OracleImage:
    """The ray-cast oracle's counts and visibility for one light, arrays indexed [y, x]."""
    light: str
    zpass: npt.NDArray[np.int32]
    zfail: npt.NDArray[np.int32]
    lit: npt.NDArray[np.uint8]
    hit: npt.NDArray[np.uint8]
    near_edge: npt.NDArray[np.uint8]
    hit_instance: npt.NDArray[np.int32]

def oracle(scene: SceneSource, light: Union[int, str] = ..., threads: int = ..., size: Optional[Sequence[int]] = ...,
           overrides: Overrides = ...) -> OracleImage:
    """The ray-cast oracle for one light (index or name); releases the GIL."""
    ...

def methods() -> List[str]: ...
def version() -> str: ...
