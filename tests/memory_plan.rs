//! Every command that rasterises a scene plans its memory before it allocates (`limits`:
//! pixels × its bytes per pixel + triangles × `RENDER_BYTES_PER_TRIANGLE`) and refuses a plan
//! above the budget. A plan below what the command really takes lets a size through that the
//! kernel then kills without a word, so each command is run as a user runs it, on a fully
//! covered scene (`error` also renders the other built-in scenes that fit, at the same size),
//! and its peak resident memory must stay within its plan (and within a few times of it, so
//! that a plan far above the truth does not refuse sizes that fit). One test runs them one
//! after another, so that their peaks do not add up on the machine. (`render --rtl` plans
//! the render and the scene set together, both measured here.)
#![cfg(target_os = "linux")]

use gbump::limits::{render_bytes, PixelUse};
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// Covers the whole image, so every pixel holds a fragment.
const SCENE: &str = "cg_wall_front";

fn work(name: &str) -> PathBuf {
    let w = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/test-memory").join(name);
    let _ = std::fs::remove_dir_all(&w);
    std::fs::create_dir_all(&w).unwrap();
    w
}

/// The peak resident bytes of `gbump args`, which must succeed.
fn peak(args: &[&str], w: &std::path::Path) -> u64 {
    let log = w.join("stderr.txt");
    let child = Command::new(env!("CARGO_BIN_EXE_gbump"))
        .args(args)
        .current_dir(w)
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(&log).unwrap())
        .spawn()
        .unwrap();
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: a zeroed rusage is a valid value for wait4 to fill.
    let mut ru: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `pid` is our unwaited child; wait4 writes only into `status` and `ru`.
    let got = unsafe { libc::wait4(pid, &mut status, 0, &mut ru) };
    assert_eq!(got, pid, "wait4: {}", std::io::Error::last_os_error());
    let ok = libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0;
    assert!(ok, "gbump {args:?} failed:\n{}", std::fs::read_to_string(&log).unwrap_or_default());
    // Linux reports kilobytes.
    ru.ru_maxrss as u64 * 1024
}

fn within_plan(use_: PixelUse, (w, h): (u32, u32), args: &[&str], name: &str) {
    let triangles = gbump::scene::Scene::load(SCENE).unwrap().triangles();
    let plan = render_bytes(use_, w, h, triangles);
    let dir = work(name);
    let got = peak(args, &dir);
    let mb = |b: u64| b as f64 / 1e6;
    println!(
        "{use_:?} at {w}x{h}: peak {:.0} MB, plan {:.0} MB ({:.2} of it)",
        mb(got),
        mb(plan),
        got as f64 / plan as f64
    );
    assert!(got <= plan, "{use_:?}: peak {:.0} MB above its plan of {:.0} MB", mb(got), mb(plan));
    assert!(
        got * 3 >= plan,
        "{use_:?}: plan {:.0} MB over three times the peak {:.0} MB",
        mb(plan),
        mb(got)
    );
}

#[test]
fn every_rasterising_command_stays_within_its_plan() {
    within_plan(
        PixelUse::Render,
        (1024, 512),
        &["render", "--scene", SCENE, "--size", "1024x512", "--out", "r"],
        "render",
    );
    within_plan(
        PixelUse::Error,
        (1024, 512),
        &["error", "--scene", SCENE, "--size", "1024x512"],
        "error",
    );
    let source = format!("scene:{SCENE}");
    // Every target (the default), under the scene's own one-light configuration and under
    // four lights: the unit sets' evaluations grow with the lights.
    let all = [
        "vectors", "--source", &source, "--size", "1024x512", "--format", "bin", "--out", "v",
    ];
    within_plan(PixelUse::SceneVectors, (1024, 512), &all, "vectors");
    let dir = work("four_lights");
    std::fs::write(dir.join("four.toml"), "lights = 4\n").unwrap();
    let four = dir.join("four.toml").display().to_string();
    let mut args = all.to_vec();
    args.extend(["--config", &four]);
    within_plan(PixelUse::SceneVectors, (1024, 512), &args, "vectors4");
    within_plan(
        PixelUse::Engines,
        (512, 256),
        &["engines", "--scene", SCENE, "--size", "512x256", "--out", "e"],
        "engines",
    );
}
