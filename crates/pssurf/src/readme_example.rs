//! Keeps the README's library example compiling and true.
#![doc = include_str!("../../../README.md")]
