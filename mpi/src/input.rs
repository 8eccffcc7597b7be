//! One rank's arguments, checked before anything is exchanged: sizes, pointers, the structure
//! of its block rows, finite values, friction coefficients, and the settings (NSGS only).

use fc3d::{
    settings_config, CError, CResult, Fc3dSettings, FC3D_ERR_INVALID_OPTION,
    FC3D_ERR_INVALID_PROBLEM, FC3D_ERR_INVALID_SIZE, FC3D_ERR_INVALID_STORAGE, FC3D_ERR_NON_FINITE,
    FC3D_ERR_NULL_POINTER, FC3D_ERR_UNSUPPORTED_SOLVER,
};
use fc3d_core::contract::ErrorEvaluation;
use fc3d_core::{Acceleration, ContactOrder, Decomposition, Method, NsgsOptions, Rescaling};
use fc3d_core::{Limits, SolverConfig};

/// `len` values at `p` (NULL is accepted for an empty array).
unsafe fn slice<'a, T>(p: *const T, len: usize, what: &str) -> CResult<&'a [T]> {
    if len == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(CError::new(
            FC3D_ERR_NULL_POINTER,
            format!("{what} is NULL"),
        ));
    }
    Ok(std::slice::from_raw_parts(p, len))
}

fn count(v: i64, what: &str) -> CResult<usize> {
    usize::try_from(v)
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, format!("{what} = {v} is negative")))
}

fn times(n: usize, k: usize, what: &str) -> CResult<usize> {
    n.checked_mul(k)
        .ok_or_else(|| CError::new(FC3D_ERR_INVALID_SIZE, format!("{what} = {n} is too large")))
}

/// One rank's problem rows as the host gave them (borrowed for the call).
pub struct LocalRows<'a> {
    /// Global id of each of this rank's contacts, in the host's order.
    pub ids: &'a [i64],
    /// `ids.len() + 1` offsets into `cols` and `blocks`.
    pub row_ptr: &'a [i64],
    /// Global contact id of each block's column.
    pub cols: &'a [i64],
    /// 9 values per block, column-major.
    pub blocks: &'a [f64],
    pub q: &'a [f64],
    pub mu: &'a [f64],
    /// The warm start.
    pub r: &'a [f64],
}

impl LocalRows<'_> {
    pub fn n_local(&self) -> usize {
        self.ids.len()
    }

    /// Host block positions of row `k`.
    pub fn row(&self, k: usize) -> std::ops::Range<usize> {
        self.row_ptr[k] as usize..self.row_ptr[k + 1] as usize
    }
}

/// Reads and checks one rank's arguments (no communication).
///
/// # Safety
/// Non-NULL pointers point to arrays of the sizes the arguments give.
#[allow(clippy::too_many_arguments)]
pub unsafe fn read_rows<'a>(
    n_local: i64,
    contact_ids: *const i64,
    n_blocks: i64,
    block_row_ptr: *const i64,
    block_col_ids: *const i64,
    blocks: *const f64,
    q: *const f64,
    mu: *const f64,
    r: *const f64,
    u: *const f64,
) -> CResult<LocalRows<'a>> {
    let n = count(n_local, "n_local")?;
    let nb = count(n_blocks, "n_blocks")?;
    let n3 = times(n, 3, "n_local")?;
    let rows = LocalRows {
        ids: slice(contact_ids, n, "contact_ids")?,
        row_ptr: slice(block_row_ptr, times(n, 1, "n_local")? + 1, "block_row_ptr")?,
        cols: slice(block_col_ids, nb, "block_col_ids")?,
        blocks: slice(blocks, times(nb, 9, "n_blocks")?, "blocks")?,
        q: slice(q, n3, "q")?,
        mu: slice(mu, n, "mu")?,
        r: slice(r, n3, "r")?,
    };
    slice(u, n3, "u")?;
    let rp = rows.row_ptr;
    if rp[0] != 0 || rp[n] != n_blocks {
        return Err(CError::new(
            FC3D_ERR_INVALID_STORAGE,
            format!(
                "block_row_ptr must run from 0 to n_blocks = {n_blocks}: it runs from {} to {}",
                rp[0], rp[n]
            ),
        ));
    }
    if let Some(k) = (0..n).find(|&k| rp[k] > rp[k + 1]) {
        return Err(CError::new(
            FC3D_ERR_INVALID_STORAGE,
            format!("block_row_ptr decreases at row {k}"),
        ));
    }
    if let Some(&id) = rows.ids.iter().chain(rows.cols).find(|&&id| id < 0) {
        return Err(CError::new(
            FC3D_ERR_INVALID_STORAGE,
            format!("contact id {id} is negative"),
        ));
    }
    let mut sorted = rows.ids.to_vec();
    sorted.sort_unstable();
    if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
        return Err(CError::new(
            FC3D_ERR_INVALID_STORAGE,
            format!("contact id {} is given twice", w[0]),
        ));
    }
    for (k, &id) in rows.ids.iter().enumerate() {
        if !rows.row(k).any(|b| rows.cols[b] == id) {
            return Err(CError::new(
                FC3D_ERR_INVALID_PROBLEM,
                format!("contact {id} (row {k}) has no diagonal block"),
            ));
        }
    }
    let finite = |v: &[f64], what: &str, per: usize| -> CResult<()> {
        match v.iter().position(|x| !x.is_finite()) {
            None => Ok(()),
            Some(i) => Err(CError::new(
                FC3D_ERR_NON_FINITE,
                format!(
                    "{what}[{i}] = {} (entry {} of {what}) is not finite",
                    v[i],
                    i / per
                ),
            )),
        }
    };
    finite(rows.blocks, "blocks", 9)?;
    finite(rows.q, "q", 3)?;
    finite(rows.mu, "mu", 1)?;
    finite(rows.r, "r", 3)?;
    if let Some(k) = rows.mu.iter().position(|&m| m < 0.0) {
        return Err(CError::new(
            FC3D_ERR_INVALID_PROBLEM,
            format!("mu of contact {} is {} < 0", rows.ids[k], rows.mu[k]),
        ));
    }
    Ok(rows)
}

/// What a distributed run takes from the settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSettings {
    pub limits: Limits,
    pub nsgs: NsgsOptions,
}

/// The NSGS settings of `settings` (NULL: Siconos' defaults), refusing what is not distributed.
///
/// # Safety
/// `settings` is NULL or made by `fc3d_settings_new` and not yet freed.
pub unsafe fn run_settings(settings: *const Fc3dSettings) -> CResult<RunSettings> {
    let config: SolverConfig = settings_config(settings)?;
    config.validate()?;
    let nsgs = match config.method {
        Method::Nsgs(o) => o,
        other => {
            return Err(CError::new(
                FC3D_ERR_UNSUPPORTED_SOLVER,
                format!(
                    "solver {} ({}) is not distributed: fc3d_mpi solves with NSGS (500) only",
                    other.siconos_id(),
                    other.label()
                ),
            ))
        }
    };
    let refuse = |what: &str| -> CResult<RunSettings> {
        Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!("the distributed NSGS does not support {what}"),
        ))
    };
    if config.rescaling != Rescaling::None {
        return refuse("rescaling (iparam[3])");
    }
    if nsgs.order != ContactOrder::Natural {
        return refuse("a shuffled contact order (iparam[5])");
    }
    if nsgs.freezing.is_some_and(|k| k > 0) {
        return refuse("freezing (iparam[19])");
    }
    if nsgs.error_evaluation == ErrorEvaluation::DumontCriterion {
        return refuse("Dumont's criterion (iparam[7] = 20)");
    }
    if nsgs.acceleration != Acceleration::None {
        return refuse("Anderson acceleration");
    }
    if nsgs.decomposition == Decomposition::Islands {
        return refuse("the islands decomposition (iparam[15] = 2)");
    }
    Ok(RunSettings {
        limits: Limits {
            tolerance: config.tolerance,
            max_iter: config.max_iter,
            time_budget: config.time_budget,
        },
        nsgs,
    })
}

/// A fingerprint of the settings, equal on two ranks only when their settings are (all ranks
/// must run the same loop).
pub fn fingerprint(s: &RunSettings) -> i64 {
    // FNV-1a over the settings' Debug text (floats print exactly: shortest round-trip form).
    let text = format!("{s:?}");
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    (h >> 1) as i64
}
