"""brume's `glossy` material as a Mitsuba 3 BSDF plugin, for scalar and vectorised variants.

brume (src/material/glossy.rs): an Ashikhmin-Shirley coupled diffuse base,
  f_d = 28 / (23 pi) albedo (1 - R0) edge(cos_i) edge(cos_o),  edge(c) = 1 - (1 - c / 2)^5,
plus a GGX reflection lobe with Schlick's Fresnel from R0 = ((ior - 1) / (ior + 1))^2 and the
height-correlated Smith G, f_s = D G F / (4 cos_i cos_o). Both are reciprocal, so Mitsuba's
naming of wi / wo does not matter for the value. Sampling (which only changes Mitsuba's noise,
not its expected image) follows brume: the diffuse lobe is picked with probability
a / (a + F(cos)) with a = albedo (1 - R0), cosine-weighted; the specular one samples
D(h) cos(theta_h).

Vectorised variants (llvm_ad_spectral, the one compare.py uses) call eval / pdf / sample with
one drjit array holding a whole wavefront of interactions, not one interaction at a time, so
everything below is written as drjit array arithmetic on mi.Float / mi.Vector3f: every
branch of the old per-interaction code became a mask, and every early `return 0` became a
dr.select on that mask. In the scalar variants mi.Float is a plain float and the same code
runs one interaction at a time, so one implementation serves both.

Two rules keep the lane-wise version equal to the per-interaction one:
- dr.select evaluates both sides in every lane, so a lane that the old code skipped (below the
  horizon, zero half vector, ...) may compute inf or NaN on the discarded side. That is
  harmless only if the discarded value is dropped by a select, never multiplied by a 0/1 mask
  (NaN * 0 = NaN), so the masking below is done with dr.select throughout.
- Both lobes are sampled in every lane and the lobe choice selects between their directions,
  which draws from the same mixture with the same random numbers as the old if/else.

Python is called once per wavefront (not per interaction) in the vectorised variants, and the
drjit operations are traced into the same kernel as the rest of Mitsuba's integrator, so the
plugin's cost there is small; in the scalar variants it is called for every floor interaction
(compare.py reports the cost; the `--floor builtin` alternative is Mitsuba's `roughplastic`,
fast but a different diffuse term).
"""

from __future__ import annotations

import math

_REGISTERED = False


def register(mi) -> None:
    global _REGISTERED
    if _REGISTERED:
        return
    import drjit as dr

    inv_pi = 1.0 / math.pi
    Float = mi.Float

    def _edge(c):
        m = 1.0 - 0.5 * c
        m2 = m * m
        return 1.0 - m2 * m2 * m

    class BrumeGlossy(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            # The parameters are plain Python floats (constants baked into the traced
            # kernels), exactly as in the scalar version.
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

        # --- brume's formulas on drjit arrays (local frame, z up), lane by lane ---
        def _schlick(self, c):
            m = 1.0 - dr.clip(c, 0.0, 1.0)
            return self.r0 + (1.0 - self.r0) * m * m * m * m * m

        def _d(self, ch):
            a2 = self.alpha * self.alpha
            den = ch * ch * (a2 - 1.0) + 1.0
            return a2 / (math.pi * den * den)

        def _lambda(self, c):
            # Only used where c > 0; the guard keeps the other lanes finite (and keeps the scalar
            # variant, where a division by a Python 0.0 raises, from raising).
            c2 = c * c
            tan2 = dr.maximum(1.0 - c2, 0.0) / dr.select(c2 > 0.0, c2, 1.0)
            return 0.5 * (dr.sqrt(1.0 + self.alpha * self.alpha * tan2) - 1.0)

        def _p_diffuse(self, ci):
            a = self.albedo * (1.0 - self.r0)
            s = self._schlick(ci)
            tot = a + s
            return dr.select(tot > 0.0, a / dr.select(tot > 0.0, tot, 1.0), 0.0)

        def _f_pdf(self, wi, wo, active=True):
            """(f * cos_o, pdf of sampling wo from wi); zero unless wi, wo are above the surface."""
            ci, co = wi.z, wo.z
            valid = active & (ci > 0.0) & (co > 0.0)
            f = self.kd * _edge(ci) * _edge(co)
            pd = self._p_diffuse(ci)
            pdf = pd * co * inv_pi
            # Half vector; the old code skipped the specular lobe when |wi + wo| = 0 or h.z <= 0.
            hs = wi + wo
            n = dr.norm(hs)
            spec = valid & (n > 0.0)
            h = hs / dr.select(n > 0.0, n, 1.0)
            spec &= h.z > 0.0
            d = self._d(h.z)
            i_dot_h = dr.dot(wi, h)
            g = 1.0 / (1.0 + self._lambda(ci) + self._lambda(co))
            # Denominators guarded only in lanes that the selects below discard (with wi, wo above
            # the surface, cos_i cos_o > 0 and wi . h = (1 + wi . wo) / |wi + wo| > 0).
            spec &= i_dot_h != 0.0
            f_s = d * g * self._schlick(i_dot_h) / (4.0 * dr.select(spec, ci * co, 1.0))
            pdf_s = (1.0 - pd) * d * h.z / (4.0 * dr.select(spec, dr.abs(i_dot_h), 1.0))
            f = dr.select(spec, f + f_s, f)
            pdf = dr.select(spec, pdf + pdf_s, pdf)
            return dr.select(valid, f * co, 0.0), dr.select(valid, pdf, 0.0)

        # --- Mitsuba interface ---
        def sample(self, ctx, si, sample1, sample2, active=True):
            wi = si.wi
            active = active & (wi.z > 0.0)
            u1, u2 = sample2.x, sample2.y
            diffuse = sample1 < self._p_diffuse(wi.z)
            phi = 2.0 * math.pi * u2
            sin_phi, cos_phi = dr.sincos(phi)
            # Diffuse lobe: cosine-weighted hemisphere (Malley), as before.
            r = dr.sqrt(u1)
            wo_d = mi.Vector3f(r * cos_phi, r * sin_phi, dr.sqrt(dr.maximum(1.0 - u1, 0.0)))
            # Specular lobe: h from D(h) cos(theta_h), then wo = reflect(wi, h).
            a2 = self.alpha * self.alpha
            tan2 = a2 * u1 / dr.maximum(1.0 - u1, 1e-7)
            ch = 1.0 / dr.sqrt(1.0 + tan2)
            sh = dr.sqrt(dr.maximum(1.0 - ch * ch, 0.0))
            h = mi.Vector3f(sh * cos_phi, sh * sin_phi, ch)
            wo_s = 2.0 * dr.dot(wi, h) * h - wi
            wo = dr.select(diffuse, wo_d, wo_s)

            fc, pdf = self._f_pdf(wi, wo, active)
            # As before, a sample whose pdf is not positive (specular wo below the horizon,
            # wi below the surface) is an invalid, zero-weight sample with pdf 0.
            ok = active & (pdf > 0.0)
            bs = dr.zeros(mi.BSDFSample3f)
            bs.wo = dr.select(ok, wo, 0.0)
            bs.pdf = dr.select(ok, pdf, 0.0)
            bs.eta = 1.0
            bs.sampled_type = dr.select(
                diffuse,
                mi.UInt32(int(mi.BSDFFlags.DiffuseReflection)),
                mi.UInt32(int(mi.BSDFFlags.GlossyReflection)),
            )
            bs.sampled_type = dr.select(ok, bs.sampled_type, mi.UInt32(0))
            bs.sampled_component = dr.select(diffuse, mi.UInt32(0), mi.UInt32(1))
            weight = dr.select(ok, fc / dr.select(ok, pdf, 1.0), 0.0)
            return bs, mi.Spectrum(weight)

        def eval(self, ctx, si, wo, active=True):
            fc, _ = self._f_pdf(si.wi, wo, active)
            return mi.Spectrum(fc)

        def pdf(self, ctx, si, wo, active=True):
            _, p = self._f_pdf(si.wi, wo, active)
            return p

        def eval_pdf(self, ctx, si, wo, active=True):
            fc, p = self._f_pdf(si.wi, wo, active)
            return mi.Spectrum(fc), p

        def traverse(self, callback):
            pass

        def to_string(self):
            return f"BrumeGlossy[albedo={self.albedo}, r0={self.r0}, alpha={self.alpha}]"

    mi.register_bsdf("brume_glossy", lambda props: BrumeGlossy(props))
    _REGISTERED = True
