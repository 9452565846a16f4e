//! Running out of memory ends the command like any other error: one line
//! on stderr and exit status 2, not the runtime's abort with a backtrace.
//! The remesher's triangle budget refuses most densities too large for
//! memory before they allocate (`--max-triangles`), but not everything a
//! run holds is counted (a run in parts on a large net holds about three
//! times what a whole run on a small one does), and a machine may have
//! less memory than the budget assumes.

use std::alloc::{GlobalAlloc, Layout, System};
use std::io::Write;

/// The system allocator, ending the process with one line and status 2
/// when an allocation fails.
pub struct ExitWhenExhausted;

// SAFETY: every call is forwarded to the system allocator unchanged; a
// failed allocation never returns.
unsafe impl GlobalAlloc for ExitWhenExhausted {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        checked(System.alloc(layout), layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        checked(System.alloc_zeroed(layout), layout.size())
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        checked(System.realloc(ptr, layout, new_size), new_size)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

fn checked(ptr: *mut u8, bytes: usize) -> *mut u8 {
    if ptr.is_null() {
        exhausted(bytes);
    }
    ptr
}

/// Says that `bytes` could not be allocated and exits with status 2,
/// allocating nothing: the line is assembled on the stack, written to the
/// unbuffered stderr, and the process ends without running destructors
/// (another thread may hold what they would need).
fn exhausted(bytes: usize) -> ! {
    let mut line = [0u8; 192];
    let mut at = 0;
    let mut push = |text: &[u8]| {
        let n = text.len().min(line.len() - at);
        line[at..at + n].copy_from_slice(&text[..n]);
        at += n;
    };
    push(b"loopsurf: out of memory: could not allocate ");
    let mut digits = [0u8; 20];
    let mut start = digits.len();
    let mut rest = bytes;
    loop {
        start -= 1;
        digits[start] = b'0' + (rest % 10) as u8;
        rest /= 10;
        if rest == 0 {
            break;
        }
    }
    push(&digits[start..]);
    push(b" more bytes; ask for a smaller output (fewer levels, a larger --size or --tolerance)\n");
    let _ = std::io::stderr().write_all(&line[..at]);
    // SAFETY: _exit ends the process at once; nothing after it runs.
    unsafe { libc::_exit(2) }
}
