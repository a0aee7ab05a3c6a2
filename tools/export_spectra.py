#!/usr/bin/env python3
"""Export brume's built-in spectral data (spectra/*.csv) from colour-science.

Run from the repository root with the test venv:
    .venv/bin/python tools/export_spectra.py

Every file is a plain CSV: optional '#' comment lines naming the source, then a header row whose
first column is `wavelength_nm`, then one row per tabulated wavelength at the source's own
sampling (no resampling here: brume integrates the piecewise-linear data exactly per bin).
"""

import os
import re
import sys
import warnings

warnings.filterwarnings("ignore")

import colour  # noqa: E402

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "spectra")

CMFS = {
    "cie1931_2deg.csv": "CIE 1931 2 Degree Standard Observer",
    "cie1964_10deg.csv": "CIE 1964 10 Degree Standard Observer",
}

# brume name -> colour-science key
ILLUMINANTS = {
    "D65": "D65",
    "D50": "D50",
    "A": "A",
    "F2": "FL2",
    "F11": "FL11",
    "LED-B1": "LED-B1",
}

CHECKER = "ColorChecker N Ohta"


def fmt(v):
    # 10 significant digits: the sources carry at most 6, so this is lossless and readable.
    # Values below 1e-15 in magnitude are interpolation noise in the sources (e.g. -1.9e-21 in
    # the 1931 z-bar tail) and are written as 0 so that non-negative data stays non-negative.
    v = float(v)
    return "0" if abs(v) < 1e-15 else f"{v:.10g}"


def column_name(patch):
    # "white 9.5 (.05 D)" -> "white", "neutral 6.5 (.44 D)" -> "neutral_6_5".
    patch = re.sub(r"\(.*\)", "", patch.lower()).strip()
    if patch.startswith(("white", "black")):
        patch = patch.split()[0]
    return re.sub(r"[^a-z0-9]+", "_", patch).strip("_")


def write(path, comments, header, rows):
    with open(path, "w", newline="\n") as f:
        for c in comments:
            f.write(f"# {c}\n")
        f.write(",".join(header) + "\n")
        for r in rows:
            f.write(",".join(fmt(v) for v in r) + "\n")
    print("wrote", os.path.relpath(path))


def source_line():
    return f"exported by tools/export_spectra.py from colour-science {colour.__version__}"


def main():
    os.makedirs(OUT, exist_ok=True)
    for fname, key in CMFS.items():
        m = colour.MSDS_CMFS[key]
        rows = [(w, *m[w]) for w in m.wavelengths]
        write(
            os.path.join(OUT, fname),
            [key + " (colour.MSDS_CMFS)", source_line(), "units: dimensionless"],
            ["wavelength_nm", "x_bar", "y_bar", "z_bar"],
            rows,
        )
    for name, key in ILLUMINANTS.items():
        sd = colour.SDS_ILLUMINANTS[key]
        rows = [(w, sd[w]) for w in sd.wavelengths]
        write(
            os.path.join(OUT, f"illuminant_{name}.csv"),
            [f"CIE illuminant {key} (colour.SDS_ILLUMINANTS['{key}'])", source_line(),
             "units: relative spectral power"],
            ["wavelength_nm", "relative_power"],
            rows,
        )
    patches = colour.SDS_COLOURCHECKERS[CHECKER]
    names = list(patches.keys())
    cols = [column_name(n) for n in names]
    wl = patches[names[0]].wavelengths
    rows = [(w, *(patches[n][w] for n in names)) for w in wl]
    write(
        os.path.join(OUT, "colorchecker.csv"),
        [f"{CHECKER} reflectances, 24 patches in chart order (colour.SDS_COLOURCHECKERS)",
         source_line(), "units: reflectance factor (0..1)"],
        ["wavelength_nm", *cols],
        rows,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
