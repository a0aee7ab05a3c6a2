"""brume from Python: load a scene, render it into numpy arrays, save what the CLI writes.

    import brume
    scene = brume.load("scenes/chromatic-fog.toml", set={"camera.width": 64, "camera.height": 48})
    result = scene.render(passes=4, seed=1)
    print(result.luminance.mean(), result.spectral.shape)
    result.save("fog.exr")

Everything here is the brume library itself (the Rust crate beside this package): loading and
its error messages, the renderer, merging and the writers are the functions the `brume`
command line calls, so the same seed gives the same bytes from Python and from the CLI.
See docs/python.md.
"""

from __future__ import annotations

import os
from typing import Any, Iterable, Mapping, Optional, Sequence, Tuple, Union

from . import _brume
from ._brume import (
    BrumeError,
    FilmError,
    RenderError,
    RenderResult,
    Scene,
    SceneError,
    __version__,
    read_film,
)

__all__ = [
    "BrumeError",
    "FilmError",
    "RenderError",
    "RenderResult",
    "Scene",
    "SceneError",
    "load",
    "merge",
    "read_film",
    "spectrum",
    "__version__",
]


def _is_toml_text(s: str) -> bool:
    # A path has neither: a TOML scene has at least one `key = value` or a table header.
    return "\n" in s or "=" in s


def load(scene: Union[str, "os.PathLike[str]"], set: Optional[Mapping[str, Any]] = None) -> Scene:
    """Loads and validates a scene: a path to a TOML scene file, or the TOML text itself.

    A ``str`` holding a newline or ``=`` is TOML text (named ``<string>`` in messages, its
    relative paths resolved from the working folder); any other ``str`` or path-like is a file.
    ``set`` overrides scene values by dotted path, as ``brume render --set KEY=VALUE``:
    ``{"media.fog.g": 0.7, "camera.width": 64, "integrator.volume": "cylinder"}``; a value
    of ``None`` switches a medium off (``{"media.fog": None}``).

    Raises SceneError with the CLI's ``file:line:column: key `a.b`: ...`` message, and
    TypeError for a ``set`` value that is no scene value (bool, int, float, str, list, dict).
    """
    if isinstance(scene, str) and _is_toml_text(scene):
        return _brume.load_scene("<string>", scene, _as_dict(set))
    if isinstance(scene, (str, os.PathLike)):
        return _brume.load_scene(os.fspath(scene), None, _as_dict(set))
    raise TypeError(f"load: expected a path or TOML text, got {type(scene).__name__}")


def _as_dict(set: Optional[Mapping[str, Any]]) -> Optional[dict]:
    if set is None:
        return None
    if not isinstance(set, Mapping):
        raise TypeError(f"set: expected a dict of dotted keys to values, got {type(set).__name__}")
    return dict(set)


def merge(films: Iterable[Union[RenderResult, str, "os.PathLike[str]"]]) -> RenderResult:
    """Merges the films of one render (``RenderResult``s of ``render(pass_range=...)`` or
    ``.brume`` files, in any order) into the film of all their passes: bit-identical to one
    render of them, as ``brume merge``. Raises FilmError for films of other renders (naming
    what differs), gaps and overlaps."""
    items = [f if isinstance(f, RenderResult) else os.fspath(f) for f in films]
    return _brume.merge(items)


def spectrum(
    name_or_line: Union[str, float, Sequence[Tuple[float, float]]],
    illuminant: Optional[str] = None,
    observer: str = "1931",
    bins: int = 32,
    lambda_min: float = 380.0,
    lambda_max: float = 780.0,
) -> dict:
    """The colour of a spectrum, as ``brume spectrum --json`` prints it: its values per bin,
    XYZ, xy, sRGB and, for an emission, its luminous efficacy.

    ``name_or_line``: a built-in name or CSV file (``"FILE:COLUMN"`` picks a column), a
    wavelength in nm (a spectral line), or a list of ``(nm, relative power)`` lines.
    ``illuminant`` makes a reflectance's colour under it."""
    if isinstance(name_or_line, str):
        return _json(_brume.spectrum_json(name_or_line, [], illuminant, observer, bins, lambda_min, lambda_max))
    if isinstance(name_or_line, (int, float)):
        lines = [(float(name_or_line), 1.0)]
    else:
        lines = [(float(nm), float(p)) for nm, p in name_or_line]
    label = "line " + ", ".join(f"{nm:g} nm" if p == 1.0 else f"{nm:g} nm x {p:g}" for nm, p in lines)
    return _json(_brume.spectrum_json(label, lines, illuminant, observer, bins, lambda_min, lambda_max))


def _json(text: str) -> dict:
    import json

    return json.loads(text)
