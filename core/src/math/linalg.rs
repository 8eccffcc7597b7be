//! Fixed-size dense kernels for one contact: 3-vectors and 3x3 matrices (row-major), written by hand
//! so that the local solvers allocate nothing and the compiler can keep everything in registers.

pub type Vec3 = [f64; 3];
/// Row-major 3x3 matrix: `m[i][j]` is row i, column j.
pub type Mat3 = [[f64; 3]; 3];

#[inline(always)]
pub fn dot3(a: &Vec3, b: &Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
pub fn norm3(a: &Vec3) -> f64 {
    dot3(a, a).sqrt()
}

/// `sqrt(x^2 + y^2)`. The plain formula is exact to an ulp and several times faster than libm's
/// `hypot` (which was 17% of an NSGS run); `hypot` is kept for the squares that overflow or
/// underflow.
#[inline(always)]
pub fn norm2(x: f64, y: f64) -> f64 {
    let s = x * x + y * y;
    if s >= f64::MIN_POSITIVE && s < f64::INFINITY {
        s.sqrt()
    } else if x == 0.0 && y == 0.0 {
        0.0
    } else {
        x.hypot(y)
    }
}

#[inline(always)]
pub fn sub3(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
pub fn add3(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
pub fn axpy3(alpha: f64, x: &Vec3, y: &Vec3) -> Vec3 {
    [
        y[0] + alpha * x[0],
        y[1] + alpha * x[1],
        y[2] + alpha * x[2],
    ]
}

/// `m * x`.
#[inline(always)]
pub fn mat3_vec(m: &Mat3, x: &Vec3) -> Vec3 {
    [dot3(&m[0], x), dot3(&m[1], x), dot3(&m[2], x)]
}

/// `y + m * x`.
#[inline(always)]
pub fn mat3_vec_add(m: &Mat3, x: &Vec3, y: &Vec3) -> Vec3 {
    // Accumulated column by column into y, in Siconos' order (bit-identical local problems).
    let row = |i: usize| y[i] + m[i][0] * x[0] + m[i][1] * x[1] + m[i][2] * x[2];
    [row(0), row(1), row(2)]
}

/// Row-major `D x D` block of W (`D` = 2 or 3, the contact dimension): a diagonal or coupling
/// block of one contact row.
pub type Block<const D: usize> = [[f64; D]; D];

/// `y + m * x` for a `D x D` block, each row summed in the order of [`mat3_vec_add`] (so that a
/// 3D sweep through the generic code gives the same bits as through the 3x3 kernel).
#[inline(always)]
pub fn block_vec_add<const D: usize>(m: &Block<D>, x: &[f64; D], y: &[f64; D]) -> [f64; D] {
    let mut out = *y;
    for (o, row) in out.iter_mut().zip(m) {
        for j in 0..D {
            *o += row[j] * x[j];
        }
    }
    out
}

/// The `D` components of contact `c` in a vector of all contacts.
#[inline(always)]
pub fn contact_of<const D: usize>(v: &[f64], c: usize) -> [f64; D] {
    let mut out = [0.0; D];
    out.copy_from_slice(&v[D * c..D * c + D]);
    out
}

/// `||a - b||^2` for two contact vectors.
#[inline(always)]
pub fn distance_sq_d<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    let mut s = 0.0;
    for k in 0..D {
        let d = a[k] - b[k];
        s += d * d;
    }
    s
}

/// `a * b`.
#[inline(always)]
pub fn mat3_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    c
}

/// Converts a column-major block of 9 values (Siconos' block layout) to a row-major matrix.
#[inline(always)]
pub fn mat3_from_col_major(b: &[f64]) -> Mat3 {
    [[b[0], b[3], b[6]], [b[1], b[4], b[7]], [b[2], b[5], b[8]]]
}

/// Max-abs entry, used to scale tolerances of singular-matrix tests.
pub fn mat3_max_abs(m: &Mat3) -> f64 {
    m.iter().flatten().fold(0.0_f64, |a, &v| a.max(v.abs()))
}

/// Solves `m x = b` by Gaussian elimination with partial pivoting. Returns `None` when a pivot is
/// zero or tiny relative to the matrix scale, or when the result is not finite.
///
/// Written out by hand (it is the stick test of every enumerative local solve, once per contact
/// and sweep): the row swaps are moves of named rows, and no entry is bounds-checked.
#[inline]
pub fn solve3(m: &Mat3, b: &Vec3) -> Option<Vec3> {
    let scale = mat3_max_abs(m);
    if !(scale > 0.0) || !scale.is_finite() {
        return None;
    }
    let tiny = scale * 1e-14;
    // Column 0: the first row of largest |entry| is the pivot row.
    let (mut r0, mut r1, mut r2) = (m[0], m[1], m[2]);
    let (mut x0, mut x1, mut x2) = (b[0], b[1], b[2]);
    if r1[0].abs() > r0[0].abs() {
        if r2[0].abs() > r1[0].abs() {
            std::mem::swap(&mut r0, &mut r2);
            std::mem::swap(&mut x0, &mut x2);
        } else {
            std::mem::swap(&mut r0, &mut r1);
            std::mem::swap(&mut x0, &mut x1);
        }
    } else if r2[0].abs() > r0[0].abs() {
        std::mem::swap(&mut r0, &mut r2);
        std::mem::swap(&mut x0, &mut x2);
    }
    if r0[0].abs() <= tiny {
        return None;
    }
    let f1 = r1[0] / r0[0];
    r1 = [r1[0] - f1 * r0[0], r1[1] - f1 * r0[1], r1[2] - f1 * r0[2]];
    x1 -= f1 * x0;
    let f2 = r2[0] / r0[0];
    r2 = [r2[0] - f2 * r0[0], r2[1] - f2 * r0[1], r2[2] - f2 * r0[2]];
    x2 -= f2 * x0;
    // Column 1.
    if r2[1].abs() > r1[1].abs() {
        std::mem::swap(&mut r1, &mut r2);
        std::mem::swap(&mut x1, &mut x2);
    }
    if r1[1].abs() <= tiny {
        return None;
    }
    let f = r2[1] / r1[1];
    let r22 = r2[2] - f * r1[2];
    x2 -= f * x1;
    if r22.abs() <= tiny {
        return None;
    }
    // Back substitution, in the order of the loop it replaces (same rounding).
    let y2 = x2 / r22;
    let y1 = (x1 - r1[2] * y2) / r1[1];
    let y0 = (x0 - r0[1] * y1 - r0[2] * y2) / r0[0];
    let x = [y0, y1, y2];
    if x.iter().all(|v| v.is_finite()) {
        Some(x)
    } else {
        None
    }
}

/// Largest eigenvalue of the symmetric part of a 2x2 matrix `[[a, b], [c, d]]`.
/// The tangent block of a non-symmetric W is not symmetrized in the solve; only this spectral
/// estimate (used to size rho) looks at its symmetric part.
pub fn lambda_max_sym2(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let off = 0.5 * (b + c);
    0.5 * (a + d) + (0.25 * (a - d) * (a - d) + off * off).sqrt()
}

/// Smallest eigenvalue of the symmetric part of a 2x2 matrix.
pub fn lambda_min_sym2(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let off = 0.5 * (b + c);
    0.5 * (a + d) - (0.25 * (a - d) * (a - d) + off * off).sqrt()
}

/// Euclidean norm of a slice: one pass of squares, and a scaled second pass only when the sum of
/// squares overflows or underflows (W scaled by 1e8 with reactions beyond 1e150).
pub fn norm(x: &[f64]) -> f64 {
    norm_of(x.iter().copied())
}

/// [`norm`] of the values `x` yields (read up to three times), e.g. a vector scaled on the fly.
pub fn norm_of(x: impl Iterator<Item = f64> + Clone) -> f64 {
    let s: f64 = x.clone().map(|v| v * v).sum();
    if s >= f64::MIN_POSITIVE && s < f64::INFINITY {
        return s.sqrt();
    }
    let amax = x.clone().fold(0.0_f64, |a, v| a.max(v.abs()));
    if amax == 0.0 || !amax.is_finite() {
        return if s.is_nan() { f64::NAN } else { amax };
    }
    let s: f64 = x.map(|v| (v / amax) * (v / amax)).sum();
    amax * s.sqrt()
}

/// Entries below [`DIVERGENCE_BOUND`] in magnitude: squares and sums of squares stay finite, so
/// every norm and error of such an iterate is finite. The global iterations (VI, ADMM) stop a
/// diverging run before it leaves this set.
pub fn bounded(v: &[f64]) -> bool {
    v.iter().all(|x| x.abs() < DIVERGENCE_BOUND)
}

/// See [`bounded`].
pub const DIVERGENCE_BOUND: f64 = 1e100;

/// `a·b` for slices of equal length.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `||a - b||^2` for slices of equal length.
pub fn distance_sq(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn solve3_matches_known_solution() {
        let m = [[4.0, -2.0, 1.0], [-2.0, 4.0, -2.0], [1.0, -2.0, 4.0]];
        let x = [1.0, -2.0, 3.0];
        let b = mat3_vec(&m, &x);
        let y = solve3(&m, &b).unwrap();
        for i in 0..3 {
            assert_relative_eq!(x[i], y[i], epsilon = 1e-14);
        }
    }

    #[test]
    fn solve3_rejects_singular() {
        let m = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]];
        assert!(solve3(&m, &[1.0, 2.0, 3.0]).is_none());
    }

    /// The textbook loop form of Gaussian elimination with partial pivoting, the oracle of the
    /// written-out [`solve3`].
    fn solve3_loops(m: &Mat3, b: &Vec3) -> Option<Vec3> {
        let (mut a, mut x) = (*m, *b);
        let scale = mat3_max_abs(m);
        if !(scale > 0.0) || !scale.is_finite() {
            return None;
        }
        let tiny = scale * 1e-14;
        for k in 0..3 {
            let mut p = k;
            for i in (k + 1)..3 {
                if a[i][k].abs() > a[p][k].abs() {
                    p = i;
                }
            }
            if a[p][k].abs() <= tiny {
                return None;
            }
            a.swap(k, p);
            x.swap(k, p);
            for i in (k + 1)..3 {
                let f = a[i][k] / a[k][k];
                for j in k..3 {
                    a[i][j] -= f * a[k][j];
                }
                x[i] -= f * x[k];
            }
        }
        for k in (0..3).rev() {
            let mut s = x[k];
            for j in (k + 1)..3 {
                s -= a[k][j] * x[j];
            }
            x[k] = s / a[k][k];
        }
        x.iter().all(|v| v.is_finite()).then_some(x)
    }

    proptest::proptest! {
        /// Same pivots, same operations, same order: the same bits as the loops, including the
        /// rejections (entries drawn from a few values, so ties and zero pivots occur).
        #[test]
        fn solve3_is_bitwise_the_loop_elimination(
            m in proptest::array::uniform3(proptest::array::uniform3(proptest::prop_oneof![
                -1e3..1e3f64,
                proptest::sample::select(vec![0.0, 1.0, -1.0, 2.0, 1e-300, 1e300]),
            ])),
            b in proptest::array::uniform3(-1e3..1e3f64),
        ) {
            let got = solve3(&m, &b).map(|x| x.map(f64::to_bits));
            let want = solve3_loops(&m, &b).map(|x| x.map(f64::to_bits));
            proptest::prop_assert_eq!(got, want);
        }
    }

    #[test]
    fn lambda_sym2() {
        assert_relative_eq!(lambda_max_sym2(2.0, 1.0, 1.0, 2.0), 3.0, epsilon = 1e-15);
        assert_relative_eq!(lambda_min_sym2(2.0, 1.0, 1.0, 2.0), 1.0, epsilon = 1e-15);
    }

    #[test]
    fn norm2_is_exact_where_squares_do_not_fit() {
        assert_eq!(norm2(3.0, 4.0), 5.0);
        assert_eq!(norm2(0.0, -0.0), 0.0);
        assert_relative_eq!(norm2(3e200, 4e200), 5e200, max_relative = 1e-15);
        assert_relative_eq!(norm2(3e-200, 4e-200), 5e-200, max_relative = 1e-15);
        assert!(norm2(f64::NAN, 1.0).is_nan());
        assert_eq!(norm2(f64::INFINITY, 1.0), f64::INFINITY);
    }

    #[test]
    fn norm_is_overflow_safe() {
        assert_relative_eq!(norm(&[3e200, 4e200]), 5e200, max_relative = 1e-15);
        assert_relative_eq!(norm(&[3e-200, 4e-200]), 5e-200, max_relative = 1e-15);
        assert_relative_eq!(norm(&[3.0, 4.0, 12.0]), 13.0, max_relative = 1e-15);
        assert_eq!(norm(&[]), 0.0);
        assert_eq!(norm(&[0.0, -0.0]), 0.0);
        assert!(norm(&[1.0, f64::NAN]).is_nan());
        assert_eq!(norm(&[1.0, f64::INFINITY]), f64::INFINITY);
    }
}
