//! What every CLI test needs: run the binary (with or without standard
//! input), a scratch file, and the check that a refusal is one clear line.

#![allow(dead_code)] // each test file uses its own share

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

/// The `loopsurf` binary run with `args` and no input.
pub fn loopsurf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_loopsurf"))
        .args(args)
        .output()
        .expect("the loopsurf binary runs")
}

/// The `loopsurf` binary run with `args`, `stdin` written to its input.
pub fn loopsurf_with_stdin(args: &[&str], stdin: &str) -> Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_loopsurf"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the loopsurf binary runs");
    // A command that refuses its arguments exits before reading: its
    // input pipe is then closed, which is no failure of the test.
    let written = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    if let Err(e) = written {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
    }
    child.wait_with_output().unwrap()
}

/// A path in this test process's own scratch directory.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("loopsurf-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// `args` with `{out}` replaced by a fresh scratch file named `name`:
/// refused cleanly (as [`assert_clean_failure`]), and nothing written
/// there. Refusal tests write to scratch paths, never next to the sources.
pub fn assert_refused_without_writing(args: &[&str], name: &str, needle: &str) {
    let out = scratch(name);
    let _ = std::fs::remove_file(&out);
    let path = out.to_str().unwrap();
    let args: Vec<&str> = args
        .iter()
        .map(|&a| if a == "{out}" { path } else { a })
        .collect();
    assert_clean_failure(&loopsurf(&args), needle);
    assert!(!out.exists(), "a refused command wrote {path}");
}

/// Exit status 2 and exactly one line on stderr that mentions `needle`.
pub fn assert_clean_failure(out: &Output, needle: &str) {
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {err}");
    assert_eq!(err.lines().count(), 1, "one line expected, got: {err}");
    assert!(err.contains(needle), "'{err}' should mention '{needle}'");
    assert!(!err.contains("panicked"));
}
