//! Every primitive through the scene pipeline: transformed into place, hit and missed from
//! outside and inside, described correctly; cut-outs; and rays that start on a surface never
//! hit that surface again (grazing and nested cases).

use glam::{Mat4, Vec2, Vec3};
use strahl::accel::AccelKind;
use strahl::geometry::{Ray, Transform, spawn_ray};
use strahl::scene::{Material, Object, Scene, Shape, Texture};
use strahl::world::{SurfaceHit, World};

fn world_of(objects: Vec<(Shape, Transform)>) -> World {
    let mut scene = Scene::empty("test");
    let m = scene.add_material(Material::diffuse("grey", strahl::color::Rgb::splat(0.5)));
    for (i, (shape, transform)) in objects.into_iter().enumerate() {
        scene.objects.push(Object {
            name: Some(format!("o{i}")),
            shape,
            transform,
            material: m,
            per_face: false,
        });
    }
    World::new(scene, AccelKind::Bvh).unwrap()
}

fn hit(world: &World, origin: Vec3, dir: Vec3) -> Option<SurfaceHit> {
    world.intersect(&Ray::new(origin, dir.normalize()))
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).length() <= tol
}

#[test]
fn transformed_sphere_is_an_ellipsoid() {
    // Unit sphere scaled to semi-axes (2, 1, 1), rotated 90° about z (long axis along y),
    // moved to (5, 0, 0).
    let t = Transform::scale(Vec3::new(2.0, 1.0, 1.0))
        .unwrap()
        .then(&Transform::rotate(Vec3::Z, 90.0).unwrap())
        .then(&Transform::translate(Vec3::new(5.0, 0.0, 0.0)));
    let w = world_of(vec![(
        Shape::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        t,
    )]);
    let h = hit(&w, Vec3::new(5.0, -10.0, 0.0), Vec3::Y).unwrap();
    assert!((h.t - 8.0).abs() < 1e-4, "{}", h.t);
    assert!(close(h.ng, -Vec3::Y, 1e-4) && h.front_face);
    let h = hit(&w, Vec3::new(-10.0, 0.0, 0.0), Vec3::X).unwrap();
    assert!((h.t - 14.0).abs() < 1e-4, "{}", h.t);
    // From inside: the far side, seen from the back.
    let h = hit(&w, Vec3::new(5.0, 0.0, 0.0), Vec3::Z).unwrap();
    assert!((h.t - 1.0).abs() < 1e-5 && !h.front_face);
    // An oblique hit: the normal is the gradient of the ellipsoid, not the radial direction.
    let dir = Vec3::new(0.0, 1.0, 0.0);
    let h = hit(&w, Vec3::new(5.5, -5.0, 0.0), dir).unwrap();
    let local = h.p - Vec3::new(5.0, 0.0, 0.0);
    let gradient = Vec3::new(local.x, local.y / 4.0, local.z).normalize();
    assert!(close(h.ng, gradient, 1e-4), "{:?} vs {gradient:?}", h.ng);
    assert!(hit(&w, Vec3::new(6.5, -5.0, 0.0), Vec3::Y).is_none());
}

#[test]
fn rotated_box_hits_and_misses() {
    let t = Transform::rotate(Vec3::Y, 45.0).unwrap();
    let w = world_of(vec![(
        Shape::Box {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        },
        t,
    )]);
    // Along x the rotated cube reaches out to √2.
    let h = hit(&w, Vec3::new(-5.0, 0.0, 0.0), Vec3::X).unwrap();
    assert!((h.t - (5.0 - 2f32.sqrt())).abs() < 1e-5);
    assert!(hit(&w, Vec3::new(-5.0, 1.2, 0.0), Vec3::X).is_none());
    let inside = hit(&w, Vec3::ZERO, Vec3::Y).unwrap();
    assert!((inside.t - 1.0).abs() < 1e-6 && !inside.front_face);
    assert!(close(inside.ng, Vec3::Y, 1e-6));
}

#[test]
fn cylinder_cone_and_frustum_between_two_points() {
    let base = Vec3::new(1.0, 0.0, 0.0);
    let top = Vec3::new(1.0, 2.0, 0.0);
    let w = world_of(vec![(
        Shape::Cylinder {
            base,
            top,
            radius: 0.5,
            caps: true,
        },
        Transform::IDENTITY,
    )]);
    let h = hit(&w, Vec3::new(1.0, 1.0, -5.0), Vec3::Z).unwrap();
    assert!((h.t - 4.5).abs() < 1e-5 && close(h.ng, -Vec3::Z, 1e-5));
    let cap = hit(&w, Vec3::new(1.1, 5.0, 0.1), -Vec3::Y).unwrap();
    assert!((cap.t - 3.0).abs() < 1e-5 && close(cap.ng, Vec3::Y, 1e-5));
    let inside = hit(&w, Vec3::new(1.0, 1.0, 0.0), Vec3::X).unwrap();
    assert!((inside.t - 0.5).abs() < 1e-5 && !inside.front_face);

    let w = world_of(vec![(
        Shape::Cone {
            base,
            apex: top,
            radius: 1.0,
            cap: true,
        },
        Transform::IDENTITY,
    )]);
    // At height 1 the cone's radius is 0.5.
    let h = hit(&w, Vec3::new(1.0, 1.0, -5.0), Vec3::Z).unwrap();
    assert!((h.t - 4.5).abs() < 1e-5);
    assert!(hit(&w, Vec3::new(1.0, 2.5, -5.0), Vec3::Z).is_none());

    let w = world_of(vec![(
        Shape::Frustum {
            base,
            top,
            base_radius: 1.0,
            top_radius: 0.5,
            caps: true,
        },
        Transform::IDENTITY,
    )]);
    // Radius at height 1 is 0.75; the top cap has radius 0.5.
    let h = hit(&w, Vec3::new(1.0, 1.0, -5.0), Vec3::Z).unwrap();
    assert!((h.t - 4.25).abs() < 1e-5);
    // 0.6 off the axis misses the top cap and meets the side where r(h) = 1 − h/4 = 0.6.
    let side = hit(&w, Vec3::new(1.6, 5.0, 0.0), -Vec3::Y).unwrap();
    assert!((side.t - 3.4).abs() < 1e-5, "{}", side.t);
    let cap = hit(&w, Vec3::new(1.4, 5.0, 0.0), -Vec3::Y).unwrap();
    assert!((cap.t - 3.0).abs() < 1e-5 && close(cap.ng, Vec3::Y, 1e-5));
}

#[test]
fn plane_parallelogram_polygon_and_triangle() {
    let w = world_of(vec![(
        Shape::Plane {
            point: Vec3::new(0.0, -1.0, 0.0),
            normal: Vec3::Y,
        },
        Transform::IDENTITY,
    )]);
    let h = hit(&w, Vec3::new(3.0, 2.0, -7.0), -Vec3::Y).unwrap();
    assert!((h.t - 3.0).abs() < 1e-5 && h.front_face);
    let below = hit(&w, Vec3::new(3.0, -2.0, -7.0), Vec3::Y).unwrap();
    assert!(!below.front_face);
    assert!(hit(&w, Vec3::ZERO, Vec3::X).is_none());

    let w = world_of(vec![(
        Shape::Parallelogram {
            origin: Vec3::ZERO,
            edge_u: Vec3::new(2.0, 0.0, 0.0),
            edge_v: Vec3::new(1.0, 1.0, 0.0),
        },
        Transform::translate(Vec3::Z),
    )]);
    let h = hit(&w, Vec3::new(1.5, 0.5, 5.0), -Vec3::Z).unwrap();
    assert!((h.t - 4.0).abs() < 1e-5 && h.front_face);
    // (1.5, 0.5) = 0.5·(2,0) + 0.5·(1,1).
    assert!((h.uv - Vec2::new(0.5, 0.5)).length() < 1e-5);
    assert!(hit(&w, Vec3::new(0.2, 0.9, 5.0), -Vec3::Z).is_none());

    let pentagon: Vec<Vec3> = (0..5)
        .map(|i| {
            let a = i as f32 / 5.0 * std::f32::consts::TAU;
            Vec3::new(a.cos(), 0.0, -a.sin())
        })
        .collect();
    let w = world_of(vec![(
        Shape::Polygon {
            vertices: pentagon,
            uvs: None,
        },
        Transform::IDENTITY,
    )]);
    let h = hit(&w, Vec3::new(0.1, 3.0, 0.2), -Vec3::Y).unwrap();
    assert!(h.front_face && close(h.ng, Vec3::Y, 1e-5));
    assert!(hit(&w, Vec3::new(0.9, 3.0, 0.9), -Vec3::Y).is_none());

    // A mirroring transform keeps the front side where the object-space normal points.
    let tri = Shape::Triangle {
        vertices: [Vec3::ZERO, Vec3::X, Vec3::Y],
        uvs: None,
    };
    let mirrored = Transform::from_matrix(Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0))).unwrap();
    let w = world_of(vec![(tri, mirrored)]);
    let h = hit(&w, Vec3::new(-0.2, 0.2, 3.0), -Vec3::Z).unwrap();
    assert!(h.front_face && close(h.ng, Vec3::Z, 1e-6));
}

#[test]
fn alpha_cut_outs_remove_surface_for_camera_and_shadow_rays() {
    let mut scene = Scene::empty("cut");
    // Left half transparent, right half opaque.
    let tex = scene.add_texture(Texture::from_fn("mask", 2, 1, |x, _| {
        [1.0, 1.0, 1.0, if x == 0 { 0.0 } else { 1.0 }]
    }));
    let m = scene.add_material(Material {
        alpha_texture: Some(tex),
        ..Material::diffuse("leaf", strahl::color::Rgb::splat(0.5))
    });
    scene.add_object(
        "leaf",
        Shape::Parallelogram {
            origin: Vec3::ZERO,
            edge_u: Vec3::X,
            edge_v: Vec3::Y,
        },
        m,
    );
    let w = World::new(scene, AccelKind::Bvh).unwrap();
    assert!(hit(&w, Vec3::new(0.25, 0.5, 1.0), -Vec3::Z).is_none());
    assert!(hit(&w, Vec3::new(0.75, 0.5, 1.0), -Vec3::Z).is_some());
    assert!(!w.occluded(&Ray::new(Vec3::new(0.25, 0.5, 1.0), -Vec3::Z), 2.0));
    assert!(w.occluded(&Ray::new(Vec3::new(0.75, 0.5, 1.0), -Vec3::Z), 2.0));
}

#[test]
fn grazing_rays_leaving_a_surface_do_not_hit_it_again() {
    let plane = Shape::Plane {
        point: Vec3::ZERO,
        normal: Vec3::Y,
    };
    let sphere = Shape::Sphere {
        center: Vec3::new(0.0, 1000.0, 0.0),
        radius: 999.0,
    };
    let w = world_of(vec![
        (plane, Transform::IDENTITY),
        (sphere, Transform::IDENTITY),
    ]);
    for (i, x) in [1e-3f32, 1.0, 300.0, 1e4].into_iter().enumerate() {
        let p = Vec3::new(x, 0.0, -x * 0.7);
        let n = Vec3::Y;
        for degrees in [1e-3f32, 0.01, 0.1, 1.0] {
            let a = degrees.to_radians();
            let dir = Vec3::new(a.cos(), a.sin(), 0.0);
            let r = spawn_ray(p, n, dir);
            if let Some(h) = w.intersect(&r) {
                assert!(
                    h.object != 0,
                    "case {i}: {degrees}° ray from x = {x} hit its own plane"
                );
            }
            // Leaving downward through the plane is allowed only from the other side.
            let down = spawn_ray(p, n, Vec3::new(a.cos(), -a.sin(), 0.0));
            assert!(
                w.intersect(&down)
                    .is_none_or(|h| h.object != 0 || h.t > 1e-3 * x.max(1.0))
            );
        }
    }
}

#[test]
fn rays_from_nested_spheres_find_the_right_surface() {
    let outer = Shape::Sphere {
        center: Vec3::ZERO,
        radius: 2.0,
    };
    let inner = Shape::Sphere {
        center: Vec3::ZERO,
        radius: 1.0,
    };
    let w = world_of(vec![
        (outer, Transform::IDENTITY),
        (inner, Transform::IDENTITY),
    ]);
    let mut sampler = strahl::sampling::Sampler::new(Default::default(), 3, 0, 0);
    for _ in 0..2000 {
        let d = strahl::sampling::warp::uniform_sphere(sampler.next_2d());
        let p = d; // on the inner sphere
        // Outward from the inner sphere: the outer sphere, from inside, at distance 1.
        let h = w.intersect(&spawn_ray(p, d, d)).unwrap();
        assert_eq!(h.object, 0);
        assert!((h.t - 1.0).abs() < 1e-4 && !h.front_face, "{}", h.t);
        // Inward: the inner sphere's far side, at distance 2.
        let h = w.intersect(&spawn_ray(p, d, -d)).unwrap();
        assert_eq!(h.object, 1);
        assert!((h.t - 2.0).abs() < 1e-4 && !h.front_face, "{}", h.t);
        // Just above the tangent plane (0.06° outward): leaves the inner sphere and hits the
        // outer one at ≈ √3. (An exactly tangent direction may round to either side.)
        let tangent = (d.any_orthonormal_vector() + d * 1e-3).normalize();
        let h = w.intersect(&spawn_ray(p, d, tangent)).unwrap();
        assert_eq!(
            h.object, 0,
            "tangent ray from {p:?} along {tangent:?} hit at t = {}",
            h.t
        );
        let along = p.dot(tangent);
        let expected = -along + (along * along + 4.0 - p.length_squared()).sqrt();
        assert!((h.t - expected).abs() < 1e-4, "{} vs {expected}", h.t);
    }
}
