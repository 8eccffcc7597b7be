//! The descriptive part of an FCLIB problem file (its `info` group), in every build.

/// What an FCLIB file says about its problem besides the numbers: the `info` group of
/// `/fclib_local` (or `/fclib_global`). Every field is optional; `None` is not written.
///
/// * `title`, `description`, `math_info`: the FCLIB strings (`fclib_info`), stored as scalar
///   fixed-length, NUL-terminated C strings (`H5LTmake_dataset_string`); they may not contain a
///   NUL byte.
/// * `number_of_degrees_of_freedom`: the integer attribute `numberOfDegreeOfFreedom` that
///   Siconos' `frictionContact_fclib_write` adds to the info group (its `ndof` argument, the
///   size of the global problem the local one was reduced from; Siconos writes -1 or 0 when it
///   does not know it).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct FclibInfo {
    pub title: Option<String>,
    pub description: Option<String>,
    pub math_info: Option<String>,
    pub number_of_degrees_of_freedom: Option<i32>,
}
