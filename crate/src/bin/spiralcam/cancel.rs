//! Ctrl-C and `kill`: SIGINT, SIGTERM and SIGHUP set a flag that every progress callback reads,
//! so a run stops within one batch, removes its temporaries and exits with 128 + the signal. A
//! run that does not stop within [`GRACE`] (a stage between progress calls) is ended from here,
//! after the temporaries are removed: nothing is left behind either way.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
#[cfg(unix)]
use std::time::Duration;

/// How long a signalled run has to stop by itself.
#[cfg(unix)]
const GRACE: Duration = Duration::from_secs(3);

static CANCELLED: AtomicBool = AtomicBool::new(false);
static SIGNAL: AtomicI32 = AtomicI32::new(0);
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Starts listening for the signals (once, at start).
pub fn install() {
    #[cfg(unix)]
    {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
            return;
        };
        std::thread::spawn(move || {
            if let Some(sig) = signals.forever().next() {
                SIGNAL.store(sig, Ordering::SeqCst);
                CANCELLED.store(true, Ordering::SeqCst);
                std::thread::sleep(GRACE);
                remove_all();
                std::process::exit(exit_code());
            }
        });
    }
}

/// Whether a signal asked the run to stop.
pub fn cancelled() -> bool {
    CANCELLED.load(Ordering::SeqCst)
}

/// The exit status after a signal: 128 + its number.
pub fn exit_code() -> i32 {
    128 + SIGNAL.load(Ordering::SeqCst)
}

/// Records a temporary to remove if the run is ended from here.
pub fn remember(path: &Path) {
    if let Ok(mut t) = TEMPORARIES.lock() {
        t.push(path.to_path_buf());
    }
}

/// Forgets a temporary (renamed or removed).
pub fn forget(path: &Path) {
    if let Ok(mut t) = TEMPORARIES.lock() {
        t.retain(|p| p != path);
    }
}

#[cfg(unix)]
fn remove_all() {
    if let Ok(t) = TEMPORARIES.lock() {
        for p in t.iter() {
            let _ = std::fs::remove_file(p);
        }
    }
}
