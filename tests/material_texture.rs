//! Textures: bilinear lookup with repeat wrap, PNG (sRGB) and EXR loading, errors naming the file;
//! and OBJ meshes through the same path a scene takes.

use std::sync::Arc;

use brume::geometry::{Geometry, Hit, Ray, ShapeDesc, ShapeKind, Transform, load_obj};
use brume::material::{Material, Texture};
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
