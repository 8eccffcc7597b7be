//! The defaults `solver_options_create` returns: Siconos 4.4's for its ids (the generated table;
//! `scripts/siconos-options.sh` and the capi-tests `siconos_options` test compare them with the
//! installed library), fc3d's own one-contact ids written from the core's defaults; and, read
//! back, the core's default configuration of every id fc3d implements.

use std::os::raw::c_int;

use super::*;
use crate::option_tree::delete_contents;
use crate::options::create_options;

struct Reference {
    id: c_int,
    iparam: &'static [(usize, c_int)],
    dparam: &'static [(usize, f64)],
    internal: &'static [c_int],
}

/// fc3d's own one-contact solvers (ids Siconos does not use).
const FC3D_OWN: &[Reference] = &[
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
];

fn reference(id: c_int) -> &'static Reference {
    FC3D_OWN
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
fn defaults_of_fc3d_own_ids_are_the_local_solvers() {
    for r in FC3D_OWN {
        check_against_reference(&defaults(r.id).expect("defaults"));
    }
}

/// Every id of Siconos' table is created as the table says, internal solvers included; an id
/// of neither Siconos nor fc3d is refused.
#[test]
fn defaults_are_siconos_table() {
    fn same(e: &Encoded, d: &siconos_table::Defaults) {
        assert_eq!(e.id, d.id);
        for k in 0..SIZE {
            let i = d
                .iparam
                .iter()
                .find(|(j, _)| *j == k)
                .map_or(0, |(_, v)| *v);
            let f = d.dparam.iter().find(|(j, _)| *j == k).map_or(
                if k == DPARAM_RESIDU {
                    f64::INFINITY
                } else {
                    0.0
                },
                |(_, v)| *v,
            );
            assert_eq!(e.iparam[k], i, "iparam[{k}] of {}", d.id);
            assert_eq!(
                e.dparam[k].to_bits(),
                f.to_bits(),
                "dparam[{k}] of {}",
                d.id
            );
        }
        assert_eq!(
            e.internal.len(),
            d.internal.len(),
            "internal solvers of {}",
            d.id
        );
        for (e, d) in e.internal.iter().zip(d.internal) {
            same(e, d);
        }
    }
    let mut n = 0;
    for d in siconos_table::TABLE {
        same(&defaults(d.id).expect("defaults"), d);
        n += 1;
    }
    // Every id of Friction_cst.h's FRICTION_SOLVER, and the VI, SOCLCP and ConvexQP solvers.
    assert_eq!(n, 83, "{n} ids");
    for id in [500, 521, 523, 600, 615, 3000, 5000] {
        assert!(siconos::ids().any(|i| i == id), "{id}");
    }
    assert!(defaults(4242).is_err());
}

/// What the C API reads from its own defaults (Siconos') is the core's default configuration of
/// the id, except where the core's preset departs from Siconos 4.4, listed here: Siconos' single
/// Newton step of 520, ACLMFP's 10000 inner SOCLCP sweeps (the core's preset: 1000) and ADMM's
/// given initial rho (the core's preset: from the eigenvalues).
#[test]
fn defaults_read_back_as_the_cores() {
    let mut failures = Vec::new();
    for method in Method::presets() {
        let id = method.siconos_id();
        if Method::preset(&id.to_string()) != Some(method) {
            continue; // a second preset of the same id (NSN-JM, PROX-NSGS): not a default
        }
        let mut expected = SolverConfig::new(method);
        match &mut expected.method {
            Method::Nsn(_) if id == 520 => expected.max_iter = 1,
            Method::Aclm(a) => a.inner_max_iter = 10000,
            Method::Admm(a) => a.initial_rho = fc3d_core::AdmmInitialRho::Given,
            _ => {}
        }
        let o = create_options(id).expect("created");
        let read = unsafe { config_from_c(&*o) };
        unsafe {
            delete_contents(o);
            crate::alloc::c_free(o);
        }
        match read {
            Ok(read) if read == expected => {}
            Ok(read) => failures.push(format!("id {id}: read {read:?}\n  core {expected:?}")),
            Err(e) => failures.push(format!("id {id}: {}", e.message)),
        }
    }
    for kind in LocalSolverKind::ALL {
        let o = create_options(kind.siconos_id()).expect("created");
        let read = unsafe { local::read(&*o) };
        unsafe {
            delete_contents(o);
            crate::alloc::c_free(o);
        }
        let expected = fc3d_core::LocalSolverOptions::new(kind);
        match read {
            Ok(read) if read == expected => {}
            Ok(read) => failures.push(format!("{kind:?}: read {read:?}\n  core {expected:?}")),
            Err(e) => failures.push(format!("{kind:?}: {}", e.message)),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
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

/// Siconos' internal solvers of PFP, ACLMFP and SOCLCP are read (PFP's tangent solver by its id,
/// each part bounded by its own limit); others are refused with their name.
#[test]
fn siconos_internal_solvers_of_the_fixed_points() {
    unsafe {
        let o = create_options(522).expect("created");
        let normal = *(*o).internalSolvers;
        let tangent = *(*o).internalSolvers.add(1);
        *(*normal).iparam = 7;
        (*tangent).solverId = 1200;
        *(*tangent).iparam = 9;
        let Method::Pfp(pfp) = config_from_c(&*o).expect("read").method else {
            panic!("not PFP")
        };
        assert_eq!(pfp.tangent, fc3d_core::TrescaInnerSolver::ProjectedGradient);
        assert_eq!((pfp.normal_max_iter, pfp.inner_max_iter), (7, 9));
        (*tangent).solverId = 1202;
        let e = config_from_c(&*o).expect_err("VI EG tangent solver");
        assert!(e.message.contains("1202 (CONVEXQP VI EG)"), "{}", e.message);
        delete_contents(o);
        crate::alloc::c_free(o);

        let o = create_options(516).expect("created");
        let soclcp = *(*o).internalSolvers;
        *(*soclcp).iparam = 123;
        let Method::Aclm(aclm) = config_from_c(&*o).expect("read").method else {
            panic!("not ACLMFP")
        };
        assert_eq!(aclm.inner_max_iter, 123);
        (*soclcp).solverId = 1107;
        assert!(
            config_from_c(&*o).is_ok(),
            "SOCLCP VI EG as the inner solver"
        );
        (*soclcp).solverId = 1150;
        let e = config_from_c(&*o).expect_err("a one-cone solver as the SOCLCP solver");
        assert!(e.message.contains("1150"), "{}", e.message);
        delete_contents(o);
        crate::alloc::c_free(o);

        let o = create_options(517).expect("created");
        assert!(config_from_c(&*o).is_ok());
        (**(*o).internalSolvers).solverId = 1150;
        let e = config_from_c(&*o).expect_err("another one-cone solver");
        assert!(e.message.contains("1150"), "{}", e.message);
        delete_contents(o);
        crate::alloc::c_free(o);
    }
}

/// NSGS's decomposition and threads slots (fc3d's, unused by Siconos): read into the core's
/// options, unknown codes refused with their slot; the sequential default needs no slot set.
#[test]
fn nsgs_decomposition_and_threads_slots() {
    use fc3d_core::Decomposition;
    let o = create_options(500).expect("created");
    let decomposition = crate::FC3D_IPARAM_NSGS_DECOMPOSITION as usize;
    let threads = crate::FC3D_IPARAM_NSGS_THREADS as usize;
    unsafe {
        let read = |o: *mut SolverOptions| match config_from_c(&*o).expect("read").method {
            Method::Nsgs(n) => (n.decomposition, n.threads),
            other => panic!("{other:?}"),
        };
        assert_eq!(read(o), (Decomposition::Sequential, 0));
        for (code, expected) in [
            (crate::FC3D_NSGS_COLOURED, Decomposition::Coloured),
            (crate::FC3D_NSGS_ISLANDS, Decomposition::Islands),
        ] {
            *(*o).iparam.add(decomposition) = code;
            *(*o).iparam.add(threads) = 3;
            assert_eq!(read(o), (expected, 3));
        }
        *(*o).iparam.add(decomposition) = 7;
        let e = config_from_c(&*o).expect_err("unknown decomposition");
        assert!(e.message.contains("iparam[15]"), "{}", e.message);
        *(*o).iparam.add(decomposition) = crate::FC3D_NSGS_COLOURED;
        *(*o).iparam.add(threads) = -1;
        assert!(config_from_c(&*o).is_err());
        *(*o).iparam.add(threads) = 0;
        // Freezing needs the sequential order: refused, naming the decomposition slot.
        *(*o).iparam.add(19) = 2;
        let e = config_from_c(&*o).expect_err("freezing with colours");
        assert!(e.message.contains("iparam[15]"), "{}", e.message);
        delete_contents(o);
        crate::alloc::c_free(o);
    }
}

/// The global ids' defaults read back are the core's presets of those ids (what the CLI and the
/// native entry's NULL settings run): one set of Siconos defaults, not two.
#[test]
fn global_defaults_read_back_are_the_core_presets() {
    use fc3d_core::global::GlobalMethod;
    for preset in GlobalMethod::presets() {
        let id = preset.siconos_id();
        let o = create_options(id).unwrap();
        let read = unsafe { global::global_config_from_c(&*o) };
        unsafe {
            delete_contents(o);
            crate::alloc::c_free(o);
        }
        let config = read.unwrap_or_else(|e| panic!("{id}: {}", e.message));
        assert_eq!(config.method, preset, "{id}");
        let (tol, max_iter) = preset.default_limits();
        assert_eq!((config.tolerance, config.max_iter), (tol, max_iter), "{id}");
    }
}
