"""shadowref: a deterministic software rasterizer with stencil shadow volumes and shadow maps.

    >>> import shadowref
    >>> frame = shadowref.render("scenes/room.yaml", method="zfail", size=(320, 240))
    >>> frame.stencil.max()          # the stencil buffer as a NumPy array, row 0 at the bottom
    >>> frame.history_at(200, 110)   # pixel history: every fragment that touched the pixel

Every buffer is a read-only NumPy array indexed ``[y, x]`` with row 0 at the BOTTOM of the picture
(as glReadPixels returns it): plot with ``imshow(a, origin="lower")``. The same scene and settings
give the same bytes for any thread count and either pipeline, and the same bytes as the command
``shadowref render``. Bad input raises SceneError, whose message is ``file:line:col: message``.
"""
from __future__ import annotations

import json
import os
import re
from typing import Any, Mapping, Optional, Sequence, Union

import numpy as np  # noqa: F401  (the buffers are NumPy arrays: fail here, not in render)

from . import _shadowref

__all__ = ["Scene", "Frame", "FragmentRecord", "OracleImage", "SceneError", "load", "loads", "render",
           "oracle", "methods", "version", "__version__"]

__version__ = _shadowref.version()


class SceneError(ValueError):
    """Bad input: a scene, an override, a method name or a setting.

    ``str(error)`` is ``file:line:col: message`` as the command line prints it; ``file``,
    ``line`` and ``column`` hold the place (None when the message names none). The N-th override
    is the file ``<command line>`` at line N.
    """

    _PLACE = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?P<message>.*)$", re.S)

    def __init__(self, text: str):
        super().__init__(text)
        match = self._PLACE.match(text)
        self.file: Optional[str] = match.group("file") if match else None
        self.line: Optional[int] = int(match.group("line")) if match else None
        self.column: Optional[int] = int(match.group("column")) if match else None
        self.message: str = match.group("message") if match else text


def _native(call, *args):
    try:
        return call(*args)
    except _shadowref.NativeError as e:
        raise SceneError(str(e)) from None


def _override_words(overrides) -> list:
    """["key=value", ...] from a list of such strings or a mapping {key: value}."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        words = []
        for key, value in overrides.items():
            if isinstance(value, bool):
                text = "true" if value else "false"
            elif isinstance(value, (str, int, float)):
                text = str(value)
            else:
                text = json.dumps(value)  # lists and maps as YAML flow
            words.append(f"{key}={text}")
        return words
    if isinstance(overrides, str):
        return [overrides]
    return [str(o) for o in overrides]


class Scene:
    """A loaded scene (docs/scene-format.md) with its overrides applied.

    Made by :func:`load` (a file or a dict) or :func:`loads` (YAML text). Remembers where it came
    from, so :meth:`with_overrides` can load it again with more overrides.
    """

    def __init__(self, native, source: tuple, overrides: list):
        self._native = native
        self._source = source
        self.overrides: list = list(overrides)

    # Read-only views of the native scene's attributes (types in __init__.pyi).
    width = property(lambda self: self._native.width, doc="The image width in pixels.")
    height = property(lambda self: self._native.height, doc="The image height in pixels.")
    method = property(lambda self: self._native.method, doc="The scene's shadow.method.")
    lights = property(lambda self: self._native.lights, doc="The names of the scene's lights, in order.")

    def with_overrides(self, overrides) -> "Scene":
        """The same source loaded again with these overrides after the ones it has."""
        more = _override_words(overrides)
        if self._source[0] == "file":
            return load(self._source[1], self.overrides + more)
        return loads(self._source[1], name=self._source[2], overrides=self.overrides + more)

    def __repr__(self) -> str:
        return f"<shadowref.Scene {self._source[1] if self._source[0] == 'file' else self._source[2]!s} " \
               f"{self.width}x{self.height} method={self.method}>"


def load(source: Union[str, os.PathLike, Mapping[str, Any]], overrides=None) -> Scene:
    """Loads a scene from a file path or from a dict holding the scene's keys.

    ``overrides`` are ``-D`` style settings applied after the file is read: a list of
    ``"key=value"`` strings (``["shadow.method=zpass", "image.width=320"]``) or a dict
    (``{"shadow.method": "zpass", "lights.fill": "off"}``). A dict scene is written out as YAML
    (JSON's syntax, which YAML reads) and loaded by the same loader as a file, named ``<dict>``;
    mesh files it names are relative to the working directory.
    """
    words = _override_words(overrides)
    if isinstance(source, Mapping):
        return loads(json.dumps(source, indent=1), name="<dict>", overrides=words)
    path = os.fspath(source)
    return Scene(_native(_shadowref.NativeScene.from_file, path, words), ("file", path), words)


def loads(text: str, name: str = "<string>", overrides=None) -> Scene:
    """Loads a scene from YAML text; ``name`` is the file name its error messages give."""
    words = _override_words(overrides)
    return Scene(_native(_shadowref.NativeScene.from_string, text, name, words), ("string", text, name), words)


def _scene_with(scene, overrides, size) -> Scene:
    """The Scene that render and oracle work on: ``scene`` (a Scene, a path or a dict) with the
    overrides and (width, height) ``size`` applied after its own."""
    words = _override_words(overrides)
    if size is not None:
        width, height = size
        words += [f"image.width={int(width)}", f"image.height={int(height)}"]
    if isinstance(scene, Scene):
        return scene.with_overrides(words) if words else scene
    return load(scene, words)


class FragmentRecord:
    """One fragment that reached the watched pixel, in drawing order; ``repr`` is the line
    ``render --pixel-history`` prints for it."""

    __slots__ = ("draw", "what", "front", "depth", "stored_depth", "stencil_passed", "depth_passed",
                 "stencil_before", "stencil_after", "color_before", "color_after")

    def __init__(self, values: Mapping[str, Any]):
        for key in self.__slots__:
            setattr(self, key, values[key])

    def __repr__(self) -> str:
        return (f"draw {self.draw}  {self.what}  {'front' if self.front else 'back'}  z={self.depth:g} "
                f"(stored {self.stored_depth:g})  stencil test {'pass' if self.stencil_passed else 'FAIL'}  "
                f"depth test {'-' if not self.stencil_passed else ('pass' if self.depth_passed else 'FAIL')}  "
                f"stencil {self.stencil_before} -> {self.stencil_after}" +
                (f"  colour ({self.color_after[0]:g}, {self.color_after[1]:g}, {self.color_after[2]:g})"
                 if self.color_after != self.color_before else ""))


class Frame:
    """The buffers of a rendered frame, as read-only NumPy arrays indexed ``[y, x]`` (row 0 at the
    bottom). A buffer the method does not use is None.

    Attributes:
        width, height, threads: the image size and the threads it was rendered on.
        color: float32 (height, width, 4), RGBA.
        depth: float32 (height, width), window depth in [0, 1].
        eye_depth: float64 (height, width), the distance along the camera's view direction
            (inf where the depth is 1 under the infinite projection of shadow volumes).
        stencil: uint8 (height, width), the stencil buffer at the end of the frame (the last
            light's counts; z-pass's -1 is 255: ``stencil.view(numpy.int8)`` reads it signed).
        accumulation: float32 (height, width, 4) for methods that accumulate, else None.
        stencil_per_light: {light: uint8 (height, width)}, each light's counts after its
            volume pass (stencil methods).
        visibility: {light: float32 (height, width)}, each scene light's shadow mask: 1 lit,
            0 in shadow, fractions with PCF and soft lights.
        shadow_maps: {"L0" or "L0.face3": float32 (h, w)} depth maps of shadow-map methods.
        stats: {counter: int}, the pipeline's counters (``render --stats``).
        pass_milliseconds: {pass: milliseconds}.
        warnings: what ``render`` would print about the scene.
        history: [FragmentRecord] when rendered with ``history=(x, y)``.
    """

    def __init__(self, values: dict, method: str):
        self._image = values.pop("image")
        self.method: str = method
        self.history = [FragmentRecord(r) for r in values.pop("history")]
        for key, value in values.items():
            setattr(self, key, value)

    def write(self, path: Union[str, os.PathLike]) -> None:
        """Writes the frame as ``render -o`` does: ``.png`` (8-bit RGB) or ``.exr`` (R, G, B, A,
        Z, stencil, and the per-light stencil and visibility channels the frame kept).
        Atomic: the file is complete or absent."""
        _native(self._image.write, os.fspath(path))

    def __repr__(self) -> str:
        return f"<shadowref.Frame {self.width}x{self.height} method={self.method} threads={self.threads}>"


def render(scene: Union[Scene, str, os.PathLike, Mapping[str, Any]], method: Optional[str] = None,
           pipeline: str = "fast", threads: int = 0, size: Optional[Sequence[int]] = None, overrides=None,
           history: Optional[Sequence[int]] = None, stencil_per_light: bool = True, visibility: bool = True,
           shadow_maps: bool = True) -> Frame:
    """Renders one frame and returns its buffers.

    Args:
        scene: a Scene, a scene file's path or a dict (as :func:`load`).
        method: a shadow method ("none", "zpass", "zfail", "auto", "shadowmap", "tsm", ...;
            :func:`methods` lists them); None: the scene's shadow.method.
        pipeline: "fast" (the threaded executor) or "reference" (the readable GL pipeline, one
            thread): the same bytes.
        threads: rasterizer threads, 0 for one per CPU this process may run on.
        size: (width, height), as the overrides image.width and image.height.
        overrides: more ``-D`` style overrides (see :func:`load`).
        history: (x, y) of a pixel whose fragments to record (on the reference pipeline).
        stencil_per_light, visibility, shadow_maps: keep those buffers (each costs memory).

    The GIL is released while it renders: other threads may run, or render too.
    """
    scene = _scene_with(scene, overrides, size)
    xy = None if history is None else (int(history[0]), int(history[1]))
    values = _native(_shadowref.render, scene._native, method or "", pipeline, int(threads), bool(stencil_per_light),
                     bool(visibility), bool(shadow_maps), xy)
    return Frame(values, method or scene.method)


class OracleImage:
    """The ray-cast oracle's answer for one light, independent of the rasterizer, as NumPy arrays
    indexed ``[y, x]`` (row 0 at the bottom): ``zpass`` and ``zfail`` (int32, what those methods
    should count), ``lit`` (uint8, 1 where the light reaches the surface), ``hit`` (uint8, 1 where
    the pixel shows a surface), ``near_edge`` (uint8, pixels a comparison may leave out: within a
    pixel of a contour, or too close to call) and ``hit_instance`` (int32, -1 for none)."""

    def __init__(self, values: dict):
        for key, value in values.items():
            setattr(self, key, value)

    def __repr__(self) -> str:
        return f"<shadowref.OracleImage light={self.light!r} {self.lit.shape[1]}x{self.lit.shape[0]}>"


def oracle(scene: Union[Scene, str, os.PathLike, Mapping[str, Any]], light: Union[int, str] = 0, threads: int = 0,
           size: Optional[Sequence[int]] = None, overrides=None) -> OracleImage:
    """Casts the ray-cast oracle for one light (its index or name) of the scene.

    Compare with a frame: ``(frame.visibility[name] == oracle.lit)[oracle.near_edge == 0]``.
    Releases the GIL while it casts.
    """
    scene = _scene_with(scene, overrides, size)
    if isinstance(light, str):
        if light not in scene.lights:
            raise SceneError(f"oracle: no light named '{light}' (the scene has {', '.join(scene.lights)})")
        light = scene.lights.index(light)
    return OracleImage(_native(_shadowref.oracle, scene._native, int(light), int(threads)))


def methods() -> list:
    """The shadow methods this build renders with."""
    return _shadowref.methods()


def version() -> str:
    """shadowref's version, e.g. "0.1.0"."""
    return _shadowref.version()
