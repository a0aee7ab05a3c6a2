"""brume's `glossy` material as a Mitsuba 3 BSDF plugin, for the scalar variants.

brume (src/material/glossy.rs): an Ashikhmin-Shirley coupled diffuse base,
  f_d = 28 / (23 pi) albedo (1 - R0) edge(cos_i) edge(cos_o),  edge(c) = 1 - (1 - c / 2)^5,
plus a GGX reflection lobe with Schlick's Fresnel from R0 = ((ior - 1) / (ior + 1))^2 and the
height-correlated Smith G, f_s = D G F / (4 cos_i cos_o). Both are reciprocal, so Mitsuba's
naming of wi / wo does not matter for the value. Sampling (which only changes Mitsuba's noise,
not its expected image) follows brume: the diffuse lobe is picked with probability
a / (a + F(cos)) with a = albedo (1 - R0), cosine-weighted; the specular one samples
D(h) cos(theta_h).

Python is called for every floor interaction, so this costs Mitsuba time: compare.py reports
how much (the `--floor builtin` alternative is Mitsuba's `roughplastic`, fast but a different
diffuse term).
"""

from __future__ import annotations

import math

_REGISTERED = False


def _edge(c: float) -> float:
    m = 1.0 - 0.5 * c
    m2 = m * m
    return 1.0 - m2 * m2 * m


def register(mi) -> None:
    global _REGISTERED
    if _REGISTERED:
        return
    inv_pi = 1.0 / math.pi

    class BrumeGlossy(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.albedo = float(props.get("albedo", 0.3))
            ior = float(props.get("ior", 1.5))
            r = (ior - 1.0) / (ior + 1.0)
            self.r0 = min(max(r * r, 0.0), 1.0)
            self.alpha = min(max(float(props.get("alpha", 0.1)), 1e-3), 1.0)
            self.kd = 28.0 / (23.0 * math.pi) * self.albedo * (1.0 - self.r0)
            flags = (
                mi.BSDFFlags.DiffuseReflection
                | mi.BSDFFlags.GlossyReflection
                | mi.BSDFFlags.FrontSide
            )
            self.m_components = [
                mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide,
                mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide,
            ]
            self.m_flags = flags

        # --- brume's formulas on plain floats (local frame, z up) ---
        def _schlick(self, c: float) -> float:
            m = 1.0 - min(max(c, 0.0), 1.0)
            return self.r0 + (1.0 - self.r0) * m * m * m * m * m

        def _d(self, ch: float) -> float:
            a2 = self.alpha * self.alpha
            den = ch * ch * (a2 - 1.0) + 1.0
            return a2 / (math.pi * den * den)

        def _lambda(self, c: float) -> float:
            c2 = c * c
            tan2 = max(1.0 - c2, 0.0) / c2
            return 0.5 * (math.sqrt(1.0 + self.alpha * self.alpha * tan2) - 1.0)

        def _half(self, a, b):
            hx, hy, hz = a[0] + b[0], a[1] + b[1], a[2] + b[2]
            n = math.sqrt(hx * hx + hy * hy + hz * hz)
            if n == 0.0:
                return None
            return hx / n, hy / n, hz / n

        def _f_pdf(self, wi, wo):
            """(f * cos_o, pdf of sampling wo from wi) for wi, wo above the surface."""
            ci, co = wi[2], wo[2]
            if ci <= 0.0 or co <= 0.0:
                return 0.0, 0.0
            f = self.kd * _edge(ci) * _edge(co)
            pd = self._p_diffuse(ci)
            pdf = pd * co * inv_pi
            h = self._half(wi, wo)
            if h is not None and h[2] > 0.0:
                d = self._d(h[2])
                i_dot_h = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]
                g = 1.0 / (1.0 + self._lambda(ci) + self._lambda(co))
                f += d * g * self._schlick(i_dot_h) / (4.0 * ci * co)
                pdf += (1.0 - pd) * d * h[2] / (4.0 * abs(i_dot_h))
            return f * co, pdf

        def _p_diffuse(self, ci: float) -> float:
            a = self.albedo * (1.0 - self.r0)
            s = self._schlick(ci)
            return a / (a + s) if a + s > 0.0 else 0.0

        # --- Mitsuba interface ---
        def sample(self, ctx, si, sample1, sample2, active=True):
            wi = (float(si.wi[0]), float(si.wi[1]), float(si.wi[2]))
            bs = mi.BSDFSample3f()
            if wi[2] <= 0.0:
                return bs, mi.Spectrum(0.0)
            u1, u2 = float(sample2[0]), float(sample2[1])
            if float(sample1) < self._p_diffuse(wi[2]):
                r = math.sqrt(u1)
                phi = 2.0 * math.pi * u2
                wo = (r * math.cos(phi), r * math.sin(phi), math.sqrt(max(1.0 - u1, 0.0)))
                bs.sampled_type = int(mi.BSDFFlags.DiffuseReflection)
                bs.sampled_component = 0
            else:
                a2 = self.alpha * self.alpha
                tan2 = a2 * u1 / max(1.0 - u1, 1e-7)
                ch = 1.0 / math.sqrt(1.0 + tan2)
                sh = math.sqrt(max(1.0 - ch * ch, 0.0))
                phi = 2.0 * math.pi * u2
                h = (sh * math.cos(phi), sh * math.sin(phi), ch)
                dot = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]
                wo = (2 * dot * h[0] - wi[0], 2 * dot * h[1] - wi[1], 2 * dot * h[2] - wi[2])
                bs.sampled_type = int(mi.BSDFFlags.GlossyReflection)
                bs.sampled_component = 1
            fc, pdf = self._f_pdf(wi, wo)
            if pdf <= 0.0:
                return mi.BSDFSample3f(), mi.Spectrum(0.0)
            bs.wo = mi.Vector3f(*wo)
            bs.pdf = pdf
            bs.eta = 1.0
            return bs, mi.Spectrum(fc / pdf)

        def eval(self, ctx, si, wo, active=True):
            fc, _ = self._f_pdf((float(si.wi[0]), float(si.wi[1]), float(si.wi[2])), (float(wo[0]), float(wo[1]), float(wo[2])))
            return mi.Spectrum(fc)

        def pdf(self, ctx, si, wo, active=True):
            _, p = self._f_pdf((float(si.wi[0]), float(si.wi[1]), float(si.wi[2])), (float(wo[0]), float(wo[1]), float(wo[2])))
            return p

        def eval_pdf(self, ctx, si, wo, active=True):
            fc, p = self._f_pdf((float(si.wi[0]), float(si.wi[1]), float(si.wi[2])), (float(wo[0]), float(wo[1]), float(wo[2])))
            return mi.Spectrum(fc), p

        def traverse(self, callback):
            pass

        def to_string(self):
            return f"BrumeGlossy[albedo={self.albedo}, r0={self.r0}, alpha={self.alpha}]"

    mi.register_bsdf("brume_glossy", lambda props: BrumeGlossy(props))
    _REGISTERED = True
