//! Built-in scenes: small rigid-body configurations assembled in code (no files) into
//! FC(W, q, mu), the way a Moreau-Jean time stepper would at one step.
//!
//! Every body has generalized velocity `v = (linear, angular)` (world frame, angular about the
//! center of mass) and mass matrix `M = diag(m I, I_body)`. A contact `c` between body `A` and
//! body `B` (or the fixed ground/walls) has a point `p`, a frame `(n, t1, t2)` with `n` pointing
//! from `B` into `A`, and a Jacobian `G_c` such that its local relative velocity is
//!
//! `u_c = G_cA v_A - G_cB v_B`, with `G_cK = [d^T  ((p - x_K) x d)^T]` for each frame direction `d`.
//!
//! One time step of length `dt` under gravity gives `v+ = v_free + M^-1 G^T r` (r are impulses),
//! `v_free = v + dt M^-1 f_ext`, hence `u = W r + q` with `W = G M^-1 G^T` (symmetric positive
//! semi-definite, rank-deficient as soon as there are more contact rows than degrees of freedom)
//! and `q = G v_free`. The block `W_cd` is non-zero exactly when contacts `c` and `d` share a body.
//!
//! One scene ([`gyro`](default_scenes)) replaces `M` by the iteration matrix `M + dt C(omega)`
//! of the linearised gyroscopic term `omega x I omega`, `C = [omega]_x I - [I omega]_x`, which makes
//! `W` non-symmetric (relative asymmetry around 1e-4), as the W of real simulators are.

pub mod sequences;

use crate::error::Fc3dError;
use crate::math::linalg::{mat3_mul, mat3_vec, Mat3, Vec3};
use crate::matrix::{BlockSparseMatrix, Delassus, DenseMatrix};
use crate::problem::FrictionProblem;

mod boxes;
mod granular;
pub use boxes::box_piles;
pub use granular::{sphere_piles, PileSpec};
pub mod towers;
pub use towers::{box_towers, TowerMotion, TowerSpec};

/// The bodies a generated scene is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PileShape {
    /// Square pyramids of spheres ([`sphere_piles`], the default).
    #[default]
    Spheres,
    /// Stepped pyramids of boxes, 4 contact points per face contact
    /// ([`box_piles`]).
    Boxes,
}

impl PileShape {
    /// The shape named `spheres` or `boxes`.
    pub fn from_name(name: &str) -> Result<PileShape, Fc3dError> {
        match name.trim() {
            "spheres" => Ok(PileShape::Spheres),
            "boxes" => Ok(PileShape::Boxes),
            other => Err(Fc3dError::InvalidOption(format!(
                "unknown shape '{other}' (spheres, boxes)"
            ))),
        }
    }
}

/// A generated scene: the piles and what they are made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GeneratedScene {
    pub pile: PileSpec,
    pub shape: PileShape,
}

impl GeneratedScene {
    /// Parses `contacts=N,piles=P,seed=S,shape=spheres|boxes` (any order; `piles` defaults to 1,
    /// `seed` to 1, `shape` to spheres).
    pub fn parse(text: &str) -> Result<GeneratedScene, Fc3dError> {
        parse_spec(text, true)
    }

    /// A short name for tables and files: `piles-c100000-p4-s1` (spheres),
    /// `boxes-c100000-p4-s1`.
    pub fn name(&self) -> String {
        match self.shape {
            PileShape::Spheres => self.pile.name(),
            PileShape::Boxes => format!(
                "boxes-c{}-p{}-s{}",
                self.pile.contacts, self.pile.piles, self.pile.seed
            ),
        }
    }

    /// Generates the scene (sparse-block W).
    pub fn generate(&self) -> Result<FrictionProblem<'static>, Fc3dError> {
        match self.shape {
            PileShape::Spheres => sphere_piles(&self.pile),
            PileShape::Boxes => box_piles(&self.pile),
        }
    }
}

/// The keys of a scene spec; `shape` only where a shape can be chosen.
fn parse_spec(text: &str, with_shape: bool) -> Result<GeneratedScene, Fc3dError> {
    let mut pile = PileSpec {
        contacts: 0,
        piles: 1,
        seed: 1,
    };
    let mut shape = PileShape::Spheres;
    let bad = |why: String| Fc3dError::InvalidOption(format!("scene spec '{text}': {why}"));
    for part in text.split(',').filter(|p| !p.trim().is_empty()) {
        let (key, value) = part
            .split_once('=')
            .ok_or_else(|| bad(format!("'{part}' is not key=value")))?;
        if with_shape && key.trim() == "shape" {
            shape = PileShape::from_name(value).map_err(|e| bad(e.to_string()))?;
            continue;
        }
        let number: u64 = value
            .trim()
            .replace('_', "")
            .parse()
            .map_err(|_| bad(format!("'{value}' is not a non-negative integer")))?;
        match key.trim() {
            "contacts" => pile.contacts = number as usize,
            "piles" => pile.piles = number as usize,
            "seed" => pile.seed = number,
            other => {
                let keys = if with_shape {
                    "contacts, piles, seed, shape"
                } else {
                    "contacts, piles, seed"
                };
                return Err(bad(format!("unknown key '{other}' ({keys})")));
            }
        }
    }
    pile.check()?;
    Ok(GeneratedScene { pile, shape })
}

/// A named built-in problem.
#[derive(Debug, Clone)]
pub struct Scene {
    pub name: &'static str,
    pub description: &'static str,
    pub problem: FrictionProblem<'static>,
}

/// Time step of every scene (s).
pub const DT: f64 = 0.01;
/// Gravity (m/s^2), along -z.
pub const GRAVITY: f64 = 9.81;

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

// ---------------------------------------------------------------------------------------------
// Rigid bodies and contacts.

#[derive(Debug, Clone)]
struct Body {
    /// Center of mass.
    x: Vec3,
    mass: f64,
    /// Inverse of the (angular part of the) iteration matrix, world frame. Non-symmetric for a
    /// gyroscopic body.
    inv_inertia: Mat3,
    /// Free velocity `(linear, angular)` after one step of external forces.
    v_free: [f64; 6],
    /// Whether the iteration matrix has the (non-symmetric) gyroscopic term.
    gyroscopic: bool,
}

#[derive(Debug, Clone)]
struct Contact {
    /// The body the normal points into.
    a: usize,
    /// The other body, `None` for the fixed ground or a wall.
    b: Option<usize>,
    point: Vec3,
    /// Rows: n, t1, t2.
    frame: Mat3,
    mu: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Storage {
    Dense,
    SparseBlock,
}

struct World {
    bodies: Vec<Body>,
    contacts: Vec<Contact>,
}

fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(a: &Vec3) -> Vec3 {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

fn transpose(m: &Mat3) -> Mat3 {
    let mut t = [[0.0; 3]; 3];
    for (i, row) in m.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            t[j][i] = *v;
        }
    }
    t
}

fn skew(a: &Vec3) -> Mat3 {
    [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]
}

fn diag(d: Vec3) -> Mat3 {
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// Inverse by the adjugate (the matrices inverted here are well conditioned inertia tensors).
fn inverse(m: &Mat3) -> Mat3 {
    let c = |i: usize, j: usize| {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
        m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]
    };
    let det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    let mut inv = [[0.0; 3]; 3];
    for (i, row) in inv.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = c(j, i) / det;
        }
    }
    inv
}

/// Rotation by `angle` about z.
fn yaw(angle: f64) -> Mat3 {
    let (s, c) = angle.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

/// A contact frame with normal `n` (rows n, t1, t2; right-handed).
fn frame(n: Vec3) -> Mat3 {
    let n = normalize(&n);
    // Any axis not parallel to n gives t1.
    let helper = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t1 = normalize(&cross(&helper, &n));
    let t1 = normalize(&cross(&n, &t1));
    let t2 = cross(&n, &t1);
    [n, t1, t2]
}

const E_Z: Vec3 = [0.0, 0.0, 1.0];

impl Body {
    /// A body with principal inertia `inertia` in the orientation `rot`, initial linear velocity
    /// `v` and angular velocity `omega`, one step of gravity applied. With `gyroscopic`, the
    /// angular iteration matrix is `I + dt C(omega)` and the gyroscopic torque is applied too.
    fn new(
        x: Vec3,
        mass: f64,
        inertia: Vec3,
        rot: Mat3,
        v: Vec3,
        omega: Vec3,
        gyroscopic: bool,
    ) -> Body {
        let i_world = mat3_mul(&mat3_mul(&rot, &diag(inertia)), &transpose(&rot));
        let (iteration, torque) = if gyroscopic {
            let i_omega = mat3_vec(&i_world, &omega);
            let mut c = mat3_mul(&skew(&omega), &i_world);
            let s = skew(&i_omega);
            for i in 0..3 {
                for j in 0..3 {
                    c[i][j] = i_world[i][j] + DT * (c[i][j] - s[i][j]);
                }
            }
            let gyro = cross(&omega, &i_omega);
            (c, [-gyro[0], -gyro[1], -gyro[2]])
        } else {
            (i_world, [0.0; 3])
        };
        let inv_inertia = inverse(&iteration);
        let dw = mat3_vec(&inv_inertia, &torque);
        Body {
            x,
            mass,
            inv_inertia,
            v_free: [
                v[0],
                v[1],
                v[2] - DT * GRAVITY,
                omega[0] + DT * dw[0],
                omega[1] + DT * dw[1],
                omega[2] + DT * dw[2],
            ],
            gyroscopic,
        }
    }

    fn sphere(x: Vec3, mass: f64, radius: f64, v: Vec3, omega: Vec3) -> Body {
        let i = 0.4 * mass * radius * radius;
        Body::new(x, mass, [i; 3], yaw(0.0), v, omega, false)
    }

    /// A box of half-extents `h`, yawed by `rot`.
    fn cuboid(x: Vec3, mass: f64, h: Vec3, rot: Mat3, v: Vec3, omega: Vec3, gyro: bool) -> Body {
        let (a, b, c) = (2.0 * h[0], 2.0 * h[1], 2.0 * h[2]);
        let k = mass / 12.0;
        let inertia = [
            k * (b * b + c * c),
            k * (a * a + c * c),
            k * (a * a + b * b),
        ];
        Body::new(x, mass, inertia, rot, v, omega, gyro)
    }
}

/// The 4 bottom corners of a box of half-extents `h`, center `x`, orientation `rot`.
fn bottom_corners(x: &Vec3, h: &Vec3, rot: &Mat3) -> [Vec3; 4] {
    let mut out = [[0.0; 3]; 4];
    for (k, (sx, sy)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .enumerate()
    {
        let d = mat3_vec(rot, &[sx * h[0], sy * h[1], -h[2]]);
        out[k] = [x[0] + d[0], x[1] + d[1], x[2] + d[2]];
    }
    out
}

impl World {
    fn new() -> World {
        World {
            bodies: Vec::new(),
            contacts: Vec::new(),
        }
    }

    fn add_body(&mut self, b: Body) -> usize {
        self.bodies.push(b);
        self.bodies.len() - 1
    }

    fn add_contact(&mut self, a: usize, b: Option<usize>, point: Vec3, normal: Vec3, mu: f64) {
        self.contacts.push(Contact {
            a,
            b,
            point,
            frame: frame(normal),
            mu,
        });
    }

    /// Contacts of the 4 bottom corners of box `a` (half-extents `h`, orientation `rot`) on the
    /// ground or on the top face of box `b`.
    fn add_box_support(&mut self, a: usize, b: Option<usize>, h: Vec3, rot: &Mat3, mu: f64) {
        let x = self.bodies[a].x;
        for p in bottom_corners(&x, &h, rot) {
            self.add_contact(a, b, p, E_Z, mu);
        }
    }

    /// `(translation part, rotation part)` of the 3x6 Jacobian of contact `c` for body `k`, signed.
    fn jacobian(&self, c: usize, k: usize) -> Option<(Mat3, Mat3)> {
        let ct = &self.contacts[c];
        let sign = if ct.a == k {
            1.0
        } else if ct.b == Some(k) {
            -1.0
        } else {
            return None;
        };
        let x = &self.bodies[k].x;
        let arm = [ct.point[0] - x[0], ct.point[1] - x[1], ct.point[2] - x[2]];
        let mut lin = [[0.0; 3]; 3];
        let mut ang = [[0.0; 3]; 3];
        for i in 0..3 {
            let d = ct.frame[i];
            let rd = cross(&arm, &d);
            for j in 0..3 {
                lin[i][j] = sign * d[j];
                ang[i][j] = sign * rd[j];
            }
        }
        Some((lin, ang))
    }

    fn bodies_of(&self, c: usize) -> impl Iterator<Item = usize> + '_ {
        let ct = &self.contacts[c];
        std::iter::once(ct.a).chain(ct.b)
    }

    /// The 3x3 block `W_cd = sum_k G_ck M_k^-1 G_dk^T` (row-major), `None` when no body is shared.
    fn block(&self, c: usize, d: usize) -> Option<Mat3> {
        let mut w = [[0.0; 3]; 3];
        let mut shared = false;
        for k in self.bodies_of(c) {
            let Some((lc, ac)) = self.jacobian(c, k) else {
                continue;
            };
            let Some((ld, ad)) = self.jacobian(d, k) else {
                continue;
            };
            shared = true;
            let body = &self.bodies[k];
            let lin = mat3_mul(&lc, &transpose(&ld));
            let ang = mat3_mul(&mat3_mul(&ac, &body.inv_inertia), &transpose(&ad));
            for i in 0..3 {
                for j in 0..3 {
                    w[i][j] += lin[i][j] / body.mass + ang[i][j];
                }
            }
        }
        shared.then_some(w)
    }

    /// `q_c = G_c v_free`.
    fn q(&self) -> Vec<f64> {
        let mut q = vec![0.0; 3 * self.contacts.len()];
        for c in 0..self.contacts.len() {
            for k in self.bodies_of(c) {
                let (l, a) = self.jacobian(c, k).expect("body of the contact");
                let v = &self.bodies[k].v_free;
                for i in 0..3 {
                    q[3 * c + i] += l[i][0] * v[0]
                        + l[i][1] * v[1]
                        + l[i][2] * v[2]
                        + a[i][0] * v[3]
                        + a[i][1] * v[4]
                        + a[i][2] * v[5];
                }
            }
        }
        q
    }

    /// The velocity change `M^-1 G^T r` of every body `(linear, angular)` under the contact
    /// impulses `r` (3 per contact).
    fn impulse_response(&self, r: &[f64]) -> Vec<[f64; 6]> {
        let mut dv = vec![[0.0; 6]; self.bodies.len()];
        for c in 0..self.contacts.len() {
            let rc = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
            for k in self.bodies_of(c) {
                let (l, a) = self.jacobian(c, k).expect("body of the contact");
                let body = &self.bodies[k];
                let force = mat3_vec(&transpose(&l), &rc);
                let torque = mat3_vec(&body.inv_inertia, &mat3_vec(&transpose(&a), &rc));
                for i in 0..3 {
                    dv[k][i] += force[i] / body.mass;
                    dv[k][3 + i] += torque[i];
                }
            }
        }
        dv
    }

    /// The block `W_cd`. With symmetric mass matrices (`symmetric`: no gyroscopic body),
    /// `W_dc = W_cd^T` exactly: the blocks below the diagonal are mirrored from those above, and
    /// the diagonal blocks symmetrized, so that rounding cannot make W non-symmetric.
    fn block_of_w(&self, c: usize, d: usize, symmetric: bool) -> Option<Mat3> {
        if !symmetric {
            return self.block(c, d);
        }
        if c > d {
            return self.block(d, c).map(|b| transpose(&b));
        }
        let mut b = self.block(c, d)?;
        if c == d {
            (b[1][0], b[2][0], b[2][1]) = (b[0][1], b[0][2], b[1][2]);
        }
        Some(b)
    }

    /// For each body, the contacts it takes part in (CSR: `(start, contacts)`), in contact order.
    fn contacts_by_body(&self) -> (Vec<usize>, Vec<usize>) {
        let mut start = vec![0usize; self.bodies.len() + 1];
        for c in 0..self.contacts.len() {
            for k in self.bodies_of(c) {
                start[k + 1] += 1;
            }
        }
        for k in 0..self.bodies.len() {
            start[k + 1] += start[k];
        }
        let mut next = start.clone();
        let mut list = vec![0usize; start[self.bodies.len()]];
        for c in 0..self.contacts.len() {
            for k in self.bodies_of(c) {
                list[next[k]] = c;
                next[k] += 1;
            }
        }
        (start, list)
    }

    /// Calls `f(c, d, W_cd)` for every non-zero block, row by row and by increasing column
    /// within a row. Only the contacts sharing a body with `c` are visited, so assembling costs
    /// O(contacts x contacts per body), never O(contacts^2).
    fn for_each_block(&self, mut f: impl FnMut(usize, usize, Mat3)) {
        let symmetric = !self.bodies.iter().any(|b| b.gyroscopic);
        let (start, list) = self.contacts_by_body();
        let mut neighbours = Vec::new();
        for c in 0..self.contacts.len() {
            neighbours.clear();
            for k in self.bodies_of(c) {
                neighbours.extend_from_slice(&list[start[k]..start[k + 1]]);
            }
            neighbours.sort_unstable();
            neighbours.dedup();
            for &d in &neighbours {
                if let Some(b) = self.block_of_w(c, d, symmetric) {
                    f(c, d, b);
                }
            }
        }
    }

    fn problem(&self, storage: Storage) -> FrictionProblem<'static> {
        let nc = self.contacts.len();
        let w = match storage {
            Storage::Dense => {
                let n = 3 * nc;
                let mut data = vec![0.0; n * n];
                self.for_each_block(|c, d, b| {
                    for i in 0..3 {
                        for j in 0..3 {
                            data[(3 * c + i) + (3 * d + j) * n] = b[i][j];
                        }
                    }
                });
                Delassus::Dense(DenseMatrix::new(n, n, data).expect("square by construction"))
            }
            Storage::SparseBlock => {
                let mut row_ptr = vec![0usize; nc + 1];
                let mut col_idx = Vec::new();
                let mut blocks = Vec::new();
                self.for_each_block(|c, d, b| {
                    row_ptr[c + 1] += 1;
                    col_idx.push(d);
                    // Column-major, as Siconos stores its blocks.
                    blocks.push([
                        b[0][0], b[1][0], b[2][0], b[0][1], b[1][1], b[2][1], b[0][2], b[1][2],
                        b[2][2],
                    ]);
                });
                for c in 0..nc {
                    row_ptr[c + 1] += row_ptr[c];
                }
                Delassus::SparseBlock(
                    BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks)
                        .expect("valid block structure by construction"),
                )
            }
        };
        let mu: Vec<f64> = self.contacts.iter().map(|c| c.mu).collect();
        FrictionProblem::new(w, self.q(), mu).expect("consistent scene")
    }
}

// ---------------------------------------------------------------------------------------------
// The scenes.

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

    #[test]
    fn frames_are_orthonormal() {
        for n in [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.3, -0.4, 0.8],
        ] {
            let f = frame(n);
            for i in 0..3 {
                for j in 0..3 {
                    let d: f64 = (0..3).map(|k| f[i][k] * f[j][k]).sum();
                    assert_relative_eq!(d, if i == j { 1.0 } else { 0.0 }, epsilon = 1e-15);
                }
            }
            assert_relative_eq!(cross(&f[0], &f[1])[2], f[2][2], epsilon = 1e-15);
        }
    }

    #[test]
    fn inverse_is_inverse() {
        let m = [[4.0, 1.0, 0.5], [0.2, 3.0, -1.0], [0.1, 0.3, 2.0]];
        let p = mat3_mul(&m, &inverse(&m));
        for (i, row) in p.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert_relative_eq!(*v, if i == j { 1.0 } else { 0.0 }, epsilon = 1e-14);
            }
        }
    }

    #[test]
    fn scene_specs_parse_with_their_shape() {
        let s = GeneratedScene::parse("contacts=100,shape=boxes,piles=2").unwrap();
        assert_eq!(
            s.pile,
            PileSpec {
                contacts: 100,
                piles: 2,
                seed: 1
            }
        );
        assert_eq!(s.shape, PileShape::Boxes);
        assert_eq!(s.name(), "boxes-c100-p2-s1");
        let d = GeneratedScene::parse("contacts=100").unwrap();
        assert_eq!(d.shape, PileShape::Spheres);
        assert_eq!(d.name(), "piles-c100-p1-s1");
        assert!(GeneratedScene::parse("contacts=100,shape=cones").is_err());
        // A plain pile spec has no shape.
        assert!(PileSpec::parse("contacts=100,shape=boxes").is_err());
        assert_eq!(
            granular::tests::bits(
                &GeneratedScene::parse("contacts=50,shape=boxes")
                    .unwrap()
                    .generate()
                    .unwrap()
            ),
            granular::tests::bits(
                &box_piles(&PileSpec {
                    contacts: 50,
                    piles: 1,
                    seed: 1
                })
                .unwrap()
            )
        );
    }
}
