//! The runtime as the generated crate holds it (`nmeaspec::runtime`), without the generated
//! sentence modules: its unit tests run here, on their own.

#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]

#[path = "src/mod.rs"]
pub mod runtime;
