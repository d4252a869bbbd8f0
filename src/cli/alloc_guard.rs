//! An allocation that fails ends the command with an error naming the stage and the size, not
//! with Rust's abort (issue 47: under `ulimit -v` a build died with "memory allocation of
//! 1006632960 bytes failed" and SIGABRT).
//!
//! Stable Rust cannot replace the allocation-error handler (`set_alloc_error_hook` is
//! unstable), so two parts work together: [`GuardedAlloc`], the binary's global allocator,
//! passes every request to the system allocator and records the size of one that fails (it
//! still returns null, so `try_reserve` keeps working); the handler [`install`] puts on SIGABRT
//! then turns the abort that follows an unhandled failure into the message and exit code 2. An
//! abort without a failed allocation before it keeps its default action.
//!
//! The stage is the one [`set_stage`] last named (`flexbody build`'s stages, or the command);
//! it is kept in a fixed buffer so that reading it in the signal handler neither allocates nor
//! locks.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU8, AtomicUsize, Ordering};

/// The system allocator, with the size of a failed request recorded for the abort handler.
pub struct GuardedAlloc;

/// Bytes of the last request the system allocator refused (0: none).
static FAILED_BYTES: AtomicUsize = AtomicUsize::new(0);

/// The running stage's name (at most [`STAGE_CAPACITY`] bytes) and its length.
const STAGE_CAPACITY: usize = 48;
static STAGE: [AtomicU8; STAGE_CAPACITY] = [const { AtomicU8::new(0) }; STAGE_CAPACITY];
static STAGE_LEN: AtomicUsize = AtomicUsize::new(0);

fn record(ptr: *mut u8, bytes: usize) -> *mut u8 {
    if ptr.is_null() {
        FAILED_BYTES.store(bytes.max(1), Ordering::SeqCst);
    }
    ptr
}

// SAFETY: every method forwards to `System` with the caller's arguments unchanged.
unsafe impl GlobalAlloc for GuardedAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        record(System.alloc(layout), layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        record(System.alloc_zeroed(layout), layout.size())
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        record(System.realloc(ptr, layout, new_size), new_size)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

/// Names the stage an allocation failure is attributed to from now on (cut to 48 bytes at a
/// character boundary).
pub fn set_stage(name: &str) {
    let mut end = name.len().min(STAGE_CAPACITY);
    while !name.is_char_boundary(end) {
        end -= 1;
    }
    STAGE_LEN.store(0, Ordering::SeqCst);
    for (slot, &b) in STAGE.iter().zip(&name.as_bytes()[..end]) {
        slot.store(b, Ordering::SeqCst);
    }
    STAGE_LEN.store(end, Ordering::SeqCst);
}

/// A fixed buffer the message is formatted into without allocating.
struct StackText {
    buf: [u8; 512],
    len: usize,
}

impl std::fmt::Write for StackText {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        let n = s.len().min(self.buf.len() - self.len);
        self.buf[self.len..self.len + n].copy_from_slice(&s.as_bytes()[..n]);
        self.len += n;
        Ok(())
    }
}

/// The message for a failed allocation of `bytes` in `stage`.
fn message(stage: &str, bytes: usize, out: &mut StackText) {
    use std::fmt::Write;
    let mib = bytes as f64 / 1048576.0;
    let _ = write!(
        out,
        "\nflexbody: out of memory in stage `{stage}`: an allocation of {bytes} bytes \
         ({mib:.1} MiB) failed; the process's memory or address-space limit (ulimit -v, a \
         cgroup, a batch system) is too small for this model: raise it, free memory, or try \
         --threads 1 (the output file is not written)\n"
    );
}

#[cfg(unix)]
mod signal {
    use std::os::raw::c_int;

    const SIGABRT: c_int = 6;
    const SIG_DFL: usize = 0;

    extern "C" {
        fn signal(signum: c_int, handler: usize) -> usize;
        fn write(fd: c_int, buf: *const u8, count: usize) -> isize;
        fn _exit(status: c_int) -> !;
        fn raise(sig: c_int) -> c_int;
    }

    /// Async-signal-safe: reads atomics, formats into a stack buffer, `write(2)`, `_exit(2)`.
    extern "C" fn on_abort(_: c_int) {
        let bytes = super::FAILED_BYTES.load(std::sync::atomic::Ordering::SeqCst);
        if bytes == 0 {
            // not an allocation failure: the default action (core dump, 134)
            // SAFETY: plain libc calls with valid arguments.
            unsafe {
                signal(SIGABRT, SIG_DFL);
                raise(SIGABRT);
            }
            return;
        }
        let mut stage = [0u8; super::STAGE_CAPACITY];
        let len = super::STAGE_LEN.load(std::sync::atomic::Ordering::SeqCst);
        for (b, slot) in stage.iter_mut().zip(&super::STAGE) {
            *b = slot.load(std::sync::atomic::Ordering::SeqCst);
        }
        let stage = std::str::from_utf8(&stage[..len]).unwrap_or("?");
        let stage = if stage.is_empty() { "start-up" } else { stage };
        let mut text = super::StackText {
            buf: [0; 512],
            len: 0,
        };
        super::message(stage, bytes, &mut text);
        // SAFETY: `text.buf[..text.len]` is initialized; fd 2 is stderr.
        unsafe {
            write(2, text.buf.as_ptr(), text.len);
            _exit(2);
        }
    }

    pub(super) fn install() {
        // SAFETY: installs a handler that only calls async-signal-safe functions.
        unsafe {
            signal(SIGABRT, on_abort as *const () as usize);
        }
    }
}

/// Installs the SIGABRT handler that reports a failed allocation (a no-op off Unix). Call once,
/// first thing in `main`.
pub fn install() {
    #[cfg(unix)]
    signal::install();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_message_names_stage_and_size_without_allocating_more_than_its_buffer() {
        let mut text = StackText {
            buf: [0; 512],
            len: 0,
        };
        message("factorization", 1006632960, &mut text);
        let s = std::str::from_utf8(&text.buf[..text.len]).unwrap();
        assert!(
            s.contains("stage `factorization`") && s.contains("1006632960 bytes (960.0 MiB)"),
            "{s}"
        );
        assert!(s.ends_with('\n'), "{s}");
    }
}
