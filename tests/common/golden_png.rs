//! The checked-in golden PNGs: compare an image with its file, or (with `GBUMP_BLESS=1`)
//! write it.

use gbump::render::output::write_png;
use std::path::Path;

/// Whether this run rewrites the golden PNGs instead of checking them.
pub fn bless() -> bool {
    std::env::var_os("GBUMP_BLESS").is_some()
}

/// `px` (`w`×`h`) against `tests/golden/{name}.png`: None when equal (or written, when
/// blessing), else how many channels differ.
pub fn check(name: &str, w: u32, h: u32, px: &[[u8; 3]]) -> Option<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/{name}.png"));
    if bless() {
        write_png(&path, w, h, px).unwrap();
        return None;
    }
    let want = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with GBUMP_BLESS=1 to create)", path.display()))
        .to_rgb8();
    let got: Vec<u8> = px.iter().flatten().copied().collect();
    let diff = want.as_raw().iter().zip(&got).filter(|(a, b)| a != b).count();
    (diff > 0).then(|| format!("{name}: {diff} of {} channels differ", got.len()))
}
