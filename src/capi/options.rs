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
use crate::nsn::{NsnFormulation, NsnLineSearch, NsnOptions};
use crate::options::{ErrorEvaluation, LocalSolverKind, LocalSolverOptions, NsgsOptions, RhoRule};
use crate::prox::{ProxInternal, ProxOptions};
use crate::solver::SolverConfig;

/// Length of iparam and dparam (Siconos' OPTIONS_PARAM_SIZE).
pub const OPTIONS_PARAM_SIZE: c_int = 20;

// Option indices (Siconos' SICONOS_IPARAM / SICONOS_DPARAM and Friction_cst.h enums).
pub(crate) const IPARAM_MAX_ITER: usize = 0;
pub(crate) const IPARAM_ITER_DONE: usize = 1;
pub(crate) const IPARAM_INTERNAL_ERROR_STRATEGY: usize = 2;
pub(crate) const IPARAM_RESCALING: usize = 3;
pub(crate) const IPARAM_NSGS_RELAXATION: usize = 4;
pub(crate) const IPARAM_NSGS_SHUFFLE: usize = 5;
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
pub(crate) const DPARAM_NSN_RHO: usize = 3;
pub(crate) const IPARAM_PROX_ERROR_STRATEGY: usize = 2;
pub(crate) const IPARAM_PROX_RELAXATION: usize = 8;
pub(crate) const IPARAM_PROX_STRATEGY: usize = 9;
pub(crate) const DPARAM_PROX_ALPHA: usize = 3;
pub(crate) const DPARAM_PROX_SIGMA: usize = 4;
pub(crate) const DPARAM_PROX_NU: usize = 5;

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
    ) {
        l.rho_rule = match p.iparam[IPARAM_NSN_RHO_STRATEGY] {
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
                    format!("rho strategy (iparam[9]) = {other} is not implemented in fc3d (0-3)"),
                ))
            }
        };
        p.require(
            IPARAM_NSN_FORMULATION,
            0,
            "Newton formulation (only Alart-Curnier STD)",
        )?;
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
                other => {
                    return Err(CError::new(FC3D_ERR_INVALID_OPTION, format!("error evaluation (iparam[7]) = {other} is not implemented in fc3d (0 full, 1 light, 2 light with full final)")))
                }
            };
            n.time_budget = p.time_budget()?;
            p.require(
                IPARAM_INTERNAL_ERROR_STRATEGY,
                1,
                "local tolerance strategy (1 = given value)",
            )?;
            p.require(IPARAM_RESCALING, 0, "rescaling")?;
            p.require(IPARAM_NSGS_RELAXATION, 0, "NSGS relaxation")?;
            p.require(IPARAM_NSGS_SHUFFLE, 0, "NSGS shuffle")?;
            p.require(
                IPARAM_ERROR_EVALUATION_FREQUENCY,
                0,
                "error evaluation frequency",
            )?;
            p.require(IPARAM_NSGS_FREEZING_CONTACT, 0, "contact freezing")?;
            if o.numberOfInternalSolvers >= 1
                && !o.internalSolvers.is_null()
                && !(*o.internalSolvers).is_null()
            {
                n.local = local_from_c(&**o.internalSolvers)?;
            }
            Ok(SolverConfig::Nsgs(n))
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

/// Writes the outputs Siconos hosts read: iterations done and final error.
pub(crate) unsafe fn write_outputs(o: &mut SolverOptions, iterations: usize, error: f64) {
    *o.iparam.add(IPARAM_ITER_DONE) = c_int::try_from(iterations).unwrap_or(c_int::MAX);
    *o.dparam.add(DPARAM_RESIDU) = error;
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
