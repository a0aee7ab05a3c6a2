"""colour-science reference computations shared by the tests and by `python reference.py`,
which prints the CIEDE2000 table for several bin counts (docs/colour.md)."""

import sys
import warnings

import numpy as np

warnings.filterwarnings("ignore")
import colour  # noqa: E402

CMFS = {
    "1931": "CIE 1931 2 Degree Standard Observer",
    "1964": "CIE 1964 10 Degree Standard Observer",
}
# brume name -> colour-science key
ILLUMINANTS = {"D65": "D65", "A": "A", "D50": "D50", "F2": "FL2", "F11": "FL11", "LED-B1": "LED-B1"}
CHECKER = "ColorChecker N Ohta"


def patches():
    return list(colour.SDS_COLOURCHECKERS[CHECKER].values())


def reference_xyz(sd, illuminant="D65", observer="1931"):
    """XYZ (white Y = 100) at 1 nm over the CMFs' range, colour-science's own interpolation."""
    cmfs = colour.MSDS_CMFS[CMFS[observer]]
    ill = colour.SDS_ILLUMINANTS[ILLUMINANTS[illuminant]].copy().align(cmfs.shape)
    sd = sd.copy().align(cmfs.shape)
    xyz = colour.sd_to_XYZ(sd, cmfs, ill, method="Integration")
    white = colour.sd_to_XYZ(
        colour.sd_ones(cmfs.shape), cmfs, ill, method="Integration"
    )
    return np.asarray(xyz), np.asarray(white)


def delta_e(xyz_a, xyz_b, white):
    wxy = colour.XYZ_to_xy(white / 100.0)
    lab_a = colour.XYZ_to_Lab(np.asarray(xyz_a) / 100.0, wxy)
    lab_b = colour.XYZ_to_Lab(np.asarray(xyz_b) / 100.0, wxy)
    return float(colour.delta_E(lab_a, lab_b, method="CIE 2000"))


def checker_errors(brume_json, bins, illuminant):
    """CIEDE2000 of brume's XYZ against the reference for the 24 patches."""
    errs = []
    for k, sd in enumerate(patches()):
        ref, white = reference_xyz(sd, illuminant)
        got = brume_json(
            "spectrum", f"colorchecker:{k + 1}", "--illuminant", illuminant, "--bins", bins
        )["XYZ"]
        errs.append(delta_e(got, ref, white))
    return np.array(errs)


if __name__ == "__main__":
    from conftest import brume_json

    print("| bins | illuminant | mean dE00 | max dE00 |")
    print("|---:|---|---:|---:|")
    for bins in map(int, sys.argv[1:] or [8, 16, 32, 64]):
        for ill in ["D65", "A", "F2", "F11", "LED-B1"]:
            e = checker_errors(brume_json, bins, ill)
            print(f"| {bins} | {ill} | {e.mean():.3f} | {e.max():.3f} |")
