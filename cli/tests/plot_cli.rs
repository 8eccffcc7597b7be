//! `fc3d plot`: a benchmark CSV becomes an SVG and a PNG; bad columns are refused with exit 1.

use std::path::PathBuf;
use std::process::Command;

/// A fresh directory under cargo's per-test temporary directory.
fn out_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temporary directory");
    dir
}

#[test]
fn a_csv_is_drawn_as_svg_and_png() {
    let dir = out_dir("plot-cli");
    let csv = dir.join("history.csv");
    std::fs::write(
        &csv,
        "shape,mu_scale,sweep,error\nspheres,0,1,0.3\nspheres,0,8,1e-3\nspheres,1,1,0.31\n\
         spheres,1,8,5e-3\n",
    )
    .unwrap();
    let stem = dir.join("picture");
    let out = Command::new(env!("CARGO_BIN_EXE_fc3d"))
        .args([
            "plot",
            csv.to_str().unwrap(),
            "--x",
            "sweep",
            "--y",
            "error",
        ])
        .args(["--by", "mu_scale", "-o", stem.to_str().unwrap()])
        .output()
        .expect("run fc3d plot");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(dir.join("picture.svg")).expect("svg written");
    assert!(
        svg.contains("<svg") && svg.contains("polyline"),
        "an SVG with curves"
    );
    let png = std::fs::read(dir.join("picture.png")).expect("png written");
    assert_eq!(&png[1..4], b"PNG");

    let out = Command::new(env!("CARGO_BIN_EXE_fc3d"))
        .args([
            "plot",
            csv.to_str().unwrap(),
            "--x",
            "sweeps",
            "--y",
            "error",
        ])
        .args(["-o", stem.to_str().unwrap()])
        .output()
        .expect("run fc3d plot");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no column 'sweeps'"));
}
