//! `fc3d solve --diagnostics`: per-contact status counts and the worst contacts after each row.

use std::process::Command;

#[test]
fn diagnostics_follow_each_scene_with_known_statuses() {
    let out = Command::new(env!("CARGO_BIN_EXE_fc3d"))
        .args(["solve", "--diagnostics=2"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let after = |scene: &str| {
        // The counts line follows the row (and AUTO's stage line, when AUTO ran).
        let mut lines = text.lines().skip_while(|l| !l.starts_with(scene));
        lines.next().unwrap();
        lines
            .find(|l| l.starts_with("#   contacts:"))
            .unwrap()
            .to_string()
    };
    // The single-contact scenes have known answers (see fc3d_core::scenes).
    assert!(after("sphere_rest").contains("0 take-off, 1 stick, 0 slide, 0 apex"));
    assert!(after("sphere_slide").contains("0 take-off, 0 stick, 1 slide, 0 apex"));
    assert!(after("sphere_takeoff").contains("1 take-off, 0 stick, 0 slide, 0 apex"));
    // At most 2 worst contacts after each counts line.
    let box_stack: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("box_stack"))
        .skip_while(|l| !l.starts_with("#   contacts:"))
        .skip(1)
        .take_while(|l| l.starts_with("#   contact "))
        .collect();
    assert_eq!(box_stack.len(), 2, "{text}");
}

#[test]
fn without_the_flag_no_diagnostics_and_a_file_after_the_flag_is_a_file() {
    let out = Command::new(env!("CARGO_BIN_EXE_fc3d"))
        .args(["solve"])
        .output()
        .unwrap();
    assert!(!String::from_utf8(out.stdout)
        .unwrap()
        .contains("#   contacts:"));
    let out = Command::new(env!("CARGO_BIN_EXE_fc3d"))
        .args(["solve", "--diagnostics", "no-such-file.dat"])
        .output()
        .unwrap();
    // The path is read as a file (and reported missing), not as K.
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("no-such-file.dat"));
}
