//! Certificates: the plain-data format ([`format`]) read by the independent [`crate::checker`], and
//! the producer ([`produce`]) that writes a certificate for every verdict of the pipeline.
//!
//! Architecture invariant: the format imports nothing from the crate; the producer may import every
//! exact layer but never geometry or output. The checker imports only the format.

pub mod format;
pub mod produce;

pub use format::*;
pub use produce::*;
