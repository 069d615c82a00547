//! What the command line shows on standard error while it works: a bar for the report's and the
//! bench's known steps, a spinner for a load of unknown length. Nothing when standard error is not
//! a terminal (indicatif's own rule).

/// A bar of `len` steps, `unit` after the count (" modes").
pub fn bar(len: u64, unit: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len);
    let template = format!("{{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}}{unit} {{msg}}");
    bar.set_style(indicatif::ProgressStyle::with_template(&template).expect("valid template"));
    bar
}

/// Runs `work`, showing a spinner with the elapsed time once it has taken a second (a
/// 2M-triangle model takes several).
pub fn spinner<T>(message: &str, work: impl FnOnce() -> T) -> T {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    let done = Arc::new(AtomicBool::new(false));
    let bar = indicatif::ProgressBar::hidden();
    let watcher = {
        let (done, bar, message) = (done.clone(), bar.clone(), message.to_owned());
        std::thread::spawn(move || {
            for _ in 0..20 {
                std::thread::sleep(std::time::Duration::from_millis(50));
                if done.load(Ordering::Relaxed) {
                    return;
                }
            }
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            bar.set_style(
                indicatif::ProgressStyle::with_template("{spinner} {msg} ({elapsed})").expect("valid template"),
            );
            bar.set_message(message);
            bar.enable_steady_tick(std::time::Duration::from_millis(120));
        })
    };
    let out = work();
    done.store(true, Ordering::Relaxed);
    let _ = watcher.join();
    bar.finish_and_clear();
    out
}
