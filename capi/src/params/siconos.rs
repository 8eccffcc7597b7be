//! Siconos 4.4 facts as data: the names of its solver ids, and the default values it puts in
//! slots that carry no fc3d setting (bookkeeping such as work-space sizes, values of options that
//! are off, and the few defaults where Siconos' C API differs from the core's Rust defaults).
//! Read off `solver_options_create(id)` of the Debian build.

use std::ffi::CStr;
use std::os::raw::c_int;

use super::{defaults, Encoded};
use fc3d_core::LocalSolverKind;

/// Siconos 4.4 names of solver ids (`solver_options_id_to_name`); fc3d's own one-contact ids
/// are named by the core's registry.
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

/// fc3d's one-contact solvers outside Siconos' range, by their registry names (NUL-terminated
/// copies made once).
fn fc3d_local_name(id: c_int) -> Option<&'static CStr> {
    static NAMES: std::sync::OnceLock<Vec<(c_int, std::ffi::CString)>> = std::sync::OnceLock::new();
    let names = NAMES.get_or_init(|| {
        LocalSolverKind::ALL
            .iter()
            .filter(|k| {
                !super::siconos::NAMES
                    .iter()
                    .any(|(i, _)| *i == k.siconos_id())
            })
            .filter_map(|k| {
                let name = std::ffi::CString::new(k.siconos_name()).ok()?;
                Some((k.siconos_id(), name))
            })
            .collect()
    });
    names
        .iter()
        .find(|(i, _)| *i == id)
        .map(|(_, n)| n.as_c_str())
}

/// Name of a solver id ("NONAME" if unknown, as Siconos).
pub(crate) fn solver_name(id: c_int) -> &'static CStr {
    NAMES
        .iter()
        .find(|(i, _)| *i == id)
        .map(|(_, n)| *n)
        .or_else(|| fc3d_local_name(id))
        .unwrap_or(c"NONAME")
}

/// The id of a solver name, 0 if unknown.
pub(crate) fn solver_name_to_id(name: &CStr) -> c_int {
    NAMES
        .iter()
        .find(|(_, n)| *n == name)
        .map(|(i, _)| *i)
        .or_else(|| {
            LocalSolverKind::ALL
                .iter()
                .find(|k| k.siconos_name().as_bytes() == name.to_bytes())
                .map(|k| k.siconos_id())
        })
        .unwrap_or(0)
}

/// Siconos' values in slots that carry no fc3d setting, per id, and (for ids fc3d only names)
/// the ids of the internal solvers Siconos creates.
struct SiconosSlots {
    id: c_int,
    iparam: &'static [(usize, c_int)],
    dparam: &'static [(usize, f64)],
    internal: &'static [c_int],
}

const SLOTS: &[SiconosSlots] = &[
    // NSGS and PROX: the ratio of the adaptive local tolerance, set while the strategy is off.
    SiconosSlots {
        id: 500,
        iparam: &[],
        dparam: &[(2, 10.0)],
        internal: &[],
    },
    SiconosSlots {
        id: 502,
        iparam: &[],
        dparam: &[(2, 10.0)],
        internal: &[],
    },
    // Nonsmooth Newton: work-space sizes, MPI and linear-solver bookkeeping; the constant rho
    // value of 504 while its rule is the spectral norm; "iterations done" of 513 and 520; and
    // Siconos' single Newton step of 520 (the core's default is 200).
    SiconosSlots {
        id: 504,
        iparam: &[(3, 100000), (5, 1), (8, 1), (13, 1), (18, -1)],
        dparam: &[(3, 1.0)],
        internal: &[],
    },
    SiconosSlots {
        id: 513,
        iparam: &[(1, 1), (3, 100000), (5, 1), (8, 1), (13, 1), (18, -1)],
        dparam: &[],
        internal: &[],
    },
    SiconosSlots {
        id: 520,
        iparam: &[
            (0, 1),
            (1, 1),
            (3, 100000),
            (5, 1),
            (8, 1),
            (13, 1),
            (18, -1),
        ],
        dparam: &[],
        internal: &[],
    },
    // EG 512 leaves the line-search constants unset (0: Siconos' built-in values).
    SiconosSlots {
        id: 512,
        iparam: &[],
        dparam: &[(4, 0.0), (5, 0.0), (6, 0.0), (7, 0.0)],
        internal: &[],
    },
    // Local Newton solvers: the hybrid strategy code and the constant rho value while the rule
    // is another; 550's hybrid iteration limit (it is not a hybrid solver).
    SiconosSlots {
        id: 550,
        iparam: &[(14, 1), (16, 10)],
        dparam: &[(3, 1.0)],
        internal: &[],
    },
    SiconosSlots {
        id: 551,
        iparam: &[(14, 2)],
        dparam: &[(3, 1.0)],
        internal: &[],
    },
    SiconosSlots {
        id: 565,
        iparam: &[(14, 2)],
        dparam: &[(3, 1.0)],
        internal: &[],
    },
    // Ids fc3d names but does not implement: Siconos' defaults.
    SiconosSlots {
        id: 501,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[565],
    },
    // NSN_AC_TEST: Siconos' newton_lsa_set_default values (fc3d reads iparam[0], dparam[0]).
    SiconosSlots {
        id: 521,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-10), (2, 1e-16)],
        internal: &[],
    },
    SiconosSlots {
        id: 508,
        iparam: &[(0, 20000)],
        dparam: &[(0, 1e-3)],
        internal: &[],
    },
    SiconosSlots {
        id: 510,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4)],
        internal: &[],
    },
    SiconosSlots {
        id: 563,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-12)],
        internal: &[],
    },
];

/// Whether Siconos' defaults of `id` are known here.
pub(super) fn has_defaults(id: c_int) -> bool {
    SLOTS.iter().any(|s| s.id == id)
}

/// Writes Siconos' values into the slots of `e` (and of its internal solvers) that carry no
/// fc3d setting, and creates the internal solvers of an id fc3d does not implement.
pub(super) fn apply_defaults(e: &mut Encoded) {
    for i in &mut e.internal {
        apply_defaults(i);
    }
    let Some(s) = SLOTS.iter().find(|s| s.id == e.id) else {
        return;
    };
    for &(k, v) in s.iparam {
        e.iparam[k] = v;
    }
    for &(k, v) in s.dparam {
        e.dparam[k] = v;
    }
    if e.internal.is_empty() {
        e.internal = s
            .internal
            .iter()
            .filter_map(|&id| defaults(id).ok())
            .collect();
    }
}
