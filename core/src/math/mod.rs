//! Fixed-size kernels every layer above uses: 3-vectors and 3x3 matrices written by hand, the
//! projections on the Coulomb cone, its dual, disks and cylinders, the rolling-friction cone
//! (`rolling`), the Jordan algebra of the second-order cone (`jordan`), the constants of the
//! self-adaptive step rule, and the extreme eigenvalues of a symmetric operator (`spectrum`).

pub mod cone;
pub mod gmres;
pub mod jordan;
pub mod linalg;
pub mod lu_cost;
pub mod lu_fill;
pub mod rolling;
pub mod sparse_cholesky;
pub mod sparse_lu;
pub mod spectrum;
pub mod step;
