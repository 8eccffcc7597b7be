//! Siconos 4.4's solver names: the `SICONOS_*_STR` variables that `Friction_cst.h`, `VI_cst.h`,
//! `SOCLCP_cst.h` and `ConvexQP_cst.h` declare (exported with Siconos' strings, as C's
//! `const char* const`), and the registry behind `solver_options_id_to_name` /
//! `solver_options_name_to_id`. The strings and the registration order are Siconos 4.4's,
//! read off the installed library (`scripts/siconos-options.sh` compares them).

use std::ffi::{c_char, CStr};
use std::os::raw::c_int;

use fc3d_core::LocalSolverKind;

/// A solver name as C sees it: `const char* const`, a pointer to a NUL-terminated static string.
#[repr(transparent)]
pub struct SolverName(*const c_char);

// SAFETY: the pointer is to an immutable static string.
unsafe impl Sync for SolverName {}

macro_rules! solver_names {
    ($( $id:tt $symbol:ident = $text:literal; )*) => {
        $(
            #[cfg(feature = "siconos-abi")]
            #[no_mangle]
            pub static $symbol: SolverName = SolverName($text.as_ptr());
        )*

        /// Every name with the id Siconos registers it under, in Siconos' registration order
        /// (`solver_options_name_to_id` returns the first id of a name given twice); `None`
        /// for a name Siconos declares but does not register.
        const NAMES: &[(Option<c_int>, &CStr)] = &[$( (solver_names!(@id $id), $text), )*];

        /// The name variable of each entry of `NAMES` (`SICONOS_FRICTION_3D_NSGS_STR`): the
        /// solver's constant in Siconos' headers with `_STR` appended.
        const NAME_VARIABLES: &[&str] = &[$( stringify!($symbol), )*];
    };
    (@id _) => { None };
    (@id $id:literal) => { Some($id) };
}

/// Ids Siconos names through a header outside fc3d's surface: LCP PGS, the normal-problem
/// solver Siconos puts in PFP's options (registered before all the others).
const OTHER_NAMES: &[(c_int, &CStr)] = &[(202, c"PGS")];

/// fc3d's own top-level solvers (ids Siconos leaves free).
const FC3D_NAMES: &[(c_int, &CStr)] = &[(crate::FC3D_AUTO, c"FC3D_AUTO")];

/// The constants of `fc3d.h` that name fc3d's own top-level solvers.
const FC3D_CONSTANTS: &[(c_int, &str)] = &[(crate::FC3D_AUTO, "FC3D_AUTO")];

solver_names! {
    1000 SICONOS_VI_EG_STR = c"VI_EG";
    1001 SICONOS_VI_FPP_STR = c"VI_FPP";
    1002 SICONOS_VI_HP_STR = c"VI_HP";
    1020 SICONOS_VI_BOX_QI_STR = c"Box VI solver based on Qi C-function";
    1021 SICONOS_VI_BOX_AVI_LSA_STR = c"Box VI solver based on the Newton-Josephy method";
    400 SICONOS_FRICTION_2D_NSGS_STR = c"F2D_NSGS";
    402 SICONOS_FRICTION_2D_CPG_STR = c"F2D_CPG";
    405 SICONOS_FRICTION_2D_ENUM_STR = c"F2D_ENUM";
    404 SICONOS_FRICTION_2D_LEMKE_STR = c"F2D_LEMKE";
    500 SICONOS_FRICTION_3D_NSGS_STR = c"FC3D_NSGS";
    501 SICONOS_FRICTION_3D_NSGSV_STR = c"FC3D_NSGSV";
    502 SICONOS_FRICTION_3D_PROX_STR = c"FC3D_PROX";
    503 SICONOS_FRICTION_3D_TFP_STR = c"FC3D_TFP";
    522 SICONOS_FRICTION_3D_PFP_STR = c"FC3D_PFP";
    504 SICONOS_FRICTION_3D_NSN_AC_STR = c"FC3D_NSN_AC";
    521 SICONOS_FRICTION_3D_NSN_AC_TEST_STR = c"FC3D_NSN_AC_TEST";
    513 SICONOS_FRICTION_3D_NSN_FB_STR = c"FC3D_NSN_FB";
    520 SICONOS_FRICTION_3D_NSN_NM_STR = c"FC3D_NSN_NM";
    505 SICONOS_FRICTION_3D_DSFP_STR = c"FC3D_DeSaxceFixedPoint";
    506 SICONOS_FRICTION_3D_VI_FPP_STR = c"FC3D_VI_FixedPointProjection";
    507 SICONOS_FRICTION_3D_VI_EG_STR = c"FC3D_VI_ExtraGradient";
    508 SICONOS_FRICTION_3D_HP_STR = c"FC3D_HyperplaneProjection";
    510 SICONOS_FRICTION_3D_NCPGlockerFBFixedPoint_STR = c"FC3D_NCPGlockerFBFixedPoint";
    511 SICONOS_FRICTION_3D_FPP_STR = c"FC3D_FixedPointProjection";
    512 SICONOS_FRICTION_3D_EG_STR = c"FC3D_ExtraGradient";
    550 SICONOS_FRICTION_3D_ONECONTACT_NSN_STR = c"FC3D_ONECONTACT_NSN";
    551 SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_STR = c"FC3D_ONECONTACT_NSN_GP";
    565 SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID_STR = c"FC3D_ONECONTACT_NSN_GP_HYBRID";
    555 SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithDiagonalization_STR = c"FC3D_ProjectionOnConeWithDiagonalization";
    552 SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone_STR = c"FC3D_ProjectionOnCone";
    553 SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithLocalIteration_STR = c"FC3D_ProjectionOnConeWithLocalIteration";
    554 SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithRegularization_STR = c"FC3D_projectionOnConeWithRegularization";
    557 SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinder_STR = c"FC3D_projectionOnCylinder";
    564 SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinderWithLocalIteration_STR = c"FC3D_projectionOnCylinderWithLocalIteration";
    558 SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone_velocity_STR = c"FC3D_ProjectionOnCone_velocity";
    561 SICONOS_FRICTION_3D_NCPGlockerFBNewton_STR = c"FC3D_NCPGlockerFBNewton";
    556 SICONOS_FRICTION_3D_NCPGlockerFBPATH_STR = c"FC3D_NCPGlockerFBPATH";
    567 SICONOS_FRICTION_3D_CONVEXQP_PG_CYLINDER_STR = c"FC3D ConvexQP PG solver";
    514 SICONOS_FRICTION_3D_GAMS_PATH_STR = c"FC3D_GAMS_PATH";
    515 SICONOS_FRICTION_3D_GAMS_PATHVI_STR = c"FC3D_GAMS_PATHVI";
    518 SICONOS_FRICTION_3D_GAMS_LCP_PATH_STR = c"FC3D_GAMS_LCP_PATH";
    519 SICONOS_FRICTION_3D_GAMS_LCP_PATHVI_STR = c"FC3D_GAMS_LCP_PATHVI";
    517 SICONOS_FRICTION_3D_SOCLCP_STR = c"FC3D_SOCLCP";
    516 SICONOS_FRICTION_3D_ACLMFP_STR = c"FC3D_ACLMFP";
    562 SICONOS_FRICTION_3D_ONECONTACT_QUARTIC_STR = c"FC3D_QUARTIC";
    563 SICONOS_FRICTION_3D_ONECONTACT_QUARTIC_NU_STR = c"FC3D_QUARTIC_NU";
    523 SICONOS_FRICTION_3D_ADMM_STR = c"FC3D ADMM";
    3000 SICONOS_ROLLING_FRICTION_3D_NSGS_STR = c"RFC3D_NSGS";
    3002 SICONOS_ROLLING_FRICTION_3D_ONECONTACT_ProjectionOnConeWithLocalIteration_STR = c"RFC3D_ProjectionOnConeWithLocalIteration";
    3001 SICONOS_ROLLING_FRICTION_3D_ONECONTACT_ProjectionOnCone_STR = c"RFC3D_ProjectionOnCone";
    3003 SICONOS_ROLLING_FRICTION_3D_ADMM_STR = c"RFC3D ADMM";
    4000 SICONOS_ROLLING_FRICTION_2D_NSGS_STR = c"RFC2D_NSGS";
    4002 SICONOS_ROLLING_FRICTION_2D_ONECONTACT_ProjectionOnConeWithLocalIteration_STR = c"RFC2D_ProjectionOnConeWithLocalIteration";
    600 SICONOS_GLOBAL_FRICTION_3D_NSGS_WR_STR = c"GFC3D_NSGS_WR";
    601 SICONOS_GLOBAL_FRICTION_3D_NSGSV_WR_STR = c"GFC3D_NSGSV_WR";
    602 SICONOS_GLOBAL_FRICTION_3D_PROX_WR_STR = c"GFC3D_PROX_WR";
    603 SICONOS_GLOBAL_FRICTION_3D_DSFP_WR_STR = c"GFC3D_DSFP_WR";
    604 SICONOS_GLOBAL_FRICTION_3D_TFP_WR_STR = c"GFC3D_TFP_WR";
    605 SICONOS_GLOBAL_FRICTION_3D_NSGS_STR = c"GFC3D_NSGS";
    606 SICONOS_GLOBAL_FRICTION_3D_NSN_AC_WR_STR = c"GFC3D_NSN_AC_WR";
    607 SICONOS_GLOBAL_FRICTION_3D_NSN_AC_STR = c"GFC3D_NSN_AC";
    608 SICONOS_GLOBAL_FRICTION_3D_GAMS_PATH_STR = c"GFC3D_GAMS_PATH";
    609 SICONOS_GLOBAL_FRICTION_3D_GAMS_PATHVI_STR = c"GFC3D_GAMS_PATHVI";
    611 SICONOS_GLOBAL_FRICTION_3D_VI_EG_STR = c"GFC3D_VI_EG";
    610 SICONOS_GLOBAL_FRICTION_3D_VI_FPP_STR = c"GFC3D_VI_FPP";
    612 SICONOS_GLOBAL_FRICTION_3D_ACLMFP_STR = c"GFC3D_ACLMFP";
    613 SICONOS_GLOBAL_FRICTION_3D_ADMM_STR = c"GFC3D ADMM";
    614 SICONOS_GLOBAL_FRICTION_3D_ADMM_WR_STR = c"GFC3D_ADMM_WR";
    615 SICONOS_GLOBAL_FRICTION_3D_IPM_STR = c"GFC3D IPM";
    5000 SICONOS_GLOBAL_ROLLING_FRICTION_3D_NSGS_WR_STR = c"GFC3D_NSGS_WR";
    1100 SICONOS_SOCLCP_NSGS_STR = c"SOCLCP_NSGS";
    1106 SICONOS_SOCLCP_VI_FPP_STR = c"SOCLCP_VI_FixedPointProjection";
    1107 SICONOS_SOCLCP_VI_EG_STR = c"SOCLCP_VI_ExtraGradient";
    1202 SICONOS_CONVEXQP_VI_EG_STR = c"CONVEXQP VI EG";
    1201 SICONOS_CONVEXQP_VI_FPP_STR = c"CONVEXQP VI FPP";
    1200 SICONOS_CONVEXQP_PG_STR = c"CONVEXQP PG";
    1203 SICONOS_CONVEXQP_ADMM_STR = c"CONVEXQP ADMM";
    _ SICONOS_FRICTION_3D_VI_FPP_Cylinder_STR = c"FC3D_VI_FPP_Cylinder";
    _ SICONOS_ROLLING_FRICTION_2D_ONECONTACT_ProjectionOnCone_STR = c"RFC2D_ProjectionOnCone";
    _ SICONOS_SOCLCP_AlartCurnierNewton_STR = c"SOCLCP_AlartCurnierNewton";
    _ SICONOS_SOCLCP_DSFP_STR = c"SOCLCP_DeSaxceFixedPoint";
    _ SICONOS_SOCLCP_DampedAlartCurnierNewton_STR = c"SOCLCP_DampedAlartCurnierNewton";
    _ SICONOS_SOCLCP_DeSaxceFixedPoint_STR = c"SOCLCP_DeSaxceFixedPoint";
    _ SICONOS_SOCLCP_EG_STR = c"SOCLCP_ExtraGradient";
    _ SICONOS_SOCLCP_FPP_STR = c"SOCLCP_FixedPointProjection";
    _ SICONOS_SOCLCP_HP_STR = c"SOCLCP_HyperplaneProjection";
    _ SICONOS_SOCLCP_NCPGlockerFBFixedPoint_STR = c"SOCLCP_NCPGlockerFBFixedPoint";
    _ SICONOS_SOCLCP_NCPGlockerFBNewton_STR = c"SOCLCP_NCPGlockerFBNewton";
    _ SICONOS_SOCLCP_NCPGlockerFBPATH_STR = c"SOCLCP_NCPGlockerFBPATH";
    _ SICONOS_SOCLCP_NSGSV_STR = c"SOCLCP_NSGSV";
    _ SICONOS_SOCLCP_NSN_AC_STR = c"SOCLCP_NSN_AC";
    _ SICONOS_SOCLCP_NSN_FB_STR = c"SOCLCP_NSN_FB";
    _ SICONOS_SOCLCP_PGoC_STR = c"SOCLCP_PGoC";
    _ SICONOS_SOCLCP_PROX_STR = c"SOCLCP_PROX";
    _ SICONOS_SOCLCP_ProjectionOnConeWithDiagonalization_STR = c"SOCLCP_ProjectionOnConeWithDiagonalization";
    _ SICONOS_SOCLCP_ProjectionOnConeWithLocalIteration_STR = c"SOCLCP_ProjectionOnConeWithLocalIteration";
    _ SICONOS_SOCLCP_ProjectionOnConeWithRegularization_STR = c"SOCLCP_ProjectionOnConeWithRegularization";
    _ SICONOS_SOCLCP_ProjectionOnCone_STR = c"SOCLCP_ProjectionOnCone";
    _ SICONOS_SOCLCP_ProjectionOnCone_velocity_STR = c"SOCLCP_ProjectionOnCone_velocity";
    _ SICONOS_SOCLCP_QUARTIC_NU_STR = c"SOCLCP_QUARTIC_NU";
    _ SICONOS_SOCLCP_QUARTIC_STR = c"SOCLCP_QUARTIC";
    _ SICONOS_SOCLCP_TFP_STR = c"SOCLCP_TFP";
    _ SICONOS_SOCLCP_projectionOnCylinder_STR = c"SOCLCP_projectionOnCylinder";
    _ SICONOS_VI_BOX_PATH_STR = c"Box VI solver based on PATH solver";
}

/// The registered (id, name) pairs in Siconos' order, then fc3d's own one-contact solvers
/// (ids Siconos leaves free, named by the core's registry).
fn registered() -> impl Iterator<Item = (c_int, &'static CStr)> {
    OTHER_NAMES
        .iter()
        .copied()
        .chain(
            NAMES
                .iter()
                .filter_map(|&(id, name)| id.map(|id| (id, name))),
        )
        .chain(fc3d_local_names().iter().map(|(id, n)| (*id, n.as_c_str())))
        .chain(FC3D_NAMES.iter().copied())
}

/// fc3d's one-contact solvers whose ids Siconos does not register, by their registry names
/// (NUL-terminated copies made once).
fn fc3d_local_names() -> &'static [(c_int, std::ffi::CString)] {
    static LOCAL: std::sync::OnceLock<Vec<(c_int, std::ffi::CString)>> = std::sync::OnceLock::new();
    LOCAL.get_or_init(|| {
        LocalSolverKind::ALL
            .iter()
            .filter(|k| !NAMES.iter().any(|(id, _)| *id == Some(k.siconos_id())))
            .filter_map(|k| {
                Some((
                    k.siconos_id(),
                    std::ffi::CString::new(k.siconos_name()).ok()?,
                ))
            })
            .collect()
    })
}

/// Siconos' name of a solver id, "NONAME" for an id it does not register (as Siconos).
pub(crate) fn solver_name(id: c_int) -> &'static CStr {
    registered()
        .find(|(i, _)| *i == id)
        .map_or(c"NONAME", |(_, n)| n)
}

/// The constant that names solver `id` in Siconos' headers (`SICONOS_FRICTION_3D_NSGS`, the
/// first one registered with that id) or in fc3d's (`FC3D_AUTO`); `None` for an id neither names.
pub(crate) fn solver_constant(id: c_int) -> Option<&'static str> {
    let siconos = NAMES
        .iter()
        .zip(NAME_VARIABLES)
        .find(|((i, _), _)| *i == Some(id))
        .and_then(|(_, variable)| variable.strip_suffix("_STR"));
    siconos.or_else(|| {
        FC3D_CONSTANTS
            .iter()
            .find(|(i, _)| *i == id)
            .map(|(_, c)| *c)
    })
}

/// Every id `solver_name` names (Siconos' registered ids and fc3d's own), each once.
pub(crate) fn named_ids() -> Vec<c_int> {
    let mut ids: Vec<c_int> = registered().map(|(id, _)| id).collect();
    ids.sort_unstable();
    ids.dedup();
    ids
}

/// The id registered under a name (the first one), 0 if none (as Siconos).
pub(crate) fn solver_name_to_id(name: &CStr) -> c_int {
    registered().find(|(_, n)| *n == name).map_or(0, |(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_ids_round_trip_as_in_siconos() {
        assert_eq!(solver_name(500), c"FC3D_NSGS");
        assert_eq!(solver_name(523), c"FC3D ADMM");
        assert_eq!(solver_name(566), c"NONAME"); // declared, not registered
        assert_eq!(solver_name(-1), c"NONAME");
        assert_eq!(solver_name_to_id(c"FC3D_NSGS"), 500);
        // 5000 shares 600's name: the first registered wins.
        assert_eq!(solver_name(5000), c"GFC3D_NSGS_WR");
        assert_eq!(solver_name_to_id(c"GFC3D_NSGS_WR"), 600);
        assert_eq!(solver_name_to_id(c"no such solver"), 0);
        assert_eq!(solver_name(590), c"FC3D_AUTO");
        assert_eq!(solver_name_to_id(c"FC3D_AUTO"), 590);
        assert_eq!(solver_constant(500), Some("SICONOS_FRICTION_3D_NSGS"));
        assert_eq!(solver_constant(505), Some("SICONOS_FRICTION_3D_DSFP"));
        assert_eq!(
            solver_constant(562),
            Some("SICONOS_FRICTION_3D_ONECONTACT_QUARTIC")
        );
        assert_eq!(solver_constant(590), Some("FC3D_AUTO"));
        assert_eq!(solver_constant(-1), None);
        for kind in LocalSolverKind::ALL {
            let id = kind.siconos_id();
            assert_ne!(solver_name(id), c"NONAME", "{kind:?}");
            assert_eq!(solver_name_to_id(solver_name(id)), id);
        }
    }
}
