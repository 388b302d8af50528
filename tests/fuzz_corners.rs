//! The suite's bounded fuzz at the edges of the configuration space, which uniform random
//! draws reach only now and then: all eight light slots serial and parallel, the widest dot
//! product with the largest table, the widest segmented unit, every width at its top and at
//! its bottom. Each is generated, linted (Verilator -Wall) and simulated on Verilator against
//! the model, exactly as `gbump fuzz` does; two carry the `normalise_b` unit,
//! one the largest `normalise_cube` map, two the `frame_transform` unit: the serial top with
//! a frame from a quaternion (`quat_frame`), and the widest L and H with a frame built per
//! fragment (`frame_build`).

use gbump::sim::fuzz::{check_config, corner_configs};
use std::time::Instant;

#[test]
fn corner_configurations_generate_lint_and_simulate_clean() {
    let work = std::path::absolute(concat!(env!("CARGO_MANIFEST_DIR"), "/target/test-regress/fuzz_corners")).unwrap();
    let mut failures = Vec::new();
    for (i, (name, cfg)) in corner_configs().into_iter().enumerate() {
        let t0 = Instant::now();
        match check_config(&cfg, &work, 1000, 11 + i as u64) {
            Ok(n) => {
                println!("{name} ({}): {n} vectors in {:.1} s", cfg.hash(), t0.elapsed().as_secs_f64());
                assert!(n > 1000, "{name}: only {n} vectors checked");
            }
            Err(e) => failures.push(format!("{name}: {e}")),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The README's guarantee table names the corners this suite runs, in order, and their
/// count, from the list the test above runs.
#[test]
fn the_readme_lists_every_corner_the_suite_runs() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let names: Vec<&str> = corner_configs().iter().map(|(n, _)| *n).collect();
    let want = format!("plus {} fixed corners (`tests/fuzz_corners.rs`: {})", names.len(), names.join("; "));
    assert!(readme.contains(&want), "README.md should say: {want}");
}
