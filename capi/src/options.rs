//! `SolverOptions`: creation with Siconos 4.4's defaults, copy, deletion, internal solvers, names,
//! and the conversion of iparam/dparam into the typed options of the core. The only place where
//! iparam/dparam indices are known.

#![allow(non_snake_case)]

use std::ffi::{c_char, CStr};
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::alloc::{c_box, c_calloc, c_copy, c_free};
use super::types::SolverOptions;
use super::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_OPTION, FC3D_ERR_UNSUPPORTED_SOLVER};
use fc3d_core::nsn::{NsnFormulation, NsnLineSearch, NsnOptions};
use fc3d_core::options::{
    ContactOrder, ErrorEvaluation, LocalSolverKind, LocalSolverOptions, LocalTolerance,
    NewtonFormulation, NsgsOptions, RhoRule,
};
use fc3d_core::prox::{ProxInternal, ProxOptions};
use fc3d_core::scaling::Rescaling;
use fc3d_core::solver::SolverConfig;

/// Length of iparam and dparam (Siconos' OPTIONS_PARAM_SIZE).
pub const OPTIONS_PARAM_SIZE: c_int = 20;

// Option indices (Siconos' SICONOS_IPARAM / SICONOS_DPARAM and Friction_cst.h enums).
pub(crate) const IPARAM_MAX_ITER: usize = 0;
pub(crate) const IPARAM_ITER_DONE: usize = 1;
pub(crate) const IPARAM_INTERNAL_ERROR_STRATEGY: usize = 2;
pub(crate) const IPARAM_RESCALING: usize = 3;
pub(crate) const IPARAM_NSGS_RELAXATION: usize = 4;
pub(crate) const IPARAM_NSGS_SHUFFLE: usize = 5;
pub(crate) const IPARAM_NSGS_SHUFFLE_SEED: usize = 6;
pub(crate) const IPARAM_ERROR_EVALUATION: usize = 7;
pub(crate) const IPARAM_ERROR_EVALUATION_FREQUENCY: usize = 8;
pub(crate) const IPARAM_NSN_RHO_STRATEGY: usize = 9;
pub(crate) const IPARAM_NSN_FORMULATION: usize = 10;
pub(crate) const IPARAM_NSN_LINESEARCH: usize = 11;
pub(crate) const IPARAM_NSN_LINESEARCH_MAX_ITER: usize = 12;
pub(crate) const IPARAM_NSN_LINEAR_SOLVER: usize = 13;
pub(crate) const IPARAM_NSN_HYBRID_STRATEGY: usize = 14;
pub(crate) const IPARAM_NSN_HYBRID_MAX_LOOP: usize = 15;
pub(crate) const IPARAM_NSN_HYBRID_MAX_ITER: usize = 16;
pub(crate) const IPARAM_NSGS_FREEZING_CONTACT: usize = 19;
pub(crate) const DPARAM_TOL: usize = 0;
pub(crate) const DPARAM_RESIDU: usize = 1;
pub(crate) const DPARAM_INTERNAL_ERROR_RATIO: usize = 2;
pub(crate) const DPARAM_NSN_RHO: usize = 3;
pub(crate) const DPARAM_NSGS_RELAXATION_VALUE: usize = 8;
pub(crate) const IPARAM_PROX_ERROR_STRATEGY: usize = 2;
pub(crate) const IPARAM_PROX_RELAXATION: usize = 8;
pub(crate) const IPARAM_PROX_STRATEGY: usize = 9;
pub(crate) const DPARAM_PROX_ALPHA: usize = 3;
pub(crate) const DPARAM_PROX_SIGMA: usize = 4;
pub(crate) const DPARAM_PROX_NU: usize = 5;
/// fc3d's value of a local solver's `iparam[9]` (rho strategy) for Dumont's rule
/// `rho_N = rho_T = alpha / W_NN`, with alpha in `dparam[3]` (Siconos 4.4 uses 0..=4). Default
/// of the local solvers `FC3D_ONECONTACT_EBP` and `FC3D_ONECONTACT_EAL` (alpha = 1).
pub const FC3D_RHO_STRATEGY_DUMONT: c_int = 10;

/// fc3d's one-contact solver ids are in 568..=599, a range Siconos 4.4 leaves free (its
/// one-contact solvers use 550..=567). FP-VI-UPK of Acary-Brémond-Huber's Table 3 on one contact:
/// projection steps with the self-adaptive rho rule (98), started from rho strategy iparam[9]
/// (default 1, spectral norm). Use it as NSGS's internal solver.
pub const FC3D_ONECONTACT_FP_VI_UPK: c_int = 570;
/// Dumont's EBP (2021): Newton on the bipotential fixed point `r = P_K(r - rho ũ)` with the
/// condensed 3x3 system (32); rho by iparam[9] (default `FC3D_RHO_STRATEGY_DUMONT`, alpha =
/// dparam[3] = 1). Use it as NSGS's internal solver.
pub const FC3D_ONECONTACT_EBP: c_int = 571;
/// Dumont's EAL (2021): Newton on the augmented-Lagrangian fixed point; the same function as
/// the Alart-Curnier Newton 550, with Dumont's rho (`FC3D_RHO_STRATEGY_DUMONT`) by default.
pub const FC3D_ONECONTACT_EAL: c_int = 572;
/// Relaxation omega of the SOCLCP Gauss-Seidel (SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE).
pub(crate) const DPARAM_SOCLCP_RELAXATION: usize = 8;
// VI family (VI_cst.h: SICONOS_VI_IPARAM / SICONOS_VI_DPARAM; FPP/EG/DSFP use the same slots).
pub(crate) const IPARAM_VI_DECREASE_RHO: usize = 3;
pub(crate) const IPARAM_VI_LINESEARCH_METHOD: usize = 6;
pub(crate) const IPARAM_VI_LS_MAX_ITER: usize = 9;
pub(crate) const IPARAM_VI_ACTIVATE_UPDATE: usize = 10;
pub(crate) const DPARAM_VI_RHO: usize = 3;
pub(crate) const DPARAM_VI_LS_TAU: usize = 4;
pub(crate) const DPARAM_VI_LS_TAUINV: usize = 5;
pub(crate) const DPARAM_VI_LS_L: usize = 6;
pub(crate) const DPARAM_VI_LS_LMIN: usize = 7;
// ADMM (Friction_cst.h: SICONOS_FRICTION_3D_ADMM_*).
pub(crate) const IPARAM_ADMM_RHO_STRATEGY: usize = 9;
pub(crate) const IPARAM_ADMM_INITIAL_RHO: usize = 10;
pub(crate) const IPARAM_ADMM_ACCELERATION: usize = 11;
pub(crate) const IPARAM_ADMM_SYMMETRY: usize = 12;
pub(crate) const IPARAM_ADMM_GET_PROBLEM_INFO: usize = 14;
pub(crate) const IPARAM_ADMM_UPDATE_S: usize = 15;
pub(crate) const IPARAM_ADMM_FULL_H: usize = 17;
pub(crate) const DPARAM_ADMM_RHO: usize = 3;
pub(crate) const DPARAM_ADMM_RESTART_ETA: usize = 4;
pub(crate) const DPARAM_ADMM_BALANCING_TAU: usize = 5;
pub(crate) const DPARAM_ADMM_BALANCING_PHI: usize = 6;

/// Siconos 4.4 names of solver ids (`solver_options_id_to_name`).
const NAMES: &[(c_int, &CStr)] = &[
    (400, c"F2D_NSGS"),
    (402, c"F2D_CPG"),
    (404, c"F2D_LEMKE"),
    (405, c"F2D_ENUM"),
    (500, c"FC3D_NSGS"),
    (501, c"FC3D_NSGSV"),
    (502, c"FC3D_PROX"),
    (503, c"FC3D_TFP"),
    (504, c"FC3D_NSN_AC"),
    (505, c"FC3D_DeSaxceFixedPoint"),
    (506, c"FC3D_VI_FixedPointProjection"),
    (507, c"FC3D_VI_ExtraGradient"),
    (508, c"FC3D_HyperplaneProjection"),
    (510, c"FC3D_NCPGlockerFBFixedPoint"),
    (511, c"FC3D_FixedPointProjection"),
    (512, c"FC3D_ExtraGradient"),
    (513, c"FC3D_NSN_FB"),
    (514, c"FC3D_GAMS_PATH"),
    (515, c"FC3D_GAMS_PATHVI"),
    (516, c"FC3D_ACLMFP"),
    (517, c"FC3D_SOCLCP"),
    (518, c"FC3D_GAMS_LCP_PATH"),
    (519, c"FC3D_GAMS_LCP_PATHVI"),
    (520, c"FC3D_NSN_NM"),
    (521, c"FC3D_NSN_AC_TEST"),
    (522, c"FC3D_PFP"),
    (523, c"FC3D ADMM"),
    (550, c"FC3D_ONECONTACT_NSN"),
    (551, c"FC3D_ONECONTACT_NSN_GP"),
    (552, c"FC3D_ProjectionOnCone"),
    (553, c"FC3D_ProjectionOnConeWithLocalIteration"),
    (554, c"FC3D_projectionOnConeWithRegularization"),
    (555, c"FC3D_ProjectionOnConeWithDiagonalization"),
    (556, c"FC3D_NCPGlockerFBPATH"),
    (557, c"FC3D_projectionOnCylinder"),
    (558, c"FC3D_ProjectionOnCone_velocity"),
    (561, c"FC3D_NCPGlockerFBNewton"),
    (562, c"FC3D_QUARTIC"),
    (563, c"FC3D_QUARTIC_NU"),
    (564, c"FC3D_projectionOnCylinderWithLocalIteration"),
    (565, c"FC3D_ONECONTACT_NSN_GP_HYBRID"),
    (567, c"FC3D ConvexQP PG solver"),
    (FC3D_ONECONTACT_FP_VI_UPK, c"FC3D_ONECONTACT_FP_VI_UPK"),
    (FC3D_ONECONTACT_EBP, c"FC3D_ONECONTACT_EBP"),
    (FC3D_ONECONTACT_EAL, c"FC3D_ONECONTACT_EAL"),
];

/// Name of a solver id ("NONAME" if unknown, as Siconos).
pub(crate) fn solver_name(id: c_int) -> &'static CStr {
    NAMES
        .iter()
        .find(|(i, _)| *i == id)
        .map_or(c"NONAME", |(_, n)| n)
}

/// Siconos 4.4 defaults: (id, nonzero iparam entries, nonzero dparam entries, internal ids).
/// Read off `solver_options_create(id)` of the Debian build; dparam[1] (the residual) starts at
/// +inf as there.
struct Defaults {
    id: c_int,
    iparam: &'static [(usize, c_int)],
    dparam: &'static [(usize, f64)],
    internal: &'static [c_int],
}

const DEFAULTS: &[Defaults] = &[
    Defaults {
        id: 500,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[565],
    },
    Defaults {
        id: 501,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[565],
    },
    Defaults {
        id: 502,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (2, 10.0), (3, 1e4), (4, 5.0), (5, 1.0)],
        internal: &[504],
    },
    Defaults {
        id: 503,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[500],
    },
    Defaults {
        id: 504,
        iparam: &[
            (0, 200),
            (3, 100000),
            (5, 1),
            (8, 1),
            (9, 1),
            (10, 2),
            (12, 100),
            (13, 1),
            (18, -1),
        ],
        dparam: &[(0, 1e-3), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 505,
        iparam: &[(0, 20000)],
        dparam: &[(0, 1e-3), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 506,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[
            (0, 1e-3),
            (3, -1.0),
            (4, 2.0 / 3.0),
            (5, 1.5),
            (6, 0.9),
            (7, 0.3),
        ],
        internal: &[],
    },
    Defaults {
        id: 507,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[
            (0, 1e-3),
            (3, -1.0),
            (4, 2.0 / 3.0),
            (5, 1.5),
            (6, 0.9),
            (7, 0.3),
        ],
        internal: &[],
    },
    Defaults {
        id: 511,
        iparam: &[(0, 20000)],
        dparam: &[(0, 1e-3), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 512,
        iparam: &[(0, 20000)],
        dparam: &[(0, 1e-3), (3, -1.0)],
        internal: &[],
    },
    Defaults {
        id: 513,
        iparam: &[
            (0, 200),
            (1, 1),
            (3, 100000),
            (5, 1),
            (8, 1),
            (12, 100),
            (13, 1),
            (18, -1),
        ],
        dparam: &[(0, 1e-3), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 516,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[],
    },
    Defaults {
        id: 517,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (8, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 520,
        iparam: &[
            (0, 1),
            (1, 1),
            (3, 100000),
            (5, 1),
            (8, 1),
            (12, 100),
            (13, 1),
            (18, -1),
        ],
        dparam: &[(0, 1e-3), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 522,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[],
    },
    Defaults {
        id: 523,
        iparam: &[(0, 20000), (10, 2), (11, 1)],
        dparam: &[(0, 1e-6), (3, 1.0), (4, 0.999), (5, 2.0), (6, 2.0)],
        internal: &[],
    },
    Defaults {
        id: 550,
        iparam: &[(0, 10), (9, 2), (11, -1), (14, 1), (15, 1), (16, 10)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 551,
        iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 565,
        iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 552,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Defaults {
        id: 553,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Defaults {
        id: 554,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Defaults {
        id: 555,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Defaults {
        id: 557,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Defaults {
        id: 558,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Defaults {
        id: 561,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-12)],
        internal: &[],
    },
    Defaults {
        id: 562,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-12)],
        internal: &[],
    },
    Defaults {
        id: 563,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-12)],
        internal: &[],
    },
    Defaults {
        id: 564,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    // fc3d's own one-contact solvers (ids Siconos does not use).
    Defaults {
        id: FC3D_ONECONTACT_FP_VI_UPK,
        iparam: &[(0, 1000), (9, 1)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Defaults {
        id: FC3D_ONECONTACT_EBP,
        iparam: &[(0, 20), (9, FC3D_RHO_STRATEGY_DUMONT)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: FC3D_ONECONTACT_EAL,
        iparam: &[(0, 20), (9, FC3D_RHO_STRATEGY_DUMONT), (11, -1), (12, 10)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Defaults {
        id: 508,
        iparam: &[(0, 20000)],
        dparam: &[(0, 1e-3)],
        internal: &[],
    },
    Defaults {
        id: 510,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4)],
        internal: &[],
    },
];

/// The one-contact solver id Siconos' NSGS-based families use inside when none is given.
fn defaults_of(id: c_int) -> Option<&'static Defaults> {
    DEFAULTS.iter().find(|d| d.id == id)
}

/// Builds a C-allocated options struct for `id` with Siconos' defaults and internal solvers.
pub(crate) fn create_options(id: c_int) -> CResult<*mut SolverOptions> {
    let d = defaults_of(id).ok_or_else(|| {
        CError::new(
            FC3D_ERR_UNSUPPORTED_SOLVER,
            format!(
                "unknown fc3d solver id {id} ({})",
                solver_name(id).to_string_lossy()
            ),
        )
    })?;
    let mut ip = [0 as c_int; OPTIONS_PARAM_SIZE as usize];
    let mut dp = [0.0 as c_double; OPTIONS_PARAM_SIZE as usize];
    for &(k, v) in d.iparam {
        ip[k] = v;
    }
    dp[DPARAM_RESIDU] = f64::INFINITY;
    for &(k, v) in d.dparam {
        dp[k] = v;
    }
    let internals = c_calloc::<*mut SolverOptions>(d.internal.len())?;
    for (k, &iid) in d.internal.iter().enumerate() {
        // SAFETY: internals has d.internal.len() slots.
        unsafe { *internals.add(k) = create_options(iid)? };
    }
    c_box(SolverOptions {
        solverId: id,
        isSet: 1,
        iSize: OPTIONS_PARAM_SIZE,
        iparam: c_copy(&ip)?,
        dSize: OPTIONS_PARAM_SIZE,
        dparam: c_copy(&dp)?,
        filterOn: 1,
        dWorkSize: 0,
        dWork: null_mut(),
        iWorkSize: 0,
        iWork: null_mut(),
        numberOfInternalSolvers: d.internal.len(),
        internalSolvers: internals,
        callback: null_mut(),
        solverParameters: null_mut(),
        solverData: null_mut(),
    })
}

/// Releases what `options` owns: parameter and work arrays, internal solvers (recursively,
/// including their structs). The struct itself is not freed (Siconos 4.4 semantics).
pub(crate) unsafe fn delete_contents(o: *mut SolverOptions) {
    if o.is_null() {
        return;
    }
    let o = &mut *o;
    c_free(o.iparam);
    c_free(o.dparam);
    c_free(o.dWork);
    c_free(o.iWork);
    if !o.internalSolvers.is_null() {
        for k in 0..o.numberOfInternalSolvers {
            let s = *o.internalSolvers.add(k);
            delete_contents(s);
            c_free(s);
        }
        c_free(o.internalSolvers);
    }
    o.iparam = null_mut();
    o.dparam = null_mut();
    o.dWork = null_mut();
    o.iWork = null_mut();
    o.dWorkSize = 0;
    o.iWorkSize = 0;
    o.internalSolvers = null_mut();
    o.numberOfInternalSolvers = 0;
    o.iSize = 0;
    o.dSize = 0;
}

unsafe fn copy_options(src: &SolverOptions) -> CResult<*mut SolverOptions> {
    let ip = super::matrix::c_slice(src.iparam, src.iSize.max(0) as usize, "iparam")?;
    let dp = super::matrix::c_slice(src.dparam, src.dSize.max(0) as usize, "dparam")?;
    let n = src.numberOfInternalSolvers;
    let internals = c_calloc::<*mut SolverOptions>(n)?;
    for k in 0..n {
        let s = if src.internalSolvers.is_null() {
            null_mut()
        } else {
            *src.internalSolvers.add(k)
        };
        *internals.add(k) = if s.is_null() {
            null_mut()
        } else {
            copy_options(&*s)?
        };
    }
    c_box(SolverOptions {
        solverId: src.solverId,
        isSet: src.isSet,
        iSize: src.iSize,
        iparam: c_copy(ip)?,
        dSize: src.dSize,
        dparam: c_copy(dp)?,
        filterOn: src.filterOn,
        dWorkSize: 0,
        dWork: null_mut(),
        iWorkSize: 0,
        iWork: null_mut(),
        numberOfInternalSolvers: n,
        internalSolvers: internals,
        callback: src.callback,
        solverParameters: src.solverParameters,
        solverData: src.solverData,
    })
}

// ---------------------------------------------------------------------------------------------
// Typed view of the parameter arrays.

struct Params<'a> {
    iparam: &'a [c_int],
    dparam: &'a [c_double],
}

impl<'a> Params<'a> {
    unsafe fn of(o: &'a SolverOptions, what: &str) -> CResult<Self> {
        if o.iparam.is_null() || o.dparam.is_null() {
            return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("{what}: iparam or dparam is NULL"),
            ));
        }
        if o.iSize < OPTIONS_PARAM_SIZE || o.dSize < OPTIONS_PARAM_SIZE {
            return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!(
                    "{what}: iSize = {} and dSize = {} must be at least {OPTIONS_PARAM_SIZE}",
                    o.iSize, o.dSize
                ),
            ));
        }
        Ok(Params {
            iparam: std::slice::from_raw_parts(o.iparam, o.iSize as usize),
            dparam: std::slice::from_raw_parts(o.dparam, o.dSize as usize),
        })
    }

    fn count(&self, k: usize, what: &str) -> CResult<usize> {
        usize::try_from(self.iparam[k]).map_err(|_| {
            CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("{what} (iparam[{k}]) = {} is negative", self.iparam[k]),
            )
        })
    }

    /// `dparam[k]`, which must be finite and > 0.
    fn positive(&self, k: usize, what: &str) -> CResult<f64> {
        let x = self.dparam[k];
        if x > 0.0 && x.is_finite() {
            Ok(x)
        } else {
            Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("{what} = {x} must be finite and > 0"),
            ))
        }
    }

    fn tolerance(&self, what: &str) -> CResult<f64> {
        let t = self.dparam[DPARAM_TOL];
        if t.is_finite() && t >= 0.0 {
            Ok(t)
        } else {
            Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("{what} tolerance (dparam[0]) = {t} must be finite and >= 0"),
            ))
        }
    }

    /// fc3d's wall-clock budget (`dparam[FC3D_DPARAM_TIME_BUDGET]`, seconds, 0 = none).
    fn time_budget(&self) -> CResult<Option<std::time::Duration>> {
        let k = super::FC3D_DPARAM_TIME_BUDGET as usize;
        let b = self.dparam[k];
        if b == 0.0 {
            Ok(None)
        } else if b > 0.0 && b.is_finite() {
            Ok(Some(std::time::Duration::from_secs_f64(b)))
        } else {
            Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("time budget (dparam[{k}]) = {b} must be 0 (none) or a positive number of seconds")))
        }
    }

    /// Rejects a non-default value of an option fc3d does not implement yet (never ignore it
    /// silently: the host asked for a behaviour).
    fn require(&self, k: usize, expected: c_int, name: &str) -> CResult<()> {
        if self.iparam[k] == expected {
            Ok(())
        } else {
            Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!(
                    "{name} (iparam[{k}]) = {} is not implemented in fc3d (only {expected})",
                    self.iparam[k]
                ),
            ))
        }
    }
}

fn unsupported_solver(id: c_int) -> CError {
    CError::new(
        FC3D_ERR_UNSUPPORTED_SOLVER,
        format!(
            "solver id {id} ({}) is not implemented in fc3d",
            solver_name(id).to_string_lossy()
        ),
    )
}

unsafe fn local_from_c(o: &SolverOptions) -> CResult<LocalSolverOptions> {
    let kind = LocalSolverKind::from_siconos_id(o.solverId)
        .ok_or_else(|| unsupported_solver(o.solverId))?;
    let p = Params::of(o, "local solver options")?;
    let mut l = LocalSolverOptions::new(kind);
    l.max_iter = p.count(IPARAM_MAX_ITER, "local max iterations")?;
    l.tolerance = p.tolerance("local")?;
    if matches!(
        kind,
        LocalSolverKind::NewtonAlartCurnier
            | LocalSolverKind::NewtonAlartCurnierGp
            | LocalSolverKind::NewtonHybrid
            | LocalSolverKind::EnhancedAugmentedLagrangian
            | LocalSolverKind::EnhancedBipotential
            | LocalSolverKind::FpViUpk
    ) {
        l.rho_rule = match p.iparam[IPARAM_NSN_RHO_STRATEGY] {
            0 => RhoRule::Constant(p.positive(DPARAM_NSN_RHO, "constant rho (dparam[3])")?),
            1 => RhoRule::SpectralNorm,
            2 => RhoRule::SplitSpectralNormCond,
            3 => RhoRule::SplitSpectralNorm,
            FC3D_RHO_STRATEGY_DUMONT => {
                RhoRule::Dumont(p.positive(DPARAM_NSN_RHO, "Dumont's alpha (dparam[3])")?)
            }
            other => {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!("rho strategy (iparam[9]) = {other} is not implemented in fc3d (0-3, {FC3D_RHO_STRATEGY_DUMONT} = Dumont)"),
                ))
            }
        };
    }
    if kind == LocalSolverKind::ProjectionOnConeWithRegularization {
        let eps = p.dparam[DPARAM_NSN_RHO];
        if !(eps >= 0.0 && eps.is_finite()) {
            return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("regularization (dparam[3]) = {eps} must be finite and >= 0"),
            ));
        }
        l.regularization = eps;
    }
    if kind == LocalSolverKind::EnhancedAugmentedLagrangian {
        p.require(
            IPARAM_NSN_FORMULATION,
            0,
            "EAL formulation (Alart-Curnier, 0)",
        )?;
        l.line_search_max_iter =
            p.count(IPARAM_NSN_LINESEARCH_MAX_ITER, "line-search max iterations")?;
        l.kind = match p.iparam[IPARAM_NSN_LINESEARCH] {
            -1 => LocalSolverKind::EnhancedAugmentedLagrangian,
            // EAL with the Goldstein-Price search is 551 with Dumont's rho.
            0 => LocalSolverKind::NewtonAlartCurnierGp,
            other => {
                return Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("line search (iparam[11]) = {other} is not implemented in fc3d (-1 none, 0 Goldstein-Price)")))
            }
        };
    }
    if matches!(
        kind,
        LocalSolverKind::NewtonAlartCurnier
            | LocalSolverKind::NewtonAlartCurnierGp
            | LocalSolverKind::NewtonHybrid
    ) {
        l.formulation = match p.iparam[IPARAM_NSN_FORMULATION] {
            0 | 2 => NewtonFormulation::AlartCurnier,
            1 | 3 => NewtonFormulation::JeanMoreau,
            other => {
                return Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("Newton formulation (iparam[10]) = {other} is not implemented in fc3d (0/2 Alart-Curnier, 1/3 Jean-Moreau)")))
            }
        };
        l.line_search_max_iter =
            p.count(IPARAM_NSN_LINESEARCH_MAX_ITER, "line-search max iterations")?;
        l.kind = match (kind, p.iparam[IPARAM_NSN_LINESEARCH]) {
            (LocalSolverKind::NewtonHybrid, 0) => LocalSolverKind::NewtonHybrid,
            (LocalSolverKind::NewtonHybrid, -1) => {
                return Err(CError::new(FC3D_ERR_INVALID_OPTION, "the hybrid Newton solver (565) needs the Goldstein-Price line search (iparam[11] = 0)"))
            }
            (_, 0) => LocalSolverKind::NewtonAlartCurnierGp,
            (_, -1) => LocalSolverKind::NewtonAlartCurnier,
            (_, other) => {
                return Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("line search (iparam[11]) = {other} is not implemented in fc3d (-1 none, 0 Goldstein-Price)")))
            }
        };
        l.hybrid_max_loop = p.count(IPARAM_NSN_HYBRID_MAX_LOOP, "hybrid max loops")?;
        l.hybrid_max_iter = p.count(IPARAM_NSN_HYBRID_MAX_ITER, "hybrid max iterations")?;
    }
    Ok(l)
}

/// The typed solver configuration described by Siconos options. Rejects unimplemented solver
/// ids and options with a message naming them.
pub(crate) unsafe fn config_from_c(o: &SolverOptions) -> CResult<SolverConfig> {
    match o.solverId {
        500 => {
            let p = Params::of(o, "NSGS options")?;
            let mut n = NsgsOptions::default();
            n.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
            n.tolerance = p.tolerance("NSGS")?;
            n.error_evaluation = match p.iparam[IPARAM_ERROR_EVALUATION] {
                0 => ErrorEvaluation::Full,
                1 => ErrorEvaluation::Light,
                2 => ErrorEvaluation::LightWithFullFinal,
                super::FC3D_ERROR_EVALUATION_DUMONT => ErrorEvaluation::DumontCriterion,
                other => {
                    return Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("error evaluation (iparam[7]) = {other} is not implemented in fc3d (0 full, 1 light, 2 light with full final, {} Dumont's criterion)", super::FC3D_ERROR_EVALUATION_DUMONT)))
                }
            };
            n.time_budget = p.time_budget()?;
            nsgs_sweep_options_from_c(&p, &mut n)?;
            if o.numberOfInternalSolvers >= 1
                && !o.internalSolvers.is_null()
                && !(*o.internalSolvers).is_null()
            {
                n.local = local_from_c(&**o.internalSolvers)?;
            }
            Ok(SolverConfig::Nsgs(n))
        }
        505 | 506 | 507 | 511 | 512 => vi_from_c(o),
        523 => admm_from_c(o),
        503 => {
            let p = Params::of(o, "TFP options")?;
            let mut t = fc3d_core::tresca::TrescaOptions {
                max_iter: p.count(IPARAM_MAX_ITER, "max iterations")?,
                tolerance: p.tolerance("TFP")?,
                time_budget: p.time_budget()?,
                ..Default::default()
            };
            require_no_extras(&p)?;
            let internal = first_internal(o);
            if let Some(i) = internal {
                t.inner = tresca_inner_from_c(i)?;
                let ip = Params::of(i, "TFP internal solver options")?;
                t.inner_max_iter = ip.count(IPARAM_MAX_ITER, "internal max iterations")?;
            }
            t.inner_tolerance = inner_tolerance_from_c(&p, internal)?;
            Ok(SolverConfig::Tresca(t))
        }
        522 => {
            let p = Params::of(o, "PFP options")?;
            let mut t = fc3d_core::pfp::PfpOptions {
                max_iter: p.count(IPARAM_MAX_ITER, "max iterations")?,
                tolerance: p.tolerance("PFP")?,
                time_budget: p.time_budget()?,
                ..Default::default()
            };
            require_no_extras(&p)?;
            let internal = first_internal(o);
            if let Some(i) = internal {
                t.tangent = tresca_inner_from_c(i)?;
                let ip = Params::of(i, "PFP internal solver options")?;
                t.inner_max_iter = ip.count(IPARAM_MAX_ITER, "internal max iterations")?;
            }
            t.inner_tolerance = inner_tolerance_from_c(&p, internal)?;
            Ok(SolverConfig::Pfp(t))
        }
        516 => {
            let p = Params::of(o, "ACLMFP options")?;
            require_no_extras(&p)?;
            if first_internal(o).is_some() {
                return Err(CError::new(FC3D_ERR_INVALID_OPTION, "ACLMFP (516) takes no internal solver in fc3d (its SOCLCP is solved by its own Gauss-Seidel)"));
            }
            Ok(SolverConfig::Aclm(fc3d_core::soclcp::AclmOptions {
                max_iter: p.count(IPARAM_MAX_ITER, "max iterations")?,
                tolerance: p.tolerance("ACLMFP")?,
                time_budget: p.time_budget()?,
                inner_tolerance: inner_tolerance_from_c(&p, None)?,
                ..Default::default()
            }))
        }
        517 => {
            let p = Params::of(o, "SOCLCP options")?;
            require_no_extras(&p)?;
            p.require(
                IPARAM_INTERNAL_ERROR_STRATEGY,
                0,
                "internal error strategy (SOCLCP has no internal solver)",
            )?;
            if first_internal(o).is_some() {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    "SOCLCP (517) takes no internal solver in fc3d",
                ));
            }
            let omega = p.dparam[DPARAM_SOCLCP_RELAXATION];
            if !(omega > 0.0 && omega < 2.0) {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!("SOCLCP relaxation (dparam[{DPARAM_SOCLCP_RELAXATION}]) = {omega} must be in (0, 2)"),
                ));
            }
            Ok(SolverConfig::Soclcp(fc3d_core::soclcp::SoclcpOptions {
                max_iter: p.count(IPARAM_MAX_ITER, "max iterations")?,
                tolerance: p.tolerance("SOCLCP")?,
                relaxation: omega,
                time_budget: p.time_budget()?,
            }))
        }
        504 | 513 | 520 => Ok(SolverConfig::Nsn(nsn_from_c(o)?)),
        502 => {
            let p = Params::of(o, "PROX options")?;
            let mut x = ProxOptions {
                max_iter: p.count(IPARAM_MAX_ITER, "max iterations")?,
                tolerance: p.tolerance("PROX")?,
                time_budget: p.time_budget()?,
                alpha: p.dparam[DPARAM_PROX_ALPHA],
                sigma: p.dparam[DPARAM_PROX_SIGMA],
                nu: p.dparam[DPARAM_PROX_NU],
                ..ProxOptions::default()
            };
            for (k, name, v) in [
                (DPARAM_PROX_ALPHA, "alpha", x.alpha),
                (DPARAM_PROX_SIGMA, "sigma", x.sigma),
                (DPARAM_PROX_NU, "nu", x.nu),
            ] {
                if !(v > 0.0 && v.is_finite()) {
                    return Err(CError::new(
                        FC3D_ERR_INVALID_OPTION,
                        format!("proximal {name} (dparam[{k}]) = {v} must be finite and > 0"),
                    ));
                }
            }
            p.require(
                IPARAM_PROX_ERROR_STRATEGY,
                0,
                "proximal internal error strategy (0 = error / 10)",
            )?;
            p.require(IPARAM_PROX_RELAXATION, 0, "proximal relaxation")?;
            p.require(
                IPARAM_PROX_STRATEGY,
                0,
                "proximal strategy (0 = proximal point)",
            )?;
            if o.numberOfInternalSolvers >= 1
                && !o.internalSolvers.is_null()
                && !(*o.internalSolvers).is_null()
            {
                x.internal = match config_from_c(&**o.internalSolvers)? {
                    SolverConfig::Nsn(n)
                        if matches!(
                            n.formulation,
                            NsnFormulation::AlartCurnier | NsnFormulation::JeanMoreau
                        ) =>
                    {
                        ProxInternal::NsnAc(n)
                    }
                    SolverConfig::Nsgs(g) => ProxInternal::Nsgs(g),
                    other => {
                        return Err(CError::new(
                            FC3D_ERR_UNSUPPORTED_SOLVER,
                            format!(
                                "PROX's internal solver {} is not supported in fc3d (504 NSN_AC or 500 NSGS)",
                                other.siconos_id()
                            ),
                        ))
                    }
                };
            }
            Ok(SolverConfig::Prox(x))
        }
        id => Err(unsupported_solver(id)),
    }
}

/// The rescaling a solver runs under. Only NSGS gives `iparam[3]` this meaning (other families
/// use index 3 for their own options): 0 none, 1 scalar; Siconos' balancing values 2-4 scale the
/// global formulation (M, H) and are rejected for the reduced problem.
pub(crate) unsafe fn rescaling_from_c(o: &SolverOptions) -> CResult<Rescaling> {
    if o.solverId != 500 {
        return Ok(Rescaling::None);
    }
    let p = Params::of(o, "NSGS options")?;
    match p.iparam[IPARAM_RESCALING] {
        0 => Ok(Rescaling::None),
        1 => Ok(Rescaling::Scalar),
        other => Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!("rescaling (iparam[3]) = {other} is not 0 (none) or 1 (scalar); balancing (2-4) applies to the global formulation only"),
        )),
    }
}

/// NSGS's sweep options: local tolerance strategy (iparam[2], ratio dparam[2]), relaxation
/// (iparam[4], omega dparam[8]), shuffling (iparam[5], seed iparam[6]), evaluation frequency
/// (iparam[8]) and freezing (iparam[19]).
fn nsgs_sweep_options_from_c(p: &Params<'_>, n: &mut NsgsOptions) -> CResult<()> {
    let invalid = |msg: String| CError::new(FC3D_ERR_INVALID_OPTION, msg);
    let ratio = || {
        let x = p.dparam[DPARAM_INTERNAL_ERROR_RATIO];
        if x > 0.0 && x.is_finite() {
            Ok(x)
        } else {
            Err(invalid(format!(
                "internal error ratio (dparam[2]) = {x} must be finite and > 0"
            )))
        }
    };
    n.local_tolerance = match p.iparam[IPARAM_INTERNAL_ERROR_STRATEGY] {
        0 => LocalTolerance::Adaptive { ratio: ratio()? },
        1 => LocalTolerance::Given,
        2 => LocalTolerance::AdaptivePerContact { ratio: ratio()? },
        other => {
            return Err(invalid(format!(
                "local tolerance strategy (iparam[2]) = {other} is not one of 0 (adaptive), 1 (given value), 2 (adaptive per contact)"
            )))
        }
    };
    n.relaxation = match p.iparam[IPARAM_NSGS_RELAXATION] {
        0 => None,
        1 => {
            let omega = p.dparam[DPARAM_NSGS_RELAXATION_VALUE];
            if !(omega > 0.0 && omega < 2.0) {
                return Err(invalid(format!(
                    "relaxation omega (dparam[8]) = {omega} must lie in (0, 2)"
                )));
            }
            Some(omega)
        }
        other => {
            return Err(invalid(format!(
                "relaxation (iparam[4]) = {other} is not 0 (off) or 1 (on, omega in dparam[8])"
            )))
        }
    };
    // The seed is an int in C; every value, negative included, is a valid seed.
    let seed = p.iparam[IPARAM_NSGS_SHUFFLE_SEED] as i64 as u64;
    n.order = match p.iparam[IPARAM_NSGS_SHUFFLE] {
        0 => ContactOrder::Natural,
        1 => ContactOrder::ShuffledOnce { seed },
        2 => ContactOrder::ShuffledEachSweep { seed },
        other => {
            return Err(invalid(format!(
                "shuffle (iparam[5]) = {other} is not 0 (off), 1 (once) or 2 (each sweep)"
            )))
        }
    };
    n.evaluation_frequency = p
        .count(
            IPARAM_ERROR_EVALUATION_FREQUENCY,
            "error evaluation frequency",
        )?
        .max(1);
    n.freezing = match p.count(IPARAM_NSGS_FREEZING_CONTACT, "contact freezing sweeps")? {
        0 => None,
        k => Some(k),
    };
    Ok(())
}

/// The first internal solver's options, if any.
unsafe fn first_internal(o: &SolverOptions) -> Option<&SolverOptions> {
    if o.numberOfInternalSolvers >= 1 && !o.internalSolvers.is_null() {
        (*o.internalSolvers).as_ref()
    } else {
        None
    }
}

/// The options TFP, PFP, ACLMFP and SOCLCP do not implement must keep their default (0).
fn require_no_extras(p: &Params<'_>) -> CResult<()> {
    p.require(IPARAM_RESCALING, 0, "rescaling")?;
    p.require(IPARAM_ERROR_EVALUATION, 0, "error evaluation")?;
    p.require(
        IPARAM_ERROR_EVALUATION_FREQUENCY,
        0,
        "error evaluation frequency",
    )
}

/// The Tresca sub-problem solver of TFP / the tangent solver of PFP, from the internal solver id:
/// 500 (NSGS on the cylinder; its own local solver is replaced by the exact Tresca solve), 566
/// (FP-VI-UPK on the cylinder), 567 (projected gradient, Algorithm 9).
unsafe fn tresca_inner_from_c(i: &SolverOptions) -> CResult<fc3d_core::tresca::TrescaInnerSolver> {
    fc3d_core::tresca::TrescaInnerSolver::from_siconos_id(i.solverId).ok_or_else(|| {
        CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!(
                "internal solver {} ({}) is not implemented for Tresca sub-problems in fc3d (500, 566 or 567)",
                i.solverId,
                solver_name(i.solverId).to_string_lossy()
            ),
        )
    })
}

/// iparam[2] = 0: adaptive inner tolerance, outer error / dparam[2]; 1: the internal solver's
/// dparam[0].
unsafe fn inner_tolerance_from_c(
    p: &Params<'_>,
    internal: Option<&SolverOptions>,
) -> CResult<fc3d_core::tresca::InnerTolerance> {
    match (p.iparam[IPARAM_INTERNAL_ERROR_STRATEGY], internal) {
        (0, _) => {
            let ratio = p.dparam[DPARAM_INTERNAL_ERROR_RATIO];
            if ratio > 0.0 && ratio.is_finite() {
                Ok(fc3d_core::tresca::InnerTolerance::Adaptive { ratio })
            } else {
                Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!("internal error ratio (dparam[{DPARAM_INTERNAL_ERROR_RATIO}]) = {ratio} must be finite and > 0"),
                ))
            }
        }
        (1, Some(i)) => Ok(fc3d_core::tresca::InnerTolerance::Given(
            Params::of(i, "internal solver options")?.tolerance("internal")?,
        )),
        (other, _) => Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!("internal error strategy (iparam[{IPARAM_INTERNAL_ERROR_STRATEGY}]) = {other} is not implemented here (0 adaptive, 1 the internal solver's tolerance when there is one)"),
        )),
    }
}

/// Nonsmooth Newton options (504, 513, 520). Honoured: iparam[0] max iterations, dparam[0]
/// tolerance, iparam[9] rho strategy (0 constant dparam[3], 1 spectral norm, 2 split with
/// conditioning, 3 split), iparam[10] formulation (504 only: 0/2 Alart-Curnier, 1/3 Jean-Moreau;
/// Siconos' "generated" variants compute the same function), iparam[11] line search (-1 none,
/// 0 Goldstein-Price, 1 Armijo), iparam[12] line-search trials, iparam[13] linear solver (0 or
/// 1: both mean a sparse LU, faer's here). Rejected: the adaptive rho (iparam[9] = 4), hybrid
/// strategies (iparam[14] != 0). iparam[3], [5], [8], [17], [18] are Siconos' internal
/// bookkeeping (work-space sizes, MPI) and carry no behaviour.
unsafe fn nsn_from_c(o: &SolverOptions) -> CResult<NsnOptions> {
    let p = Params::of(o, "NSN options")?;
    let formulation = match o.solverId {
        504 => match p.iparam[IPARAM_NSN_FORMULATION] {
            0 | 2 => NsnFormulation::AlartCurnier,
            1 | 3 => NsnFormulation::JeanMoreau,
            other => {
                return Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("NSN formulation (iparam[10]) = {other} is not implemented in fc3d (0/2 Alart-Curnier, 1/3 Jean-Moreau)")))
            }
        },
        513 => NsnFormulation::FischerBurmeister,
        _ => NsnFormulation::NaturalMap,
    };
    if o.solverId != 504 {
        p.require(
            IPARAM_NSN_FORMULATION,
            0,
            "NSN formulation (fixed by the solver id)",
        )?;
    }
    let mut n = NsnOptions::new(formulation);
    n.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
    n.tolerance = p.tolerance("NSN")?;
    n.time_budget = p.time_budget()?;
    n.rho_rule = match p.iparam[IPARAM_NSN_RHO_STRATEGY] {
        0 => {
            let rho = p.dparam[DPARAM_NSN_RHO];
            if !(rho > 0.0 && rho.is_finite()) {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!("constant rho (dparam[3]) = {rho} must be finite and > 0"),
                ));
            }
            RhoRule::Constant(rho)
        }
        1 => RhoRule::SpectralNorm,
        2 => RhoRule::SplitSpectralNormCond,
        3 => RhoRule::SplitSpectralNorm,
        other => {
            return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("rho strategy (iparam[9]) = {other} is not implemented in fc3d (0-3; the adaptive rule 4 is not)"),
            ))
        }
    };
    n.line_search = match p.iparam[IPARAM_NSN_LINESEARCH] {
        -1 => NsnLineSearch::None,
        0 => NsnLineSearch::GoldsteinPrice,
        1 => NsnLineSearch::Armijo,
        other => {
            return Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("line search (iparam[11]) = {other} is not implemented in fc3d (-1 none, 0 Goldstein-Price, 1 Armijo)")))
        }
    };
    n.line_search_max_iter =
        p.count(IPARAM_NSN_LINESEARCH_MAX_ITER, "line-search max iterations")?;
    if n.line_search != NsnLineSearch::None && n.line_search_max_iter == 0 {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            "line-search max iterations (iparam[12]) must be >= 1",
        ));
    }
    match p.iparam[IPARAM_NSN_LINEAR_SOLVER] {
        0 | 1 => {}
        other => {
            return Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("linear solver (iparam[13]) = {other} is not implemented in fc3d (0 or 1: a sparse LU)")))
        }
    }
    p.require(IPARAM_NSN_HYBRID_STRATEGY, 0, "NSN hybrid strategy")?;
    Ok(n)
}

/// Writes the outputs Siconos hosts read: iterations done and final error (and Dumont's
/// criterion where it was measured).
pub(crate) unsafe fn write_outputs(o: &mut SolverOptions, report: &fc3d_core::SolveReport) {
    *o.iparam.add(IPARAM_ITER_DONE) = c_int::try_from(report.iterations).unwrap_or(c_int::MAX);
    *o.dparam.add(DPARAM_RESIDU) = report.error;
    if let Some(d) = report.dumont_criterion {
        *o.dparam.add(super::FC3D_DPARAM_DUMONT_CRITERION as usize) = d;
    }
}

fn invalid(msg: String) -> CError {
    CError::new(FC3D_ERR_INVALID_OPTION, msg)
}

/// A line-search constant: 0 (unset, as in the defaults of 511/512) means Siconos' built-in
/// value; anything else is taken as given (and checked by `ViOptions::validate`).
fn vi_constant(p: &Params<'_>, k: usize, default: f64) -> f64 {
    if p.dparam[k] == 0.0 {
        default
    } else {
        p.dparam[k]
    }
}

/// DSFP 505, VI_FPP 506, VI_EG 507, FPP 511, EG 512.
unsafe fn vi_from_c(o: &SolverOptions) -> CResult<SolverConfig> {
    use fc3d_core::vi::{SelfAdaptiveStep, StepRatio, StepSize, ViOptions, ViSolver};
    let solver =
        ViSolver::from_siconos_id(o.solverId).ok_or_else(|| unsupported_solver(o.solverId))?;
    let what = solver.short_name();
    let p = Params::of(o, &format!("{what} options"))?;
    let mut v = ViOptions::new(solver);
    v.max_iter = p.count(IPARAM_MAX_ITER, "max iterations")?;
    v.tolerance = p.tolerance(what)?;
    v.time_budget = p.time_budget()?;
    // Siconos' VI ids use iparam[7] = 0 full, 1 light with full final, 2 light.
    v.error_evaluation = match p.iparam[IPARAM_ERROR_EVALUATION] {
        0 => ErrorEvaluation::Full,
        1 => ErrorEvaluation::LightWithFullFinal,
        2 => ErrorEvaluation::Light,
        other => return Err(invalid(format!("{what}: error evaluation (iparam[7]) = {other} is not implemented in fc3d (0 full, 1 light with full final, 2 light)"))),
    };
    // iparam[8] (error evaluation frequency) is set but unused by Siconos' VI solvers too.
    let rho = p.dparam[DPARAM_VI_RHO];
    if !rho.is_finite() || rho == 0.0 {
        return Err(invalid(format!("{what}: rho (dparam[3]) = {rho} must be finite and non-zero (> 0 fixed, < 0 self-adaptive from -rho)")));
    }
    v.step = if rho > 0.0 {
        StepSize::Fixed(rho)
    } else if solver == ViSolver::DeSaxceFixedPoint {
        return Err(invalid(format!(
            "DSFP: rho (dparam[3]) = {rho} must be > 0 (DSFP has a fixed rho)"
        )));
    } else {
        let d = SelfAdaptiveStep::default();
        StepSize::SelfAdaptive(SelfAdaptiveStep {
            initial_rho: -rho,
            ratio: match p.iparam[IPARAM_VI_LINESEARCH_METHOD] {
                0 => StepRatio::Khobotov,
                1 => StepRatio::SolodovTseng,
                other => return Err(invalid(format!("{what}: line search (iparam[6]) = {other} is not implemented in fc3d (0 Armijo with Khobotov's ratio, 1 Solodov-Tseng's)"))),
            },
            nu: vi_constant(&p, DPARAM_VI_LS_TAU, d.nu),
            increase: vi_constant(&p, DPARAM_VI_LS_TAUINV, d.increase),
            l: vi_constant(&p, DPARAM_VI_LS_L, d.l),
            l_min: vi_constant(&p, DPARAM_VI_LS_LMIN, d.l_min),
            max_trials: match p.count(IPARAM_VI_LS_MAX_ITER, "line-search max iterations")? {
                0 => d.max_trials,
                m => m,
            },
        })
    };
    p.require(IPARAM_VI_DECREASE_RHO, 0, "rho decrease rule")?;
    p.require(
        IPARAM_VI_ACTIVATE_UPDATE,
        0,
        "update inside the line search",
    )?;
    v.validate().map_err(|e| invalid(e.to_string()))?;
    Ok(SolverConfig::Vi(v))
}

/// ADMM 523.
unsafe fn admm_from_c(o: &SolverOptions) -> CResult<SolverConfig> {
    use fc3d_core::admm::{AdmmAcceleration, AdmmInitialRho, AdmmOptions, AdmmRhoStrategy};
    let p = Params::of(o, "ADMM options")?;
    let mut a = AdmmOptions {
        max_iter: p.count(IPARAM_MAX_ITER, "max iterations")?,
        tolerance: p.tolerance("ADMM")?,
        time_budget: p.time_budget()?,
        rho: p.dparam[DPARAM_ADMM_RHO],
        restart_eta: p.dparam[DPARAM_ADMM_RESTART_ETA],
        balancing_tau: p.dparam[DPARAM_ADMM_BALANCING_TAU],
        balancing_phi: p.dparam[DPARAM_ADMM_BALANCING_PHI],
        ..AdmmOptions::default()
    };
    a.rho_strategy = match p.iparam[IPARAM_ADMM_RHO_STRATEGY] {
        0 => AdmmRhoStrategy::Constant,
        2 => AdmmRhoStrategy::ResidualBalancing,
        3 => AdmmRhoStrategy::ScaledResidualBalancing,
        other => return Err(invalid(format!("ADMM: rho strategy (iparam[9]) = {other} is not implemented in fc3d (0 constant, 2 residual balancing, 3 scaled residual balancing)"))),
    };
    a.initial_rho = match p.iparam[IPARAM_ADMM_INITIAL_RHO] {
        0 => AdmmInitialRho::Given,
        1 => AdmmInitialRho::NormInf,
        2 => AdmmInitialRho::Eigenvalues,
        other => return Err(invalid(format!("ADMM: initial rho (iparam[10]) = {other} is not implemented in fc3d (0 given, 1 norm inf, 2 eigenvalues)"))),
    };
    a.acceleration = match p.iparam[IPARAM_ADMM_ACCELERATION] {
        0 => AdmmAcceleration::None,
        1 | 2 => AdmmAcceleration::Accelerated,
        other => return Err(invalid(format!("ADMM: acceleration (iparam[11]) = {other} is not implemented in fc3d (0 none, 1 or 2 accelerated with restart)"))),
    };
    // fc3d factors W + rho I with a general sparse LU, exact for any W: the symmetry choices
    // that keep W as it is (0 check, 1 forced symmetric, 2 forced asymmetric, 4 assume) all
    // lead there; 3 would symmetrize W, i.e. solve another problem.
    match p.iparam[IPARAM_ADMM_SYMMETRY] {
        0 | 1 | 2 | 4 => {}
        other => return Err(invalid(format!("ADMM: symmetry (iparam[12]) = {other} is not implemented in fc3d (W is never symmetrized; 0, 1, 2, 4 accepted)"))),
    }
    // iparam[13] (forced sparse storage) is what fc3d always does: any value is accepted.
    p.require(IPARAM_RESCALING, 0, "rescaling")?;
    p.require(IPARAM_ADMM_GET_PROBLEM_INFO, 0, "problem info printing")?;
    p.require(IPARAM_ADMM_UPDATE_S, 0, "De Saxcé term update (0 = yes)")?;
    p.require(IPARAM_ADMM_FULL_H, 0, "full H")?;
    a.validate().map_err(|e| invalid(e.to_string()))?;
    Ok(SolverConfig::Admm(a))
}

// ---------------------------------------------------------------------------------------------
// Siconos API.

/// Options for solver `solverId` with Siconos 4.4's defaults (and default internal solvers).
/// NULL for an id that is not an fc3d solver. Release with `solver_options_delete` then `free`.
#[no_mangle]
pub extern "C" fn solver_options_create(solverId: c_int) -> *mut SolverOptions {
    ffi_guard(
        "solver_options_create",
        |_| null_mut(),
        || create_options(solverId),
    )
}

/// Releases everything `options` owns (parameter arrays, work arrays, internal solvers), but not
/// the struct itself, nor `callback`, `solverParameters`, `solverData` (the caller's).
#[no_mangle]
pub unsafe extern "C" fn solver_options_delete(options: *mut SolverOptions) {
    ffi_guard(
        "solver_options_delete",
        |_| (),
        || {
            delete_contents(options);
            Ok(())
        },
    )
}

/// Replaces internal solver number `internal_solver_number` of `parent` by new options for
/// `solver_id` with their defaults (the old internal solver is released).
#[no_mangle]
pub unsafe extern "C" fn solver_options_update_internal(
    parent: *mut SolverOptions,
    internal_solver_number: usize,
    solver_id: c_int,
) {
    ffi_guard(
        "solver_options_update_internal",
        |_| (),
        || {
            if parent.is_null() {
                return Err(CError::null("parent"));
            }
            let p = &mut *parent;
            if internal_solver_number >= p.numberOfInternalSolvers || p.internalSolvers.is_null() {
                return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("internal solver {internal_solver_number} does not exist ({} internal solvers)", p.numberOfInternalSolvers),
            ));
            }
            let fresh = create_options(solver_id)?;
            let slot = p.internalSolvers.add(internal_solver_number);
            delete_contents(*slot);
            c_free(*slot);
            *slot = fresh;
            Ok(())
        },
    )
}

/// Sets internal solver `n` of `options` to `NSO`, which `options` then owns (the previous one is
/// released).
#[no_mangle]
pub unsafe extern "C" fn solver_options_set_internal_solver(
    options: *mut SolverOptions,
    n: usize,
    NSO: *mut SolverOptions,
) {
    ffi_guard(
        "solver_options_set_internal_solver",
        |_| (),
        || {
            if options.is_null() {
                return Err(CError::null("options"));
            }
            let o = &mut *options;
            if n >= o.numberOfInternalSolvers || o.internalSolvers.is_null() {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!(
                        "internal solver {n} does not exist ({} internal solvers)",
                        o.numberOfInternalSolvers
                    ),
                ));
            }
            let slot = o.internalSolvers.add(n);
            if *slot != NSO {
                delete_contents(*slot);
                c_free(*slot);
                *slot = NSO;
            }
            Ok(())
        },
    )
}

/// Internal solver `n` of `options` (owned by `options`), or NULL.
#[no_mangle]
pub unsafe extern "C" fn solver_options_get_internal_solver(
    options: *mut SolverOptions,
    n: usize,
) -> *mut SolverOptions {
    ffi_guard(
        "solver_options_get_internal_solver",
        |_| null_mut(),
        || {
            if options.is_null() {
                return Err(CError::null("options"));
            }
            let o = &*options;
            if n >= o.numberOfInternalSolvers || o.internalSolvers.is_null() {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!(
                        "internal solver {n} does not exist ({} internal solvers)",
                        o.numberOfInternalSolvers
                    ),
                ));
            }
            Ok(*o.internalSolvers.add(n))
        },
    )
}

/// A deep copy of `source` (parameters and internal solvers); `callback`, `solverParameters` and
/// `solverData` are shared, as in Siconos.
#[no_mangle]
pub unsafe extern "C" fn solver_options_copy(source: *mut SolverOptions) -> *mut SolverOptions {
    ffi_guard(
        "solver_options_copy",
        |_| null_mut(),
        || {
            if source.is_null() {
                return Err(CError::null("source"));
            }
            copy_options(&*source)
        },
    )
}

/// Siconos' name of a solver id ("NONAME" if unknown); a static string, do not free.
#[no_mangle]
pub extern "C" fn solver_options_id_to_name(Id: c_int) -> *const c_char {
    ffi_guard(
        "solver_options_id_to_name",
        |_| c"NONAME".as_ptr(),
        || Ok(solver_name(Id).as_ptr()),
    )
}

/// The id of a Siconos solver name, 0 if unknown.
#[no_mangle]
pub unsafe extern "C" fn solver_options_name_to_id(pName: *const c_char) -> c_int {
    ffi_guard(
        "solver_options_name_to_id",
        |_| 0,
        || {
            if pName.is_null() {
                return Err(CError::null("pName"));
            }
            let name = CStr::from_ptr(pName);
            Ok(NAMES
                .iter()
                .find(|(_, n)| *n == name)
                .map_or(0, |(i, _)| *i))
        },
    )
}

/// Prints the options (and internal solvers) to stdout.
#[no_mangle]
pub unsafe extern "C" fn solver_options_print(options: *mut SolverOptions) {
    ffi_guard(
        "solver_options_print",
        |_| (),
        || {
            if options.is_null() {
                return Err(CError::null("options"));
            }
            print_options(&*options, 0);
            Ok(())
        },
    )
}

unsafe fn print_options(o: &SolverOptions, depth: usize) {
    let pad = "  ".repeat(depth);
    println!(
        "{pad}solver {} ({})",
        o.solverId,
        solver_name(o.solverId).to_string_lossy()
    );
    if let Ok(p) = Params::of(o, "") {
        println!("{pad}  iparam: {:?}", p.iparam);
        println!("{pad}  dparam: {:?}", p.dparam);
    }
    for k in 0..o.numberOfInternalSolvers {
        if o.internalSolvers.is_null() {
            break;
        }
        let s = *o.internalSolvers.add(k);
        if !s.is_null() {
            println!("{pad}  internal solver {k}:");
            print_options(&*s, depth + 2);
        }
    }
}
