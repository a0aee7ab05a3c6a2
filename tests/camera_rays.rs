use brume::camera::Camera;
use glam::Vec3;

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

#[test]
fn orthographic_pixel_centres() {
    // Looking down -Z from z = 10, a 4 m x 2 m view on 8 x 4 pixels: 0.5 m pixels.
    let cam = Camera::orthographic(
        8,
        4,
        Vec3::new(1.0, 2.0, 10.0),
        Vec3::new(1.0, 2.0, 0.0),
        Vec3::Y,
        4.0,
        2.0,
    );
    assert_eq!(cam.resolution(), (8, 4));
    for j in 0..4 {
        for i in 0..8 {
            let r = cam.generate_ray(i as f32 + 0.5, j as f32 + 0.5);
            let x = 1.0 - 2.0 + 0.5 * (i as f32 + 0.5);
            let y = 2.0 + 1.0 - 0.5 * (j as f32 + 0.5); // row 0 at the top
            assert!(close(r.o, Vec3::new(x, y, 10.0)), "{i},{j}: {:?}", r.o);
            assert!(close(r.d, Vec3::NEG_Z));
        }
    }
    // Image corners map to the view rectangle's corners.
    assert!(close(
        cam.generate_ray(0.0, 0.0).o,
        Vec3::new(-1.0, 3.0, 10.0)
    ));
    assert!(close(
        cam.generate_ray(8.0, 4.0).o,
        Vec3::new(3.0, 1.0, 10.0)
    ));
}

#[test]
fn perspective_pixel_centres() {
    let (w, h) = (201u32, 101u32);
    let pos = Vec3::new(0.0, 1.0, 5.0);
    let cam = Camera::perspective(w, h, pos, Vec3::new(0.0, 1.0, 0.0), Vec3::Y, 60.0);
    // Centre pixel looks straight ahead.
    let c = cam.generate_ray(100.5, 50.5);
    assert!(close(c.o, pos) && close(c.d, Vec3::NEG_Z));
    // Top edge middle: half the vertical fov above the axis; right edge middle: aspect-scaled.
    let top = cam.generate_ray(100.5, 0.0).d;
    assert!((top.y.atan2(-top.z).to_degrees() - 30.0).abs() < 1e-3);
    let right = cam.generate_ray(w as f32, 50.5).d;
    let t = 30f32.to_radians().tan() * w as f32 / h as f32;
    assert!((right.x / -right.z - t).abs() < 1e-4 && right.y.abs() < 1e-6);
    // Every pixel centre: the ray hits the image plane at z = 4 at the pixel's planar position.
    let half_h = 30f32.to_radians().tan();
    for j in (0..h).step_by(10) {
        for i in (0..w).step_by(10) {
            let r = cam.generate_ray(i as f32 + 0.5, j as f32 + 0.5);
            assert!((r.d.length() - 1.0).abs() < 1e-6);
            let p = r.o + r.d / -r.d.z; // one metre in front
            let sx = (2.0 * (i as f32 + 0.5) / w as f32 - 1.0) * half_h * w as f32 / h as f32;
            let sy = (1.0 - 2.0 * (j as f32 + 0.5) / h as f32) * half_h;
            assert!(close(p, Vec3::new(sx, 1.0 + sy, 4.0)), "{i},{j}");
        }
    }
}

#[test]
fn degenerate_up_vector_still_gives_finite_rays() {
    let cam = Camera::perspective(10, 10, Vec3::ZERO, Vec3::new(0.0, -5.0, 0.0), Vec3::Y, 45.0);
    let r = cam.generate_ray(3.5, 7.5);
    assert!(r.d.is_finite() && (r.d.length() - 1.0).abs() < 1e-6);
}

fn cameras() -> [Camera; 2] {
    let eye = Vec3::new(0.3, -0.2, 4.0);
    let at = Vec3::new(0.1, 0.2, 0.0);
    [
        Camera::perspective(16, 12, eye, at, Vec3::Y, 50.0),
        Camera::orthographic(16, 12, eye, at, Vec3::Y, 3.2, 2.4),
    ]
}

/// `project` inverts `generate_ray`: a point on a pixel's ray lands in that pixel, with the
/// ray's reversed direction and the distance along it (perspective) or the view axis.
#[test]
fn project_inverts_generate_ray() {
    for cam in cameras() {
        for (x, y) in [(0.2, 0.3), (7.5, 6.5), (15.9, 11.9), (3.01, 9.99)] {
            let r = cam.generate_ray(x, y);
            let p = r.o + r.d * 3.0;
            let pr = cam.project(p).expect("in view");
            assert_eq!(pr.pixel, (y as u32) * 16 + x as u32, "{cam:?} {x} {y}");
            assert!(close(pr.to_camera, -r.d), "{:?}", pr.to_camera);
            assert!((pr.dist - 3.0).abs() < 1e-4, "{}", pr.dist);
        }
        // Behind the camera, and beside the image.
        let r = cam.generate_ray(8.0, 6.0);
        assert!(cam.project(r.o - r.d * 2.0).is_none());
        let beside = cam.generate_ray(8.0, 6.0).o + Vec3::new(40.0, 0.0, -3.0);
        assert!(cam.project(beside).is_none());
    }
}

/// The importance integrates to one over what a pixel sees: midpoint quadrature of
/// `importance * cos(theta_x)` over a tilted plane (area elements `dA`), summed per pixel,
/// is 1 in every pixel the plane covers to within 1 % (the quadrature's edge error: a
/// pixel holds about 5 000 cells).
#[test]
fn importance_integrates_to_one_per_pixel() {
    for cam in cameras() {
        // A plane through (0, 0, 0) with normal n, tilted from the view axis.
        let n = Vec3::new(0.3, 0.2, 1.0).normalize();
        let u = n.cross(Vec3::X).normalize();
        let v = n.cross(u);
        let (cells, half) = (1600, 4.0f32);
        let da = (2.0 * half / cells as f32).powi(2);
        let mut sums = vec![0.0f64; 16 * 12];
        for i in 0..cells {
            for j in 0..cells {
                let a = -half + (i as f32 + 0.5) * 2.0 * half / cells as f32;
                let b = -half + (j as f32 + 0.5) * 2.0 * half / cells as f32;
                let p = u * a + v * b;
                if let Some(pr) = cam.project(p) {
                    let cos = n.dot(pr.to_camera).abs();
                    sums[pr.pixel as usize] += (pr.importance * cos * da) as f64;
                }
            }
        }
        for (k, s) in sums.iter().enumerate() {
            assert!((s - 1.0).abs() < 0.01, "{cam:?} pixel {k}: {s}");
        }
    }
}
