//! The source fingerprint: a hash of every file the library compiles in (`DIRS`) and of
//! Cargo.toml and Cargo.lock, as
//! `GBUMP_SOURCE_HASH`. The CLI prints it with `--version`, the Python module and the C
//! library carry it, so a module or library built from other sources than the gbump beside
//! it is told apart (their version numbers are the same).

use std::path::{Path, PathBuf};

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let p = e.path();
        if p.is_dir() {
            files(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// Folders the library compiles in (`include_str!`): its sources, the testbench templates,
/// the scenes, the C header and DPI package, the area model's samples.
const DIRS: [&str; 5] = ["src", "testbench", "scenes", "include", "tests/area_model"];

fn main() {
    let mut all = Vec::new();
    // Everything the library compiles in: its sources, the testbench templates and the
    // area model's samples (include_str!), the manifest.
    for d in DIRS {
        files(Path::new(d), &mut all);
    }
    all.push(PathBuf::from("Cargo.toml"));
    all.push(PathBuf::from("Cargo.lock"));
    all.sort();
    // FNV-1a over each path and its bytes: no dependency, stable across platforms.
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for p in &all {
        let bytes = std::fs::read(p).unwrap_or_default();
        for b in p.to_string_lossy().as_bytes().iter().chain([0u8].iter()).chain(bytes.iter()) {
            h ^= *b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    println!("cargo:rustc-env=GBUMP_SOURCE_HASH={h:016x}");
    for d in DIRS {
        println!("cargo:rerun-if-changed={d}");
    }
    println!("cargo:rerun-if-changed=Cargo.toml");
    println!("cargo:rerun-if-changed=Cargo.lock");
}
