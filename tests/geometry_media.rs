//! Medium bookkeeping: a box inside a sphere inside a room. Every segment of a walked ray must
//! report the medium an analytic classification gives, including rays that graze edges, faces
//! and the sphere's silhouette.

use brume::geometry::{Geometry, Ray, ShapeDesc, ShapeKind, Transform, spawn};
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

const ROOM: f32 = 5.0; // half size
const SPHERE_C: Vec3 = Vec3::new(0.3, -0.2, 0.1);
const SPHERE_R: f32 = 2.0;
const BOX_C: Vec3 = Vec3::new(0.5, 0.0, 0.0);
const BOX_H: Vec3 = Vec3::new(0.6, 0.5, 0.4);
const FOG: Option<u32> = Some(0);
const SMOKE: Option<u32> = Some(1);
const GLASS: Option<u32> = Some(2);

fn scene(box_rotation: Vec3) -> Geometry {
    let room = ShapeDesc {
        interior: FOG,
        exterior: None,
        material: Some(0),
        ..ShapeDesc::new(
            ShapeKind::Box {
                size: Vec3::splat(2.0 * ROOM),
            },
            Transform::IDENTITY,
        )
    };
    let sphere = ShapeDesc {
        interior: SMOKE,
        exterior: FOG,
        ..ShapeDesc::new(
            ShapeKind::Sphere { radius: SPHERE_R },
            Transform::translate(SPHERE_C),
        )
    };
    let cube = ShapeDesc {
        interior: GLASS,
        exterior: SMOKE,
        material: Some(1),
        ..ShapeDesc::new(
            ShapeKind::Box { size: 2.0 * BOX_H },
            Transform::new(BOX_C, box_rotation, Vec3::ONE),
        )
    };
    // An open quad in the fog, declared with the fog on both sides: not a boundary.
    let shelf = ShapeDesc {
        interior: FOG,
        exterior: FOG,
        material: Some(0),
        ..ShapeDesc::new(
            ShapeKind::Quad {
                size: glam::Vec2::splat(1.5),
            },
            Transform::translate(Vec3::new(-3.5, 0.0, 0.0)),
        )
    };
    Geometry::new(vec![room, sphere, cube, shelf]).unwrap()
}

/// Analytic medium at `p` and its distance to the nearest boundary (for the box: to its face
/// planes in the box frame, enough to flag ambiguous points).
fn truth(p: Vec3, box_to_local: &dyn Fn(Vec3) -> Vec3) -> (Option<u32>, f32) {
    let q = box_to_local(p);
    let box_d = (q.abs() - BOX_H).abs().min_element();
    let box_in = q.abs().cmplt(BOX_H).all();
    let s = (p - SPHERE_C).length();
    let room_d = (p.abs() - Vec3::splat(ROOM)).abs().min_element();
    let room_in = p.abs().cmplt(Vec3::splat(ROOM)).all();
    let near = box_d.min((s - SPHERE_R).abs()).min(room_d);
    let m = if box_in {
        GLASS
    } else if s < SPHERE_R {
        SMOKE
    } else if room_in {
        FOG
    } else {
        None
    };
    (m, near)
}

/// Walks a ray through the scene using only `medium_at` for the start and `medium_after` at
/// each crossing; checks points along every segment. Returns the number of checked points.
fn walk_and_check(
    geo: &Geometry,
    ray: Ray,
    box_to_local: &dyn Fn(Vec3) -> Vec3,
    label: &str,
) -> usize {
    let mut medium = geo.medium_at(ray.o);
    let (m0, d0) = truth(ray.o, box_to_local);
    if d0 > 1e-3 {
        assert_eq!(medium, m0, "{label}: medium_at origin {:?}", ray.o);
    }
    let mut r = ray;
    let mut checked = 0;
    for _ in 0..64 {
        let hit = geo.intersect(&r, f32::INFINITY);
        let t_end = hit.map_or(20.0, |h| h.t);
        for k in 1..8 {
            let p = r.at(t_end * k as f32 / 8.0);
            let (m, near) = truth(p, box_to_local);
            if near > 1e-3 {
                assert_eq!(medium, m, "{label}: segment medium at {p:?}");
                checked += 1;
            }
        }
        let Some(h) = hit else { return checked };
        medium = geo.medium_after(&h, r.d);
        r = spawn(h.p, h.ng, r.d);
    }
    panic!("{label}: ray did not leave the scene");
}

fn random_dir(rng: &mut Pcg64Mcg) -> Vec3 {
    let z = 1.0 - 2.0 * rng.random::<f32>();
    let phi = std::f32::consts::TAU * rng.random::<f32>();
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

fn run(rotation: Vec3, seed: u64) {
    let geo = scene(rotation);
    let tr = Transform::new(BOX_C, rotation, Vec3::ONE);
    let to_local = move |p: Vec3| tr.inv_point(p);
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut checked = 0;

    // Random rays from anywhere in the room.
    for i in 0..3000 {
        let o = (Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - 1.0) * (ROOM * 0.99);
        checked += walk_and_check(
            &geo,
            Ray::new(o, random_dir(&mut rng)),
            &to_local,
            &format!("random {i}"),
        );
    }
    // Rays through box edges and corners, from every direction.
    for i in 0..3000 {
        let mut e = Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - 1.0;
        let axis = rng.random_range(0..3);
        for a in 0..3 {
            if a != axis || i % 5 == 0 {
                e[a] = e[a].signum(); // on an edge (every fifth: a corner)
            }
        }
        let p = tr.point(e * BOX_H);
        let d = random_dir(&mut rng);
        checked += walk_and_check(
            &geo,
            Ray::new(p - d * 3.0, d),
            &to_local,
            &format!("edge {i}"),
        );
    }
    // Rays lying in a box face plane or a room wall plane (exact grazing).
    for i in 0..2000 {
        let axis = rng.random_range(0..3);
        let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
        let mut d = random_dir(&mut rng);
        d[axis] = 0.0;
        let d = d.normalize();
        let mut o = (Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - 1.0) * 0.9;
        o[axis] = sign;
        let ray = if i % 2 == 0 {
            let wd = tr.vector(d).normalize();
            Ray::new(tr.point(o * BOX_H) - wd * 2.5, wd)
        } else {
            Ray::new(o * ROOM - d * 0.5 * ROOM, d)
        };
        checked += walk_and_check(&geo, ray, &to_local, &format!("face {i}"));
    }
    // Rays tangent to the sphere.
    for i in 0..2000 {
        let n = random_dir(&mut rng);
        let mut d = random_dir(&mut rng);
        d = (d - n * d.dot(n)).normalize();
        let p = SPHERE_C + n * SPHERE_R;
        checked += walk_and_check(
            &geo,
            Ray::new(p - d * 2.5, d),
            &to_local,
            &format!("tangent {i}"),
        );
    }
    assert!(checked > 50_000, "too few points checked: {checked}");
}

#[test]
fn media_along_rays_axis_aligned_box() {
    run(Vec3::ZERO, 11);
}

#[test]
fn media_along_rays_rotated_box() {
    run(Vec3::new(30.0, 45.0, 10.0), 12);
}

#[test]
fn medium_at_each_region() {
    let geo = scene(Vec3::ZERO);
    assert_eq!(geo.medium_at(BOX_C), GLASS);
    assert_eq!(geo.medium_at(SPHERE_C + Vec3::new(0.0, 0.0, 1.5)), SMOKE);
    assert_eq!(geo.medium_at(Vec3::new(-4.0, 4.0, 4.0)), FOG);
    assert_eq!(geo.medium_at(Vec3::new(-3.5, 0.0, 0.0)), FOG); // on the shelf quad
    assert_eq!(geo.medium_at(Vec3::new(9.0, 0.0, 0.0)), None);
    // Just inside / outside each boundary.
    assert_eq!(
        geo.medium_at(BOX_C + Vec3::new(BOX_H.x - 1e-3, 0.0, 0.0)),
        GLASS
    );
    assert_eq!(
        geo.medium_at(BOX_C + Vec3::new(BOX_H.x + 1e-3, 0.0, 0.0)),
        SMOKE
    );
    assert_eq!(geo.medium_at(Vec3::new(ROOM - 1e-3, 1.0, 1.0)), FOG);
}
