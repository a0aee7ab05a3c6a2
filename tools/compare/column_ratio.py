"""brume / Mitsuba per band of image columns, from the images of density_check.py's `mitsuba`
and `brume` subcommands: for each band, the ratio of the mean Y (Rec.709 luminance) summed over
the band's pixels in the chosen rows, with its standard error from the spread over the renders
of each (independent renders of other seeds). Used to localise a difference along a beam that
crosses the image (chromatic-fog's spot beam runs along the rows).

    python tools/compare/column_ratio.py MITSUBA_DIR BRUME_DIR [--rows 40:88] [--bands 44:48,48:56,...]

A folder may also hold the two halves of a protocol reference renamed mitsuba-0.exr and
mitsuba-1.exr (two renders: a rough standard error), or light_trace.py's renders
(reference-K.exr), which are taken when there are no mitsuba-K.exr, or single_scatter.py's
quadrature (one reference-0.exr, no noise of its own).
"""
from __future__ import annotations

import argparse
import glob
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare import read_rgb  # noqa: E402

Y = np.array([0.2126, 0.7152, 0.0722])
BANDS = "44:48,48:56,56:64,64:80,80:128,128:208,208:256,0:256"


def band_sums(paths: list[str], rows: slice, bands: list[tuple[int, int]]) -> np.ndarray:
    """(renders, bands): Y summed over each band of the rows, per render."""
    out = []
    for p in paths:
        y = read_rgb(p)[rows] @ Y
        out.append([y[:, a:b].sum() for a, b in bands])
    return np.array(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mitsuba", type=Path)
    ap.add_argument("brume", type=Path)
    ap.add_argument("--rows", default="40:88")
    ap.add_argument("--bands", default=BANDS)
    a = ap.parse_args()
    r0, r1 = (int(x) for x in a.rows.split(":"))
    bands = [tuple(int(x) for x in b.split(":")) for b in a.bands.split(",")]
    refs = sorted(glob.glob(str(a.mitsuba / "mitsuba-[0-9]*.exr"))) or sorted(
        glob.glob(str(a.mitsuba / "reference-[0-9]*.exr")))
    m = band_sums(refs, slice(r0, r1), bands)
    b = band_sums(sorted(glob.glob(str(a.brume / "brume-*.exr"))), slice(r0, r1), bands)
    if len(m) < 1 or len(b) < 2:
        raise SystemExit("need a reference and 2 or more brume renders")
    for j, (c0, c1) in enumerate(bands):
        mm, bb = m[:, j].mean(), b[:, j].mean()
        r = bb / mm
        m_se = m[:, j].std(ddof=1) / np.sqrt(len(m)) if len(m) > 1 else 0.0  # one: a quadrature
        se = r * np.hypot(m_se / mm, b[:, j].std(ddof=1) / np.sqrt(len(b)) / bb)
        print(f"columns {c0:3d}-{c1:3d}: brume / reference {r:.4f} +- {se:.4f} (z {(r - 1) / se:+.1f})")


if __name__ == "__main__":
    main()
