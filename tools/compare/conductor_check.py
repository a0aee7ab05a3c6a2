"""Cross-check of brume's `conductor` material against Mitsuba 3's `roughconductor`, per region.

Renders come from density_check.py's `mitsuba` and `brume` subcommands (K Mitsuba renders of other
seeds with their mean, J brume renders of other seeds); this tool reads them and prints, per
region, the brume / Mitsuba ratio of the mean luminance Y (Rec.709 of linear RGB) and of R, G, B
with its standard error and z = (ratio - 1) / se, both errors from the spread of the independent
renders (density_check.stats).

Two known differences are divided out, and both the raw and the corrected ratios are printed:
- Masking-shadowing: Mitsuba's `roughconductor` uses the separable Smith G1(wo) G1(wi), brume the
  height-correlated 1 / (1 + L(wo) + L(wi)); for the light of the scene's first spot or point
  light reflected straight to the camera their ratio is (1 + L_o)(1 + L_i) / (1 + L_o + L_i)
  (`g_ratio`, per pixel centre), averaged over each region with Mitsuba's Y as weights (`G pred`).
  Light reaching the camera by other paths through the metal (the wall lit by it, the wall
  reflected in it) is not predicted: there brume is expected brighter by a similar fraction.
- The light's emission and the film without the metal: k = brume / Mitsuba over the conductors'
  pixels of a control scene in which every conductor is a Lambert surface of albedo 0.5
  (`--write-control`), rendered the same way (`--control-mitsuba`, `--control-brume`).
corrected = ratio / (G pred x k), its se from the ratio's and k's.

Regions: the pixels whose centre ray first hits a quad of a given material (`mat:NAME`), and each
of those cut into an image grid of --cols x --rows blocks (`NAME rIcJ`, blocks of fewer than 20
pixels skipped). Quads only (the scenes this tool is for); brume's quad is its size in the local
XY plane, normal +Z, scaled, then rotated about X, Y, Z, then translated.

Example (from the repository root; the venv of tools/compare/requirements.txt):
  export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so
  P=python; S=tools/compare/scenes/rough-gold.toml
  $P tools/compare/density_check.py mitsuba $S --renders 8 --spp 2048 --out out/gold
  $P tools/compare/density_check.py brume $S --renders 6 --passes 64 --out out/gold
  $P tools/compare/conductor_check.py $S --write-control out/control.toml
  $P tools/compare/density_check.py mitsuba out/control.toml --renders 8 --spp 1024 --out out/control
  $P tools/compare/density_check.py brume out/control.toml --renders 6 --passes 64 --out out/control
  $P tools/compare/conductor_check.py $S --mitsuba out/gold --brume out/gold/brume-*.exr \
      --control-mitsuba out/control --control-brume out/control/brume-*.exr --out out/gold-check.json
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import density_check  # noqa: E402


def _rotation(deg: list[float]) -> np.ndarray:
    """brume's R = Rz Ry Rx for Euler angles in degrees."""
    x, y, z = (math.radians(float(a)) for a in deg)
    rx = np.array([[1, 0, 0], [0, math.cos(x), -math.sin(x)], [0, math.sin(x), math.cos(x)]])
    ry = np.array([[math.cos(y), 0, math.sin(y)], [0, 1, 0], [-math.sin(y), 0, math.cos(y)]])
    rz = np.array([[math.cos(z), -math.sin(z), 0], [math.sin(z), math.cos(z), 0], [0, 0, 1]])
    return rz @ ry @ rx


def first_hits(desc: dict):
    """Per pixel centre: the material of the first quad hit ("" for none), the hit point and
    the quad's normal."""
    o, d = density_check.camera_rays(desc["camera"])
    best = np.full(d.shape[:2], np.inf)
    owner = np.full(d.shape[:2], "", dtype=object)
    normal = np.zeros(d.shape)
    for s in desc.get("shapes", []):
        if s["type"] != "quad" or "material" not in s:
            continue
        t = s.get("transform", {})
        scale = np.array(t.get("scale", [1, 1, 1]), dtype=float)
        r = _rotation(t.get("rotate", [0, 0, 0]))
        c = np.array(t.get("translate", [0, 0, 0]), dtype=float)
        half = np.array(s.get("size", [1, 1]), dtype=float) / 2 * scale[:2]
        u, v, n = r[:, 0], r[:, 1], r[:, 2]
        dn = d @ n
        with np.errstate(divide="ignore", invalid="ignore"):
            dist = ((c - o) @ n) / dn
        p = o + dist[..., None] * d
        inside = (np.abs((p - c) @ u) <= half[0]) & (np.abs((p - c) @ v) <= half[1])
        hit = inside & (dist > 1e-6) & (dist < best)
        best[hit] = dist[hit]
        owner[hit] = s["material"]
        normal[hit] = n
    return owner, o + np.where(np.isfinite(best), best, 0.0)[..., None] * d, normal, o


def material_masks(desc: dict) -> dict[str, np.ndarray]:
    """Per material, the pixels whose centre ray first hits one of its quads."""
    owner = first_hits(desc)[0]
    return {name: owner == name for name in sorted(set(owner.ravel()) - {""})}


def g_ratio(desc: dict) -> np.ndarray:
    """Per pixel, brume's height-correlated Smith G over Mitsuba's separable one for the light
    of the scene's first spot or point light reflected by a conductor at the pixel centre's hit,
    (1 + L_o)(1 + L_i) / (1 + L_o + L_i) (the two differ only there for that direct light);
    1 elsewhere. Isotropic alpha."""
    owner, p, n, cam = first_hits(desc)
    out = np.ones(owner.shape)
    lights = [l for l in desc.get("lights", []) if l["type"] in ("spot", "point")]
    if not lights:
        return out
    light = np.array(lights[0]["position"], dtype=float)
    for name, m in desc.get("materials", {}).items():
        if m.get("type") != "conductor":
            continue
        a = float(m.get("roughness", 0.1))
        mask = owner == name

        def lam(w, n):
            c = np.abs(np.sum(w * n, -1))
            t2 = (1 - c * c) / np.maximum(c * c, 1e-12)
            return 0.5 * (np.sqrt(1 + a * a * t2) - 1)

        wo = (cam - p)[mask]
        wi = (light - p)[mask]
        nm = n[mask]
        lo = lam(wo / np.linalg.norm(wo, axis=-1, keepdims=True), nm)
        li = lam(wi / np.linalg.norm(wi, axis=-1, keepdims=True), nm)
        out[mask] = (1 + lo) * (1 + li) / (1 + lo + li)
    return out


def write_control(src: Path, dst: Path) -> None:
    """The scene with every conductor replaced by a Lambert surface of albedo 0.5 (same name):
    the light's emission and the film compared without the metal."""
    out, skip = [], False
    for line in src.read_text().splitlines():
        if line.strip() == 'type = "conductor"':
            out += ['type = "lambert"', "albedo = 0.5"]
            skip = True
            continue
        if skip and line.split("=")[0].strip() in ("eta", "k", "f0", "roughness"):
            continue
        skip = skip and not line.startswith("[")
        out.append(line)
    dst.write_text("\n".join(out) + "\n")


def regions(desc: dict, cols: int, rows: int) -> dict[str, np.ndarray]:
    out = {}
    for name, m in material_masks(desc).items():
        out[f"mat:{name}"] = m
        h, w = m.shape
        for i in range(rows):
            for j in range(cols):
                block = np.zeros_like(m)
                block[i * h // rows:(i + 1) * h // rows, j * w // cols:(j + 1) * w // cols] = True
                if (m & block).sum() >= 20:
                    out[f"{name} r{i}c{j}"] = m & block
    out["all"] = np.ones_like(next(iter(out.values())))
    return out


def load_pair(mitsuba: Path, brume: list[Path]) -> tuple[list, list, dict]:
    m_paths = sorted(mitsuba.glob("mitsuba-[0-9]*.exr"), key=lambda q: int(q.stem.split("-")[1]))
    m_imgs = [density_check.read_exr(q)["RGB"] for q in m_paths]
    b_imgs = [density_check.read_exr(q)["RGB"] for q in brume]
    if len(m_imgs) < 2 or len(b_imgs) < 2:
        raise SystemExit("needs 2 or more renders of each renderer for their errors")
    return m_imgs, b_imgs, json.loads((mitsuba / "mitsuba.json").read_text())


def control_k(desc: dict, a) -> tuple[float, float]:
    """brume / Mitsuba of Y on the control scene over the conductors' pixels, and its se."""
    if a.control_mitsuba is None:
        return 1.0, 0.0
    m_imgs, b_imgs, _ = load_pair(a.control_mitsuba, a.control_brume)
    owner = first_hits(desc)[0]
    names = [k for k, m in desc["materials"].items() if m.get("type") == "conductor"]
    mask = np.isin(owner, names)
    bm, bse, _ = density_check.stats(b_imgs, mask, None)
    mm, mse, _ = density_check.stats(m_imgs, mask, None)
    k = bm[0] / mm[0]
    return k, k * math.hypot(bse[0] / bm[0], mse[0] / mm[0])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene", type=Path)
    p.add_argument("--write-control", type=Path, default=None, help="write the control scene there and stop")
    p.add_argument("--mitsuba", type=Path, help="folder of density_check.py mitsuba")
    p.add_argument("--brume", type=Path, nargs="+", help="2+ brume EXRs of other seeds")
    p.add_argument("--control-mitsuba", type=Path, default=None, help="the control scene's Mitsuba folder")
    p.add_argument("--control-brume", type=Path, nargs="+", default=None, help="the control scene's brume EXRs")
    p.add_argument("--cols", type=int, default=4)
    p.add_argument("--rows", type=int, default=3)
    p.add_argument("--out", type=Path, default=None, help="JSON of the table")
    a = p.parse_args()
    if a.write_control:
        return write_control(a.scene, a.write_control)
    desc = tomllib.loads(a.scene.read_text())
    masks = regions(desc, a.cols, a.rows)
    m_imgs, b_imgs, meta = load_pair(a.mitsuba, a.brume)
    g = g_ratio(desc)
    y_m = np.mean(m_imgs, 0) @ density_check.LUMA
    k, k_se = control_k(desc, a)
    print(f"scene {a.scene}: {len(b_imgs)} brume renders, {len(m_imgs)} Mitsuba renders "
          f"({meta.get('spp_per_render_per_group')} spp each, {meta.get('variant')})")
    print(f"control k (brume / Mitsuba without the metal) = {k:.5f} ± {k_se:.5f}")
    print(f"{'region':14s} {'pixels':>6s} {'brume Y':>10s} {'mitsuba Y':>10s} {'ratio Y':>16s} {'z':>6s}"
          f" {'G pred':>7s} {'corrected':>16s} {'z':>6s}")
    rows, zs = [], []
    for name, mask in masks.items():
        bm, bse, _ = density_check.stats(b_imgs, mask, None)
        mm, mse, _ = density_check.stats(m_imgs, mask, None)
        r = bm / mm
        se = r * np.sqrt((bse / bm) ** 2 + (mse / mm) ** 2)
        z = (r - 1) / se
        # The G difference predicted for this region (weights: Mitsuba's Y), and the control's k.
        pred = float((y_m[mask] * g[mask]).sum() / y_m[mask].sum())
        c = r[0] / (pred * k)
        c_se = c * math.hypot(se[0] / r[0], k_se / k)
        cz = (c - 1) / c_se
        zs.append(cz)
        print(f"{name:14s} {int(mask.sum()):6d} {bm[0]:10.4g} {mm[0]:10.4g} {r[0]:9.4f} ± {se[0]:.4f} {z[0]:+6.2f}"
              f" {pred:7.4f} {c:9.4f} ± {c_se:.4f} {cz:+6.2f}")
        rows.append({"region": name, "pixels": int(mask.sum()), "brume": bm.tolist(), "brume_se": bse.tolist(),
                     "mitsuba": mm.tolist(), "mitsuba_se": mse.tolist(), "ratio": r.tolist(),
                     "ratio_se": se.tolist(), "z": z.tolist(), "g_predicted": pred, "corrected": c,
                     "corrected_se": c_se, "corrected_z": cz})
    zs = np.array(zs)
    print(f"{len(zs)} regions, corrected: max |z| {np.abs(zs).max():.2f}, rms z {np.sqrt((zs**2).mean()):.2f}")
    if a.out:
        a.out.parent.mkdir(parents=True, exist_ok=True)
        a.out.write_text(json.dumps({"scene": str(a.scene), "mitsuba": meta, "brume": [str(q) for q in a.brume],
                                     "channels": ["Y", "R", "G", "B"], "control_k": [k, k_se], "regions": rows},
                                    indent=2))


if __name__ == "__main__":
    main()
