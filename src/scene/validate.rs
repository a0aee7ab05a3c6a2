//! Range and reference checks on a scene description, before anything heavy is allocated.

use super::desc::{LightKind, MaterialKind, SceneDesc, ShapeKindDesc, SpectrumDesc, SpectrumRef};
use super::load::LoadedScene;
use crate::spectrum::MAX_BINS;

/// One problem: the dotted key it is about and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    pub key: String,
    pub message: String,
}

/// Whether `name` is a built-in spectrum (`D65`, `colorchecker:dark_skin`, ...): its part before
/// any `:column` names a built-in table.
pub fn is_builtin(name: &str) -> bool {
    let base = name.split(':').next().unwrap_or(name);
    crate::spectrum::builtin_table(base).is_some()
}

fn builtin_list() -> String {
    crate::spectrum::builtin_names()
        .collect::<Vec<_>>()
        .join(", ")
}

/// Largest image side and pixel count accepted (beyond this the film alone would exhaust memory).
pub const MAX_SIDE: u32 = 32_768;
pub const MAX_PIXELS: u64 = 1 << 27;
/// Largest texture accepted, checked from the image header before any decoding.
pub const MAX_TEXTURE_SIDE: u32 = 16_384;
pub const MAX_TEXTURE_PIXELS: u64 = 1 << 26;

struct Checker<'a> {
    scene: &'a LoadedScene,
    problems: Vec<Problem>,
}

impl Checker<'_> {
    fn fail(&mut self, key: impl Into<String>, message: impl Into<String>) {
        self.problems.push(Problem {
            key: key.into(),
            message: message.into(),
        });
    }

    fn positive(&mut self, key: &str, v: f64) {
        if !(v.is_finite() && v > 0.0) {
            self.fail(key, format!("must be a finite number > 0, got {v}"));
        }
    }

    fn non_negative(&mut self, key: &str, v: f64) {
        if !(v.is_finite() && v >= 0.0) {
            self.fail(key, format!("must be a finite number >= 0, got {v}"));
        }
    }

    fn range(&mut self, key: &str, v: f64, lo: f64, hi: f64, what: &str) {
        if !(v.is_finite() && v >= lo && v <= hi) {
            self.fail(key, format!("must be {what}, got {v}"));
        }
    }

    fn vector(&mut self, key: &str, v: [f32; 3]) {
        if v.iter().any(|c| !c.is_finite()) {
            self.fail(key, "must hold finite numbers");
        }
    }

    fn direction(&mut self, key: &str, v: [f32; 3]) {
        self.vector(key, v);
        if v.iter().all(|c| *c == 0.0) {
            self.fail(key, "must not be the zero vector");
        }
    }

    fn file(&mut self, key: &str, rel: &str) {
        let p = self.scene.resolve(rel);
        if !p.is_file() {
            self.fail(key, format!("file not found: {}", p.display()));
        }
    }

    /// A texture file: present, readable as an image, and of sane size, judged from its header
    /// so that a forged or absurd file is refused before its pixels are allocated.
    fn texture(&mut self, key: &str, rel: &str) {
        let p = self.scene.resolve(rel);
        if !p.is_file() {
            return self.fail(key, format!("file not found: {}", p.display()));
        }
        let dims = image::ImageReader::open(&p)
            .and_then(|r| r.with_guessed_format())
            .map_err(|e| e.to_string())
            .and_then(|r| r.into_dimensions().map_err(|e| e.to_string()));
        match dims {
            Err(e) => self.fail(key, format!("{}: not a readable image: {e}", p.display())),
            Ok((w, h)) => {
                if w == 0
                    || h == 0
                    || w > MAX_TEXTURE_SIDE
                    || h > MAX_TEXTURE_SIDE
                    || w as u64 * h as u64 > MAX_TEXTURE_PIXELS
                {
                    self.fail(
                        key,
                        format!(
                            "{}: a {w}x{h} texture is outside the supported 1..={MAX_TEXTURE_SIDE} \
                             pixels per side ({MAX_TEXTURE_PIXELS} pixels in all)",
                            p.display()
                        ),
                    );
                }
            }
        }
    }

    fn spectrum_ref(&mut self, key: &str, r: &SpectrumRef, desc: &SceneDesc) {
        match r {
            SpectrumRef::Constant(v) => self.non_negative(key, *v),
            SpectrumRef::Rgb(rgb) => {
                if rgb.iter().any(|c| !(c.is_finite() && *c >= 0.0)) {
                    self.fail(key, "RGB components must be finite and >= 0");
                }
            }
            SpectrumRef::Named(n) => {
                let file = n.split(':').next().unwrap_or(n);
                if !desc.spectra.contains_key(n)
                    && !is_builtin(n)
                    && !self.scene.resolve(file).is_file()
                {
                    self.fail(
                        key,
                        format!(
                            "`{n}` is not a spectrum in [spectra], a built-in ({}), or a CSV file",
                            builtin_list()
                        ),
                    );
                }
            }
        }
    }

    fn named_spectrum(&mut self, key: &str, s: &SpectrumDesc) {
        let sources = s.sources();
        if sources.len() != 1 {
            self.fail(
                key,
                format!(
                    "give exactly one of file, builtin, value, rgb, power_law (found {})",
                    if sources.is_empty() {
                        "none".to_string()
                    } else {
                        sources.join(", ")
                    }
                ),
            );
        }
        if let Some(f) = &s.file
            && !is_builtin(f)
        {
            // `file.csv:column` names a column of the file.
            let path = match f.rsplit_once(':') {
                Some((p, _)) if !self.scene.resolve(f).is_file() => p,
                _ => f,
            };
            self.file(&format!("{key}.file"), path);
        }
        if let Some(b) = &s.builtin
            && !is_builtin(b)
        {
            self.fail(
                format!("{key}.builtin"),
                format!("unknown built-in spectrum `{b}`"),
            );
        }
        if let Some(v) = s.value {
            self.non_negative(&format!("{key}.value"), v);
        }
        if let Some(rgb) = s.rgb
            && rgb.iter().any(|c| !(c.is_finite() && *c >= 0.0))
        {
            self.fail(
                format!("{key}.rgb"),
                "RGB components must be finite and >= 0",
            );
        }
        if let Some(p) = &s.power_law {
            self.non_negative(&format!("{key}.power_law.k"), p.k);
            self.range(
                &format!("{key}.power_law.p"),
                p.p,
                -20.0,
                20.0,
                "in [-20, 20]",
            );
            self.positive(&format!("{key}.power_law.lambda_ref"), p.lambda_ref);
        }
        if let Some(sc) = s.scale {
            self.non_negative(&format!("{key}.scale"), sc);
        }
    }

    fn reference<T>(
        &mut self,
        key: &str,
        name: &str,
        map: &std::collections::BTreeMap<String, T>,
        what: &str,
    ) {
        if !map.contains_key(name) {
            let known: Vec<&str> = map.keys().map(String::as_str).collect();
            self.fail(
                key,
                format!(
                    "no {what} named `{name}` (defined: {})",
                    if known.is_empty() {
                        "none".into()
                    } else {
                        known.join(", ")
                    }
                ),
            );
        }
    }
}

pub fn validate(scene: &LoadedScene) -> Vec<Problem> {
    let d = &scene.desc;
    let mut c = Checker {
        scene,
        problems: Vec::new(),
    };

    let f = &d.film;
    if !(1..=MAX_BINS).contains(&f.bins) {
        c.fail(
            "film.bins",
            format!("must be in 1..={MAX_BINS}, got {}", f.bins),
        );
    }
    c.range(
        "film.lambda_min",
        f.lambda_min,
        200.0,
        2000.0,
        "in [200, 2000] nm",
    );
    c.range(
        "film.lambda_max",
        f.lambda_max,
        200.0,
        2000.0,
        "in [200, 2000] nm",
    );
    if f.lambda_max <= f.lambda_min {
        c.fail("film.lambda_max", "must be greater than film.lambda_min");
    }
    c.range(
        "film.exposure",
        f.exposure as f64,
        -64.0,
        64.0,
        "in [-64, 64] stops",
    );
    for (i, o) in f.outputs.iter().enumerate() {
        if crate::film::output::format_of(std::path::Path::new(o)).is_err() {
            c.fail(
                format!("film.outputs.{i}"),
                format!("`{o}`: use a .exr or .png extension"),
            );
        }
    }

    let cam = &d.camera;
    for (k, v) in [("camera.width", cam.width), ("camera.height", cam.height)] {
        if !(1..=MAX_SIDE).contains(&v) {
            c.fail(k, format!("must be in 1..={MAX_SIDE} pixels, got {v}"));
        }
    }
    if cam.width as u64 * cam.height as u64 > MAX_PIXELS {
        c.fail(
            "camera.width",
            format!("the image has more than {MAX_PIXELS} pixels"),
        );
    }
    c.vector("camera.position", cam.position);
    c.vector("camera.look_at", cam.look_at);
    c.direction("camera.up", cam.up);
    if cam.position == cam.look_at {
        c.fail("camera.look_at", "must differ from camera.position");
    }
    c.range(
        "camera.fov",
        cam.fov as f64,
        1e-3,
        179.0,
        "in (0, 179] degrees",
    );
    c.positive("camera.view_width", cam.view_width as f64);
    c.positive("camera.view_height", cam.view_height as f64);

    let it = &d.integrator;
    c.positive("integrator.radius", it.radius as f64);
    if !(it.alpha > 0.0 && it.alpha <= 1.0) {
        c.fail(
            "integrator.alpha",
            format!("must be in (0, 1], got {}", it.alpha),
        );
    }
    if !(it.q > 0.0 && it.q <= 1.0) {
        c.fail("integrator.q", format!("must be in (0, 1], got {}", it.q));
    }
    if !(1..=1_000_000_000_000).contains(&it.forward_rays) {
        c.fail(
            "integrator.forward_rays",
            format!("must be in 1..=1e12, got {}", it.forward_rays),
        );
    }
    if !(1..=4096).contains(&it.camera_samples) {
        c.fail("integrator.camera_samples", "must be in 1..=4096");
    }
    if !(1..=4096).contains(&it.max_depth) {
        c.fail("integrator.max_depth", "must be in 1..=4096");
    }
    if !(it.channel_floor > 0.0 && it.channel_floor <= 1.0) {
        c.fail("integrator.channel_floor", "must be in (0, 1]");
    }
    if it.passes == 0 {
        c.fail("integrator.passes", "must be at least 1");
    }

    for (name, s) in &d.spectra {
        c.named_spectrum(&format!("spectra.{name}"), s);
    }

    for (name, m) in &d.materials {
        let key = format!("materials.{name}");
        if let Some(a) = &m.albedo {
            c.spectrum_ref(&format!("{key}.albedo"), a, d);
        }
        if let Some(t) = &m.texture {
            c.texture(&format!("{key}.texture"), t);
        }
        if let Some(ior) = &m.ior {
            c.spectrum_ref(&format!("{key}.ior"), ior, d);
            if let SpectrumRef::Constant(v) = ior {
                c.range(&format!("{key}.ior"), *v, 1.0, 5.0, "in [1, 5]");
            }
        }
        if let Some(r) = m.roughness {
            c.range(
                &format!("{key}.roughness"),
                r as f64,
                1e-4,
                1.0,
                "in [1e-4, 1]",
            );
        }
        match m.kind {
            MaterialKind::Lambert | MaterialKind::Glossy => {
                if m.albedo.is_none() && m.texture.is_none() {
                    c.fail(&key, "needs `albedo` or `texture`");
                }
            }
            MaterialKind::Dielectric => {
                if m.ior.is_none() {
                    c.fail(&key, "a dielectric needs `ior`");
                }
            }
            MaterialKind::Mirror => {}
        }
    }

    for (name, m) in &d.media {
        let key = format!("media.{name}");
        if let Some(s) = &m.sigma_s {
            c.spectrum_ref(&format!("{key}.sigma_s"), s, d);
        }
        c.spectrum_ref(&format!("{key}.sigma_a"), &m.sigma_a, d);
        for (k, message) in m.check(&|f| scene.resolve(f).is_file()) {
            c.fail(
                if k.is_empty() {
                    key.clone()
                } else {
                    format!("{key}.{k}")
                },
                message,
            );
        }
    }
    if let Some(m) = &d.medium {
        c.reference("medium", m, &d.media, "medium");
    }

    for (i, s) in d.shapes.iter().enumerate() {
        let key = format!("shapes.{i}");
        let size_len = match s.kind {
            ShapeKindDesc::Quad => Some(2),
            ShapeKindDesc::Box => Some(3),
            _ => None,
        };
        if let Some(n) = size_len {
            match &s.size {
                Some(v) if v.len() == n => {
                    if v.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
                        c.fail(format!("{key}.size"), "sizes must be finite and > 0");
                    }
                }
                Some(v) => c.fail(
                    format!("{key}.size"),
                    format!("needs {n} numbers, got {}", v.len()),
                ),
                None => c.fail(
                    &key,
                    format!("a {:?} needs `size` ({n} numbers)", s.kind).to_lowercase(),
                ),
            }
        }
        if matches!(s.kind, ShapeKindDesc::Sphere | ShapeKindDesc::Disc) {
            match s.radius {
                Some(r) => c.positive(&format!("{key}.radius"), r as f64),
                None => c.fail(&key, "needs `radius`"),
            }
        }
        if s.kind == ShapeKindDesc::Mesh {
            match &s.file {
                Some(f) => c.file(&format!("{key}.file"), f),
                None => c.fail(&key, "a mesh needs `file`"),
            }
        }
        if let Some(m) = &s.material {
            c.reference(&format!("{key}.material"), m, &d.materials, "material");
        }
        for (k, v) in [("interior", &s.interior), ("exterior", &s.exterior)] {
            if let Some(m) = v {
                c.reference(&format!("{key}.{k}"), m, &d.media, "medium");
            }
        }
        if let Some(e) = &s.emit {
            c.spectrum_ref(&format!("{key}.emit"), e, d);
        }
        c.non_negative(&format!("{key}.emit_scale"), s.emit_scale as f64);
        let t = &s.transform;
        c.vector(&format!("{key}.transform.translate"), t.translate);
        c.vector(&format!("{key}.transform.rotate"), t.rotate);
        if t.scale.iter().any(|x| !(x.is_finite() && *x != 0.0)) {
            c.fail(
                format!("{key}.transform.scale"),
                "scale factors must be finite and non-zero",
            );
        }
    }

    for (i, l) in d.lights.iter().enumerate() {
        let key = format!("lights.{i}");
        if let Some(s) = &l.spectrum {
            c.spectrum_ref(&format!("{key}.spectrum"), s, d);
        }
        let needs = |what: &str| format!("a {:?} light needs `{what}`", l.kind).to_lowercase();
        match l.kind {
            LightKind::Directional => match l.irradiance {
                Some(e) => c.positive(&format!("{key}.irradiance"), e as f64),
                None => c.fail(&key, needs("irradiance")),
            },
            _ => match l.power {
                Some(p) => c.positive(&format!("{key}.power"), p as f64),
                None => c.fail(&key, needs("power")),
            },
        }
        if l.kind != LightKind::Directional {
            match l.position {
                Some(p) => c.vector(&format!("{key}.position"), p),
                None => c.fail(&key, needs("position")),
            }
        }
        if matches!(
            l.kind,
            LightKind::Directional | LightKind::Spot | LightKind::Laser
        ) {
            match l.direction {
                Some(v) => c.direction(&format!("{key}.direction"), v),
                None => c.fail(&key, needs("direction")),
            }
        }
        if l.kind == LightKind::Spot {
            match l.angle {
                Some(a) => c.range(
                    &format!("{key}.angle"),
                    a as f64,
                    1e-3,
                    90.0,
                    "in (0, 90] degrees",
                ),
                None => c.fail(&key, needs("angle")),
            }
            if let Some(s) = l.soft_edge {
                c.range(
                    &format!("{key}.soft_edge"),
                    s as f64,
                    0.0,
                    90.0,
                    "in [0, 90] degrees",
                );
            }
        }
        if l.kind == LightKind::Laser {
            match l.radius {
                Some(r) => c.positive(&format!("{key}.radius"), r as f64),
                None => c.fail(&key, needs("radius")),
            }
        }
    }
    c.problems
}
