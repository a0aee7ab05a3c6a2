"""Scene handling of the protocol (protocol.py): --set edits applied for both renderers, brume's
[integrator] table stripped to its defaults, and the checks of what Mitsuba 3 cannot render."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import numpy as np

import density_media
import mitsuba_scene

# Integrator keys that define the scene rather than tune the estimator: max_depth truncates the
# transported light (the image converges to another value without it), and Mitsuba mirrors it.
SCENE_KEYS = ("max_depth",)

def parse_value(text: str):
    """A --set value is TOML, as brume's --set reads it."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError as e:
        raise SystemExit(f"--set value {text!r} is not TOML ({e}); strings need quotes") from e


def apply_set(desc: dict, key: str, value) -> None:
    """Set a dotted path (list indices as numbers, like brume's `lights.1.power`) in place."""
    parts = key.split(".")
    node = desc
    for p in parts[:-1]:
        node = node[int(p)] if isinstance(node, list) else node.setdefault(p, {})
    last = parts[-1]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value


def edited_desc(scene: Path, sets: list[str]) -> dict:
    desc = tomllib.loads(scene.read_text())
    for s in sets:
        key, _, val = s.partition("=")
        if key.startswith("integrator"):
            raise SystemExit(f"--set {s}: integrator keys tune brume only: use --brume-set")
        apply_set(desc, key, parse_value(val))
    return desc


def strip_integrator(text: str) -> tuple[str, list[str], list[str]]:
    """The scene text with its [integrator] table reduced to SCENE_KEYS: (text, kept, removed).
    Line-based, so the rest of the file stays byte-identical; checked by parsing both."""
    lines = text.splitlines(keepends=True)
    out, inside = [], False
    for line in lines:
        s = line.strip()
        if s.startswith("["):
            inside = re.match(r"^\[\s*integrator\s*\]", s) is not None
        elif inside and s and not s.startswith("#"):
            key = s.split("=")[0].strip()
            if key not in SCENE_KEYS:
                continue
        out.append(line)
    new = "".join(out)
    old_d, new_d = tomllib.loads(text), tomllib.loads(new)
    integ = old_d.pop("integrator", {})
    new_integ = new_d.pop("integrator", {})
    if old_d != new_d or new_integ != {k: v for k, v in integ.items() if k in SCENE_KEYS}:
        raise SystemExit("cannot strip [integrator] line by line (multi-line values or dotted keys?)")
    return new, sorted(new_integ), sorted(k for k in integ if k not in SCENE_KEYS)



def spectral_media(desc: dict, base: Path) -> bool:
    """Whether some medium's coefficients vary with wavelength (then volpathmis)."""
    grid = mitsuba_scene.Grid(desc.get("film", {}))
    for m in desc.get("media", {}).values():
        for key in ("sigma_s", "sigma_a"):
            v = np.asarray(mitsuba_scene.coefficient(desc, base, m.get(key, 0.0), grid), dtype=float)
            if v.ndim and not np.all(v == v.flat[0]):
                return True
    return False


def check_mappable(desc: dict, base: Path) -> None:
    for i, light in enumerate(desc.get("lights", [])):
        sp = light.get("spectrum")
        if isinstance(sp, dict) and ("line" in sp or "lines" in sp):
            raise NotImplementedError(
                f"lights.{i}: a spectral line (brume gives it a 0.1 nm bin of its own and splits the film's bins "
                f"around it; Mitsuba would sample that box with 1/4000 of its wavelengths); compare with a band "
                f"for both renderers, e.g. --set 'lights.{i}.spectrum=\"laser-532nm.csv\"' (the 14 nm triangle "
                f"the golden images pin)")
    grid = mitsuba_scene.Grid(desc.get("film", {}))
    if density_media.bin_groups(desc, base, grid) is not None:
        raise NotImplementedError(
            "a chromatic medium with a density: Mitsuba's grid medium is grey, so the image is a sum of "
            "one render per bin group (density_check.py), not one timed render")
