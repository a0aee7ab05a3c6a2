"""A Mitsuba 3 integrator that renders brume's `surface` layer of a scene with one homogeneous
medium: the radiance of the first non-null surface a camera ray meets, attenuated by the medium
in front of it, without the light the medium scatters towards the camera.

For each camera ray it walks through null (index-matched) boundaries to the first surface with
a BSDF, adding up the optical depth sigma_t x length of every stretch inside the medium
(`sigma_t`: a float, or the medium's own spectrum, evaluated at each path's wavelengths), then
asks the inner integrator (volpath)
for the radiance arriving along a ray that starts a hair (`eps`) in front of that surface, and
returns it times exp(-depth). That is the surface layer's definition: light whose first
interaction on the way back from the camera is the surface. The medium layer is the whole image
minus this (tools/compare/layers.py).

Registered as "surface_layer":
  {"type": "surface_layer", "inner": {"type": "volpath", ...}, "sigma_t": 0.1}
"""

import drjit as dr
import mitsuba as mi

# Null boundaries a camera ray may cross before its surface (fog-room-laser: one box face).
MAX_NULL = 8


class SurfaceLayer(mi.SamplingIntegrator):
    def __init__(self, props):
        super().__init__(props)
        self.inner = props.get("inner")
        st = props.get("sigma_t", 0.0)
        # A grey medium's float, or a spectrum (a texture evaluated at the path's wavelengths).
        self.sigma_t, self.sigma_t_tex = (float(st), None) if isinstance(st, (int, float)) else (0.0, st)
        self.eps = props.get("eps", 1e-4)

    def _sigma_t(self, wavelengths):
        if self.sigma_t_tex is None:
            return mi.Spectrum(self.sigma_t)
        si = dr.zeros(mi.SurfaceInteraction3f)
        si.wavelengths = wavelengths
        return self.sigma_t_tex.eval(si)

    def sample(self, scene, sampler, ray, medium=None, active=True):
        ray = mi.Ray3f(ray)
        active = mi.Bool(active)
        cur = mi.MediumPtr(medium)
        in_medium = cur != None  # noqa: E711 (a pointer array compared lane by lane)
        st = self._sigma_t(ray.wavelengths)
        depth = mi.Spectrum(0.0)
        found = mi.Bool(False)
        walking = mi.Bool(active)
        hit_p = mi.Point3f(0.0)
        hit_medium = mi.MediumPtr(cur)
        for _ in range(MAX_NULL):
            si = scene.ray_intersect(ray, walking)
            valid = walking & si.is_valid()
            null = valid & mi.has_flag(si.bsdf(ray).flags(), mi.BSDFFlags.Null)
            depth += dr.select(valid & in_medium, si.t * st, 0.0)
            surface = valid & ~null
            hit_p = dr.select(surface, si.p, hit_p)
            hit_medium = dr.select(surface, cur, hit_medium)
            found |= surface
            walking &= null
            nxt = si.spawn_ray(ray.d)
            ray = mi.Ray3f(dr.select(null, nxt.o, ray.o), ray.d, ray.time, ray.wavelengths)
            cur = dr.select(null, si.target_medium(ray.d), cur)
            in_medium = cur != None  # noqa: E711
        # The inner integrator takes one medium for all lanes: the surfaces must be in vacuum
        # (fog-cube's wall, fog-room-laser's walls, each 0.2 or 1 mm behind a fog box's null
        # face). A lane whose surface is inside a medium returns nothing and counts as invalid;
        # layers.py compares the layer's mean with brume's, which would show it.
        in_vacuum = found & (hit_medium == None)  # noqa: E711
        start = mi.RayDifferential3f(mi.Ray3f(hit_p - ray.d * self.eps, ray.d, ray.time, ray.wavelengths))
        L, _, _ = self.inner.sample(scene, sampler, start, None, in_vacuum)
        return dr.select(in_vacuum, L * dr.exp(-depth), 0.0), in_vacuum, []

    def aov_names(self):
        return []

    def to_string(self):
        return f"SurfaceLayer[sigma_t={self.sigma_t}]"


def register() -> None:
    mi.register_integrator("surface_layer", lambda props: SurfaceLayer(props))
