//! Writes the generated box towers of docs/newton.md (`scenes::box_towers`: boxes stacked face on
//! face, 4 contact points per face) as Siconos `.dat` files, so that fc3d and Siconos solve the
//! same problems (`scripts/compare-newton.sh`):
//! `cargo run --release -p fc3d-core --example write_towers -- DIR [quick]`
//! (quick: the towers of up to 52 contacts only).

use std::path::Path;

use fc3d_core::io::write_dat_file;
use fc3d_core::scenes::{box_towers, TowerMotion, TowerSpec};

/// (towers, boxes per tower): 8, 16, 52, 128 and 1000 contacts.
const SIZES: [(usize, usize); 5] = [(1, 2), (1, 4), (1, 13), (4, 8), (25, 10)];

fn main() {
    let mut args = std::env::args().skip(1);
    let dir = args.next().expect("usage: write_towers DIR [quick]");
    let quick = args.next().as_deref() == Some("quick");
    std::fs::create_dir_all(&dir).expect("output directory");
    for (towers, height) in SIZES {
        if quick && towers * height > 13 {
            continue;
        }
        for motion in [TowerMotion::Rest, TowerMotion::Settling] {
            let spec = TowerSpec {
                towers,
                height,
                motion,
                seed: 1,
            };
            let problem = box_towers(&spec).expect("tower scene");
            let path = Path::new(&dir).join(format!("{}.dat", spec.name()));
            write_dat_file(&problem, &path).expect("write the problem");
            println!("{}", path.display());
        }
    }
}
