//! The library's error type. Every failure a user can cause (a bad path, a malformed model, an
//! incomplete sky, a size the adapter cannot hold) becomes one line that names the file or the
//! setting and the problem, and maps to a documented process exit code.

use std::path::{Path, PathBuf};

/// Everything that can go wrong in the library, by who has to act on it.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An input file or folder is missing, unreadable or malformed.
    #[error("{}: {problem}", path.display())]
    Input { path: PathBuf, problem: String },
    /// A setting is out of range or asks for something the renderer cannot do.
    #[error("{0}")]
    Setting(String),
    /// No adapter, a device error, or a size beyond the adapter's limits.
    #[error("GPU: {0}")]
    Gpu(String),
    /// An output file could not be written.
    #[error("{}: {problem}", path.display())]
    Output { path: PathBuf, problem: String },
    /// Standard output was closed by its reader (a pipe into `head`): the program ends quietly,
    /// with the status of a Unix tool killed by SIGPIPE.
    #[error("standard output closed")]
    StdoutClosed,
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    pub fn input(path: impl AsRef<Path>, problem: impl Into<String>) -> Self {
        Error::Input { path: path.as_ref().to_path_buf(), problem: problem.into() }
    }

    pub fn output(path: impl AsRef<Path>, problem: impl Into<String>) -> Self {
        Error::Output { path: path.as_ref().to_path_buf(), problem: problem.into() }
    }

    /// Process exit code for this error; the README's table lists them.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Setting(_) => 2,
            Error::Input { .. } => 3,
            Error::Gpu(_) => 4,
            Error::Output { .. } => 5,
            Error::StdoutClosed => 141,
        }
    }
}
