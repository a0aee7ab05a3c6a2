//! Textures: bilinear lookup with repeat or clamp wrap, PNG and EXR loading in sRGB or linear
//! encoding, errors naming the file, scene textures (EXR, options, texels above 1);
//! and OBJ meshes through the same path a scene takes.

use std::sync::Arc;

use brume::geometry::{Geometry, Hit, Ray, ShapeDesc, ShapeKind, Transform, load_obj};
use brume::material::{Encoding, Material, Texture, Wrap};
use brume::spectrum::Spectrum;
use glam::{Vec2, Vec3};

/// A stand-in for the RGB-to-spectrum upsampler: bins are (r, g, b, r+g+b).
fn conv(c: [f32; 3]) -> Spectrum {
    Spectrum::from_slice(&[c[0], c[1], c[2], c[0] + c[1] + c[2]])
}

fn close(a: f32, b: f32) -> bool {
    (a - b).abs() < 1e-5
}

#[test]
fn bilinear_lookup_with_repeat_wrap() {
    // 2 x 2: top row red, green; bottom row blue, white.
    let rgb = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
    ];
    let t = Texture::from_rgb(2, 2, &rgb, 4, &conv);
    // Texel centres (v = 0 at the bottom).
    assert!(close(t.lookup(Vec2::new(0.25, 0.75))[0], 1.0)); // red, top-left
    assert!(close(t.lookup(Vec2::new(0.75, 0.75))[1], 1.0)); // green, top-right
    assert!(close(t.lookup(Vec2::new(0.25, 0.25))[2], 1.0)); // blue, bottom-left
    assert!(close(t.lookup(Vec2::new(0.75, 0.25))[3], 3.0)); // white
    // Centre of the image: average of all four.
    let c = t.lookup(Vec2::splat(0.5));
    assert!(close(c[0], 0.5) && close(c[1], 0.5) && close(c[2], 0.5) && close(c[3], 1.5));
    // Repeat wrap: u = 0 sits between the left and (wrapped) right texel columns.
    let w = t.lookup(Vec2::new(0.0, 0.75));
    assert!(close(w[0], 0.5) && close(w[1], 0.5));
    assert_eq!(
        t.lookup(Vec2::new(3.25, -1.25)),
        t.lookup(Vec2::new(0.25, 0.75))
    );
    assert_eq!(
        t.lookup(Vec2::new(0.3, 0.3))[4],
        0.0,
        "lanes past n stay zero"
    );
}

#[test]
fn png_and_exr_load() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("t.png");
    let mut img = image::RgbImage::new(2, 1);
    img.put_pixel(0, 0, image::Rgb([255, 0, 0]));
    img.put_pixel(1, 0, image::Rgb([0, 188, 255])); // sRGB 188 ~ linear 0.5
    img.save(&png).unwrap();
    let t = Texture::load(&png, 4, &conv).unwrap();
    assert_eq!(t.resolution(), (2, 1));
    let right = t.lookup(Vec2::new(0.75, 0.5));
    assert!(
        (right[1] - 0.503).abs() < 0.01,
        "sRGB decoded to linear: {}",
        right[1]
    );
    assert!(close(right[0], 0.0) && close(right[2], 1.0));

    let exr_path = dir.path().join("t.exr");
    exr::prelude::write_rgb_file(&exr_path, 3, 2, |x, y| (x as f32, y as f32, 2.5f32)).unwrap();
    let t = Texture::load(&exr_path, 4, &conv).unwrap();
    assert_eq!(t.resolution(), (3, 2));
    let texel = t.lookup(Vec2::new(2.5 / 3.0, 0.25)); // x = 2, bottom row y = 1
    assert!(close(texel[0], 2.0) && close(texel[1], 1.0) && close(texel[2], 2.5));

    let missing = dir.path().join("nope.png");
    let err = Texture::load(&missing, 4, &conv).unwrap_err().to_string();
    assert!(err.contains("nope.png"), "{err}");
    let err = Texture::load(&dir.path().join("x.tga"), 4, &conv)
        .unwrap_err()
        .to_string();
    assert!(err.contains("x.tga"), "{err}");
}

#[test]
fn textured_lambert_uses_hit_uv_on_quads_spheres_and_meshes() {
    let rgb = [[0.2, 0.2, 0.2], [0.8, 0.8, 0.8]];
    let m = Material::lambert_textured(Arc::new(Texture::from_rgb(2, 1, &rgb, 4, &conv)));
    let geo = Geometry::new(vec![
        ShapeDesc::new(
            ShapeKind::Quad {
                size: Vec2::splat(2.0),
            },
            Transform::IDENTITY,
        ),
        ShapeDesc::new(
            ShapeKind::Sphere { radius: 1.0 },
            Transform::translate(Vec3::new(5.0, 0.0, 0.0)),
        ),
    ])
    .unwrap();
    let h: Hit = geo
        .intersect(&Ray::new(Vec3::new(0.5, 0.3, 1.0), Vec3::NEG_Z), 10.0)
        .unwrap();
    assert!(close(h.uv.x, 0.75) && close(h.uv.y, 0.65));
    let f = m.eval(Vec3::Z, Vec3::new(0.0, 0.6, 0.8), &h);
    assert!(close(f[0], 0.8 / std::f32::consts::PI));
    let h = geo
        .intersect(&Ray::new(Vec3::new(5.0, -5.0, 0.0), Vec3::Y), 10.0)
        .unwrap();
    assert!(close(h.uv.x, 0.75) && close(h.uv.y, 0.5)); // azimuth 270 degrees at the equator
}

#[test]
fn obj_meshes_load_with_uvs_and_normals() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("quad.obj");
    std::fs::write(
        &path,
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n",
    )
    .unwrap();
    let kind = load_obj(&path).unwrap();
    let ShapeKind::Mesh {
        indices,
        uvs,
        normals,
        ..
    } = &kind
    else {
        panic!()
    };
    assert_eq!(indices.len(), 2);
    assert!(uvs.is_some() && normals.is_some());
    let geo = Geometry::new(vec![ShapeDesc::new(kind, Transform::translate(Vec3::Z))]).unwrap();
    assert!((geo.area(0) - 4.0).abs() < 1e-5);
    let h = geo
        .intersect(&Ray::new(Vec3::new(0.5, -0.5, 3.0), Vec3::NEG_Z), 10.0)
        .unwrap();
    assert!(close(h.t, 2.0) && close(h.uv.x, 0.75) && close(h.uv.y, 0.25));
    assert!((h.ns - Vec3::Z).length() < 1e-6 && (h.ng - Vec3::Z).length() < 1e-6);

    let err = load_obj(&dir.path().join("missing.obj"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("missing.obj"), "{err}");
}

#[test]
fn colour_space_and_wrap() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("t.png");
    let mut img = image::RgbImage::new(2, 1);
    img.put_pixel(0, 0, image::Rgb([255, 0, 0]));
    img.put_pixel(1, 0, image::Rgb([0, 188, 255]));
    img.save(&png).unwrap();
    let linear = Texture::load_encoded(&png, Encoding::Linear, 4, &conv).unwrap();
    let right = linear.lookup(Vec2::new(0.75, 0.5));
    assert!(close(right[1], 188.0 / 255.0), "stored value: {}", right[1]);
    let srgb = Texture::load_encoded(&png, Encoding::Srgb, 4, &conv).unwrap();
    assert!((srgb.lookup(Vec2::new(0.75, 0.5))[1] - 0.503).abs() < 0.01);

    let exr_path = dir.path().join("t.exr");
    exr::prelude::write_rgb_file(&exr_path, 1, 1, |_, _| (0.5f32, 0.5f32, 0.5f32)).unwrap();
    assert_eq!(Encoding::default_for(&exr_path), Encoding::Linear);
    assert_eq!(Encoding::default_for(&png), Encoding::Srgb);
    let t = Texture::load_encoded(&exr_path, Encoding::Srgb, 4, &conv).unwrap();
    assert!(
        (t.lookup(Vec2::splat(0.5))[0] - 0.214).abs() < 0.001,
        "sRGB-decoded EXR"
    );

    // 2 x 1: red | green. Repeat wraps u = 0 between the two columns; clamp keeps the edge.
    let rgb = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let repeat = Texture::from_rgb(2, 1, &rgb, 4, &conv);
    assert!(close(repeat.lookup(Vec2::new(0.0, 0.5))[0], 0.5));
    let clamp = Texture::from_rgb(2, 1, &rgb, 4, &conv).with_wrap(Wrap::Clamp);
    assert_eq!(clamp.wrap(), Wrap::Clamp);
    assert!(close(clamp.lookup(Vec2::new(0.0, 0.5))[0], 1.0));
    assert!(close(clamp.lookup(Vec2::new(-3.0, 7.0))[0], 1.0));
    assert!(close(clamp.lookup(Vec2::new(5.0, 0.5))[1], 1.0));
    assert_eq!(
        repeat.lookup(Vec2::new(0.25, 0.5)),
        clamp.lookup(Vec2::new(0.25, 0.5)),
        "inside, the two agree"
    );
}

const TEXTURED: &str = r#"
[camera]
width = 8
height = 8

[materials.wall]
type = "lambert"
albedo = 1.0
texture = TEXTURE

[[shapes]]
type = "quad"
size = [1, 1]
material = "wall"
"#;

fn textured(dir: &std::path::Path, texture: &str) -> Result<brume::scene::Scene, String> {
    let text = TEXTURED.replace("TEXTURE", texture);
    let loaded =
        brume::scene::load_str(&text, &dir.join("scene.toml"), &[]).map_err(|e| e.to_string())?;
    brume::scene::build(&loaded).map_err(|e| e.to_string())
}

fn albedo_at(scene: &brume::scene::Scene, uv: Vec2) -> Spectrum {
    match &scene.materials[0] {
        Material::Lambert { albedo } => albedo.at(uv),
        other => panic!("{other:?}"),
    }
}

/// Scenes take EXR textures (docs/scene-format.md said so; the header check refused them),
/// `colour_space` and `wrap`; texels above 1 are an albedo above 1 and need
/// `allow_energy_gain`; texels that are not finite are refused.
#[test]
fn scene_textures_exr_colour_space_and_wrap() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, v: f32| {
        exr::prelude::write_rgb_file(dir.path().join(name), 2, 1, |x, _| {
            if x == 0 {
                (v, v, v)
            } else {
                (0.25f32, 0.25, 0.25)
            }
        })
        .unwrap()
    };
    write("half.exr", 0.5);
    write("bright.exr", 1.5);
    write("nan.exr", f32::NAN);
    let s = textured(dir.path(), "\"half.exr\"").unwrap_or_else(|e| panic!("{e}"));
    let left = albedo_at(&s, Vec2::new(0.25, 0.5));
    assert!(
        (left[0] - 0.5).abs() < 0.02,
        "EXR is linear by default: {}",
        left[0]
    );

    let srgb = textured(
        dir.path(),
        "{ file = \"half.exr\", colour_space = \"srgb\" }",
    )
    .unwrap();
    assert!((albedo_at(&srgb, Vec2::new(0.25, 0.5))[0] - 0.214).abs() < 0.02);
    let clamp = textured(dir.path(), "{ file = \"half.exr\", wrap = \"clamp\" }").unwrap();
    let edge = albedo_at(&clamp, Vec2::new(0.0, 0.5))[0];
    let wrapped = albedo_at(&s, Vec2::new(0.0, 0.5))[0];
    assert!(
        (edge - 0.5).abs() < 0.02 && (wrapped - 0.375).abs() < 0.02,
        "{edge} {wrapped}"
    );

    let e = textured(dir.path(), "\"bright.exr\"")
        .err()
        .expect("texel above 1");
    assert!(
        e.starts_with(&format!(
            "{}:9:1: key `materials.wall.texture`",
            dir.path().join("scene.toml").display()
        )) && e.contains("allow_energy_gain"),
        "{e}"
    );
    let text = "\"bright.exr\"\nallow_energy_gain = true";
    let bright = textured(dir.path(), text).unwrap_or_else(|e| panic!("{e}"));
    assert!(albedo_at(&bright, Vec2::new(0.25, 0.5))[0] > 1.2);
    let e = textured(dir.path(), "\"nan.exr\"")
        .err()
        .expect("NaN texel");
    assert!(e.contains("not finite"), "{e}");
    let e = textured(dir.path(), "{ file = \"half.exr\", wrap = \"mirror\" }")
        .err()
        .expect("unknown wrap");
    assert!(
        e.contains(":9:") && e.contains("key `materials.wall.texture.wrap`"),
        "{e}"
    );
    let e = textured(dir.path(), "{ file = \"half.exr\", gamma = 2.2 }")
        .err()
        .expect("unknown key");
    assert!(e.contains("key `materials.wall.texture.gamma`"), "{e}");
}
