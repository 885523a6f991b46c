//! A progress bar on standard error for long work (rendering and measuring deep levels, census).
//!
//! Written by hand rather than with `indicatif`: what is needed is one throttled line (a bar,
//! done/total, elapsed seconds) redrawn with `\r`, about sixty lines; `indicatif` would add five
//! crates (console, unicode-width, portable-atomic, unit-prefix, web-time) to a dependency set the
//! other branches are editing at the same time. The bar is off unless [`set_progress`] turned it
//! on (the CLI does when standard error is a terminal and `--no-progress` is not given), so the
//! library, the tests and the benchmarks print nothing. The cost per unit of work is one add and
//! one compare: the line is redrawn only every [`STEP`] units.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

static ENABLED: AtomicBool = AtomicBool::new(false);

/// Units of work between two redraws (2^16 cells).
pub const STEP: u64 = 1 << 16;

/// Turns progress bars on or off for the whole process (off by default).
pub fn set_progress(on: bool) {
    ENABLED.store(on, Ordering::Relaxed);
}

/// A progress bar over `total` units of work.
pub struct Progress {
    label: &'static str,
    total: u64,
    done: u64,
    next: u64,
    step: u64,
    shown: bool,
    enabled: bool,
    start: Instant,
}

impl Progress {
    /// A bar for `total` units, drawn only when progress bars are on.
    pub fn new(label: &'static str, total: u64) -> Progress {
        Progress::with_step(label, total, STEP)
    }

    /// A bar redrawn every `step` units (for work whose units are slow, such as census faces).
    pub fn with_step(label: &'static str, total: u64, step: u64) -> Progress {
        let step = step.max(1);
        Progress {
            label,
            total: total.max(1),
            done: 0,
            next: step,
            step,
            shown: false,
            enabled: ENABLED.load(Ordering::Relaxed),
            start: Instant::now(),
        }
    }

    /// One more unit done.
    #[inline]
    pub fn tick(&mut self) {
        self.done += 1;
        if self.done >= self.next {
            self.next = self.done + self.step;
            if self.enabled {
                self.draw();
            }
        }
    }

    /// `n` more units done.
    pub fn add(&mut self, n: u64) {
        self.done += n;
        if self.done >= self.next {
            self.next = self.done + self.step;
            if self.enabled {
                self.draw();
            }
        }
    }

    fn draw(&mut self) {
        const WIDTH: u64 = 30;
        let done = self.done.min(self.total);
        let filled = (done * WIDTH / self.total) as usize;
        let bar = format!(
            "{}{}",
            "#".repeat(filled),
            "-".repeat(WIDTH as usize - filled)
        );
        let mut err = std::io::stderr().lock();
        let _ = write!(
            err,
            "\r{} [{bar}] {:>3}% {done}/{} {:.0} s",
            self.label,
            done * 100 / self.total,
            self.total,
            self.start.elapsed().as_secs_f64()
        );
        let _ = err.flush();
        self.shown = true;
    }

    /// Clears the line (if anything was drawn).
    pub fn finish(&mut self) {
        if self.shown {
            let mut err = std::io::stderr().lock();
            let _ = write!(err, "\r\x1b[2K");
            let _ = err.flush();
            self.shown = false;
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hidden_bar_counts_and_throttles() {
        let mut p = Progress::new("test", 3 * STEP);
        assert!(!p.enabled || ENABLED.load(Ordering::Relaxed));
        for _ in 0..STEP + 5 {
            p.tick();
        }
        assert_eq!(p.done, STEP + 5);
        assert_eq!(p.next, 2 * STEP);
        p.add(STEP);
        assert_eq!(p.next, 3 * STEP + 5);
    }
}
