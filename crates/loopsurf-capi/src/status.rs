//! Status codes, the thread-local error message, the library version, the
//! release of arrays handed to the caller, and the one wrapper every
//! exported function runs its body in (pointer checks, panic catching).

use loopsurf::Error;
use std::cell::RefCell;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Success.
pub const LS_OK: c_int = 0;
/// A required pointer argument was NULL.
pub const LS_ERR_NULL_POINTER: c_int = -1;
/// A file could not be opened, read or written, or its format is unknown.
pub const LS_ERR_IO: c_int = -2;
/// A file does not parse (malformed line, truncated data, polygon face).
pub const LS_ERR_PARSE: c_int = -3;
/// The net is not a manifold or is inconsistently oriented.
pub const LS_ERR_NON_MANIFOLD: c_int = -4;
/// Empty net, zero-area triangle, repeated vertex in a triangle, or no
/// tangent plane at the queried point.
pub const LS_ERR_DEGENERATE: c_int = -5;
/// A vertex or triangle index outside the net.
pub const LS_ERR_INDEX_OUT_OF_RANGE: c_int = -6;
/// (v, w) outside the triangle (v < 0, w < 0 or v + w > 1 beyond 1e-12),
/// or a curve parameter t outside [0, n] or an arc length outside [0, L].
pub const LS_ERR_PARAMETER_OUT_OF_RANGE: c_int = -7;
/// A NaN or infinite input number.
pub const LS_ERR_NOT_FINITE: c_int = -8;
/// The operation is not available in this version.
pub const LS_ERR_UNSUPPORTED: c_int = -9;
/// A surface stream that is truncated, damaged or of another version.
pub const LS_ERR_BAD_STREAM: c_int = -10;
/// Any other argument that makes no sense (no such edge, bad level count).
pub const LS_ERR_INVALID_ARGUMENT: c_int = -11;
/// A bug in loopsurf (a caught panic); please report the message.
pub const LS_ERR_INTERNAL: c_int = -12;
/// The result would pass its triangle budget (`max_triangles` of the
/// call's options): refused before the memory is spent; the message says
/// how many triangles the request needs.
pub const LS_ERR_OVER_BUDGET: c_int = -13;

/// Why a call failed: a status code and the message `ls_last_error` shows.
pub(crate) struct Fail {
    code: c_int,
    message: String,
}

impl Fail {
    pub(crate) fn new(code: c_int, message: impl Into<String>) -> Fail {
        Fail {
            code,
            message: message.into(),
        }
    }

    /// The same failure, its message prefixed with where it happened.
    pub(crate) fn context(self, at: &str) -> Fail {
        Fail::new(self.code, format!("{at}: {}", self.message))
    }
}

impl From<Error> for Fail {
    fn from(err: Error) -> Fail {
        Fail::new(code_of(&err), err.to_string())
    }
}

/// The status code of a library error, by its kind (file context stripped).
fn code_of(err: &Error) -> c_int {
    match err.root() {
        Error::Io { .. } | Error::UnknownFormat { .. } => LS_ERR_IO,
        Error::Malformed { .. } | Error::Truncated { .. } | Error::Polygon { .. } => LS_ERR_PARSE,
        Error::NonManifoldEdge { .. }
        | Error::NonManifoldVertex { .. }
        | Error::InteriorValenceTwo { .. }
        | Error::InconsistentOrientation { .. }
        | Error::NonOrientable { .. } => LS_ERR_NON_MANIFOLD,
        Error::EmptyMesh { .. }
        | Error::RepeatedIndex { .. }
        | Error::ZeroArea { .. }
        | Error::NoTangentPlane { .. } => LS_ERR_DEGENERATE,
        Error::IndexOutOfRange { .. } => LS_ERR_INDEX_OUT_OF_RANGE,
        Error::NonFiniteCoordinate { .. } => LS_ERR_NOT_FINITE,
        Error::BadParameter { v, w, .. } if !v.is_finite() || !w.is_finite() => LS_ERR_NOT_FINITE,
        Error::BadParameter { .. } => LS_ERR_PARAMETER_OUT_OF_RANGE,
        Error::Stream { .. } => LS_ERR_BAD_STREAM,
        Error::OverBudget { .. } => LS_ERR_OVER_BUDGET,
        _ => LS_ERR_INVALID_ARGUMENT,
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Runs the body of exported function `name`: a failure or a panic becomes
/// a status code and this thread's last-error message; nothing unwinds into C.
pub(crate) fn run(name: &str, body: impl FnOnce() -> Result<(), Fail>) -> c_int {
    let fail = match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => return LS_OK,
        Ok(Err(fail)) => fail,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Fail::new(
                LS_ERR_INTERNAL,
                format!("internal error (please report): {what}"),
            )
        }
    };
    let text = format!("{name}: {}", fail.message).replace('\0', " ");
    LAST_ERROR.with(|e| *e.borrow_mut() = CString::new(text).unwrap_or_default());
    fail.code
}

/// Runs a function that returns nothing (the `_free` family): a panic is
/// swallowed, recorded as the last error, and never unwinds into C.
pub(crate) fn run_void(name: &str, body: impl FnOnce()) {
    run(name, || {
        body();
        Ok(())
    });
}

/// Borrows a required input; NULL is an error naming the argument.
///
/// # Safety
/// `p` is NULL or points to a live, properly aligned `T`.
pub(crate) unsafe fn input<'a, T>(p: *const T, what: &str) -> Result<&'a T, Fail> {
    p.as_ref()
        .ok_or_else(|| Fail::new(LS_ERR_NULL_POINTER, format!("{what} is NULL")))
}

/// Borrows a required handle mutably; NULL is an error naming the argument.
///
/// # Safety
/// `p` is NULL or points to a live `T` no other thread is using.
pub(crate) unsafe fn input_mut<'a, T>(p: *mut T, what: &str) -> Result<&'a mut T, Fail> {
    p.as_mut()
        .ok_or_else(|| Fail::new(LS_ERR_NULL_POINTER, format!("{what} is NULL")))
}

/// Checks a required output pointer, to be written only once all work succeeded.
pub(crate) fn output<T>(p: *mut T, what: &str) -> Result<*mut T, Fail> {
    if p.is_null() {
        Err(Fail::new(LS_ERR_NULL_POINTER, format!("{what} is NULL")))
    } else {
        Ok(p)
    }
}

/// The last failure on the calling thread, e.g. `"ls_evaluate: point (v, w)
/// = (0.8, 0.7) of triangle 12: outside the triangle ..."`; an empty string
/// if no call has failed on this thread. The text stays valid until the next
/// failing call on the same thread; copy it to keep it.
#[no_mangle]
pub extern "C" fn ls_last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// The name and meaning of a status code, e.g. `"LS_ERR_NULL_POINTER: a
/// required pointer was NULL"`; a static string, never NULL.
#[no_mangle]
pub extern "C" fn ls_status_string(status: c_int) -> *const c_char {
    let s: &'static CStr = match status {
        LS_OK => c"LS_OK: success",
        LS_ERR_NULL_POINTER => c"LS_ERR_NULL_POINTER: a required pointer was NULL",
        LS_ERR_IO => c"LS_ERR_IO: a file could not be read or written, or its format is unknown",
        LS_ERR_PARSE => c"LS_ERR_PARSE: the file does not parse",
        LS_ERR_NON_MANIFOLD => c"LS_ERR_NON_MANIFOLD: the net is not manifold or not consistently oriented",
        LS_ERR_DEGENERATE => c"LS_ERR_DEGENERATE: empty net, zero-area triangle, repeated vertex, or no tangent plane",
        LS_ERR_INDEX_OUT_OF_RANGE => c"LS_ERR_INDEX_OUT_OF_RANGE: a vertex or triangle index outside the net",
        LS_ERR_PARAMETER_OUT_OF_RANGE => c"LS_ERR_PARAMETER_OUT_OF_RANGE: (v, w) outside the triangle, or a curve parameter or arc length outside its curve",
        LS_ERR_NOT_FINITE => c"LS_ERR_NOT_FINITE: a NaN or infinite number",
        LS_ERR_UNSUPPORTED => c"LS_ERR_UNSUPPORTED: not available in this version",
        LS_ERR_BAD_STREAM => c"LS_ERR_BAD_STREAM: truncated, damaged or foreign surface stream",
        LS_ERR_INVALID_ARGUMENT => c"LS_ERR_INVALID_ARGUMENT: an argument that makes no sense",
        LS_ERR_INTERNAL => c"LS_ERR_INTERNAL: internal error (a bug; please report)",
        LS_ERR_OVER_BUDGET => c"LS_ERR_OVER_BUDGET: the result would pass its triangle budget",
        _ => c"unknown loopsurf status code",
    };
    s.as_ptr()
}

/// Writes the library version (each pointer may be NULL).
#[no_mangle]
pub unsafe extern "C" fn ls_version(major: *mut c_int, minor: *mut c_int, patch: *mut c_int) {
    let parse = |s: &str| s.parse().unwrap_or(0);
    for (p, v) in [
        (major, env!("CARGO_PKG_VERSION_MAJOR")),
        (minor, env!("CARGO_PKG_VERSION_MINOR")),
        (patch, env!("CARGO_PKG_VERSION_PATCH")),
    ] {
        if !p.is_null() {
            *p = parse(v);
        }
    }
}

/// Frees an array that a function handed to the caller (`ls_refine`,
/// `ls_refine_origins`, `ls_net_hard_edges`, `ls_net_folds`,
/// `ls_surface_folded_patches`, `ls_mesh_hard_edges`, ...); NULL is
/// ignored. The arrays come from `malloc`, so C's `free` releases them
/// too; this is for languages without the C allocator (Fortran).
#[no_mangle]
pub unsafe extern "C" fn ls_free_array(array: *mut c_void) {
    libc::free(array);
}

/// An options struct of the C ABI: `struct_size` first, fields only ever
/// appended, defaults from the matching `*_default()` function.
pub(crate) trait Options: Copy {
    /// The options every field of which takes its default.
    fn defaults() -> Self;
    /// The size of the struct when this type first shipped: a caller
    /// compiled against that header passes at least this many bytes.
    const FIRST_SIZE: usize;
}

/// Reads a caller's options: NULL gives the defaults; a caller compiled
/// against an older header (smaller `struct_size`) gets the defaults for
/// the fields it does not know; a newer one's extra fields are ignored.
///
/// # Safety
/// `p` is NULL or points to at least `struct_size` readable bytes.
pub(crate) unsafe fn read_options<T: Options>(p: *const T, what: &str) -> Result<T, Fail> {
    let mut options = T::defaults();
    if p.is_null() {
        return Ok(options);
    }
    // Only the leading `usize` is read before the size is known good.
    let size = *(p as *const usize);
    if size < T::FIRST_SIZE {
        return Err(Fail::new(
            LS_ERR_INVALID_ARGUMENT,
            format!(
                "{what}: struct_size {size} is smaller than any version of this struct ({} bytes): fill it with its *_default() function",
                T::FIRST_SIZE
            ),
        ));
    }
    let known = size.min(std::mem::size_of::<T>());
    std::ptr::copy_nonoverlapping(p as *const u8, &mut options as *mut T as *mut u8, known);
    Ok(options)
}

/// Writes the defaults of an options struct into `out` (the body of every
/// `*_default()` function).
///
/// # Safety
/// `out` is NULL or points to a writable `T`.
pub(crate) unsafe fn write_defaults<T: Options>(name: &str, out: *mut T) -> c_int {
    run(name, || {
        *output(out, "options")? = T::defaults();
        Ok(())
    })
}
