//! A boundary around third-party parsers that panic on damaged input.
//!
//! Some crates we read files with index their tables with values read from
//! the file, or unwrap what they parse, and panic on corrupt data instead of
//! returning an error: `laz`'s arithmetic decoder, `gltf`'s validation and
//! `ply-rs`'s header grammar did, found by the fuzz targets.
//! No check of ours before the call can always tell, so the call is made
//! through [`run_reader`] and the reader turns the message of a panic into
//! its own error, naming the file. Our own code must not rely on this: it refuses bad input
//! with an error.
//!
//! A program that installs [`quiet_caught_panics`] (the CLI does) prints
//! nothing for a panic caught here, so a damaged file reads as one error, not
//! as a crash followed by an error. That holds for panics on the calling
//! thread, and for panics in the source of a reader that decodes on worker
//! threads ([`WORKER_READERS`]: the LAZ decompressor, on rayon's threads)
//! raised while a guarded call runs: the worker's panic travels to the thread
//! that called the reader, where the guard catches it. Panics anywhere else
//! print as before.

use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Third-party readers that decode on worker threads, as their source files'
/// folders in a panic's location: `laz-0.13.0/src/...` from the registry,
/// `third_party/laz/src/...` for the patched copy the workspace builds. We
/// call them only through the guard, so a panic there is one the guard will
/// catch.
const WORKER_READERS: &[&str] = &["/laz-", "third_party/laz/"];

/// How many guarded calls are running, on any thread.
static GUARDED_CALLS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// Whether this thread is inside [`catch_panic`].
    static CATCHING: Cell<bool> = const { Cell::new(false) };
}

/// Replaces the panic hook with one that stays silent for panics that
/// [`catch_panic`] catches on the thread it runs on or that a guarded reader
/// raises on its worker threads, and hands every other panic to the hook it
/// replaces. Call once, early (later calls do nothing).
pub fn quiet_caught_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let on_a_reader_s_worker = GUARDED_CALLS.load(Ordering::SeqCst) > 0
                && info.location().is_some_and(|l| WORKER_READERS.iter().any(|r| l.file().contains(r)));
            if !CATCHING.with(Cell::get) && !on_a_reader_s_worker {
                previous(info);
            }
        }));
    });
}

/// Runs the third-party reader `what` (e.g. "the PLY reader") as `f`. A panic
/// inside it becomes the message "`what` failed on damaged data (the panic's
/// message); the file is corrupt", for the caller's own error at the file's
/// place.
pub fn run_reader<T>(what: &str, f: impl FnOnce() -> T) -> Result<T, String> {
    catch_panic(f).map_err(|why| format!("{what} failed on damaged data ({why}); the file is corrupt"))
}

/// Runs `f`, returning the message of a panic inside it instead of unwinding.
pub fn catch_panic<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    let outer = CATCHING.with(|c| c.replace(true));
    GUARDED_CALLS.fetch_add(1, Ordering::SeqCst);
    let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    GUARDED_CALLS.fetch_sub(1, Ordering::SeqCst);
    CATCHING.with(|c| c.set(outer));
    caught.map_err(|payload| {
        payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".into())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_its_message() {
        assert_eq!(catch_panic(|| 7), Ok(7));
        let v: Vec<u32> = vec![1, 2];
        let i = v.len() + 3;
        let e = catch_panic(|| v[i]).unwrap_err();
        assert!(e.contains("index out of bounds"), "{e}");
        assert_eq!(catch_panic(|| -> u32 { panic!("{} apples", 3) }), Err("3 apples".to_string()));
        assert_eq!(
            run_reader("the pear reader", || -> u32 { panic!("bruised") }),
            Err("the pear reader failed on damaged data (bruised); the file is corrupt".to_string())
        );
    }
}
