//! The solver families, one module each, in the order of the seed paper's tables: nonsmooth
//! Gauss-Seidel, the VI / fixed-point projection family, nonsmooth Newton, the proximal point
//! method, the optimization-based fixed points (Tresca, Panagiotopoulos, ACLM, and the SOCLCP
//! relaxation they build on) and ADMM. Each family's settings implement
//! [`crate::contract::Family`]; `config` dispatches to them.

pub mod aclm;
pub mod admm;
pub mod auto;
pub mod nsgs;
pub mod nsn;
pub mod pfp;
pub mod planar;
pub mod prox;
pub mod rolling;
pub mod soclcp;
pub mod tresca;
pub mod vi;
