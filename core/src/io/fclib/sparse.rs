//! Reading a sparse matrix group of CSparse fields (triplets, compressed columns or compressed
//! rows; see the parent module's documentation).

use hdf5_metno as hdf5;
use hdf5_metno::types::TypeDescriptor;

use super::reader::Reader;
use crate::alloc::{reserve, try_collect};
use crate::error::Fc3dError;

/// A sparse matrix read from a file: its size and `(row, column, value)` entries (duplicates not
/// yet summed).
pub(super) struct SparseEntries {
    pub(super) nrows: usize,
    pub(super) ncols: usize,
    pub(super) entries: Vec<(usize, usize, f64)>,
}

impl Reader {
    /// Converts a stored index to `usize`, checking `0 <= v < bound`.
    fn index(
        &self,
        path: &str,
        k: usize,
        v: i64,
        bound: usize,
        what: &str,
    ) -> Result<usize, Fc3dError> {
        usize::try_from(v)
            .ok()
            .filter(|&u| u < bound)
            .ok_or_else(|| {
                self.invalid(format!(
                    "{path}[{k}] = {v}: {what} index out of range 0..{bound}"
                ))
            })
    }

    /// Checks a compressed pointer array (`outer + 1` non-decreasing entries from 0, the last one
    /// within the index and value arrays) and returns it as `usize`.
    fn pointers(
        &self,
        path: &str,
        p: &[i64],
        outer: usize,
        n_idx: usize,
        n_x: usize,
    ) -> Result<Vec<usize>, Fc3dError> {
        if p.len() != outer + 1 {
            return Err(self.invalid(format!(
                "{path}/p has {} entries, expected {} for a compressed matrix",
                p.len(),
                outer + 1
            )));
        }
        if p[0] != 0 {
            return Err(self.invalid(format!("{path}/p[0] = {}, expected 0", p[0])));
        }
        if let Some(k) = p.windows(2).position(|w| w[1] < w[0]) {
            return Err(self.invalid(format!(
                "{path}/p decreases at {}: {} then {}",
                k + 1,
                p[k],
                p[k + 1]
            )));
        }
        let last = p[outer] as u64; // >= 0: starts at 0 and never decreases
        if last > n_idx as u64 || last > n_x as u64 {
            return Err(self.invalid(format!(
                "{path}/p ends at {last} but i has {n_idx} and x {n_x} entries"
            )));
        }
        try_collect(
            p.iter().map(|&v| v as usize),
            &format!("{}: {path}/p", self.label),
        )
    }

    /// Reads the sparse matrix group `ppath/name` (triplets, CSC or CSR; see the module doc).
    pub(super) fn matrix(
        &self,
        parent: &hdf5::Group,
        ppath: &str,
        name: &str,
    ) -> Result<SparseEntries, Fc3dError> {
        let g = self.group(parent, ppath, name)?;
        let path = format!("{ppath}/{name}");
        let nrows = self.size(&g, &path, "m")?;
        let ncols = self.size(&g, &path, "n")?;
        let nz = self.int_scalar(&g, &path, "nz")?;
        // nzmax is informational (Siconos writes more or fewer values than it says).
        self.int_scalar(&g, &path, "nzmax")?;
        let p = self.ints(&g, &path, "p")?;
        let idx = self.ints(&g, &path, "i")?;
        let x = {
            let (ds, xpath) = self.dataset(&g, &path, "x")?;
            match self.type_of(&ds, &xpath)? {
                TypeDescriptor::Float(_) => {}
                other => {
                    return Err(self.invalid(format!(
                        "{xpath} holds {other} values, expected floating-point numbers"
                    )))
                }
            }
            ds.read_raw::<f64>()
                .map_err(|e| self.hdf5_error(&xpath, e))?
        };
        let mut entries = Vec::new();
        match nz {
            nz if nz >= 0 => {
                let count = nz as u64;
                for (field, len) in [("p", p.len()), ("i", idx.len()), ("x", x.len())] {
                    if (len as u64) < count {
                        return Err(self.invalid(format!(
                            "{path}/{field} has {len} entries, fewer than nz = {nz} triplets"
                        )));
                    }
                }
                let count = count as usize;
                reserve(&mut entries, count, &format!("{}: {path}", self.label))?;
                for k in 0..count {
                    let row = self.index(&format!("{path}/i"), k, idx[k], nrows, "row")?;
                    let col = self.index(&format!("{path}/p"), k, p[k], ncols, "column")?;
                    entries.push((row, col, x[k]));
                }
                self.check_finite(&format!("{path}/x"), &x[..count])?;
            }
            -1 | -2 => {
                let by_columns = nz == -1;
                let (outer, inner, inner_name) = if by_columns {
                    (ncols, nrows, "row")
                } else {
                    (nrows, ncols, "column")
                };
                let ptr = self.pointers(&path, &p, outer, idx.len(), x.len())?;
                reserve(&mut entries, ptr[outer], &format!("{}: {path}", self.label))?;
                let ipath = format!("{path}/i");
                for o in 0..outer {
                    for k in ptr[o]..ptr[o + 1] {
                        let in_ = self.index(&ipath, k, idx[k], inner, inner_name)?;
                        entries.push(if by_columns {
                            (in_, o, x[k])
                        } else {
                            (o, in_, x[k])
                        });
                    }
                }
                self.check_finite(&format!("{path}/x"), &x[..ptr[outer]])?;
            }
            _ => {
                return Err(self.invalid(format!(
                    "{path}/nz = {nz}: expected a triplet count (>= 0), -1 (compressed columns) \
                     or -2 (compressed rows)"
                )))
            }
        }
        Ok(SparseEntries {
            nrows,
            ncols,
            entries,
        })
    }
}
