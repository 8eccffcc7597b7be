//! Siconos 4.4 facts as data: the names of its solver ids, and the default values it puts in
//! slots that carry no fc3d setting (bookkeeping such as work-space sizes, values of options that
//! are off, and the few defaults where Siconos' C API differs from the core's Rust defaults).
//! Read off `solver_options_create(id)` of the Debian build.

use std::os::raw::c_int;

use super::{defaults, Encoded};

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
