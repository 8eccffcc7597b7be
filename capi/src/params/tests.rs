//! The defaults `solver_options_create` returns, checked against Siconos 4.4's (read off the
//! Debian build's `solver_options_create(id)`, kept here as data), and the round trip from the
//! core's typed defaults to the slots and back.

use std::os::raw::c_int;

use super::*;
use crate::options::{create_options, delete_contents};

struct Reference {
    id: c_int,
    iparam: &'static [(usize, c_int)],
    dparam: &'static [(usize, f64)],
    internal: &'static [c_int],
}

const SICONOS: &[Reference] = &[
    Reference {
        id: 500,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[565],
    },
    Reference {
        id: 501,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[565],
    },
    Reference {
        id: 502,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (2, 10.0), (3, 1e4), (4, 5.0), (5, 1.0)],
        internal: &[504],
    },
    Reference {
        id: 503,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[500],
    },
    Reference {
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
    Reference {
        id: 505,
        iparam: &[(0, 20000)],
        dparam: &[(0, 1e-3), (3, 1.0)],
        internal: &[],
    },
    Reference {
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
    Reference {
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
    Reference {
        id: 511,
        iparam: &[(0, 20000)],
        dparam: &[(0, 1e-3), (3, 1.0)],
        internal: &[],
    },
    Reference {
        id: 512,
        iparam: &[(0, 20000)],
        dparam: &[(0, 1e-3), (3, -1.0)],
        internal: &[],
    },
    Reference {
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
    Reference {
        id: 516,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[],
    },
    Reference {
        id: 517,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (8, 1.0)],
        internal: &[],
    },
    Reference {
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
    Reference {
        id: 522,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4), (2, 10.0)],
        internal: &[],
    },
    Reference {
        id: 523,
        iparam: &[(0, 20000), (11, 2), (12, 1)],
        dparam: &[(0, 1e-6), (3, 1.0), (4, 0.999), (5, 2.0), (6, 2.0)],
        internal: &[],
    },
    Reference {
        id: 550,
        iparam: &[(0, 10), (9, 2), (11, -1), (14, 1), (15, 1), (16, 10)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Reference {
        id: 551,
        iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Reference {
        id: 565,
        iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Reference {
        id: 552,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Reference {
        id: 553,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Reference {
        id: 554,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Reference {
        id: 555,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Reference {
        id: 557,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Reference {
        id: 558,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Reference {
        id: 561,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-12)],
        internal: &[],
    },
    Reference {
        id: 562,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-12)],
        internal: &[],
    },
    Reference {
        id: 563,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-12)],
        internal: &[],
    },
    Reference {
        id: 564,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    // fc3d's own one-contact solvers (ids Siconos does not use).
    Reference {
        id: 570,
        iparam: &[(0, 1000), (9, 1)],
        dparam: &[(0, 1e-14)],
        internal: &[],
    },
    Reference {
        id: 571,
        iparam: &[(0, 20), (9, 10)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Reference {
        id: 572,
        iparam: &[(0, 20), (9, 10), (11, -1), (12, 10)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[],
    },
    Reference {
        id: 508,
        iparam: &[(0, 2_000_000), (12, 50)],
        dparam: &[(0, 1e-3), (4, 0.99)],
        internal: &[],
    },
    Reference {
        id: 510,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-4)],
        internal: &[],
    },
];

fn reference(id: c_int) -> &'static Reference {
    SICONOS
        .iter()
        .find(|r| r.id == id)
        .expect("a reference row")
}

fn check_against_reference(e: &Encoded) {
    let r = reference(e.id);
    let mut iparam = [0; SIZE];
    let mut dparam = [0.0; SIZE];
    dparam[DPARAM_RESIDU] = f64::INFINITY;
    for &(k, v) in r.iparam {
        iparam[k] = v;
    }
    for &(k, v) in r.dparam {
        dparam[k] = v;
    }
    assert_eq!(e.iparam, iparam, "iparam of {}", e.id);
    assert_eq!(e.dparam, dparam, "dparam of {}", e.id);
    let internal: Vec<c_int> = e.internal.iter().map(|i| i.id).collect();
    assert_eq!(internal, r.internal, "internal solvers of {}", e.id);
    for i in &e.internal {
        check_against_reference(i);
    }
}

#[test]
fn defaults_are_siconos_slot_for_slot() {
    for r in SICONOS {
        check_against_reference(&defaults(r.id).expect("defaults"));
    }
    assert!(defaults(4242).is_err());
}

/// What the C API reads from its own defaults is the core's default configuration of the id:
/// one place holds the defaults. The one exception is Siconos' single Newton step of 520.
#[test]
fn defaults_read_back_as_the_cores() {
    for method in Method::presets() {
        let id = method.siconos_id();
        if Method::preset(&id.to_string()) != Some(method) {
            continue; // a second preset of the same id (NSN-JM, PROX-NSGS): not a default
        }
        let mut expected = SolverConfig::new(method);
        if id == 520 {
            expected.max_iter = 1;
        }
        let o = create_options(id).expect("created");
        let read = unsafe { config_from_c(&*o) };
        unsafe {
            delete_contents(o);
            crate::alloc::c_free(o);
        }
        assert_eq!(read.expect("valid defaults"), expected, "id {id}");
    }
    for kind in LocalSolverKind::ALL {
        let o = create_options(kind.siconos_id()).expect("created");
        let read = unsafe { local::read(&*o) };
        unsafe {
            delete_contents(o);
            crate::alloc::c_free(o);
        }
        assert_eq!(
            read.expect("valid defaults"),
            fc3d_core::LocalSolverOptions::new(kind),
            "{kind:?}"
        );
    }
}

/// A setting the core rejects is reported with the slot it came from.
#[test]
fn rejected_settings_name_their_slot() {
    let o = create_options(500).expect("created");
    unsafe {
        *(*o).iparam.add(4) = 1;
        *(*o).dparam.add(8) = 2.5;
        let e = config_from_c(&*o).expect_err("omega out of range");
        assert!(e.message.contains("dparam[8]"), "{}", e.message);
        *(*o).iparam.add(4) = 0;
        *(*o).dparam.add(0) = -1.0;
        let e = config_from_c(&*o).expect_err("negative tolerance");
        assert!(e.message.contains("dparam[0]"), "{}", e.message);
        delete_contents(o);
        crate::alloc::c_free(o);
    }
    for (setting, _) in SETTING_SLOTS {
        assert!(!setting.is_empty());
    }
}
