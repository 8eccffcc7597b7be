//! The built-in scenes: small configurations (spheres, boxes, stacks, a gyroscopic stack) that
//! `fc3d` solves when it is given no file.

use super::world::{bottom_corners, normalize, yaw, Body, Storage, World, E_Z};
use crate::math::linalg::Vec3;
use crate::problem::FrictionProblem;

/// A named built-in problem.
#[derive(Debug, Clone)]
pub struct Scene {
    pub name: &'static str,
    pub description: &'static str,
    pub problem: FrictionProblem<'static>,
}

/// The default problem set, in a fixed order (tiny dense ones first).
pub fn default_scenes() -> Vec<Scene> {
    vec![
        Scene {
            name: "sphere_rest",
            description: "sphere resting on a plane: 1 contact, stick (r = (m g dt, 0, 0), u = 0)",
            problem: sphere_on_plane([0.0; 3], [0.0; 3], 0.5),
        },
        Scene {
            name: "sphere_slide",
            description: "sphere sliding on a plane (v = (2, 0.5, 0)): 1 contact, slide",
            problem: sphere_on_plane([2.0, 0.5, 0.0], [0.0; 3], 0.3),
        },
        Scene {
            name: "sphere_takeoff",
            description: "sphere thrown upward (v = (0.3, 0, 2)): 1 contact, take-off (r = 0, u = q)",
            problem: sphere_on_plane([0.3, 0.0, 2.0], [0.0; 3], 0.5),
        },
        Scene {
            name: "box_on_ground",
            description: "box resting on the ground, 4 corner contacts (12 rows, 6 dofs)",
            problem: box_on_ground(),
        },
        Scene {
            name: "box_stack",
            description: "3 stacked boxes, top one smaller, yawed 30 deg and sliding (12 contacts, 18 dofs)",
            problem: box_stack(),
        },
        Scene {
            name: "box_bridge",
            description: "2 boxes side by side (frictionless side contact) bridged by a third (16 contacts, 18 dofs)",
            problem: box_bridge(),
        },
        Scene {
            name: "sphere_pile",
            description: "5 spheres (3 + 2) between two frictionless walls, mu in {0, 0.2, 0.3, 0.5} (9 contacts)",
            problem: sphere_pile(),
        },
        Scene {
            name: "gyro_stack",
            description: "2 stacked boxes with a gyroscopic iteration matrix: W non-symmetric (~1e-4 relative), top box sliding",
            problem: gyro_stack(),
        },
    ]
}

/// Sphere of mass 1, radius 0.1, touching the plane z = 0: `W = diag(1, 3.5, 3.5)`.
fn sphere_on_plane(v: Vec3, omega: Vec3, mu: f64) -> FrictionProblem<'static> {
    let radius = 0.1;
    let mut w = World::new();
    let s = w.add_body(Body::sphere([0.0, 0.0, radius], 1.0, radius, v, omega));
    w.add_contact(s, None, [0.0; 3], E_Z, mu);
    w.problem(Storage::Dense)
}

fn box_on_ground() -> FrictionProblem<'static> {
    let h = [0.5, 0.3, 0.2];
    let mut w = World::new();
    let rot = yaw(0.0);
    let b = w.add_body(Body::cuboid(
        [0.0, 0.0, h[2]],
        2.0,
        h,
        rot,
        [0.0; 3],
        [0.0; 3],
        false,
    ));
    w.add_box_support(b, None, h, &rot, 0.6);
    w.problem(Storage::SparseBlock)
}

fn box_stack() -> FrictionProblem<'static> {
    let mut w = World::new();
    let h0 = [0.5, 0.5, 0.25];
    let h1 = [0.4, 0.4, 0.2];
    let h2 = [0.25, 0.2, 0.15];
    let r0 = yaw(0.0);
    let r1 = yaw(0.1);
    let r2 = yaw(std::f64::consts::PI / 6.0);
    let z0 = h0[2];
    let z1 = 2.0 * h0[2] + h1[2];
    let z2 = 2.0 * (h0[2] + h1[2]) + h2[2];
    let none = [0.0; 3];
    let b0 = w.add_body(Body::cuboid([0.0, 0.0, z0], 4.0, h0, r0, none, none, false));
    let b1 = w.add_body(Body::cuboid(
        [0.05, 0.0, z1],
        2.0,
        h1,
        r1,
        none,
        none,
        false,
    ));
    let b2 = w.add_body(Body::cuboid(
        [0.0, 0.05, z2],
        0.5,
        h2,
        r2,
        [0.4, 0.1, 0.0],
        none,
        false,
    ));
    w.add_box_support(b0, None, h0, &r0, 0.6);
    w.add_box_support(b1, Some(b0), h1, &r1, 0.4);
    w.add_box_support(b2, Some(b1), h2, &r2, 0.3);
    w.problem(Storage::SparseBlock)
}

fn box_bridge() -> FrictionProblem<'static> {
    let mut w = World::new();
    let h = [0.3, 0.3, 0.3];
    let ht = [0.55, 0.25, 0.1];
    let r = yaw(0.0);
    let none = [0.0; 3];
    let left = w.add_body(Body::cuboid([-0.3, 0.0, 0.3], 1.0, h, r, none, none, false));
    let right = w.add_body(Body::cuboid([0.3, 0.0, 0.3], 1.5, h, r, none, none, false));
    let top = w.add_body(Body::cuboid(
        [0.0, 0.0, 0.7],
        0.8,
        ht,
        r,
        [0.05, 0.0, -0.1],
        none,
        false,
    ));
    w.add_box_support(left, None, h, &r, 0.5);
    w.add_box_support(right, None, h, &r, 0.5);
    // Face-to-face side contact at x = 0, frictionless, normal into the right box.
    for (y, z) in [(-0.3, 0.0), (0.3, 0.0), (0.3, 0.6), (-0.3, 0.6)] {
        w.add_contact(right, Some(left), [0.0, y, z], [1.0, 0.0, 0.0], 0.0);
    }
    // The top plate's corners rest two on each box.
    for p in bottom_corners(&[0.0, 0.0, 0.7], &ht, &r) {
        let support = if p[0] < 0.0 { left } else { right };
        w.add_contact(top, Some(support), p, E_Z, 0.7);
    }
    w.problem(Storage::SparseBlock)
}

fn sphere_pile() -> FrictionProblem<'static> {
    let mut w = World::new();
    let rad = 0.1;
    let spacing = 2.05 * rad;
    let none = [0.0; 3];
    let bottom: Vec<usize> = (-1..=1)
        .map(|i| {
            w.add_body(Body::sphere(
                [f64::from(i) * spacing, 0.0, rad],
                1.0,
                rad,
                none,
                none,
            ))
        })
        .collect();
    // A top sphere resting on two bottom ones: half the spacing away horizontally.
    let dz = ((2.0 * rad).powi(2) - (0.5 * spacing).powi(2)).sqrt();
    let top: Vec<usize> = [-0.5, 0.5]
        .iter()
        .map(|&s| {
            w.add_body(Body::sphere(
                [s * spacing, 0.0, rad + dz],
                0.8,
                rad,
                [0.0, 0.02, 0.0],
                none,
            ))
        })
        .collect();
    let mu_ground = [0.5, 0.3, 0.5];
    for (k, &b) in bottom.iter().enumerate() {
        let x = w.bodies[b].x;
        w.add_contact(b, None, [x[0], x[1], 0.0], E_Z, mu_ground[k]);
    }
    // Walls at x = -/+ (spacing + rad), frictionless.
    let wall = spacing + rad;
    w.add_contact(bottom[0], None, [-wall, 0.0, rad], [1.0, 0.0, 0.0], 0.0);
    w.add_contact(bottom[2], None, [wall, 0.0, rad], [-1.0, 0.0, 0.0], 0.0);
    // Sphere-sphere contacts, with mu 0 on one of them.
    let mu_pair = [[0.3, 0.2], [0.0, 0.3]];
    for (t, &tb) in top.iter().enumerate() {
        for (k, &bb) in bottom[t..t + 2].iter().enumerate() {
            let (xa, xb) = (w.bodies[tb].x, w.bodies[bb].x);
            let n = normalize(&[xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]]);
            let p = [xb[0] + rad * n[0], xb[1] + rad * n[1], xb[2] + rad * n[2]];
            w.add_contact(tb, Some(bb), p, n, mu_pair[t][k]);
        }
    }
    w.problem(Storage::SparseBlock)
}

fn gyro_stack() -> FrictionProblem<'static> {
    let mut w = World::new();
    let h0 = [0.5, 0.35, 0.2];
    let h1 = [0.3, 0.2, 0.1];
    let r0 = yaw(0.0);
    let r1 = yaw(0.3);
    let b0 = w.add_body(Body::cuboid(
        [0.0, 0.0, h0[2]],
        3.0,
        h0,
        r0,
        [0.0; 3],
        [0.001, -0.002, 0.006],
        true,
    ));
    let b1 = w.add_body(Body::cuboid(
        [0.0, 0.0, 2.0 * h0[2] + h1[2]],
        1.0,
        h1,
        r1,
        [0.3, -0.2, 0.0],
        [0.004, 0.003, 0.01],
        true,
    ));
    w.add_box_support(b0, None, h0, &r0, 0.5);
    w.add_box_support(b1, Some(b0), h1, &r1, 0.25);
    w.problem(Storage::SparseBlock)
}

#[cfg(test)]
mod tests {
    use super::super::{DT, GRAVITY};
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn names_are_unique_and_problems_consistent() {
        let scenes = default_scenes();
        let mut names: Vec<_> = scenes.iter().map(|s| s.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), scenes.len());
        for s in &scenes {
            assert!(s.problem.n_contacts() >= 1, "{}", s.name);
        }
    }

    #[test]
    fn sphere_delassus_is_known() {
        // m = 1, I = 2/5 m R^2: W = diag(1/m, 1/m + R^2/I, same) = diag(1, 3.5, 3.5).
        let p = sphere_on_plane([0.0; 3], [0.0; 3], 0.5);
        let w = p.w().to_dense();
        let expected = [[1.0, 0.0, 0.0], [0.0, 3.5, 0.0], [0.0, 0.0, 3.5]];
        for i in 0..3 {
            for j in 0..3 {
                assert_relative_eq!(w.get(i, j), expected[i][j], epsilon = 1e-12);
            }
        }
        assert_relative_eq!(p.q()[0], -DT * GRAVITY, epsilon = 1e-15);
    }

    #[test]
    fn symmetry_as_built() {
        for s in default_scenes() {
            let a = s.problem.w().relative_asymmetry();
            if s.name == "gyro_stack" {
                assert!(a > 1e-5 && a < 1e-3, "{}: asymmetry {a}", s.name);
            } else {
                assert_eq!(a, 0.0, "{}", s.name);
            }
        }
    }
}
