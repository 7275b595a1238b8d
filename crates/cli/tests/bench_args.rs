//! `tidepack bench` refuses arguments it cannot honour before rendering anything.

#![cfg(feature = "bench")]

use std::process::Command;

#[test]
fn zero_frames_are_refused() {
    let output = Command::new(env!("CARGO_BIN_EXE_tidepack")).args(["bench", "--frames", "0"]).output().expect("run tidepack");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--frames") && stderr.contains("0 is not in 1.."), "{stderr}");
}
