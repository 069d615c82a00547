//! `ssdo`: a deferred wgpu renderer for screen-space directional occlusion (Ritschel, Grosch &
//! Seidel 2009), with screen-space ambient occlusion beside it for comparison.
//!
//! The binary (`src/main.rs`) is a thin command line over this library; the tests drive the same
//! library headlessly on a software adapter.

pub mod app;
pub mod budget;
pub mod compare;
pub mod error;
pub mod gpu;
pub mod guard;
pub mod headless;
pub mod knobs;
pub mod output;
pub mod preset;
pub mod reference;
pub mod render;
pub mod report;
pub mod reproduce;
pub mod scene;
pub mod shaders;
pub mod spec;
pub mod text;
pub mod tune;

pub use error::{Error, Result};
