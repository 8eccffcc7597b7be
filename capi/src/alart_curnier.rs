//! Siconos' one-contact Alart-Curnier functions (`fc3d_AlartCurnier_functions.h`,
//! `AlartCurnierGenerated.h`): `F(R, u)` and its two derivative blocks at an independent
//! reaction `R` and velocity `u`, for hosts that assemble their own Newton.
//!
//! Siconos' layout: 3x3 blocks column-major (`A[i + 3 j]`), `A = dF/du` (velocity) and
//! `B = dF/dR` (reaction), `rho = (rho_N, rho_T1, rho_T2)`. The numbers come from the core's
//! per-contact residual (the one NSN assembles); this layer packs them as Siconos does and
//! writes the entries each Siconos function writes (callers may rely on the others being left
//! alone). `R`, `velocity`, `rho` and `F` must not be NULL (nothing is written otherwise, the
//! reason in `fc3d_last_error_message`); a NULL `A` or `B` asks for `F` alone.

#![allow(non_snake_case)]

use std::os::raw::c_double;

use super::{ffi_guard, CError, CResult};
use fc3d_core::math::linalg::{Mat3, Vec3};
use fc3d_core::solvers::nsn::{alart_curnier_parts, TangentRadius};

/// Which Siconos variant is packed.
#[derive(Clone, Copy, PartialEq)]
enum Variant {
    /// `computeAlartCurnierSTD`: every entry of `A` and `B` written.
    Standard,
    /// `computeAlartCurnierSTDOld`: as Standard, but `R_N - rho_N u_N = 0` counts as active
    /// (`F_N = rho_N u_N`, `dF_N/du_N = rho_N`).
    StandardOld,
    /// `computeAlartCurnierJeanMoreau`: radius `mu R_N`, `R_N - rho_N u_N = 0` active; Siconos leaves `A[0,1]`, `A[0,2]`,
    /// `A[1,0]`, `A[2,0]`, `B[0,1]`, `B[0,2]` untouched.
    JeanMoreau,
    /// `fc3d_AlartCurnierFunctionGenerated`: `rho_T1` and `rho_T2` apart, all entries written.
    Generated { jean_moreau: bool },
}

unsafe fn read3(p: *const c_double, what: &str) -> CResult<Vec3> {
    if p.is_null() {
        return Err(CError::null(what));
    }
    Ok([*p, *p.add(1), *p.add(2)])
}

// Siconos' seven arguments and the variant.
#[allow(clippy::too_many_arguments)]
unsafe fn evaluate(
    variant: Variant,
    R: *const c_double,
    velocity: *const c_double,
    mu: c_double,
    rho: *const c_double,
    F: *mut c_double,
    A: *mut c_double,
    B: *mut c_double,
) -> CResult<()> {
    let r = read3(R, "R")?;
    let mut u = read3(velocity, "velocity")?;
    let rho = read3(rho, "rho")?;
    let generated = matches!(variant, Variant::Generated { .. });
    if F.is_null() && !(generated && !A.is_null() && !B.is_null()) {
        return Err(CError::null("F"));
    }
    let radius = match variant {
        Variant::Standard | Variant::StandardOld | Variant::Generated { jean_moreau: false } => {
            TangentRadius::AlartCurnier
        }
        Variant::JeanMoreau => TangentRadius::JeanMoreau,
        Variant::Generated { jean_moreau: true } => TangentRadius::JeanMoreauClamped,
    };
    // Two tangential rhos: with u' = (u_N, rho_T1 u_T1, rho_T2 u_T2) and rho_T = 1 the residual
    // is the same function, and dF/du = dF/du' diag(1, rho_T1, rho_T2).
    let rho_t = if generated {
        u[1] *= rho[1];
        u[2] *= rho[2];
        1.0
    } else {
        rho[1]
    };
    let (mut f, dr, mut du) = alart_curnier_parts(&r, &u, mu, rho[0], rho_t, radius);
    if generated {
        for row in du.iter_mut() {
            row[1] *= rho[1];
            row[2] *= rho[2];
        }
    }
    // Siconos' earlier function and its Jean-Moreau one take `R_N - rho_N u_N = 0` as active.
    let active_at_zero = matches!(variant, Variant::StandardOld | Variant::JeanMoreau)
        && r[0] - rho[0] * u[0] == 0.0;
    let (mut du, mut dr) = (du, dr);
    if active_at_zero {
        f[0] = rho[0] * u[0];
        du[0][0] = rho[0];
        dr[0][0] = 0.0;
    }
    if !F.is_null() {
        std::ptr::copy_nonoverlapping(f.as_ptr(), F, 3);
    }
    let both = !A.is_null() && !B.is_null();
    match variant {
        Variant::Standard | Variant::StandardOld | Variant::Generated { .. } if both => {
            write_all(A, &du);
            write_all(B, &dr);
        }
        Variant::Standard | Variant::StandardOld => {
            // Siconos clears the coupling entries of whichever block it was given.
            for m in [A, B] {
                if !m.is_null() {
                    for (i, j) in [(0, 1), (0, 2), (1, 0), (2, 0)] {
                        *m.add(i + 3 * j) = 0.0;
                    }
                }
            }
        }
        Variant::JeanMoreau if both => {
            let skipped_a = [(0, 1), (0, 2), (1, 0), (2, 0)];
            let skipped_b = [(0, 1), (0, 2)];
            for i in 0..3 {
                for j in 0..3 {
                    if !skipped_a.contains(&(i, j)) {
                        *A.add(i + 3 * j) = du[i][j];
                    }
                    if !skipped_b.contains(&(i, j)) {
                        *B.add(i + 3 * j) = dr[i][j];
                    }
                }
            }
        }
        _ => {}
    }
    Ok(())
}

/// `m` (row-major) into a column-major 3x3 block.
unsafe fn write_all(out: *mut c_double, m: &Mat3) {
    for (i, row) in m.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            *out.add(i + 3 * j) = *v;
        }
    }
}

/// Siconos' Alart-Curnier function: `F_N = R_N - (R_N - rho_N u_N)_+`, `F_T = R_T - P_D(mu (R_N -
/// rho_N u_N)_+)(R_T - rho_T u_T)` (`rho_T = rho[1]`), `A = dF/du`, `B = dF/dR` column-major (all
/// 18 entries when both are given).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn computeAlartCurnierSTD(
    R: *mut c_double,
    velocity: *mut c_double,
    mu: c_double,
    rho: *mut c_double,
    F: *mut c_double,
    A: *mut c_double,
    B: *mut c_double,
) {
    ffi_guard(
        "computeAlartCurnierSTD",
        |_| (),
        || evaluate(Variant::Standard, R, velocity, mu, rho, F, A, B),
    );
}

/// Siconos' earlier `computeAlartCurnierSTD` (exported by Siconos, declared by its tests): the same
/// function, with `R_N - rho_N u_N = 0` taken as the active side of the normal part.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn computeAlartCurnierSTDOld(
    R: *mut c_double,
    velocity: *mut c_double,
    mu: c_double,
    rho: *mut c_double,
    F: *mut c_double,
    A: *mut c_double,
    B: *mut c_double,
) {
    ffi_guard(
        "computeAlartCurnierSTDOld",
        |_| (),
        || evaluate(Variant::StandardOld, R, velocity, mu, rho, F, A, B),
    );
}

/// Siconos' Jean-Moreau variant (Christensen and Pang's): the disk radius is `mu R_N`, negative
/// where `R_N < 0`, `|R_T - rho_T u_T| < 1e-20` counts as sticking whatever the radius, and
/// `R_N - rho_N u_N = 0` counts as active. As in Siconos, `A[0,1]`, `A[0,2]`, `A[1,0]`,
/// `A[2,0]`, `B[0,1]`, `B[0,2]` are not written. (Siconos' generated Jean-Moreau function clamps
/// the radius at 0: `fc3d_AlartCurnierJeanMoreauFunctionGenerated`.)
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn computeAlartCurnierJeanMoreau(
    R: *mut c_double,
    velocity: *mut c_double,
    mu: c_double,
    rho: *mut c_double,
    F: *mut c_double,
    A: *mut c_double,
    B: *mut c_double,
) {
    ffi_guard(
        "computeAlartCurnierJeanMoreau",
        |_| (),
        || evaluate(Variant::JeanMoreau, R, velocity, mu, rho, F, A, B),
    );
}

/// Siconos' generated Alart-Curnier function: as `computeAlartCurnierSTD` with `rho_T1 = rho[1]`
/// and `rho_T2 = rho[2]` for the two tangential components; `F` alone when `A` or `B` is NULL, `A`
/// and `B` alone when `F` is NULL. (Siconos' generated code floors the disk radius at DBL_EPSILON,
/// which changes `F_T` by at most 2.2e-16.)
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_AlartCurnierFunctionGenerated(
    R: *mut c_double,
    velocity: *mut c_double,
    mu: c_double,
    rho: *mut c_double,
    F: *mut c_double,
    A: *mut c_double,
    B: *mut c_double,
) {
    ffi_guard(
        "fc3d_AlartCurnierFunctionGenerated",
        |_| (),
        || {
            evaluate(
                Variant::Generated { jean_moreau: false },
                R,
                velocity,
                mu,
                rho,
                F,
                A,
                B,
            )
        },
    );
}

/// Siconos' generated Jean-Moreau function: radius `mu (R_N)_+`, `rho_T1`, `rho_T2` apart, every
/// entry of `A` and `B` written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_AlartCurnierJeanMoreauFunctionGenerated(
    R: *mut c_double,
    velocity: *mut c_double,
    mu: c_double,
    rho: *mut c_double,
    F: *mut c_double,
    A: *mut c_double,
    B: *mut c_double,
) {
    ffi_guard(
        "fc3d_AlartCurnierJeanMoreauFunctionGenerated",
        |_| (),
        || {
            evaluate(
                Variant::Generated { jean_moreau: true },
                R,
                velocity,
                mu,
                rho,
                F,
                A,
                B,
            )
        },
    );
}
