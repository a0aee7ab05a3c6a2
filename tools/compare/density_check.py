"""Cross-check of brume's density fields (grid, height, layer) against Mitsuba 3, per image region.

Subcommands (from the repository root, with the venv of tools/compare/requirements.txt; the LLVM
variant needs DRJIT_LIBLLVM_PATH, e.g. /usr/lib/x86_64-linux-gnu/libLLVM-19.so from libllvm19):

  self-test SCENE          brume's field as this tool evaluates it (density_media.Field, used for
                           the masks) against Mitsuba's `gridvolume` of the translation, at random
                           points inside the medium's box; prints the largest differences and the
                           interpolation bound of a height or layer profile.
  mitsuba SCENE --out DIR  K independent Mitsuba renders (--renders K, --spp N each, other seeds):
                           DIR/mitsuba-K.exr, their mean and per-pixel standard error
                           (mitsuba-mean.exr, mitsuba-se.exr: sd over renders / sqrt(K)) and
                           mitsuba.json (spp, seconds, bin groups). --per-bin: one grey render
                           per film bin, every medium with that bin's coefficients and every light
                           with only that bin's light, summed (no spectral weights in any path; a
                           bin's render wastes the wavelengths Mitsuba samples outside it, so it is
                           slow: a check, not a reference).
  brume SCENE --out DIR    J brume renders of other seeds (--renders J --passes P): DIR/brume-J.exr.
  check SCENE --mitsuba DIR --brume A.exr [B.exr ...]
                           the per-region table below (and --out PREFIX: PREFIX.json, and
                           PREFIX-regions.png, the regions over Mitsuba's mean image).

Media translation: density_media.py (gridvolume of the same .vol for type "grid"; a 1 x 1024 x 1
grid along `up` for "height" and "layer", with its error bound). A CHROMATIC medium with a density
(coefficients that differ between film bins) cannot be one Mitsuba render: its grid medium's
extinction is `scale` (a float) times a wavelength-independent grid. So each of the K images is the
sum of one render per group of film bins with equal coefficients (density_media.bin_groups; one
per bin for a power-law fog), each with that group's sigma_t and albedo and with every light's
spectrum zeroed outside the group. brume's lights, surfaces and media are constant within a bin,
so the radiance is too, and the group images add up to the spectral image; the wavelengths a
group's render samples outside its bins carry no light (wasted samples, not bias). A grey medium
is one render of the whole spectrum. Spots get brume's soft edge (spot_profile "exact").

Regions come from the density field projected along each pixel's camera ray (through the pixel's
centre): tau = sum over media with a density of sigma_t(l_Y) * integral of rho ds over the ray's
chord of the medium's box (midpoint rule, --steps per chord; sigma_t of the film bin holding
555 nm; surfaces inside a box that would cut the chord are not seen). Exclusive, in this order:
  surfaces   tau < 0.01: the surfaces behind, seen through (almost) no medium (for the plume: the
             floor, the wall, the spot and the plume's shadow on it);
  layer-top  height and layer fields only: tau >= 0.05 and rho at the ray's rho-weighted mean
             height between 0.05 and 0.5 of rho's largest value in the box (the fog thinning out);
  inside     tau > 1;
  edge       0.05 <= tau <= 0.5;
  mid        0.5 < tau <= 1;  faint  0.01 <= tau < 0.05;  all  every pixel.
Per region and per renderer, the mean of Y (Rec.709 luminance of the linear RGB) and of R, G, B
over the region's pixels, for each independent image; its mean over images and standard error
sd / sqrt(n). The ratio brume / Mitsuba has the standard error of a ratio of independent means,
r sqrt((se_b / b)^2 + (se_m / m)^2), and z = (r - 1) / se. With a single brume image its error
is taken from its `noise` layer summed as independent pixels: a LOWER BOUND (brume's pixels in a
pass share forward rays; docs/photometry.md), flagged in the table; give 2 or more brume renders
of different seeds (the `brume` subcommand) for an honest one. brume's EXR must be radiometric
(film.units, the default): Mitsuba's images are in brume's radiometric units (mitsuba_scene.py).

Reading the table: brume's gathered light is blurred over its integration radius. Before its
spheres were cut at the surfaces their camera segment ends on (docs/media.md, "Spheres at
surfaces"), the fog seen within a few radii of the floor of height-fog-chromatic read 1.5-2 % low
at the automatic radius, from the balls that reached through the floor. What is left is the
blur itself, where the image changes fastest (0.1 % on the surfaces beside the fog's silhouette,
a few tenths of a percent in the blue channel at the fog's edge; docs/media.md).
Check a suspicious region at a smaller radius
(`--set integrator.radius=...`, the `brume` subcommand's --set) before blaming the field.
z assumes the standard errors are exact: with J brume renders their estimate has J - 1 degrees
of freedom (|z| up to about 3 is within the spread of 4 renders).

Example (the two scenes of this check):
  export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so
  P=.venv/bin/python; S=tools/compare/scenes/height-fog-chromatic.toml
  $P tools/compare/density_check.py self-test $S
  $P tools/compare/density_check.py mitsuba $S --renders 8 --spp 64 --out out/hfc
  $P tools/compare/density_check.py brume $S --renders 4 --passes 64 --out out/hfc
  $P tools/compare/density_check.py check $S --mitsuba out/hfc --brume out/hfc/brume-*.exr --out out/hfc/check
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import OpenEXR

sys.path.insert(0, str(Path(__file__).resolve().parent))
import density_media  # noqa: E402
import mitsuba_scene  # noqa: E402

REGIONS = ("surfaces", "layer-top", "inside", "edge", "mid", "faint", "all")
LUMA = np.array([0.2126, 0.7152, 0.0722])


def read_exr(path: Path) -> dict[str, np.ndarray]:
    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        out = {k: np.asarray(v.pixels, dtype=np.float64) for k, v in ch.items()}
        hdr = f.header()
    if "RGB" not in out and all(c in out for c in "RGB"):
        out["RGB"] = np.stack([out[c] for c in "RGB"], -1)
    units = hdr.get("brumeUnits")
    if units is not None and units != "radiometric":
        raise SystemExit(f"{path}: brumeUnits = {units}; render with --set film.units=radiometric")
    return out


def write_exr(path: Path, rgb: np.ndarray) -> None:
    with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION}, {"RGB": np.ascontiguousarray(rgb, dtype=np.float32)}) as f:
        f.write(str(path))


# ----------------------------------------------------------------------------- masks

def camera_rays(cam: dict) -> tuple[np.ndarray, np.ndarray]:
    """Origin (3,) and unit directions (H, W, 3) through the pixel centres, row 0 at the top."""
    w, h = int(cam.get("width", 256)), int(cam.get("height", 256))
    if cam.get("type", "perspective") != "perspective":
        raise NotImplementedError("masks: perspective cameras only")
    o = np.array(cam.get("position", [0, 0, 5]), dtype=float)
    fwd = np.array(cam.get("look_at", [0, 0, 0]), dtype=float) - o
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, np.array(cam.get("up", [0, 1, 0]), dtype=float))
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    t = np.tan(np.radians(float(cam.get("fov", 40.0))) / 2)
    x = (2 * (np.arange(w) + 0.5) / w - 1) * t * w / h
    y = (1 - 2 * (np.arange(h) + 0.5) / h) * t
    d = fwd + x[None, :, None] * right + y[:, None, None] * up
    return o, d / np.linalg.norm(d, axis=-1, keepdims=True)


def _chord(f: density_media.Field, o: np.ndarray, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Entry and exit distances of rays (n, 3) through the medium's box (t0 >= t1: none)."""
    m = f.world_to_box
    lo_ = m[:3, :3] @ o + m[:3, 3]
    ld = d @ m[:3, :3].T
    with np.errstate(divide="ignore", invalid="ignore"):
        a = (-1.0 - lo_) / ld
        b = (1.0 - lo_) / ld
    near = np.where(np.isnan(a), -np.inf, np.minimum(a, b)).max(1)
    far = np.where(np.isnan(b), np.inf, np.maximum(a, b)).min(1)
    return np.maximum(near, 0.0), far


def tau_map(scene: Path, steps: int = 400) -> tuple[np.ndarray, np.ndarray | None]:
    """(optical depth per pixel at the film bin of 555 nm, relative rho at the rho-weighted mean
    height per pixel for stratified fields (else None))."""
    desc = tomllib.loads(scene.read_text())
    grid = mitsuba_scene.Grid(desc.get("film", {}))
    ybin = int(np.clip(np.searchsorted(grid.edges, 555.0) - 1, 0, grid.n - 1))
    o, dirs = camera_rays(desc["camera"])
    hh, ww = dirs.shape[:2]
    tau = np.zeros(hh * ww)
    top = None
    for name, m in desc.get("media", {}).items():
        if "density" not in m:
            continue
        f = density_media.Field(desc, scene.parent, name)
        st, _ = density_media.coefficients(desc, scene.parent, m, grid)
        d = dirs.reshape(-1, 3)
        t0, t1 = _chord(f, o, d)
        rmax = f.rho_range()[1]
        depth, hsum = np.zeros(len(d)), np.zeros(len(d))
        for s in range(0, len(d), 2048):
            sl = slice(s, s + 2048)
            ok = t1[sl] > t0[sl]
            if not ok.any():
                continue
            a, b = t0[sl][ok], t1[sl][ok]
            ds = (b - a) / steps
            ts = a[:, None] + (np.arange(steps) + 0.5)[None, :] * ds[:, None]
            p = o + ts[..., None] * d[sl][ok][:, None, :]
            r = f.rho(p.reshape(-1, 3)).reshape(ts.shape)
            idx = np.arange(len(d))[sl][ok]
            depth[idx] = (r * ds[:, None]).sum(1)
            if f.kind != "grid":
                hsum[idx] = (r * ds[:, None] * (p @ f.up)).sum(1)
        tau += st[ybin] * depth
        if f.kind != "grid":
            hbar = np.divide(hsum, depth, out=np.zeros_like(depth), where=depth > 0)
            rel = np.where(depth > 0, density_media.profile(f.dens, hbar) / rmax, 0.0)
            top = rel if top is None else np.maximum(top, rel)
    return tau.reshape(hh, ww), None if top is None else top.reshape(hh, ww)


def regions(tau: np.ndarray, top: np.ndarray | None) -> dict[str, np.ndarray]:
    out = {}
    taken = np.zeros(tau.shape, bool)

    def add(name, m):
        nonlocal taken
        out[name] = m & ~taken
        taken |= m

    add("surfaces", tau < 0.01)
    if top is not None:
        add("layer-top", (tau >= 0.05) & (top >= 0.05) & (top <= 0.5))
    add("inside", tau > 1.0)
    add("edge", (tau >= 0.05) & (tau <= 0.5))
    add("mid", (tau > 0.5) & (tau <= 1.0))
    add("faint", (tau >= 0.01) & (tau < 0.05))
    out["all"] = np.ones(tau.shape, bool)
    return out


# ----------------------------------------------------------------------------- renders

def mitsuba_renders(a) -> None:
    import mitsuba as mi

    mi.set_variant(a.variant)
    desc = tomllib.loads(a.scene.read_text())
    grid = mitsuba_scene.Grid(desc.get("film", {}))
    groups = density_media.bin_groups(desc, a.scene.parent, grid) or [None]
    if a.per_bin:
        # One grey render per film bin: no spectral weights in any path (a check of the
        # integrators' spectral sampling, e.g. chromatic-fog's volpath against volpathmis).
        groups = [[i] for i in range(grid.n)]
    for name, m in desc.get("media", {}).items():
        if "density" in m:
            print(f"medium {name}: {m['density']['type']}: {density_media.interpolation_bound(desc, name)}", flush=True)
    print(f"bin groups: {groups if groups != [None] else 'one render (grey media)'}", flush=True)
    scenes = [mi.load_dict(mitsuba_scene.load(a.scene, a.spp, integrator=a.integrator, spot_profile=a.spot_profile, bins=g))
              for g in groups]
    a.out.mkdir(parents=True, exist_ok=True)
    imgs, cpu0, wall0 = [], time.process_time(), time.perf_counter()
    for k in range(a.renders):
        img = 0.0
        for i, sc in enumerate(scenes):
            img = img + np.asarray(mi.render(sc, spp=a.spp, seed=a.seed + 1000 * k + i), dtype=np.float64)
        imgs.append(img)
        write_exr(a.out / f"mitsuba-{k}.exr", img)
        print(f"render {k + 1}/{a.renders}: {time.perf_counter() - wall0:.0f} s wall, "
              f"{time.process_time() - cpu0:.0f} CPU s so far", flush=True)
    stack = np.stack(imgs)
    write_exr(a.out / "mitsuba-mean.exr", stack.mean(0))
    write_exr(a.out / "mitsuba-se.exr", stack.std(0, ddof=1) / np.sqrt(len(imgs)))
    meta = {"scene": str(a.scene), "variant": a.variant, "integrator": a.integrator, "spot_profile": a.spot_profile, "renders": a.renders,
            "spp_per_render_per_group": a.spp, "bin_groups": groups, "seed": a.seed,
            "wall_s": time.perf_counter() - wall0, "cpu_s": time.process_time() - cpu0}
    (a.out / "mitsuba.json").write_text(json.dumps(meta, indent=2))
    print(json.dumps(meta), flush=True)


def brume_renders(a) -> None:
    a.out.mkdir(parents=True, exist_ok=True)
    for j in range(a.renders):
        out = a.out / f"brume-{j}.exr"
        cmd = [a.brume, "render", str(a.scene), "--seed", str(a.seed + j), "--passes", str(a.passes), "-o", str(out), "--quiet"]
        for s in a.set:
            cmd += ["--set", s]
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True)
        print(f"{out}: {time.perf_counter() - t0:.1f} s", flush=True)


# ----------------------------------------------------------------------------- the check

def region_means(img: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """[Y, R, G, B] means over the mask."""
    rgb = img[mask].mean(0)
    return np.concatenate([[rgb @ LUMA], rgb])


def stats(images: list[np.ndarray], mask: np.ndarray, noise: np.ndarray | None) -> tuple[np.ndarray, np.ndarray, bool]:
    """(mean [Y, R, G, B], standard error, whether the error is a lower bound)."""
    per = np.array([region_means(im, mask) for im in images])
    if len(images) >= 2:
        return per.mean(0), per.std(0, ddof=1) / np.sqrt(len(images)), False
    if noise is None:
        return per[0], np.zeros(4), True
    se_rgb = np.sqrt((noise[mask] ** 2).sum(0)) / mask.sum()
    se_y = np.sqrt(((noise[mask] ** 2) @ (LUMA**2)).sum()) / mask.sum()
    return per[0], np.concatenate([[se_y], se_rgb]), True


def check(a) -> None:
    tau, top = tau_map(a.scene, a.steps)
    masks = regions(tau, top)
    meta_path = a.mitsuba / "mitsuba.json"
    meta = json.loads(meta_path.read_text()) if meta_path.exists() else {}
    m_imgs = [read_exr(p)["RGB"] for p in sorted(a.mitsuba.glob("mitsuba-[0-9]*.exr"), key=lambda p: int(p.stem.split("-")[1]))]
    if len(m_imgs) < 2:
        raise SystemExit(f"{a.mitsuba}: needs 2 or more mitsuba-K.exr renders for Mitsuba's error")
    b_exr = [read_exr(p) for p in a.brume]
    b_imgs = [e["RGB"] for e in b_exr]
    noise = b_exr[0].get("noise") if len(b_exr) == 1 else None
    if b_imgs[0].shape != m_imgs[0].shape:
        raise SystemExit(f"image sizes differ: brume {b_imgs[0].shape}, mitsuba {m_imgs[0].shape}")
    rows = []
    print(f"scene {a.scene}: {len(b_imgs)} brume image(s), {len(m_imgs)} Mitsuba renders "
          f"({meta.get('spp_per_render_per_group', '?')} spp each per bin group, groups {meta.get('bin_groups', '?')})")
    print(f"tau at the film bin of 555 nm: max {tau.max():.3f}; {(tau > 0.01).mean():.3f} of the pixels see tau > 0.01")
    head = (f"{'region':10s} {'pixels':>7s} {'brume Y':>11s} {'mitsuba Y':>11s} {'rel se b/m':>13s} {'ratio Y':>16s} {'z':>6s}"
            "   R ratio (z)    G ratio (z)    B ratio (z)")
    print(head)
    for name in REGIONS:
        mask = masks.get(name)
        if mask is None or mask.sum() == 0:
            continue
        bm, bse, lower = stats(b_imgs, mask, noise)
        mm, mse, _ = stats(m_imgs, mask, None)
        r = bm / mm
        se = r * np.sqrt((bse / bm) ** 2 + (mse / mm) ** 2)
        z = (r - 1) / se
        flag = " (brume se: lower bound)" if lower else ""
        chans = "  ".join(f"{r[i]:.4f} ({z[i]:+.1f})" for i in (1, 2, 3))
        rse = f"{bse[0] / bm[0]:.4f}/{mse[0] / mm[0]:.4f}"
        print(f"{name:10s} {int(mask.sum()):7d} {bm[0]:11.5g} {mm[0]:11.5g} {rse:>13s} {r[0]:9.4f} ± {se[0]:.4f} {z[0]:+6.2f}   {chans}{flag}")
        rows.append({"region": name, "pixels": int(mask.sum()), "brume": bm.tolist(), "brume_se": bse.tolist(),
                     "brume_se_lower_bound": lower, "mitsuba": mm.tolist(), "mitsuba_se": mse.tolist(),
                     "ratio": r.tolist(), "ratio_se": se.tolist(), "z": z.tolist()})
    if a.out:
        a.out.parent.mkdir(parents=True, exist_ok=True)
        out = {"scene": str(a.scene), "brume": [str(p) for p in a.brume], "mitsuba": meta, "channels": ["Y", "R", "G", "B"],
               "tau_max": float(tau.max()), "regions": rows}
        a.out.with_suffix(".json").write_text(json.dumps(out, indent=2))
        regions_png(a.out.with_name(a.out.name + "-regions.png"), np.mean(m_imgs, 0), masks)


def regions_png(path: Path, img: np.ndarray, masks: dict) -> None:
    """Mitsuba's mean image (grey, log scale) with each region tinted."""
    from PIL import Image

    y = img @ LUMA
    pos = y[y > 0]
    lo, hi = (np.percentile(pos, 1), np.percentile(pos, 99.5)) if pos.size else (1e-6, 1.0)
    g = np.clip(np.log(np.maximum(y, lo) / lo) / np.log(hi / lo), 0, 1)
    out = np.repeat(g[..., None], 3, -1) * 0.6
    tint = {"surfaces": (0.2, 0.2, 0.2), "layer-top": (0.9, 0.9, 0.0), "inside": (0.9, 0.1, 0.1),
            "edge": (0.1, 0.5, 0.9), "mid": (0.9, 0.5, 0.1), "faint": (0.1, 0.8, 0.3)}
    for k, c in tint.items():
        if k in masks:
            out[masks[k]] += 0.4 * np.array(c)
    Image.fromarray((np.clip(out, 0, 1) * 255).astype(np.uint8)).save(path)


def self_test(a) -> None:
    import mitsuba as mi

    mi.set_variant(a.variant)
    desc = tomllib.loads(a.scene.read_text())
    grid = mitsuba_scene.Grid(desc.get("film", {}))
    rng = np.random.default_rng(1)
    for name, m in desc.get("media", {}).items():
        if "density" not in m:
            continue
        f = density_media.Field(desc, a.scene.parent, name)
        groups = density_media.bin_groups(desc, a.scene.parent, grid)
        med = density_media.heterogeneous(mi, desc, a.scene.parent, name, grid, groups[0] if groups else None)
        vol = mi.load_dict(med["sigma_t"])
        scale = float(m["density"].get("multiplier", 1.0)) if f.kind == "grid" else 1.0
        # Random points inside the box (local [-0.999, 0.999]^3: off the faces).
        q = rng.uniform(-0.999, 0.999, size=(a.points, 3))
        p = q @ f.box_to_world[:3, :3].T + f.box_to_world[:3, 3]
        it = mi.Interaction3f()
        it.p = mi.Point3f(*[np.ascontiguousarray(c, dtype=np.float32) for c in p.T])
        theirs = np.asarray(vol.eval_1(it), dtype=np.float64) * scale
        ours = f.rho(p)
        rmax = f.rho_range()[1]
        err = np.abs(theirs - ours)
        print(f"medium {name} ({f.kind}): {a.points} points in its box: max |Mitsuba - brume field| = "
              f"{err.max():.3g} ({err.max() / rmax:.3g} of rho's max {rmax:.4g}); "
              f"max relative where rho > 1e-3 max: {(err / np.maximum(ours, 1e-300))[ours > 1e-3 * rmax].max():.3g}")
        print(f"  interpolation bound of the translation: {density_media.interpolation_bound(desc, name)}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    st = sub.add_parser("self-test")
    st.add_argument("scene", type=Path)
    st.add_argument("--variant", default="llvm_ad_spectral")
    st.add_argument("--points", type=int, default=200000)
    mt = sub.add_parser("mitsuba")
    mt.add_argument("scene", type=Path)
    mt.add_argument("--out", type=Path, required=True)
    mt.add_argument("--renders", type=int, default=8)
    mt.add_argument("--spp", type=int, default=64, help="per render and per bin group")
    mt.add_argument("--seed", type=int, default=1)
    mt.add_argument("--variant", default="llvm_ad_spectral")
    mt.add_argument("--integrator", choices=list(mitsuba_scene.INTEGRATORS), default="volpath")
    mt.add_argument("--per-bin", action="store_true", help="one grey render per film bin (every medium), summed")
    mt.add_argument("--spot-profile", choices=list(mitsuba_scene.SPOT_PROFILES), default="exact",
                    help="spots' soft edge: brume's (a projected texture) or Mitsuba's own ramp")
    bt = sub.add_parser("brume")
    bt.add_argument("scene", type=Path)
    bt.add_argument("--out", type=Path, required=True)
    bt.add_argument("--renders", type=int, default=4)
    bt.add_argument("--passes", type=int, default=32)
    bt.add_argument("--seed", type=int, default=100)
    bt.add_argument("--brume", default="target/release/brume")
    bt.add_argument("--set", action="append", default=[], help="brume --set KEY=VALUE (repeatable)")
    ck = sub.add_parser("check")
    ck.add_argument("scene", type=Path)
    ck.add_argument("--mitsuba", type=Path, required=True, help="folder of the mitsuba subcommand")
    ck.add_argument("--brume", type=Path, nargs="+", required=True, help="brume EXR(s): 2+ renders of other seeds for its error")
    ck.add_argument("--steps", type=int, default=400, help="midpoints per chord for tau")
    ck.add_argument("--out", type=Path, default=None, help="prefix of the JSON and the regions PNG")
    a = ap.parse_args()
    {"self-test": self_test, "mitsuba": mitsuba_renders, "brume": brume_renders, "check": check}[a.cmd](a)


if __name__ == "__main__":
    main()
