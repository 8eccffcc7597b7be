//! Helpers shared by integration tests.
#![allow(dead_code)]

pub mod extremes;
pub mod global;
pub mod honesty;
