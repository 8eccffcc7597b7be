//! Siconos 4.4's defaults as data: what its `solver_options_create(id)` returns for every solver
//! id of the friction headers (`siconos_table.rs`, generated from the installed library), turned
//! into the options fc3d allocates. fc3d's `solver_options_create` returns exactly these, so a
//! host or a Siconos test that edits a few slots of the defaults runs what it would run with
//! Siconos; `tests.rs` checks that, read back, they are the core's default configurations.

use std::os::raw::c_int;

use super::siconos_table::{Defaults, TABLE};
use super::Encoded;

impl Defaults {
    fn encode(&self) -> Encoded {
        let mut e = Encoded::new(self.id);
        for &(k, v) in self.iparam {
            e.iparam[k] = v;
        }
        for &(k, v) in self.dparam {
            e.dparam[k] = v;
        }
        e.internal = self.internal.iter().map(Defaults::encode).collect();
        e
    }
}

/// Siconos' defaults of `id`, if `id` is one of the solver ids of the friction headers.
pub(super) fn defaults(id: c_int) -> Option<Encoded> {
    TABLE.iter().find(|d| d.id == id).map(Defaults::encode)
}

/// The ids Siconos' defaults are known for, in the headers' order.
#[cfg(test)]
pub(super) fn ids() -> impl Iterator<Item = c_int> {
    TABLE.iter().map(|d| d.id)
}
