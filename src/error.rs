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

/// The value named `s` (any letter case) among `named`, or a setting error that lists the names:
/// how every named choice (mode, variant, view, sender sky) is read from the command line.
pub fn by_name<T: Copy>(what: &str, s: &str, named: impl IntoIterator<Item = (&'static str, T)>) -> Result<T> {
    let named: Vec<(&str, T)> = named.into_iter().collect();
    named.iter().find(|(name, _)| name.eq_ignore_ascii_case(s)).map(|&(_, value)| value).ok_or_else(|| {
        let names: Vec<&str> = named.iter().map(|&(name, _)| name).collect();
        Error::Setting(format!("unknown {what} '{s}' (expected {})", names.join(", ")))
    })
}

/// A named choice's `Display` (its name) and `FromStr` (through [`by_name`], any letter case):
/// `named_choice!(View, "view", View::ALL.map(|v| (v.name(), v)))`. The type has a `name()`.
macro_rules! named_choice {
    ($ty:ty, $what:literal, $named:expr) => {
        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $ty {
            type Err = $crate::Error;
            fn from_str(s: &str) -> $crate::Result<Self> {
                $crate::error::by_name($what, s, $named)
            }
        }
    };
}
pub(crate) use named_choice;

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

/// `value` if it is finite and within [lo, hi]; otherwise an error naming the flag and the range.
pub fn in_range(name: &str, value: f32, lo: f32, hi: f32) -> Result<f32> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        let num = crate::text::num;
        Err(Error::Setting(format!("--{name} {}: must be a finite number from {} to {}", num(value), num(lo), num(hi))))
    }
}
