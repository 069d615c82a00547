//! The net under the code that reads untrusted files: a panic inside [`catch`] (in another
//! crate's parser, or in ours) becomes an error value instead of ending the program, and the
//! default hook's message and backtrace stay off standard error, so the user sees the one line
//! the caller writes. Each caught panic is still a bug: it is logged at debug level and counted
//! ([`caught`]), and the property tests and fuzz targets fail on any.

use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Once;

thread_local! {
    /// How many [`catch`] calls this thread is inside.
    static DEPTH: Cell<u32> = const { Cell::new(0) };
}
/// How many [`catch`] calls any thread is inside: a panic on one of rayon's workers, which
/// rayon carries back to the guarded caller, is quiet while this is not zero.
static GUARDED: AtomicUsize = AtomicUsize::new(0);
/// Panics caught since the process started.
static CAUGHT: AtomicUsize = AtomicUsize::new(0);
static HOOK: Once = Once::new();

/// Runs `work`; a panic inside it is returned as its message.
pub fn catch<T>(work: impl FnOnce() -> T) -> std::result::Result<T, String> {
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let on_guarded_worker = rayon::current_thread_index().is_some() && GUARDED.load(Ordering::SeqCst) > 0;
            if DEPTH.with(Cell::get) > 0 || on_guarded_worker {
                CAUGHT.fetch_add(1, Ordering::SeqCst);
                log::debug!("caught a panic while reading an input: {info}");
            } else {
                previous(info);
            }
        }));
    });
    DEPTH.with(|d| d.set(d.get() + 1));
    GUARDED.fetch_add(1, Ordering::SeqCst);
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
    GUARDED.fetch_sub(1, Ordering::SeqCst);
    DEPTH.with(|d| d.set(d.get() - 1));
    result.map_err(|payload| {
        let text = payload.downcast_ref::<&str>().map(|s| s.to_string());
        text.or_else(|| payload.downcast_ref::<String>().cloned()).unwrap_or_else(|| "a panic".into())
    })
}

/// How many panics [`catch`] has caught in this process.
pub fn caught() -> usize {
    CAUGHT.load(Ordering::SeqCst)
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_panic_inside_is_an_error_with_its_message_and_is_counted() {
        let before = super::caught();
        let result: Result<(), String> = super::catch(|| panic!("index {} out of range", 7));
        assert_eq!(result, Err("index 7 out of range".to_string()));
        assert!(super::caught() > before);
        assert_eq!(super::catch(|| 3), Ok(3));
    }
}
