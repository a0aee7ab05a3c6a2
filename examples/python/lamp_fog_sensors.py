"""A lamp in fog: the illuminance on the road against the fog's visibility.

lamp-fog.toml (beside this file) hangs a 1000 lm lamp 4 m above a road in fog; the sensor
`road` reads the illuminance 3 m from the lamp's foot, the light the fog scatters included.
This sweeps the visibility (meteorological optical range) and plots the sensor's value with its
95 % interval against the direct light alone, I cos(theta) / d^2 exp(-sigma_t d).

    python examples/python/lamp_fog_sensors.py -o lamp/           # full size
    python examples/python/lamp_fog_sensors.py -o lamp/ --small   # what the tests run
"""

import argparse
import json
import math
from pathlib import Path

import brume

SCENE = Path(__file__).resolve().parent / "lamp-fog.toml"
# The lamp's intensity (1000 lm, isotropic), and the sensor's distance and cosine to it.
INTENSITY = 1000.0 / (4.0 * math.pi)
DISTANCE = math.hypot(3.0, 4.0)
COSINE = 4.0 / DISTANCE


def direct(visibility):
    """Illuminance of the lamp's unscattered light (lx): sigma_t = ln(20) / visibility."""
    return INTENSITY * COSINE / DISTANCE**2 * math.exp(-math.log(20.0) / visibility * DISTANCE)


def sweep(visibilities, passes, seed):
    scene = brume.load(SCENE)
    rows = []
    for v in visibilities:
        result = scene.with_set({"media.fog.visibility": float(v)}).render(
            passes=passes, seed=seed, progress=False)
        road = next(s for s in result.sensors if s["name"] == "road")
        rows.append({
            "visibility_m": float(v),
            "illuminance_lx": road["value"],
            "std_error_lx": road["std_error"],
            "ci95_lx": road["ci95"],
            "direct_lx": direct(v),
        })
    return rows


def plot(rows, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    v = [r["visibility_m"] for r in rows]
    e = [r["illuminance_lx"] for r in rows]
    lo = [r["illuminance_lx"] - r["ci95_lx"][0] for r in rows]
    hi = [r["ci95_lx"][1] - r["illuminance_lx"] for r in rows]
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.errorbar(v, e, yerr=[lo, hi], fmt="o-", label="brume (sensor, 95 %)")
    ax.plot(v, [r["direct_lx"] for r in rows], "k--", label="direct light only")
    ax.set_xscale("log")
    ax.set_xlabel("visibility (m)")
    ax.set_ylabel("illuminance on the road (lx)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--out", type=Path, default=Path("lamp-fog"))
    ap.add_argument("--small", action="store_true", help="a quick run (the test suite's)")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    if args.small:
        rows = sweep([10.0, 50.0, 400.0], passes=3, seed=1)
    else:
        rows = sweep([5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 400.0], passes=40, seed=1)
    (args.out / "sweep.json").write_text(json.dumps(rows, indent=1))
    plot(rows, args.out / "sweep.png")
    for r in rows:
        print(f"visibility {r['visibility_m']:g} m: {r['illuminance_lx']:.4g} lx "
              f"(direct alone {r['direct_lx']:.4g} lx)")


if __name__ == "__main__":
    main()
