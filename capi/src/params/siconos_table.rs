//! Siconos 4.4's `solver_options_create(id)` for every solver id of the friction headers, as
//! data: the slots that differ from a fresh options struct (0, and +inf in dparam[1]) and the
//! internal solvers, nested. Generated from the installed libsiconos_numerics by
//! `scripts/siconos-options.sh --write-table`; do not edit by hand.

use std::os::raw::{c_double, c_int};

/// One options struct of Siconos' defaults: the slots that differ from a fresh struct (0, and
/// +inf in dparam[1]) and its internal solvers.
pub(super) struct Defaults {
    pub id: c_int,
    pub iparam: &'static [(usize, c_int)],
    pub dparam: &'static [(usize, c_double)],
    pub internal: &'static [Defaults],
}

#[rustfmt::skip]
pub(super) const TABLE: &[Defaults] = &[
    Defaults {
        id: 400,
        iparam: &[(0, 1000), (7, 2)],
        dparam: &[(0, 0.0001)],
        internal: &[
        ],
    },
    Defaults {
        id: 402,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001)],
        internal: &[
        ],
    },
    Defaults {
        id: 404,
        iparam: &[(0, 10000)],
        dparam: &[(0, 9.9999999999999995e-07)],
        internal: &[
        ],
    },
    Defaults {
        id: 405,
        iparam: &[],
        dparam: &[(0, 9.9999999999999995e-07)],
        internal: &[
        ],
    },
    Defaults {
        id: 500,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 565,
                iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
                dparam: &[(0, 1e-14), (3, 1.0)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 501,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001)],
        internal: &[
            Defaults {
                id: 550,
                iparam: &[(0, 10), (9, 2), (11, -1), (14, 1), (15, 1), (16, 10)],
                dparam: &[(0, 1e-14), (3, 1.0)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 502,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (2, 10.0), (3, 10000.0), (4, 5.0), (5, 1.0)],
        internal: &[
            Defaults {
                id: 504,
                iparam: &[(0, 200), (3, 100000), (5, 1), (8, 1), (9, 1), (10, 2), (12, 100), (13, 1), (18, -1)],
                dparam: &[(0, 0.001), (3, 1.0)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 503,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 500,
                iparam: &[(0, 1000), (2, 1), (7, 2)],
                dparam: &[(0, 0.0001), (2, 10.0)],
                internal: &[
                    Defaults {
                        id: 564,
                        iparam: &[(0, 50)],
                        dparam: &[(0, 1e-14)],
                        internal: &[
                        ],
                    },
                ],
            },
        ],
    },
    Defaults {
        id: 504,
        iparam: &[(0, 200), (3, 100000), (5, 1), (8, 1), (9, 1), (10, 2), (12, 100), (13, 1), (18, -1)],
        dparam: &[(0, 0.001), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 505,
        iparam: &[(0, 20000)],
        dparam: &[(0, 0.001), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 506,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 507,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 508,
        iparam: &[(0, 2000000), (12, 50)],
        dparam: &[(0, 0.001), (4, 0.98999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 510,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 511,
        iparam: &[(0, 20000)],
        dparam: &[(0, 0.001), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 512,
        iparam: &[(0, 20000)],
        dparam: &[(0, 0.001), (3, -1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 513,
        iparam: &[(0, 200), (1, 1), (3, 100000), (5, 1), (8, 1), (12, 100), (13, 1), (18, -1)],
        dparam: &[(0, 0.001), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 514,
        iparam: &[(0, 10000)],
        dparam: &[(0, 1.0000000000000001e-09)],
        internal: &[
        ],
    },
    Defaults {
        id: 515,
        iparam: &[(0, 10000)],
        dparam: &[(0, 1.0000000000000001e-09)],
        internal: &[
        ],
    },
    Defaults {
        id: 516,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 1100,
                iparam: &[(0, 10000)],
                dparam: &[(0, 0.0001), (8, 1.0)],
                internal: &[
                    Defaults {
                        id: 1151,
                        iparam: &[(0, 1000)],
                        dparam: &[(0, 9.9999999999999998e-17)],
                        internal: &[
                        ],
                    },
                ],
            },
        ],
    },
    Defaults {
        id: 517,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (8, 1.0)],
        internal: &[
            Defaults {
                id: 1151,
                iparam: &[(0, 1000)],
                dparam: &[(0, 9.9999999999999998e-17)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 518,
        iparam: &[(0, 10000)],
        dparam: &[(0, 1.0000000000000001e-09)],
        internal: &[
        ],
    },
    Defaults {
        id: 519,
        iparam: &[(0, 10000)],
        dparam: &[(0, 1.0000000000000001e-09)],
        internal: &[
        ],
    },
    Defaults {
        id: 520,
        iparam: &[(0, 1), (1, 1), (3, 100000), (5, 1), (8, 1), (12, 100), (13, 1), (18, -1)],
        dparam: &[(0, 0.001), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 521,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-10), (2, 9.9999999999999998e-17)],
        internal: &[
        ],
    },
    Defaults {
        id: 522,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 202,
                iparam: &[(0, 1000)],
                dparam: &[(0, 9.9999999999999995e-07)],
                internal: &[
                ],
            },
            Defaults {
                id: 1201,
                iparam: &[(0, 1000), (7, 1)],
                dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 523,
        iparam: &[(0, 20000), (11, 2), (12, 1)],
        dparam: &[(0, 9.9999999999999995e-07), (3, 1.0), (4, 0.999), (5, 2.0), (6, 2.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 550,
        iparam: &[(0, 10), (9, 2), (11, -1), (14, 1), (15, 1), (16, 10)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 551,
        iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 552,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[
        ],
    },
    Defaults {
        id: 553,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[
        ],
    },
    Defaults {
        id: 554,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[
        ],
    },
    Defaults {
        id: 555,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[
        ],
    },
    Defaults {
        id: 558,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[
        ],
    },
    Defaults {
        id: 556,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 561,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 562,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 563,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 557,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[
        ],
    },
    Defaults {
        id: 564,
        iparam: &[(0, 1000)],
        dparam: &[(0, 1e-14)],
        internal: &[
        ],
    },
    Defaults {
        id: 565,
        iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
        dparam: &[(0, 1e-14), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 566,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 567,
        iparam: &[(0, 20000), (10, 20)],
        dparam: &[(0, 9.9999999999999995e-07), (3, -0.001), (4, 1.0000000000000001e-09), (5, 0.90000000000000002), (6, 0.66666666666666663)],
        internal: &[
        ],
    },
    Defaults {
        id: 600,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 565,
                iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
                dparam: &[(0, 1e-14), (3, 1.0)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 601,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001)],
        internal: &[
            Defaults {
                id: 550,
                iparam: &[(0, 10), (9, 2), (11, -1), (14, 1), (15, 1), (16, 10)],
                dparam: &[(0, 1e-14), (3, 1.0)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 602,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (2, 10.0), (3, 10000.0), (4, 5.0), (5, 1.0)],
        internal: &[
            Defaults {
                id: 504,
                iparam: &[(0, 200), (3, 100000), (5, 1), (8, 1), (9, 1), (10, 2), (12, 100), (13, 1), (18, -1)],
                dparam: &[(0, 0.001), (3, 1.0)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 603,
        iparam: &[(0, 20000)],
        dparam: &[(0, 0.001), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 604,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 500,
                iparam: &[(0, 1000), (2, 1), (7, 2)],
                dparam: &[(0, 0.0001), (2, 10.0)],
                internal: &[
                    Defaults {
                        id: 564,
                        iparam: &[(0, 50)],
                        dparam: &[(0, 1e-14)],
                        internal: &[
                        ],
                    },
                ],
            },
        ],
    },
    Defaults {
        id: 605,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 565,
                iparam: &[(0, 10), (9, 3), (12, 10), (14, 2), (15, 1), (16, 100)],
                dparam: &[(0, 1e-14), (3, 1.0)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 606,
        iparam: &[(0, 200), (3, 100000), (5, 1), (8, 1), (9, 1), (10, 2), (12, 100), (13, 1), (18, -1)],
        dparam: &[(0, 0.001), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 607,
        iparam: &[(0, 200), (8, 1), (10, 1), (12, 1000), (18, -1)],
        dparam: &[(0, 1e-10), (3, 1.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 608,
        iparam: &[(0, 10000)],
        dparam: &[(0, 1.0000000000000001e-09)],
        internal: &[
        ],
    },
    Defaults {
        id: 609,
        iparam: &[(0, 10000)],
        dparam: &[(0, 1.0000000000000001e-09)],
        internal: &[
        ],
    },
    Defaults {
        id: 610,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 611,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 612,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (2, 2.0)],
        internal: &[
            Defaults {
                id: 1203,
                iparam: &[(0, 1000), (9, 2), (10, 2)],
                dparam: &[(0, 9.9999999999999995e-07), (3, 1.0), (4, 0.999), (5, 2.0), (6, 10.0)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 613,
        iparam: &[(0, 20000), (8, 50), (11, 2), (12, 1)],
        dparam: &[(0, 9.9999999999999995e-07), (3, 0.10000000000000001), (4, 0.999), (5, 2.0), (6, 10.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 614,
        iparam: &[(0, 20000), (11, 2), (12, 1)],
        dparam: &[(0, 9.9999999999999995e-07), (3, 1.0), (4, 0.999), (5, 2.0), (6, 2.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 615,
        iparam: &[(0, 200), (11, 1), (15, 1)],
        dparam: &[(0, 1e-08), (7, 1.0000000000000001e-05), (8, 3.0), (9, 1.0), (10, 0.80000000000000004), (11, 0.089999999999999997)],
        internal: &[
        ],
    },
    Defaults {
        id: 3000,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 3002,
                iparam: &[(0, 1000), (10, 1)],
                dparam: &[(0, 9.9999999999999998e-13)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 3001,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 3002,
        iparam: &[(0, 1000), (10, 1)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 3003,
        iparam: &[(0, 20000), (11, 2), (12, 1)],
        dparam: &[(0, 9.9999999999999995e-07), (3, 1.0), (4, 0.999), (5, 2.0), (6, 2.0)],
        internal: &[
        ],
    },
    Defaults {
        id: 4000,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 3002,
                iparam: &[(0, 1000), (10, 1)],
                dparam: &[(0, 9.9999999999999998e-13)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 4001,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 4002,
        iparam: &[(0, 1000), (10, 1)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 5000,
        iparam: &[(0, 1000), (2, 1), (7, 2)],
        dparam: &[(0, 0.0001), (2, 10.0)],
        internal: &[
            Defaults {
                id: 3002,
                iparam: &[(0, 1000), (10, 1)],
                dparam: &[(0, 9.9999999999999998e-13)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 1000,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 1001,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 1002,
        iparam: &[(0, 20000), (9, 100)],
        dparam: &[(0, 0.001), (4, 1.0), (8, 0.80000000000000004)],
        internal: &[
        ],
    },
    Defaults {
        id: 1020,
        iparam: &[(0, 1000), (5, 1), (10, 3)],
        dparam: &[(0, 1e-10), (2, 9.9999999999999998e-17)],
        internal: &[
        ],
    },
    Defaults {
        id: 1021,
        iparam: &[(0, 100), (5, 1)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
            Defaults {
                id: 306,
                iparam: &[(0, 10000)],
                dparam: &[(0, 9.9999999999999998e-13)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 1022,
        iparam: &[(0, 10000)],
        dparam: &[(0, 9.9999999999999998e-13)],
        internal: &[
        ],
    },
    Defaults {
        id: 1100,
        iparam: &[(0, 1000)],
        dparam: &[(0, 0.0001), (8, 1.0)],
        internal: &[
            Defaults {
                id: 1151,
                iparam: &[(0, 1000)],
                dparam: &[(0, 9.9999999999999998e-17)],
                internal: &[
                ],
            },
        ],
    },
    Defaults {
        id: 1106,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 1107,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 1150,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-17)],
        internal: &[
        ],
    },
    Defaults {
        id: 1151,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-17)],
        internal: &[
        ],
    },
    Defaults {
        id: 1152,
        iparam: &[(0, 1000)],
        dparam: &[(0, 9.9999999999999998e-17)],
        internal: &[
        ],
    },
    Defaults {
        id: 1200,
        iparam: &[(0, 20000), (10, 20)],
        dparam: &[(0, 9.9999999999999995e-07), (3, -0.001), (4, 1.0000000000000001e-09), (5, 0.90000000000000002), (6, 0.66666666666666663)],
        internal: &[
        ],
    },
    Defaults {
        id: 1201,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 1202,
        iparam: &[(0, 20000), (7, 1)],
        dparam: &[(0, 0.001), (3, -1.0), (4, 0.66666666666666663), (5, 1.5), (6, 0.90000000000000002), (7, 0.29999999999999999)],
        internal: &[
        ],
    },
    Defaults {
        id: 1203,
        iparam: &[(0, 20000), (9, 2), (10, 2)],
        dparam: &[(0, 9.9999999999999995e-07), (3, 1.0), (4, 0.999), (5, 2.0), (6, 10.0)],
        internal: &[
        ],
    },
];
