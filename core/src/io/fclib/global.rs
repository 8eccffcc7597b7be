//! `/fclib_global`: read into a [`GlobalProblem`] (M and H in compressed rows), reduced to the
//! local form for [`super::read_fclib_file`] through the problem's own reduction (M factored
//! block by block, [`crate::matrix::HForm`]), and written as Siconos'
//! `globalFrictionContact_fclib_write` writes it (M and H as triplets); a global rolling
//! problem is written as FCLIB's `fclib_write_global_rolling` lays it out
//! (`/fclib_global_rolling`, with `vectors/mu_r`).

use std::path::Path;

use hdf5_metno as hdf5;

use super::reader::Reader;
use super::write::{floats, ints, replace_file, string_checks};
use crate::alloc::{bytes_of, ensure_headroom};
use crate::error::Fc3dError;
use crate::io::info::FclibInfo;
use crate::matrix::CsrMatrix;
use crate::problem::{FrictionProblem, GlobalProblem, GlobalRollingProblem};

impl Reader {
    /// The global problem of the group `/fclib_global`.
    pub(super) fn read_global(&self, g: &hdf5::Group) -> Result<GlobalProblem<'static>, Fc3dError> {
        let gp = "/fclib_global";
        self.spacedim(g, gp)?;
        if g.link_exists("G") {
            return Err(Fc3dError::Unsupported(format!(
                "{}: {gp}/G present: global problems with bilateral constraints (G, b) are not \
                 supported",
                self.label
            )));
        }
        let m = self.matrix(g, gp, "M")?;
        if m.nrows != m.ncols {
            return Err(self.invalid(format!(
                "{gp}/M is {}x{}, expected a square matrix",
                m.nrows, m.ncols
            )));
        }
        let ndof = m.nrows;
        let h = self.matrix(g, gp, "H")?;
        if h.nrows != ndof {
            return Err(self.invalid(format!("{gp}/H has {} rows but M has {ndof}", h.nrows)));
        }
        let nc = self.contacts(&format!("{gp}/H"), h.ncols)?;
        let vp = format!("{gp}/vectors");
        let v = self.group(g, gp, "vectors")?;
        let f = self.floats(&v, &vp, "f")?;
        self.check_len(&format!("{vp}/f"), f.len(), ndof, "the size of M")?;
        let w = self.floats(&v, &vp, "w")?;
        self.check_len(&format!("{vp}/w"), w.len(), h.ncols, "the columns of H")?;
        let mu = self.floats(&v, &vp, "mu")?;
        self.check_len(&format!("{vp}/mu"), mu.len(), nc, "one per contact")?;
        // `CsrMatrix::from_triplets` allocates without a fallible path: probe first.
        for (name, rows, entries) in [("M", ndof, &m.entries), ("H", ndof, &h.entries)] {
            let bytes = bytes_of(rows.saturating_add(1).saturating_add(entries.len() * 3), 8);
            ensure_headroom(bytes, &format!("the compressed rows of {gp}/{name}"))?;
        }
        let m = CsrMatrix::from_triplets(ndof, ndof, &m.entries)?;
        let h = CsrMatrix::from_triplets(ndof, h.ncols, &h.entries)?;
        GlobalProblem::new(m, h, f, w, mu).map_err(|e| match e {
            Fc3dError::OutOfMemory { .. } => e,
            e => self.invalid(format!("{gp}: {e}")),
        })
    }

    /// The local problem of `/fclib_global`: W = H^T M^-1 H (3x3 sparse-block, every diagonal
    /// block and every block with a non-zero entry), q = H^T M^-1 f + w. A singular M is an
    /// [`Fc3dError::InvalidStructure`] naming the file.
    pub(super) fn read_global_reduced(
        &self,
        g: &hdf5::Group,
    ) -> Result<FrictionProblem<'static>, Fc3dError> {
        let global = self.read_global(g)?;
        let reduced = global
            .operator()
            .and_then(|mut operator| global.reduce(&mut operator));
        reduced.map_err(|e| match e {
            Fc3dError::OutOfMemory { .. } => e,
            e => self.invalid(format!("reducing the global problem: {e}")),
        })
    }
}

/// Writes `problem` to `path` as an FCLIB global problem, as Siconos'
/// `globalFrictionContact_fclib_write` does: `/fclib_global` with `spacedim`, M and H as
/// triplets (their stored entries), `vectors/f` (q), `vectors/w` (b), `vectors/mu`, and the info
/// group from `info` (no G, no `vectors/b`). The file is replaced, through a temporary file
/// renamed at the end (see [`super::write_fclib_file`]): on any error `path` is left as it was.
/// Errors: matrices too large for FCLIB's 32-bit indices or an info string with a NUL byte are
/// [`Fc3dError::Unsupported`]; a file that cannot be written is an [`Fc3dError::Io`].
pub fn write_fclib_global_file(
    problem: &GlobalProblem<'_>,
    path: &Path,
    info: &FclibInfo,
) -> Result<(), Fc3dError> {
    write_global_group(path, "fclib_global", problem, None, info)
}

/// Writes a global rolling problem to `path` as FCLIB's `fclib_write_global_rolling` lays it out:
/// `/fclib_global_rolling` with `spacedim` = 5, M and H as triplets, `vectors/f`, `w`, `mu` and
/// `mu_r`, and the info group (the same file handling and errors as
/// [`write_fclib_global_file`]).
pub fn write_fclib_global_rolling_file(
    problem: &GlobalRollingProblem<'_>,
    path: &Path,
    info: &FclibInfo,
) -> Result<(), Fc3dError> {
    write_global_group(
        path,
        "fclib_global_rolling",
        problem.base(),
        Some(problem.mu_r()),
        info,
    )
}

/// Writes the group `name` of a global problem (and its rolling coefficients).
fn write_global_group<const D: usize>(
    path: &Path,
    name: &str,
    problem: &GlobalProblem<'_, D>,
    mu_r: Option<&[f64]>,
    info: &FclibInfo,
) -> Result<(), Fc3dError> {
    let label = path.display().to_string();
    let m = Triplets::of(problem.m(), &label, "M")?;
    let h = Triplets::of(problem.h(), &label, "H")?;
    string_checks(info, &label)?;
    let group = Group {
        name,
        spacedim: D as i32,
        q: problem.q(),
        b: problem.b(),
        mu: problem.mu(),
        mu_r,
    };
    replace_file(path, |file| write_global(file, &group, &m, &h, info))
}

/// What a global group holds besides M and H.
struct Group<'a> {
    name: &'a str,
    spacedim: i32,
    q: &'a [f64],
    b: &'a [f64],
    mu: &'a [f64],
    mu_r: Option<&'a [f64]>,
}

/// A matrix as FCLIB's triplets (`nz` entries: row `i`, column `p`, value `x`).
struct Triplets {
    rows: i32,
    cols: i32,
    p: Vec<i32>,
    i: Vec<i32>,
    x: Vec<f64>,
}

impl Triplets {
    fn of(m: &CsrMatrix, label: &str, name: &str) -> Result<Self, Fc3dError> {
        let int = |v: usize, what: &str| {
            i32::try_from(v).map_err(|_| {
                Fc3dError::Unsupported(format!(
                    "{label}: {what} of {name} ({v}) does not fit FCLIB's 32-bit int indices"
                ))
            })
        };
        let (rows, cols) = (int(m.nrows(), "the rows")?, int(m.ncols(), "the columns")?);
        int(m.nnz(), "the entries")?;
        let what = format!("the triplets of {name}");
        let mut p = crate::error::try_vec(m.nnz(), 0, &what)?;
        let mut i = crate::error::try_vec(m.nnz(), 0, &what)?;
        let mut x = crate::error::try_vec(m.nnz(), 0.0, &what)?;
        let mut k = 0;
        // Rows and columns fit an i32 (checked above).
        m.for_each_entry(|r, c, v| {
            i[k] = r as i32;
            p[k] = c as i32;
            x[k] = v;
            k += 1;
        });
        Ok(Triplets {
            rows,
            cols,
            p,
            i,
            x,
        })
    }
}

/// Writes the global group into a new file. Errors are messages naming the object that failed.
fn write_global(
    file: &hdf5::File,
    g: &Group<'_>,
    m: &Triplets,
    h: &Triplets,
    info: &FclibInfo,
) -> Result<(), String> {
    let root = format!("/{}", g.name);
    let at = |what: &str| {
        let what = format!("{root}/{what}");
        move |e: hdf5::Error| format!("{what}: {e}")
    };
    let global = file.create_group(g.name).map_err(at(""))?;
    ints(&global, "spacedim", &[g.spacedim]).map_err(at("spacedim"))?;
    for (name, t) in [("M", m), ("H", h)] {
        let group = global.create_group(name).map_err(at(name))?;
        let nz = t.x.len() as i32;
        for (field, value) in [("nzmax", nz), ("m", t.rows), ("n", t.cols), ("nz", nz)] {
            ints(&group, field, &[value]).map_err(at(&format!("{name}/{field}")))?;
        }
        ints(&group, "p", &t.p).map_err(at(&format!("{name}/p")))?;
        ints(&group, "i", &t.i).map_err(at(&format!("{name}/i")))?;
        floats(&group, "x", &t.x).map_err(at(&format!("{name}/x")))?;
    }
    let vectors = global.create_group("vectors").map_err(at("vectors"))?;
    floats(&vectors, "f", g.q).map_err(at("vectors/f"))?;
    floats(&vectors, "w", g.b).map_err(at("vectors/w"))?;
    floats(&vectors, "mu", g.mu).map_err(at("vectors/mu"))?;
    if let Some(mu_r) = g.mu_r {
        floats(&vectors, "mu_r", mu_r).map_err(at("vectors/mu_r"))?;
    }
    let info_group = global.create_group("info").map_err(at("info"))?;
    super::info_group::write_info(&info_group, info).map_err(|e| format!("{root}/{e}"))
}
