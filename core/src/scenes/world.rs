//! The rigid bodies and contacts scenes are assembled from, and the assembly of FC(W, q, mu)
//! at one time step (see the module above for the model).

use super::{DT, GRAVITY};
use crate::math::linalg::{mat3_mul, mat3_vec, Mat3, Vec3};
use crate::matrix::{BlockSparseMatrix, Delassus, DenseMatrix};
use crate::problem::FrictionProblem;

#[derive(Debug, Clone)]
pub(super) struct Body {
    /// Center of mass.
    pub(super) x: Vec3,
    pub(super) mass: f64,
    /// Inverse of the (angular part of the) iteration matrix, world frame. Non-symmetric for a
    /// gyroscopic body.
    pub(super) inv_inertia: Mat3,
    /// Free velocity `(linear, angular)` after one step of external forces.
    pub(super) v_free: [f64; 6],
    /// Whether the iteration matrix has the (non-symmetric) gyroscopic term.
    pub(super) gyroscopic: bool,
}

#[derive(Debug, Clone)]
pub(super) struct Contact {
    /// The body the normal points into.
    pub(super) a: usize,
    /// The other body, `None` for the fixed ground or a wall.
    pub(super) b: Option<usize>,
    pub(super) point: Vec3,
    /// Rows: n, t1, t2.
    pub(super) frame: Mat3,
    pub(super) mu: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Storage {
    Dense,
    SparseBlock,
}

pub(super) struct World {
    pub(super) bodies: Vec<Body>,
    pub(super) contacts: Vec<Contact>,
}

pub(super) fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn normalize(a: &Vec3) -> Vec3 {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

pub(super) fn transpose(m: &Mat3) -> Mat3 {
    let mut t = [[0.0; 3]; 3];
    for (i, row) in m.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            t[j][i] = *v;
        }
    }
    t
}

pub(super) fn skew(a: &Vec3) -> Mat3 {
    [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]
}

pub(super) fn diag(d: Vec3) -> Mat3 {
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// Inverse by the adjugate (the matrices inverted here are well conditioned inertia tensors).
pub(super) fn inverse(m: &Mat3) -> Mat3 {
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
pub(super) fn yaw(angle: f64) -> Mat3 {
    let (s, c) = angle.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

/// A contact frame with normal `n` (rows n, t1, t2; right-handed).
pub(super) fn frame(n: Vec3) -> Mat3 {
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

pub(super) const E_Z: Vec3 = [0.0, 0.0, 1.0];

impl Body {
    /// A body with principal inertia `inertia` in the orientation `rot`, initial linear velocity
    /// `v` and angular velocity `omega`, one step of gravity applied. With `gyroscopic`, the
    /// angular iteration matrix is `I + dt C(omega)` and the gyroscopic torque is applied too.
    pub(super) fn new(
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

    pub(super) fn sphere(x: Vec3, mass: f64, radius: f64, v: Vec3, omega: Vec3) -> Body {
        let i = 0.4 * mass * radius * radius;
        Body::new(x, mass, [i; 3], yaw(0.0), v, omega, false)
    }

    /// A box of half-extents `h`, yawed by `rot`.
    pub(super) fn cuboid(
        x: Vec3,
        mass: f64,
        h: Vec3,
        rot: Mat3,
        v: Vec3,
        omega: Vec3,
        gyro: bool,
    ) -> Body {
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
pub(super) fn bottom_corners(x: &Vec3, h: &Vec3, rot: &Mat3) -> [Vec3; 4] {
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
    pub(super) fn new() -> World {
        World {
            bodies: Vec::new(),
            contacts: Vec::new(),
        }
    }

    pub(super) fn add_body(&mut self, b: Body) -> usize {
        self.bodies.push(b);
        self.bodies.len() - 1
    }

    pub(super) fn add_contact(
        &mut self,
        a: usize,
        b: Option<usize>,
        point: Vec3,
        normal: Vec3,
        mu: f64,
    ) {
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
    pub(super) fn add_box_support(
        &mut self,
        a: usize,
        b: Option<usize>,
        h: Vec3,
        rot: &Mat3,
        mu: f64,
    ) {
        let x = self.bodies[a].x;
        for p in bottom_corners(&x, &h, rot) {
            self.add_contact(a, b, p, E_Z, mu);
        }
    }

    /// `(translation part, rotation part)` of the 3x6 Jacobian of contact `c` for body `k`, signed.
    pub(super) fn jacobian(&self, c: usize, k: usize) -> Option<(Mat3, Mat3)> {
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

    pub(super) fn bodies_of(&self, c: usize) -> impl Iterator<Item = usize> + '_ {
        let ct = &self.contacts[c];
        std::iter::once(ct.a).chain(ct.b)
    }

    /// The 3x3 block `W_cd = sum_k G_ck M_k^-1 G_dk^T` (row-major), `None` when no body is shared.
    pub(super) fn block(&self, c: usize, d: usize) -> Option<Mat3> {
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
    pub(super) fn q(&self) -> Vec<f64> {
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
    pub(super) fn impulse_response(&self, r: &[f64]) -> Vec<[f64; 6]> {
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
    pub(super) fn block_of_w(&self, c: usize, d: usize, symmetric: bool) -> Option<Mat3> {
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
    pub(super) fn contacts_by_body(&self) -> (Vec<usize>, Vec<usize>) {
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
    pub(super) fn for_each_block(&self, mut f: impl FnMut(usize, usize, Mat3)) {
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

    pub(super) fn problem(&self, storage: Storage) -> FrictionProblem<'static> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

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
}
