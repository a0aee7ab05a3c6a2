"""tools/compare/light_trace.py, the independent reference for spot-lit fog (a light tracer and a
quadrature of single scattering, sharing no code with brume or Mitsuba), and brume against it.

The scene is chromatic-fog's geometry with a thinner image: a 3 m fog box (absorbing a little,
forward scattering g = 0.3), a 4 degree soft-edged spot 5 cm from its face (the beam enters
3.5 mm wide), and a white wall beyond its far end; 48 x 24 pixels, 4 film bins. Band sums of Y over
columns, with standard errors from independent runs of other seeds; every bound is a z-bound at
fixed seeds."""

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "compare"))

SCENE = """
[film]
bins = 4
[camera]
width = 48
height = 24
position = [{x}, 0.1, {dist}]
look_at = [{x}, 0.0, 0.0]
fov = 30.0
[integrator]
max_depth = {depth}
[media.fog]
sigma_s = 1.0
sigma_a = 0.1
g = 0.3
[materials.white]
type = "lambert"
albedo = 0.8
[[shapes]]
type = "box"
size = [3.0, 1.2, 1.2]
interior = "fog"
[[shapes]]
type = "quad"
size = [1.5, 1.5]
material = "white"
transform = {{ rotate = [0.0, -90.0, 0.0], translate = [1.55, 0.0, 0.0] }}
[[lights]]
type = "spot"
position = [-1.55, 0.0, 0.0]
direction = [1.0, 0.0, 0.0]
angle = 4.0
soft_edge = 1.0
power = 200.0
spectrum = "D65"
"""

# Two views: the beam's middle, from 30 cm past the fog's face (where the quadrature's pixel
# samples resolve the beam: 2 cm wide and more, against 4 mm between samples), and its entry,
# the spot and the first 60 cm of fog (for the tracer against brume).
MIDDLE = {"x": -0.5, "dist": 1.5}
ENTRY = {"x": -1.2, "dist": 1.2}
# Bands of columns across each view, then the whole image. The fog's face is at column 12.6 of
# the entry's view (the spot at 10.7).
BANDS = {-0.5: [(0, 8), (8, 16), (16, 32), (32, 48), (0, 48)], -1.2: [(12, 16), (16, 24), (24, 48), (0, 48)]}
LUMA = np.array([0.2126, 0.7152, 0.0722])


def scene_file(tmp_path: Path, depth: int, view: dict) -> Path:
    p = tmp_path / f"spot-fog-{depth}-{view['x']}.toml"
    p.write_text(SCENE.format(depth=depth, **view))
    return p


def bands(img: np.ndarray, view: dict) -> np.ndarray:
    return np.array([img[:, a:b].sum() for a, b in BANDS[view["x"]]])


def assert_agree(runs: np.ndarray, ref: np.ndarray, ref_se: np.ndarray, z_max: float) -> None:
    mean, se = runs.mean(0), runs.std(0, ddof=1) / np.sqrt(len(runs))
    z = (mean - ref) / np.hypot(se, ref_se)
    assert np.all(np.abs(z) < z_max), (mean / ref, z)
    # Not vacuous: every band is measured to better than 3 %.
    assert np.all(np.hypot(se, ref_se) < 0.03 * ref), np.hypot(se, ref_se) / ref


@pytest.mark.parametrize("light", ["spot", "point"])
def test_light_tracer_single_scattering_matches_quadrature(tmp_path, light):
    """The tracer's first collisions (order 1) against the quadrature: the camera's importance,
    the light's profile and power, the transmittances and the film's Y weights of one against
    those of the other (the quadrature integrates along the camera rays, the tracer splats
    photons: nothing shared but the scene). The point light stands where the spot does."""
    import light_trace as lt
    import single_scatter as ss

    path = scene_file(tmp_path, 32, MIDDLE)
    if light == "point":
        text = path.read_text().replace('type = "spot"', 'type = "point"')
        path.write_text(text.replace("angle = 4.0\n", "").replace("soft_edge = 1.0\n", "").replace("direction = [1.0, 0.0, 0.0]\n", ""))
    scene = lt.load(path)
    quad = bands(ss.single_scatter_y(scene, nsub=8), MIDDLE)
    photons = 1e5 if light == "spot" else 6e5  # a point light sends most photons away from the view
    runs = np.array([bands(lt.render(scene, photons, seed)[0, 1], MIDDLE) for seed in range(4)])
    assert_agree(runs, quad, np.zeros_like(quad), 4.0)


def test_brume_matches_light_tracer(brume, tmp_path):
    """brume's default integrator (next-event estimation of the spot, integration spheres for the
    rest) against the independent tracer, in absolute units (scale 1): single scattering alone
    against the quadrature, then every order together against the tracer."""
    import light_trace as lt
    import single_scatter as ss
    from compare import read_rgb
    from conftest import run_brume

    def brume_bands(path: Path, view: dict, seeds, passes: int, *sets: str) -> np.ndarray:
        out = []
        for s in seeds:
            exr = tmp_path / f"b-{path.stem}-{s}.exr"
            args = [a for kv in sets for a in ("--set", kv)]
            run_brume("render", path, "--passes", passes, "--seed", s, "-o", exr, "--quiet", *args)
            out.append(bands(read_rgb(exr) @ LUMA, view))
        return np.array(out)

    single = scene_file(tmp_path, 1, MIDDLE)
    quad = bands(ss.single_scatter_y(lt.load(single), nsub=8), MIDDLE)
    # Next-event estimation's band sums are skewed where the beam is thinner than a pixel (a
    # render of 32 passes reads up to 1.11 of the quadrature at the left band, median 1.007,
    # over 24 seeds): 8 renders keep the z-bound honest.
    assert_agree(brume_bands(single, MIDDLE, range(8), 32), quad, np.zeros_like(quad), 4.0)

    full = scene_file(tmp_path, 32, ENTRY)
    traced = np.array([bands(lt.render(lt.load(full), 3e5, 10 + s).sum(0)[1], ENTRY) for s in range(4)])
    # The budgets pinned at the cheapest pass (q stays automatic): they change the cost and the
    # noise, not the expectation this test checks, and the tuner's choice on this beam-lit fog
    # swings with the seed (16 camera paths x 50 000 forward rays on seed 5, 50 000 x 1 on seed
    # 7: over a minute each of a debug build's 128 passes, against about 10 s at the cheapest).
    cheapest = ("integrator.forward_rays=10000", "integrator.camera_samples=1")
    runs = brume_bands(full, ENTRY, range(8), 128, *cheapest)
    assert_agree(runs, traced.mean(0), traced.std(0, ddof=1) / 2, 4.0)


def test_light_tracer_refuses_what_it_cannot_trace(tmp_path):
    """A scene outside the tracer's reach is refused, naming the key, not traced wrongly."""
    import light_trace as lt

    text = SCENE.format(depth=32, **ENTRY)
    for old, new, key in [
        ('type = "spot"', 'type = "laser"', "lights[0]"),
        ('sigma_s = 1.0', 'sigma_s = 1.0\ndensity = { type = "constant", value = 1.0 }', "media.fog"),
        ("[film]", '[film]\ncolour_space = "acescg"', "film"),
        ("position = [-1.55, 0.0, 0.0]\n", "", "lights[0]: `position` is missing"),
        ('interior = "fog"', 'interior = "smoke"', "media: `smoke` is missing"),
        ("[[lights]]", "[[lightz]]", "lights: none"),
        ("[film]", "[film", "not valid TOML"),
        ("albedo = 0.8", 'texture = { file = "wall.exr" }', "materials.white.texture"),
    ]:
        p = tmp_path / "bad.toml"
        p.write_text(text.replace(old, new, 1))
        with pytest.raises(lt.Refused, match=key.replace("[", r"\[").replace("]", r"\]")):
            lt.load(p)


# fog-cube's setting (an orthographic camera normal to a 1 m fog cube, a parallel light 45
# degrees from the view, the wall with fog-cube's texture), small: 32 x 32 pixels, 4 bins. brume
# gathers at fog-cube's own automatic radius (1.5 footprints of its 128 pixels): at this image's
# automatic radius, 9.4 cm at 16 x 16 pixels, brume read 0.5-1.3 % low per quadrant (and warned).
CUBE = """
[film]
bins = 4
[camera]
type = "orthographic"
width = 32
height = 32
position = [0.0, 0.0, 3.0]
look_at = [0.0, 0.0, 0.0]
view_width = 1.0
view_height = 1.0
[integrator]
max_depth = {depth}
radius = 0.0117
[media.fog]
sigma_s = 0.8
sigma_a = 0.2
g = 0.5
[materials.wall]
type = "lambert"
albedo = 0.4
{texture}
[[shapes]]
type = "box"
size = [1.0, 1.0, 1.0]
interior = "fog"
{wall}
[[lights]]
type = "directional"
direction = [0.5, -0.5, -0.70710678]
irradiance = 1000.0
spectrum = "D65"
"""
WALL = """[[shapes]]
type = "quad"
size = [1.0, 1.0]
material = "wall"
transform = { translate = [0.0, 0.0, -0.5002] }"""
# Quadrants of the 32 x 32 image (the light enters at the top left), then the whole image.
CUBE_BANDS = [(slice(0, 16), slice(0, 16)), (slice(0, 16), slice(16, 32)), (slice(16, 32), slice(0, 16)),
              (slice(16, 32), slice(16, 32)), (slice(0, 32), slice(0, 32))]


def cube_bands(img: np.ndarray) -> np.ndarray:
    return np.array([img[r, c].sum() for r, c in CUBE_BANDS])


def cube_single_scatter_y(scene, nsub: int) -> np.ndarray:
    """Single scattering of the parallel light seen by the orthographic camera, by quadrature:
    per pixel nsub^2 rays at the midpoints of its rectangle, along each Gauss-Legendre in 8 equal
    pieces of its chord through the box, the light's path to each point from the box's own slab
    intersection. Shares with the tracer only the scene's loading and the film's weights."""
    import light_trace as lt

    cam, box, light = scene.camera, scene.box, scene.lights[0]
    _, d, t, _ = light.parallel
    irradiance = light.power / (4 * float(t @ t))  # W/(m^2 nm) per bin: power is over the square
    cw = lt.xyz_weights(scene.edges)
    f = (np.arange(cam.w * nsub) + 0.5) / (cam.w * nsub)
    sx, sy = np.meshgrid(2 * f - 1, 1 - 2 * f)
    o = cam.pos + (sx.ravel()[:, None] * 0.5 * cam.view[0]) * cam.right + (sy.ravel()[:, None] * 0.5 * cam.view[1]) * cam.up
    fwd = np.tile(cam.fwd, (len(o), 1))
    tn, tf = box.interval(o, fwd)
    x, wq = np.polynomial.legendre.leggauss(16)
    y = np.zeros(len(o))
    for piece in range(8):
        a = tn + (tf - tn) * piece / 8
        b = tn + (tf - tn) * (piece + 1) / 8
        for xi, wi in zip(x, wq):
            s = 0.5 * (a + b) + 0.5 * (b - a) * xi
            p = o + s[:, None] * fwd
            _, back = box.interval(p, np.tile(-d, (len(p), 1)))
            phase = lt.hg(np.array(d @ -cam.fwd), box.g)
            for k in range(len(scene.edges) - 1):
                st = box.sigma_s[k] + box.sigma_a[k]
                radiance = box.sigma_s[k] * irradiance[k] * phase * np.exp(-st * (s - tn) - st * back)
                y += np.where(tf > tn, 0.5 * (b - a) * wi * cw[1, k] * radiance, 0.0)
    return y.reshape(cam.h, nsub, cam.w, nsub).mean((1, 3))


def cube_file(tmp_path: Path, depth: int, wall: bool) -> Path:
    """The small cube; the wall, when there is one, carries fog-cube's own texture."""
    p = tmp_path / f"cube-{depth}-{wall}.toml"
    texture = f'texture = "{ROOT / "scenes" / "textures" / "brume-pattern.png"}"' if wall else ""
    p.write_text(CUBE.format(depth=depth, wall=WALL if wall else "", texture=texture))
    return p


def test_light_tracer_parallel_light_and_orthographic_camera_match_quadrature(tmp_path):
    """A directional light and an orthographic camera (fog-cube's setting): the tracer's first
    collisions against the quadrature, per quadrant. The fog is grey, so the tracer traces its
    4 bins as one problem: this also checks that the bins' weights are summed right."""
    import light_trace as lt

    scene = lt.load(cube_file(tmp_path, 32, wall=False))
    quad = cube_bands(cube_single_scatter_y(scene, nsub=4))
    # 8 runs: with 4, a standard error from 3 degrees of freedom lets |z| pass 4 by chance in
    # one band of the five in about 1 in 8 seeds.
    runs = np.array([cube_bands(lt.render(scene, 1e5, seed)[0, 1]) for seed in range(8)])
    assert_agree(runs, quad, np.zeros_like(quad), 4.0)


def test_brume_matches_light_tracer_under_parallel_light(brume, tmp_path):
    """brume's defaults against the tracer in fog-cube's setting, its textured wall included
    (the tracer upsamples the texture with its own fit), every order of scattering and the wall,
    per quadrant and per colour channel, in absolute units (scale 1)."""
    import light_trace as lt
    from compare import read_rgb
    from conftest import run_brume

    path = cube_file(tmp_path, 32, wall=True)
    traced = []
    for s in range(8):
        xyz = lt.render(lt.load(path), 2e5, 20 + s).sum(0)
        rgb = np.einsum("ij,jhw->hwi", lt.xyz_to_rec709(), xyz)
        traced.append(np.concatenate([cube_bands(rgb[..., c]) for c in range(3)]))
    traced = np.array(traced)
    out = []
    for s in range(8):
        exr = tmp_path / f"cube-{s}.exr"
        run_brume("render", path, "--passes", 16, "--seed", s, "-o", exr, "--quiet")
        img = read_rgb(exr)
        out.append(np.concatenate([cube_bands(img[..., c]) for c in range(3)]))
    assert_agree(np.array(out), traced.mean(0), traced.std(0, ddof=1) / np.sqrt(len(traced)), 4.0)
