//! Bad input, tried systematically: each case must end with a message that names the input
//! and the fix, a non-zero exit, no panic, and no partial output left in the output folder.

use assert_cmd::Command;
use std::path::Path;

#[path = "common/fake_tools.rs"]
mod fake_tools;

const WALL: &str = include_str!("../scenes/cg_wall_front.toml");
const TORUS: &str = include_str!("../scenes/torus_caps.toml");

/// (case, files to create, arguments, substrings the error must contain)
type Case = (&'static str, Vec<(&'static str, Vec<u8>)>, Vec<&'static str>, Vec<&'static str>);

fn scene(edit: impl Fn(&str) -> String) -> Vec<(&'static str, Vec<u8>)> {
    vec![("s.toml", edit(WALL).into())]
}

/// A configuration with the frame_transform unit, to which a frame source is added.
const FRAME: &str = "bump_state = \"fragment\"\nlight_mode = \"parallel\"\ninterpolate = \"hl\"\nrenormalise = true\nrenormalise_bump = true\nframe_transform = true\n";

/// An EMBM configuration (`tests/configs/embm.toml`'s fields).
const EMBM: &str = "lights = 4\nlight_mode = \"parallel\"\nbump_state = \"fragment\"\nenv_map_bits = 4\n";

fn cfg(text: &str) -> Vec<(&'static str, Vec<u8>)> {
    vec![("c.toml", text.into())]
}

fn space(text: &str) -> Vec<(&'static str, Vec<u8>)> {
    vec![("sp.toml", text.into())]
}

fn sweep() -> Vec<&'static str> {
    vec!["sweep", "--space", "sp.toml", "--out", "out", "--work", "w"]
}

/// A PNG of little more than a header declaring `w`×`h` greyscale pixels: tiny on disk, huge decoded.
fn png_header(w: u32, h: u32) -> Vec<u8> {
    let crc = |bytes: &[u8]| {
        let mut c = 0xffff_ffffu32;
        for b in bytes {
            c ^= *b as u32;
            for _ in 0..8 {
                c = if c & 1 == 1 { 0xedb8_8320 ^ (c >> 1) } else { c >> 1 };
            }
        }
        !c
    };
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([8, 0, 0, 0, 0]);
    let mut v = b"\x89PNG\r\n\x1a\n".to_vec();
    v.extend(13u32.to_be_bytes());
    v.extend(&ihdr);
    v.extend(crc(&ihdr).to_be_bytes());
    // A first IDAT chunk ends the header; its (truncated) zlib stream is never reached.
    let idat = b"IDAT\x78\x9c";
    v.extend(2u32.to_be_bytes());
    v.extend(idat);
    v.extend(crc(idat).to_be_bytes());
    v.extend(0u32.to_be_bytes());
    v.extend(b"IEND");
    v.extend(crc(b"IEND").to_be_bytes());
    v
}

fn render(extra: &[&'static str]) -> Vec<&'static str> {
    let mut v = vec!["render", "--scene", "s.toml", "--size", "32x16", "--out", "out"];
    v.extend_from_slice(extra);
    v
}

fn render_cfg() -> Vec<&'static str> {
    vec![
        "render",
        "--scene",
        "cg_wall_front",
        "--size",
        "32x16",
        "--config",
        "c.toml",
        "--out",
        "out",
    ]
}

fn cases() -> Vec<Case> {
    let r = |a: &str, b: &str| {
        let (a, b) = (a.to_string(), b.to_string());
        move |t: &str| {
            assert!(t.contains(&a), "test setup: `{a}` not in the scene");
            t.replacen(&a, &b, 1)
        }
    };
    let bump = "source = { kind = \"bricks\", rows = 8, cols = 4, mortar = 0.08 }";
    // Line `k` after the `[camera]` header of the base scene, where the edits below put a table.
    let after_camera = |k: usize| -> &'static str {
        let camera = WALL.lines().position(|l| l.trim() == "[camera]").expect("[camera]") + 1;
        Box::leak(format!("s.toml:{}", camera + k).into_boxed_str())
    };
    vec![
        (
            "unclosed table header",
            scene(r("[camera]", "[camera")),
            render(&[]),
            vec!["s.toml:", "fix:"],
        ),
        (
            "string for a number",
            scene(r("shininess = 8", "shininess = \"eight\"")),
            render(&[]),
            vec!["s.toml:", "invalid type"],
        ),
        (
            "a date where a number goes (TOML reads it as a date-time, not a map)",
            scene(r("height = 2.0", "height = 1979-05-27")),
            render(&[]),
            vec!["s.toml:", "camera.height", "date-time `1979-05-27`"],
        ),
        (
            "NaN",
            scene(r("height = 2.0", "height = nan")),
            render(&[]),
            vec!["s.toml", "camera.height", "finite"],
        ),
        (
            "+infinity",
            scene(r("colour = [0.95, 0.95, 0.95]", "colour = [inf, 0.95, 0.95]")),
            render(&[]),
            vec!["lights[0].colour[0]", "finite"],
        ),
        (
            "-infinity",
            scene(r("ambient = [0.05, 0.05, 0.05]", "ambient = [-inf, 0.05, 0.05]")),
            render(&[]),
            vec!["ambient[0]", "finite"],
        ),
        (
            "zero image size",
            scene(r("size = [256, 128]", "size = [0, 128]")),
            render_nosize(),
            vec!["size[0]", "1..=8192"],
        ),
        (
            "negative image size",
            scene(r("size = [256, 128]", "size = [-5, 128]")),
            render_nosize(),
            vec!["s.toml:", "invalid value"],
        ),
        (
            "huge image size",
            scene(r("size = [256, 128]", "size = [100000, 128]")),
            render_nosize(),
            vec!["size[0]", "1..=8192"],
        ),
        (
            "unknown field",
            scene(r("shininess = 8", "shininess = 8\nshinyness = 3")),
            render(&[]),
            vec!["unknown field", "shinyness"],
        ),
        (
            "a stray key beside a kind that takes no fields",
            scene(r(
                "shape = { kind = \"plane\", size = [4.0, 2.0] }",
                "shape = { kind = \"teapot\", segments = 9 }",
            )),
            render(&[]),
            vec!["s.toml:", "unknown field `segments`", "takes no fields"],
        ),
        (
            "a stray key beside a flat height source",
            scene(r(
                "source = { kind = \"bricks\", rows = 8, cols = 4, mortar = 0.08 }",
                "source = { kind = \"flat\", sise = 3 }",
            )),
            render(&[]),
            vec!["s.toml:", "unknown field `sise`"],
        ),
        (
            "every object with both blends off",
            scene(r("bump = {", "diffuse = false\nspecular = false\nbump = {")),
            render(&[]),
            vec!["s.toml:", "objects[0].diffuse", "nothing would be lit", "fix:"],
        ),
        (
            "a scene shown that covers no pixel",
            scene(r("target = [0.0, 0.0, 0.0]", "target = [0.0, 0.0, 12.0]")),
            vec!["scenes", "--show", "s.toml"],
            vec!["s.toml", "no object covers a pixel"],
        ),
        (
            "missing camera",
            scene(|t| t.replace("[camera]", "[kamera]")),
            render(&[]),
            vec!["s.toml", "kamera"],
        ),
        (
            "no objects",
            scene(|t| t[..t.find("[[objects]]").unwrap()].to_string()),
            render(&[]),
            vec!["s.toml", "objects"],
        ),
        (
            "zero light direction",
            scene(r(
                "kind = \"point\"\nposition = [0.0, 0.0, 3.0]",
                "kind = \"directional\"\ndirection = [0.0, 0.0, 0.0]",
            )),
            render(&[]),
            vec!["lights[0].direction", "shorter than 1e-12"],
        ),
        (
            "eye on the target",
            scene(r("eye = [0.0, 0.0, 6.0]", "eye = [0.0, 0.0, 0.0]")),
            render(&[]),
            vec!["camera.eye", "coincide"],
        ),
        (
            "up along the view",
            scene(r("up = [0.0, 1.0, 0.0]", "up = [0.0, 0.0, 1.0]")),
            render(&[]),
            vec!["s.toml", "camera.up", "parallel to the view", "fix:"],
        ),
        (
            "point light without a position",
            scene(r("kind = \"point\"\nposition = [0.0, 0.0, 3.0]", "kind = \"point\"")),
            render(&[]),
            vec!["s.toml", "lights[0]", "needs `position`", "fix:"],
        ),
        (
            "spot light without a direction",
            scene(r("kind = \"point\"", "kind = \"spot\"")),
            render(&[]),
            vec!["s.toml", "lights[0]", "needs `direction`", "fix:"],
        ),
        (
            "a direction on a point light",
            scene(r(
                "kind = \"point\"\nposition = [0.0, 0.0, 3.0]",
                "kind = \"point\"\nposition = [0.0, 0.0, 3.0]\ndirection = [0.0, 0.0, -1.0]",
            )),
            render(&[]),
            vec!["s.toml", "lights[0].direction", "does nothing on a point light", "fix:"],
        ),
        (
            "a cut-off on a directional light",
            scene(r(
                "kind = \"point\"\nposition = [0.0, 0.0, 3.0]",
                "kind = \"directional\"\ndirection = [0.0, 0.0, 1.0]\ncutoff_deg = 20.0",
            )),
            render(&[]),
            vec!["s.toml", "lights[0].cutoff_deg", "does nothing on a directional light", "fix:"],
        ),
        (
            "bump cylinder_sides past MAX_CYLINDER_SIDES",
            scene(r("strength = 10.0", "strength = 10.0, cylinder_sides = 4294967295")),
            render(&[]),
            vec!["s.toml", "objects[0].bump.cylinder_sides", "MAX_CYLINDER_SIDES", "fix:"],
        ),
        (
            "k above 1",
            scene(r("colour = [0.95, 0.95, 0.95]", "colour = [0.95, 0.95, 0.95]\nk = 1.5")),
            render(&[]),
            vec!["lights[0].k", "[0, 1]"],
        ),
        (
            "colour above 1",
            scene(r("colour = [0.95, 0.95, 0.95]", "colour = [2.0, 0.95, 0.95]")),
            render(&[]),
            vec!["lights[0].colour[0]", "out of range"],
        ),
        (
            "spot cut-off of 120 degrees",
            scene(r(
                "kind = \"point\"\nposition = [0.0, 0.0, 3.0]",
                "kind = \"spot\"\nposition = [0.0, 0.0, 3.0]\ndirection = [0.0, 0.0, -1.0]\ncutoff_deg = 120.0",
            )),
            render(&[]),
            vec!["lights[0].cutoff_deg", "[0, 90]"],
        ),
        (
            "negative bump strength",
            scene(r("strength = 10.0", "strength = -1.0")),
            render(&[]),
            vec!["objects[0].bump.strength"],
        ),
        (
            "bump map of size 0",
            scene(r("size = 128, strength", "size = 0, strength")),
            render(&[]),
            vec!["objects[0].bump.size", "2..=4096"],
        ),
        (
            "bump map of size 1",
            scene(r("size = 128, strength", "size = 1, strength")),
            render(&[]),
            vec!["objects[0].bump.size"],
        ),
        (
            "zero segments",
            scene(r("segments = [16, 8]", "segments = [0, 8]")),
            render(&[]),
            vec!["objects[0].segments[0]", "1..=1024"],
        ),
        (
            "sphere of one segment around",
            scene(|t: &str| r("kind = \"plane\", size = [4.0, 2.0]", "kind = \"sphere\", radius = 1.0")(t).replace("segments = [16, 8]", "segments = [1, 8]")),
            render(&[]),
            vec!["s.toml:23:1", "objects[0].segments[0]", "for a sphere", "3..=1024"],
        ),
        (
            "an up vector too short to give a direction",
            scene(r("up = [0.0, 1.0, 0.0]", "up = [0.0, 1e-13, 0.0]")),
            render(&[]),
            vec!["camera.up", "shorter than 1e-12", "fix: give a vector of length 1e-12 or more"],
        ),
        (
            "a prism with a u scale (each facet spans the map's u once)",
            scene(|t: &str| r("kind = \"plane\", size = [4.0, 2.0]", "kind = \"cylinder\", radius = 1.0, height = 2.0, sides = 6")(t)),
            render(&[]),
            vec!["objects[0].uv_scale[0]", "2 on a prism", "fix: drop uv_scale[0]"],
        ),
        (
            "a prism whose baked cylinder normals count other sides",
            scene(|t: &str| {
                r("kind = \"plane\", size = [4.0, 2.0]", "kind = \"cylinder\", radius = 1.0, height = 2.0, sides = 6")(t)
                    .replace("uv_scale = [2.0, 1.0]", "uv_scale = [1.0, 1.0]")
                    .replace("strength = 10.0", "strength = 10.0, cylinder_sides = 8")
            }),
            render(&[]),
            vec!["objects[0].bump.cylinder_sides", "8 on a prism of 6 sides", "fix: set cylinder_sides = 6"],
        ),
        (
            "quoted keys keep their line",
            scene(r("shape = { kind = \"plane\", size = [4.0, 2.0] }", "\"shape\" = { \"kind\" = \"plane\", \"size\" = [4.0, -2.0] }")),
            render(&[]),
            vec!["s.toml:22:", "objects[0].shape.size", "out of range"],
        ),
        (
            "object smaller than a pixel",
            scene(r("size = [4.0, 2.0]", "size = [4e-6, 2e-6]")),
            render(&[]),
            vec!["s.toml", "`objects`", "no object covers a pixel centre in front of camera.eye at 32×16", "fix:", "camera.target"],
        ),
        (
            "every object behind the eye (the camera looks away from them)",
            scene(r("target = [0.0, 0.0, 0.0]", "target = [0.0, 0.0, 12.0]")),
            render(&[]),
            vec!["s.toml", "no object covers a pixel centre in front of camera.eye", "move camera.eye back"],
        ),
        (
            "object beside the camera's view as a vector source",
            vec![("far.toml", r("target = [0.0, 0.0, 0.0]", "target = [50.0, 0.0, 0.0]")(WALL).into())],
            vec!["vectors", "--source", "scene:far.toml", "--target", "top", "--out", "out"],
            vec!["far.toml", "no object covers a pixel centre", "fix:"],
        ),
        (
            "prism with two sides",
            scene(r(
                "shape = { kind = \"plane\", size = [4.0, 2.0] }",
                "shape = { kind = \"cylinder\", radius = 1.0, height = 1.0, sides = 2 }",
            )),
            render(&[]),
            vec!["objects[0].shape.sides"],
        ),
        (
            "sphere of radius 0",
            scene(r(
                "shape = { kind = \"plane\", size = [4.0, 2.0] }",
                "shape = { kind = \"sphere\", radius = 0.0 }",
            )),
            render(&[]),
            vec!["objects[0].shape.radius"],
        ),
        (
            "unknown shape",
            scene(r("kind = \"plane\"", "kind = \"dodecahedron\"")),
            render(&[]),
            vec!["s.toml:", "dodecahedron"],
        ),
        (
            "unknown height source",
            scene(r("kind = \"bricks\"", "kind = \"cobbles\"")),
            render(&[]),
            vec!["s.toml:", "cobbles"],
        ),
        (
            "mortar wider than a brick",
            scene(r("mortar = 0.08", "mortar = 0.9")),
            render(&[]),
            vec!["objects[0].bump.source.mortar"],
        ),
        (
            "missing PNG height map",
            scene(r(bump, "source = { kind = \"png\", path = \"none.png\" }")),
            render(&[]),
            vec!["none.png", "PNG"],
        ),
        (
            "corrupt PNG height map",
            vec![
                ("s.toml", WALL.replacen(bump, "source = { kind = \"png\", path = \"bad.png\" }", 1).into()),
                ("bad.png", "\u{89}PNG not really".into()),
            ],
            render(&[]),
            vec!["bad.png", "PNG", "field `objects[0].bump.source.path`"],
        ),
        (
            "unknown scene name",
            vec![],
            vec!["render", "--scene", "nosuchscene", "--out", "out"],
            vec!["unknown scene", "gbump scenes"],
        ),
        (
            "missing scene file",
            vec![],
            vec!["render", "--scene", "missing.toml", "--out", "out"],
            vec!["missing.toml", "check the path"],
        ),
        (
            "empty scene file",
            vec![("s.toml", Vec::new())],
            render(&[]),
            vec!["s.toml:", "missing field"],
        ),
        (
            "normal_bits 0",
            cfg("normal_bits = 0\n"),
            render_cfg(),
            vec!["c.toml", "normal_bits", "3..=16"],
        ),
        (
            "normal_bits 1",
            cfg("normal_bits = 1\n"),
            render_cfg(),
            vec!["normal_bits", "3..=16"],
        ),
        ("lh_bits 33", cfg("lh_bits = 33\n"), render_cfg(), vec!["lh_bits", "4..=24"]),
        (
            "a table header where a number goes",
            cfg("[lights]\na = 1\n"),
            render_cfg(),
            vec!["c.toml:1:1", "`lights`: invalid type: map", "1..=8"],
        ),
        (
            "a renamed field out of range, under its old name",
            cfg("lights = 1\ndot_bits = 99\n"),
            render_cfg(),
            vec!["c.toml:2:1", "field `dot_bits`", "2..=16"],
        ),
        (
            "a renamed field under both names",
            cfg("lights = 1\n\"dot_bits\" = 9\ndot_frac_bits = 8\n"),
            render_cfg(),
            vec!["c.toml:2:1", "given twice", "keep `dot_frac_bits`"],
        ),
        (
            "a key with no value at the end of the file",
            cfg("lh_bits = 16\nshininess = "),
            render_cfg(),
            vec!["c.toml:2:", "`shininess` has no value"],
        ),
        (
            "a key with no value before the next line",
            cfg("lh_bits =\nshininess = 8\n"),
            render_cfg(),
            vec!["c.toml:1:", "`lh_bits` has no value"],
        ),
        (
            "triangle banks with per-fragment state",
            cfg("bump_state = \"fragment\"\ntriangle_banks = 4\n"),
            render_cfg(),
            vec!["c.toml", "`triangle_banks`", "does nothing here", "leave"],
        ),
        (
            "render --rtl of a palette configuration",
            cfg("palette = true\n"),
            vec!["render", "--scene", "torus_caps", "--size", "16x12", "--rtl", "--config", "c.toml", "--out", "out"],
            vec!["c.toml", "palette", "drop --rtl"],
        ),
        (
            "a built frame with no frame_transform unit to use it",
            cfg("bump_state = \"fragment\"\nframe_build = true\n"),
            render_cfg(),
            vec!["c.toml", "`frame_build`", "frame_transform", "drop frame_build"],
        ),
        (
            "L and H at the pixel without a frame (V is constant only in eye space)",
            cfg("bump_state = \"fragment\"\nlight_mode = \"parallel\"\ninterpolate = \"hl\"\nrenormalise = true\npixel_lh = true\n"),
            render_cfg(),
            vec!["c.toml:5:1", "`pixel_lh`", "eye space", "drop pixel_lh"],
        ),
        (
            "L and H at the pixel with H alone interpolated",
            cfg(&format!("{FRAME}pixel_lh = true\n").replace("interpolate = \"hl\"", "interpolate = \"h\"")),
            render_cfg(),
            vec!["c.toml:7:1", "`pixel_lh`", "interpolate = \"hl\" and renormalise = true"],
        ),
        (
            "a triangle's frame beside a built one",
            cfg(&format!("{FRAME}frame_build = true\ntriangle_frame = true\n")),
            render_cfg(),
            vec!["c.toml", "`triangle_frame`", "frame_build and triangle_frame", "keep one"],
        ),
        (
            "a quaternion frame with no frame_transform unit",
            cfg("bump_state = \"fragment\"\nframe_quaternion = true\n"),
            render_cfg(),
            vec!["c.toml", "`frame_quaternion`", "frame_transform = true", "drop frame_quaternion"],
        ),
        (
            "a quaternion frame beside a triangle's frame",
            cfg(&format!("{FRAME}triangle_frame = true\nframe_quaternion = true\n")),
            render_cfg(),
            vec!["c.toml", "`frame_quaternion`", "triangle_frame and frame_quaternion", "keep one"],
        ),
        (
            "segments of a power table",
            cfg("power_unit = \"table\"\npower_segments = 4\n"),
            render_cfg(),
            vec!["c.toml", "`power_segments`", "does nothing here"],
        ),
        (
            "a broken scene file shown",
            scene(r("size = [256, 128]", "size = ")),
            vec!["scenes", "--show", "s.toml"],
            vec!["s.toml:", "`size` has no value"],
        ),
        ("dot_frac_bits 64", cfg("dot_frac_bits = 64\n"), render_cfg(), vec!["dot_frac_bits", "2..=16"]),
        (
            "negative width",
            cfg("colour_bits = -8\n"),
            render_cfg(),
            vec!["c.toml:1:", "invalid value"],
        ),
        (
            "table size not a power of two",
            cfg("power_entries = 100\n"),
            render_cfg(),
            vec!["power_entries", "power of two"],
        ),
        (
            "table larger than the index",
            cfg("dot_frac_bits = 4\npower_entries = 256\n"),
            render_cfg(),
            vec!["power_entries", "dot_frac_bits"],
        ),
        ("zero light slots", cfg("lights = 0\n"), render_cfg(), vec!["lights", "1..=8"]),
        ("nine light slots", cfg("lights = 9\n"), render_cfg(), vec!["lights", "1..=8"]),
        (
            "unknown rounding",
            cfg("rounding = \"sideways\"\n"),
            render_cfg(),
            vec!["c.toml:1:", "sideways"],
        ),
        (
            "fewer slots than the scene's lights",
            cfg("lights = 1\n"),
            vec!["render", "--scene", "torus_caps", "--config", "c.toml", "--out", "out"],
            vec!["2 bump lights", "lights = 2"],
        ),
        (
            "no blend unit at all",
            cfg("diffuse = false\nspecular = false\n"),
            render_cfg(),
            vec!["diffuse", "enable"],
        ),
        (
            "size 0x10",
            vec![],
            vec!["render", "--scene", "cg_wall_front", "--size", "0x10", "--out", "out"],
            vec!["--size", "WxH"],
        ),
        (
            "size abc",
            vec![],
            vec!["render", "--scene", "cg_wall_front", "--size", "abc", "--out", "out"],
            vec!["--size", "WxH"],
        ),
        (
            "random:0",
            vec![],
            vec!["vectors", "--source", "random:0", "--out", "out"],
            vec!["random:0", "below 1", "MAX_RANDOM_VECTORS"],
        ),
        (
            "random:1e3",
            vec![],
            vec!["vectors", "--source", "random:1e3", "--out", "out"],
            vec!["random:1e3", "decimal digits alone", "fix:"],
        ),
        (
            "--shininess on a scene source",
            vec![],
            vec!["vectors", "--source", "scene:torus_caps", "--shininess", "8", "--out", "out"],
            vec!["--shininess has no effect", "own shininess", "drop --shininess"],
        ),
        (
            "--seed on a corner source",
            vec![],
            vec!["vectors", "--source", "corners", "--seed", "4", "--out", "out"],
            vec!["--seed has no effect", "drop --seed"],
        ),
        (
            "--level on a random source",
            vec![],
            vec!["vectors", "--source", "random:10", "--level", "2", "--out", "out"],
            vec!["--level has no effect", "corner catalogue"],
        ),
        (
            "unknown source",
            vec![],
            vec!["vectors", "--source", "bogus", "--out", "out"],
            vec!["--source bogus", "scene:NAME"],
        ),
        (
            "unsweepable unit",
            vec![],
            vec!["vectors", "--source", "exhaustive:dot_clamp", "--out", "out"],
            vec!["dot_clamp", "random:N"],
        ),
        (
            "unknown target",
            vec![],
            vec!["vectors", "--source", "corners", "--target", "alu", "--out", "out"],
            vec!["--target alu", "top"],
        ),
        (
            "shininess 5000",
            vec![],
            vec!["vectors", "--source", "corners", "--shininess", "5000", "--out", "out"],
            vec!["--shininess", "0..=1024"],
        ),
        (
            "cube map of size 0",
            vec![],
            vec!["rom", "--cube-size", "0", "--out", "out"],
            vec!["--cube-size", "1..=1024"],
        ),
        (
            "scene vectors of a palette configuration",
            cfg("palette = true\n"),
            vec!["vectors", "--source", "scene:torus_caps", "--config", "c.toml", "--out", "out"],
            vec!["palette", "palette = false"],
        ),
        (
            "a result file named as a missing folder",
            vec![],
            vec!["error", "--json", "missing_dir/"],
            vec!["missing_dir/", "names a folder", "give a file name"],
        ),
        (
            "a wrong type inside a shape",
            vec![(
                "s.toml",
                include_str!("../scenes/torus_caps.toml").replacen("major = 1.0", "major = \"big\"", 1).into(),
            )],
            vec!["render", "--scene", "s.toml", "--out", "out"],
            vec!["s.toml:25:", "objects[0].shape.major", "expected f64"],
        ),
        (
            "a scene named twice to fit-table",
            vec![],
            vec!["fit-table", "--scene", "torus_caps", "--scene", "torus_caps"],
            vec!["--scene torus_caps", "more than once"],
        ),
        (
            "an EMBM scene's map reader as a target of its own",
            cfg(EMBM),
            vec!["vectors", "--source", "scene:torus_caps", "--target", "env_fetch_specular", "--config", "c.toml", "--out", "out"],
            vec!["--target env_fetch_specular", "own maps", "only the top loads", "exhaustive:env_fetch_specular"],
        ),
        (
            "corrupt vector manifest",
            vec![("m.json", "{ not json".into())],
            vec!["regress", "--sim", "icarus", "--vectors", "m.json", "--work", "out"],
            vec!["m.json", "manifest"],
        ),
        (
            "a set's .hex data file given as its manifest",
            vec![("set.hex", "0123456789abcdef\n".into())],
            vec!["regress", "--sim", "icarus", "--vectors", "set.hex", "--work", "out"],
            vec!["set.hex:1:", "give the set's manifest", "set.json (the .hex file"],
        ),
        (
            "fuzz for -1 minutes",
            vec![],
            vec!["fuzz", "--minutes=-1", "--work", "out"],
            vec!["--minutes -1", "a negative number"],
        ),
        // A name that becomes part of a path (issue item 5).
        (
            "scene name climbs out of --out",
            scene(r("name = \"cg_wall_front\"", "name = \"../escaped\"")),
            render(&[]),
            vec!["s.toml:3", "`name`", "../escaped", "fix:"],
        ),
        (
            "absolute scene name",
            scene(r("name = \"cg_wall_front\"", "name = \"/tmp/gbump-absolute-name\"")),
            render(&[]),
            vec!["s.toml:3", "`name`", "fix:"],
        ),
        (
            "hidden scene name",
            scene(r("name = \"cg_wall_front\"", "name = \".hidden\"")),
            render(&[]),
            vec!["s.toml:3", "`name`"],
        ),
        (
            "scene file stem with a space as a vector source",
            vec![("my scene.toml", WALL.into())],
            vec!["vectors", "--source", "scene:my scene.toml", "--target", "top", "--out", "out"],
            vec!["--source scene:my scene.toml", "holding ' '", "fix: rename the scene file"],
        ),
        (
            "scene file stem too long for its sets' file names",
            vec![("cccccccccccccccccccccccccc.toml", WALL.into())],
            vec!["vectors", "--source", "scene:cccccccccccccccccccccccccc.toml", "--size", "32x24", "--out", "out"],
            vec!["_light_accumulate_power_table.hex", "MAX_NAME_CHARS", "fix: rename the scene file: at least 1 character shorter,"],
        ),
        (
            "scene file regressed with a stem too long for its top set's file names",
            vec![("cccccccccccccccccccccccccccccccccccccccc.toml", WALL.into())],
            vec!["regress", "--scene", "cccccccccccccccccccccccccccccccccccccccc.toml", "--no-scenes", "--random-icarus", "10", "--target", "top", "--sim", "icarus", "--work", "w"],
            vec!["--scene cccccccccccccccccccccccccccccccccccccccc.toml:", "_top_power_table.hex", "MAX_NAME_CHARS", "fix: rename the scene file: at least"],
        ),
        (
            "scene file given to a fit (regressed at the end) with a stem too long for its sets",
            vec![("cccccccccccccccccccccccccccccccccccccccc.toml", WALL.into())],
            vec!["fit", "--scene", "cccccccccccccccccccccccccccccccccccccccc.toml", "--budget", "max<=2", "--out", "out", "--work", "w"],
            vec!["MAX_NAME_CHARS", "fix: rename the scene file: at least"],
        ),
        (
            "scene file with a non-ASCII name regressed as the user's own scene",
            vec![("scène.toml", WALL.into())],
            vec!["regress", "--scene", "scène.toml", "--no-scenes", "--random-icarus", "10", "--target", "top", "--sim", "icarus", "--work", "w"],
            vec!["--scene scène.toml:", "scene_scène", "holding 'è', which a plain name may not", "fix: rename the scene file"],
        ),
        (
            "report run outside the checkout, its default sweep space absent",
            vec![],
            vec!["report", "--out", "out", "--work", "w"],
            vec!["--space sweeps/small.toml: not found from", "fix: run gbump report from the checkout, or pass --space FILE"],
        ),
        (
            "sweep space with a hidden stem",
            vec![(".sp.toml", "[grid]\nlights = [1, 2]\n".into())],
            vec!["sweep", "--space", ".sp.toml", "--out", "out", "--work", "w"],
            vec![".sp.toml", "file name", "fix:"],
        ),
        // Sizes and counts bounded before allocating (item 6).
        (
            "PNG header declaring 12000x12000",
            vec![
                ("s.toml", WALL.replacen(bump, "source = { kind = \"png\", path = \"big.png\" }", 1).into()),
                ("big.png", png_header(12000, 12000)),
            ],
            render(&[]),
            vec!["big.png", "12000x12000", "MAX_BUMP_SIDE"],
        ),
        (
            "PNG header declaring 2^31-1 a side (past the decoder's own allocation limit)",
            vec![
                ("s.toml", WALL.replacen(bump, "source = { kind = \"png\", path = \"huge.png\" }", 1).into()),
                ("huge.png", png_header(i32::MAX as u32, i32::MAX as u32)),
            ],
            render(&[]),
            vec!["huge.png", "2147483647x2147483647", "MAX_BUMP_SIDE"],
        ),
        (
            "teapot at the largest segments",
            scene(|t| {
                t.replacen("kind = \"plane\", size = [4.0, 2.0]", "kind = \"teapot\"", 1)
                    .replacen("segments = [16, 8]", "segments = [1024, 1024]", 1)
            }),
            render(&[]),
            // The object that makes them is named, with its shape's own rule and its segments.
            vec!["s.toml", "MAX_TRIANGLES", "(a teapot) makes", "64 triangles per segment pair", "[1024, 1024]"],
        ),
        (
            "an output folder whose files pass the system's path length",
            vec![],
            vec![
                "render",
                "--scene",
                "torus_caps",
                "--size",
                "32x16",
                "--out",
                // 4,086 characters: the folders can be made, their files cannot; the run
                // fails with every folder made, and none may be left.
                Box::leak(format!("out/{}/{}", vec!["d".repeat(200); 20].join("/"), "e".repeat(62)).into_boxed_str()),
            ],
            vec!["torus_caps_golden.png", "File name too long", "fix:"],
        ),
        (
            "an unknown subcommand with a carriage return",
            vec![],
            vec!["rend\rer", "--out", "out"],
            vec!["unrecognized subcommand", "rend\\u{d}er"],
        ),
        (
            "a value clap refuses, holding a carriage return",
            vec![],
            vec!["vectors", "--source", "random:10", "--out", "out", "--format", "b\rin"],
            vec!["invalid value", "b\\u{d}in", "--format"],
        ),
        (
            "an output folder holding a bell character (it would be written raw into every header)",
            vec![],
            vec!["rtl", "--out", "o\u{7}bell"],
            vec!["--out \"o\\u{7}bell\"", "control character", "fix:"],
        ),
        (
            "a configuration path holding a newline",
            vec![],
            vec!["rtl", "--config", "x\ny.toml", "--out", "out"],
            vec!["--config \"x\\ny.toml\"", "control character", "fix:"],
        ),
        (
            "a source given as --source=VALUE holding a newline",
            vec![],
            vec!["vectors", "--source=random:1\n0", "--out", "out"],
            vec!["--source \"random:1\\n0\"", "control character", "fix:"],
        ),
        (
            "a random count past 64 bits, quoted as given",
            vec![],
            vec!["vectors", "--source", "random:99999999999999999999999", "--out", "out"],
            vec!["99999999999999999999999 exceeds MAX_RANDOM_VECTORS", "fix:"],
        ),
        (
            "a scene that needs more lights than the --config file has: the file is named",
            vec![("one.toml", "lights = 1\nlight_mode = \"parallel\"\n".into())],
            vec!["vectors", "--source", "scene:torus_caps", "--config", "one.toml", "--out", "out"],
            vec!["one.toml: field `lights`", "2 bump lights", "fix: set lights = 2"],
        ),
        (
            "a configuration written under a scene's [pipeline] header",
            vec![("c.toml", "[pipeline]\nlights = 2\n".into())],
            vec!["rtl", "--config", "c.toml", "--out", "out"],
            vec!["c.toml:1:", "unknown field `pipeline`", "a configuration file is flat"],
        ),
        (
            "--size 16384x16384",
            vec![],
            vec!["render", "--scene", "cg_wall_front", "--size", "16384x16384", "--out", "out"],
            vec!["--size", "MAX_IMAGE_SIDE"],
        ),
        (
            "--size 8192x8192 does not fit in memory",
            vec![],
            vec!["render", "--scene", "cg_wall_front", "--size", "8192x8192", "--out", "out"],
            vec!["8192x8192", "GiB", "MAX_MEMORY_BYTES", "fix:"],
        ),
        (
            "sweep grid of 423360 points",
            space("[grid]\nlights = [1, 2, 3, 4, 5, 6, 7, 8]\nnormal_bits = [3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16]\nlh_bits = [4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24]\ndot_bits = [2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16]\nk_bits = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]\n"),
            sweep(),
            vec!["sp.toml", "423360", "MAX_SWEEP_POINTS"],
        ),
        (
            "config read from /dev/urandom",
            vec![],
            vec!["render", "--scene", "cg_wall_front", "--config", "/dev/urandom", "--out", "out"],
            vec!["/dev/urandom", "MAX_INPUT_BYTES"],
        ),
        (
            "scene read from /dev/urandom",
            vec![],
            vec!["render", "--scene", "/dev/urandom", "--out", "out"],
            vec!["/dev/urandom", "MAX_INPUT_BYTES"],
        ),
        (
            "error --random beyond its memory bound",
            vec![],
            vec!["error", "--random", "10000000000"],
            vec!["--random", "MAX_ERROR_STIMULI"],
        ),
        (
            "exhaustive texture_modulate at 12-bit colour",
            cfg("colour_bits = 12\n"),
            vec!["vectors", "--source", "exhaustive:texture_modulate", "--config", "c.toml", "--out", "out"],
            vec!["MAX_EXHAUSTIVE_VECTORS", "random:N"],
        ),
        // Every input checked before the first expensive step or output (item 7).
        (
            "sweep of an unknown scene",
            space("scene = \"nosuchscene\"\n[grid]\nlights = [1, 2]\n"),
            sweep(),
            vec!["sp.toml:1", "`scene`", "nosuchscene", "gbump scenes"],
        ),
        (
            "error --size 0x0",
            vec![],
            vec!["error", "--size", "0x0", "--random", "10"],
            vec!["--size 0x0", "WxH"],
        ),
        (
            "report with a missing space",
            vec![],
            vec!["report", "--space", "nosuch.toml", "--out", "out", "--work", "w"],
            vec!["nosuch.toml", "check the path"],
        ),
        // Zero and empty refused before anything is written (item 8).
        (
            "error --random 0",
            vec![],
            vec!["error", "--random", "0"],
            vec!["--random", "0 is below 1"],
        ),
        (
            "exhaustive sweep of the power unit under its old name",
            cfg(""),
            vec!["vectors", "--source", "exhaustive:power_table", "--config", "c.toml", "--out", "out"],
            vec!["exhaustive:power_table", "renamed `power_unit`", "fix:"],
        ),
        (
            "a target under its old name",
            cfg(""),
            vec!["vectors", "--source", "corners", "--target", "power_table", "--config", "c.toml", "--out", "out"],
            vec!["--target power_table", "renamed `power_unit`", "fix:"],
        ),
        (
            "exhaustive power unit without a specular path",
            cfg("specular = false\n"),
            vec!["vectors", "--source", "exhaustive:power_unit", "--config", "c.toml", "--out", "out"],
            vec!["power_unit", "specular = false", "fix:"],
        ),
        (
            "target absent from the configuration",
            cfg("diffuse = false\n"),
            vec!["vectors", "--source", "corners", "--target", "diffuse_blend", "--config", "c.toml", "--out", "out"],
            vec!["--target diffuse_blend", "diffuse = false"],
        ),
        (
            "the same target twice",
            vec![],
            vec!["vectors", "--source", "corners", "--target", "top", "--target", "top", "--out", "out"],
            vec!["--target top", "second time"],
        ),
        (
            "a target already in all",
            vec![],
            vec!["vectors", "--source", "random:10", "--target", "all", "--target", "bump_fetch", "--out", "out"],
            vec!["--target bump_fetch", "second time"],
        ),
        (
            "fuzz --configs 0",
            vec![],
            vec!["fuzz", "--configs", "0", "--work", "w"],
            vec!["--configs", "0 is below 1"],
        ),
        (
            "fuzz --random 0",
            vec![],
            vec!["fuzz", "--random", "0", "--work", "w"],
            vec!["--random", "0 is below 1"],
        ),
        (
            "regress --target of a unit the configuration lacks",
            vec![],
            vec!["regress", "--target", "normalise", "--work", "w"],
            vec!["--target normalise", "the configuration has no normalise", "fix:"],
        ),
        (
            "regress --target unknown",
            vec![],
            vec!["regress", "--target", "top", "--target", "bogus", "--work", "w"],
            vec!["--target bogus: unknown", "fix:"],
        ),
        (
            "regress --max-errors 0",
            vec![],
            vec!["regress", "--max-errors", "0", "--work", "w"],
            vec!["--max-errors", "0 is below 1"],
        ),
        (
            "a scene the configuration another --scene derives cannot render",
            vec![],
            vec!["vectors", "--source", "scene:torus_caps", "--scene", "cg_wall_front", "--size", "16x12", "--out", "out"],
            vec!["the configuration --scene cg_wall_front derives", "fix: give --scene torus_caps", "gbump config --scene torus_caps"],
        ),
        (
            "regress --max-errors past a bench's 32-bit count",
            vec![],
            vec!["regress", "--max-errors", "2147483648", "--work", "w"],
            vec!["--max-errors", "2147483648", "MAX_ERRORS_REPORTED"],
        ),
        (
            "cosim --max-errors past a bench's 32-bit count",
            vec![],
            vec!["cosim", "--max-errors", "4294967295", "--work", "w"],
            vec!["--max-errors", "4294967295", "MAX_ERRORS_REPORTED"],
        ),
        // Messages point at the right line and name the right file (item 9).
        (
            "wrong type in a scene's [pipeline]",
            scene(r("[camera]", "[pipeline]\nlights = \"two\"\n\n[camera]")),
            render(&[]),
            vec![after_camera(1), "pipeline.lights", "invalid type"],
        ),
        (
            "out-of-range value in a scene's [pipeline]",
            scene(r("[camera]", "[pipeline]\nshininess = 8\ndot_bits = 99\n\n[camera]")),
            render(&[]),
            vec![after_camera(2), "pipeline.dot_bits", "2..=16"],
        ),
        (
            "a renamed field under both names in a scene's [pipeline]",
            scene(r("[camera]", "[pipeline]\ndot_frac_bits = 8\n\"dot_bits\" = 6\n\n[camera]")),
            render(&[]),
            vec![after_camera(2), "given twice", "keep `dot_frac_bits`"],
        ),
        (
            "a dotted [pipeline] key out of range",
            scene(r("[camera]", "pipeline.lights = 9\n\n[camera]")),
            render(&[]),
            vec![after_camera(0), "pipeline.lights", "1..=8"],
        ),
        (
            "[pipeline] lights below the scene's bump lights",
            vec![("t.toml", TORUS.replacen("[camera]", "[pipeline]\nlights = 1\n\n[camera]", 1).into())],
            vec!["render", "--scene", "t.toml", "--size", "16x16", "--out", "out"],
            vec!["t.toml:9", "pipeline.lights", "(t.toml) has 2 bump lights", "lights = 2"],
        ),
        (
            "wrong type in a sweep grid",
            space("scene = \"torus_caps\"\n\n[grid]\nlights = [1, 2]\nnormal_bits = [6, \"eight\"]\n"),
            sweep(),
            vec!["sp.toml:5", "grid.normal_bits", "invalid type"],
        ),
        (
            "a sweep grid none of whose points can render its scene",
            space("scene = \"torus_caps\"\n\n[grid]\nlights = [1]\n"),
            sweep(),
            vec!["sp.toml", "no grid point can render the scene torus_caps", "2 bump lights", "fix: change the grid"],
        ),
        (
            "a sweep grid whose every point is an invalid combination",
            space("[grid]\npalette = [true]\nrenormalise_bump = [true]\n"),
            sweep(),
            vec!["sp.toml", "every point is an invalid combination", "palette=true renormalise_bump=true", "fix:"],
        ),
        (
            "--json naming the --config it reads",
            vec![("c.toml", "lights = 2\n".into())],
            vec!["error", "--config", "c.toml", "--json", "c.toml", "--random", "10", "--size", "32x24"],
            vec!["c.toml: an input of this run", "fix: give the output another path"],
        ),
        (
            "a sweep whose results would be written over its space file",
            vec![("pts.json", "scene = \"torus_caps\"\n[grid]\nlights = [2]\n".into())],
            vec!["sweep", "--space", "pts.json", "--out", ".", "--work", "w"],
            vec!["pts.json: an input of this run"],
        ),
        (
            "an output file in a folder nothing can be written in",
            vec![],
            vec!["area", "--json", "/proc/gbump.json", "--work", "w"],
            vec!["--json", "cannot write in /proc", "fix: give a path under a folder you can write to"],
        ),
        (
            "a --work folder that is a file",
            vec![("afile", "x".into())],
            vec!["bench", "--work", "afile"],
            vec!["gbump: error: --work afile: afile is a file, not a folder", "\n  fix: give a folder path"],
        ),
        (
            "an --out folder that is a file (gbump's own check: exit 1, not the parser's 2)",
            vec![("afile", "x".into())],
            vec!["rom", "--out", "afile"],
            vec!["gbump: error: --out afile: afile is a file, not a folder", "\n  fix: give a folder path"],
        ),
        (
            "a corner level out of its range",
            vec![],
            vec!["vectors", "--source", "corners", "--level", "3", "--out", "out"],
            vec!["gbump: error: --level 3: 3 is not in 1..=2", "fix: use 1..=2"],
        ),
        (
            "error at a size no built-in scene covers a pixel of",
            vec![],
            vec!["error", "--size", "1x1", "--random", "10"],
            vec!["--size 1x1", "no object covers a pixel", "fix: give a larger --size"],
        ),
        (
            "a fit budget beyond any colour's range",
            vec![],
            vec!["fit", "--scene", "torus_caps", "--budget", "max<=1e308", "--no-regress", "--out", "out"],
            vec!["max<=1e308", "out of range", "at most 4095 LSB"],
        ),
        (
            "a negative --min-throughput",
            vec![],
            vec!["fit", "--scene", "torus_caps", "--budget", "max<=2", "--min-throughput=-1", "--out", "out"],
            vec!["--min-throughput -1", "a negative number"],
        ),
        (
            "power-space --max-n beyond MAX_SHININESS",
            vec![],
            vec!["power-space", "--max-n", "99999999999"],
            vec!["--max-n", "1..=1024"],
        ),
        (
            "a counted field given a value of the wrong type",
            vec![("c.toml", "lights = nan\n".into())],
            vec!["rtl", "--config", "c.toml", "--out", "out"],
            vec!["c.toml:1", "`lights`", "fix: `lights` is a whole number in 1..=8"],
        ),
        (
            "a negative count",
            vec![],
            vec!["regress", "--random", "-5", "--work", "w"],
            vec!["--random -5: a negative number", "fix: give --random a value in its range"],
        ),
        (
            "a minus zero, after a space (the parser took it for a flag)",
            vec![],
            vec!["rom", "--shininess", "-0", "--out", "out"],
            vec!["--shininess -0: a negative number", "fix: give --shininess a value in its range"],
        ),
        (
            "a minus zero, after `=` (the parser read it as 0)",
            vec![],
            vec!["rom", "--shininess=-0", "--out", "out"],
            vec!["--shininess -0: a negative number", "fix: give --shininess a value in its range"],
        ),
        (
            "unknown field in a sweep base",
            space("[base]\nlights = 2\nbogus = 1\n\n[grid]\nlights = [1, 2]\n"),
            sweep(),
            vec!["sp.toml:3", "base.bogus", "unknown field"],
        ),
        (
            "manifest naming a file outside its folder",
            vec![(
                "m.json",
                include_str!("../vectors/corners_top.json")
                    .replacen("\"name\": \"corners_top.hex\"", "\"name\": \"../corners_top.hex\"", 1)
                    .into(),
            )],
            vec!["regress", "--sim", "icarus", "--vectors", "m.json", "--work", "w"],
            vec!["m.json", "hex.name", "../corners_top.hex"],
        ),
        (
            "manifest column whose role alone was edited",
            vec![(
                "m.json",
                include_str!("../vectors/corners_top.json")
                    .replacen("\"role\": \"expected\"", "\"role\": \"stimulus\"", 1)
                    .into(),
            )],
            vec!["regress", "--sim", "icarus", "--vectors", "m.json", "--work", "w"],
            vec!["m.json", "columns", "(stimulus, u8.0)", "(expected, u8.0)"],
        ),
        (
            "manifest with a key gbump does not write",
            vec![(
                "m.json",
                include_str!("../vectors/corners_top.json")
                    .replacen("\"count\":", "\"sead\": 1,\n  \"count\":", 1)
                    .into(),
            )],
            vec!["regress", "--sim", "icarus", "--vectors", "m.json", "--work", "w"],
            vec!["m.json", "unknown field `sead`"],
        ),
        (
            "render of a built-in scene at a size too small for any pixel centre: the size is the fault, not the scene",
            vec![],
            vec!["render", "--scene", "torus_caps", "--size", "1x1", "--out", "o"],
            vec!["scene torus_caps at 1x1: no object covers a pixel centre", "fix: give a larger size (the scene's own is 256x192)"],
        ),
        (
            "a size that starts with a minus sign (clap had said `unexpected argument '-1'`)",
            vec![],
            vec!["render", "--size", "-16x12", "--out", "o"],
            vec!["--size -16x12: a negative number", "fix:"],
        ),
        (
            "manifest naming neither a text nor a binary file",
            vec![("m.json", {
                let t = include_str!("../vectors/corners_top.json");
                let (a, b) = (t.find("  \"hex\": {").unwrap(), t.find("  \"power_table\": {").unwrap());
                format!("{}{}", &t[..a], &t[b..]).into()
            })],
            vec!["regress", "--sim", "icarus", "--vectors", "m.json", "--work", "w"],
            vec!["m.json: names neither a `hex` nor a `bin` file", "fix: regenerate the set with: gbump vectors"],
        ),
        (
            "regress --scene-size 8192x8192",
            vec![],
            vec!["regress", "--scene-size", "8192x8192", "--work", "w"],
            vec!["8192x8192", "MAX_MEMORY_BYTES"],
        ),
        (
            "cosim --lib given a folder",
            vec![],
            vec!["cosim", "--lib", "/tmp", "--work", "w"],
            vec!["/tmp: a folder, not the gbump C library", "fix:"],
        ),
        (
            "cosim --lib given a device",
            vec![],
            vec!["cosim", "--lib", "/dev/null", "--work", "w"],
            vec!["/dev/null: not a regular file", "fix:"],
        ),
        (
            "regress --scene-size on a stream without scenes",
            vec![],
            vec!["regress", "--stream", "random:100", "--scene-size", "8x8", "--work", "w"],
            vec!["--scene-size 8x8", "no effect", "fix:"],
        ),
        (
            "regress --scene-size with --no-scenes",
            vec![],
            vec!["regress", "--no-scenes", "--scene-size", "8x8", "--work", "w"],
            vec!["--scene-size 8x8", "--no-scenes", "fix:"],
        ),
        (
            "a scene's fragments at a size too small for any object",
            vec![],
            vec!["vectors", "--source", "scene:torus_caps", "--size", "1x1", "--out", "out"],
            vec!["torus_caps at 1x1", "give a larger size", "256x192"],
        ),
        (
            "regress --seed on a stream that draws nothing at random",
            vec![],
            vec!["regress", "--stream", "corners", "--seed", "5", "--work", "w"],
            vec!["--seed 5", "no effect", "fix:"],
        ),
        (
            "regress --waves on a stream",
            vec![],
            vec!["regress", "--stream", "random:100", "--waves", "--work", "w"],
            vec!["--waves", "no waveforms", "fix:"],
        ),
        (
            "regress --scene-size for a palette configuration",
            cfg("palette = true\n"),
            vec!["regress", "--config", "c.toml", "--scene-size", "8x8", "--work", "w"],
            vec!["--scene-size 8x8", "palette configuration", "fix:"],
        ),
        (
            "--size for a source without an image",
            vec![],
            vec!["vectors", "--source", "corners", "--size", "64x64", "--out", "out"],
            vec!["--size", "scene:NAME"],
        ),
        (
            "output folder is a file",
            vec![("out", "I am a file".into())],
            vec!["rtl", "--out", "out"],
            vec!["out"],
        ),
        (
            "more bump lights than light slots",
            scene(|t| {
                let light = "\n[[lights]]\nkind = \"directional\"\ndirection = [0.0, 0.0, 1.0]\ncolour = [0.1, 0.1, 0.1]\n";
                t.to_string() + &light.repeat(9)
            }),
            render_nosize(),
            vec!["s.toml", "light slots", "bump = false"],
        ),
        (
            "a scene's derived configuration with more bump lights than slots",
            scene(|t| {
                let light = "\n[[lights]]\nkind = \"directional\"\ndirection = [0.0, 0.0, 1.0]\ncolour = [0.1, 0.1, 0.1]\n";
                t.to_string() + &light.repeat(9)
            }),
            vec!["rtl", "--scene", "s.toml", "--out", "out"],
            vec!["s.toml", "light slots"],
        ),
        (
            "an array longer than its field",
            scene(r("size = [256, 128]", "size = [256, 128, 3]")),
            render_nosize(),
            vec!["s.toml:", "size", "3 values where the field takes 2", "give exactly 2"],
        ),
        (
            "a huge number",
            scene(r("height = 2.0", "height = 1e300")),
            render_nosize(),
            vec!["s.toml:", "1e300 is out of range"],
        ),
        (
            "a folder as the configuration",
            vec![],
            vec!["render", "--config", ".", "--out", "out"],
            vec!["folder", "give the file itself"],
        ),
        (
            "--shininess on a ROM power table",
            cfg(include_str!("configs/power_rom.toml")),
            vec!["vectors", "--source", "random:10", "--target", "top", "--config", "c.toml", "--shininess", "3", "--out", "out"],
            vec!["--shininess 3", "ROM holding shininess", "fix:"],
        ),
        (
            "--shininess on a squaring power unit's own unit set",
            cfg("power_unit = \"squaring\"\n"),
            vec!["vectors", "--source", "random:10", "--target", "power_unit", "--config", "c.toml", "--shininess", "40", "--out", "out"],
            vec!["--shininess 40", "squares for shininess", "fix:"],
        ),
        (
            "--shininess on a squaring power unit's exhaustive sweep",
            cfg("power_unit = \"squaring\"\n"),
            vec!["vectors", "--source", "exhaustive:power_unit", "--config", "c.toml", "--shininess", "40", "--out", "out"],
            vec!["--shininess 40", "squares for shininess", "fix:"],
        ),
        (
            "--shininess on EMBM, which has no power unit",
            cfg(EMBM),
            vec!["vectors", "--source", "random:10", "--config", "c.toml", "--shininess", "40", "--out", "out"],
            vec!["--shininess has no effect", "EMBM has no power unit", "fix: drop --shininess"],
        ),
        (
            "area-model calibrated on fewer configurations than its coefficients",
            vec![],
            vec!["area-model", "--configs", "tests/area_model/configs", "--calibrate", "3"],
            vec!["--calibrate 3", "8 coefficients", "fix: --calibrate 8 or more"],
        ),
        (
            "an interface JSON given as the configuration",
            cfg("{\n  \"top\": \"gbump_pipeline_3dc36989\"\n}\n"),
            vec!["rtl", "--config", "c.toml", "--out", "out"],
            vec!["c.toml: JSON, not a configuration's TOML", "fix:"],
        ),
        (
            "an exhaustive source with another target",
            vec![],
            vec!["vectors", "--source", "exhaustive:power_unit", "--target", "top", "--out", "out"],
            vec!["--target", "power_unit", "fix:"],
        ),
        (
            "regress --random on Icarus alone, which runs no Verilator",
            vec![],
            vec!["regress", "--sim", "icarus", "--random", "7", "--no-scenes", "--work", "w"],
            vec!["--random 7: no effect on this run", "fix: drop --random (--random-icarus is Icarus's)"],
        ),
        (
            "regress --random-icarus on Verilator alone",
            vec![],
            vec!["regress", "--sim", "verilator", "--random-icarus", "9", "--no-scenes", "--work", "w"],
            vec!["--random-icarus 9: no effect on this run", "fix: drop --random-icarus"],
        ),
        (
            "regress --seed with no random vectors to draw",
            vec![],
            vec!["regress", "--random", "0", "--random-icarus", "0", "--seed", "5", "--work", "w"],
            vec!["--seed 5: no effect on this run", "fix: drop --seed"],
        ),
        (
            "rom --cube-size other than the configuration's normalisation cube map",
            cfg("renormalise = true\ninterpolate = \"hl\"\nbump_state = \"fragment\"\nlight_mode = \"parallel\"\ncube_map_face = 32\n"),
            vec!["rom", "--config", "c.toml", "--cube-size", "6", "--out", "out"],
            vec!["--cube-size 6", "fix: drop --cube-size", "whose cube_map_face is the size you want"],
        ),
        (
            "regress --vectors with --random",
            vec![],
            vec!["regress", "--vectors", "x.json", "--random", "5", "--work", "w"],
            vec!["cannot be used with"],
        ),
        (
            "--json under a file",
            vec![("afile", "a file".into())],
            vec!["error", "--json", "afile/x.json", "--random", "10"],
            vec!["afile is a file", "fix:"],
        ),
        (
            "a sweep grid value outside its field's range",
            space("scene = \"torus_caps\"\n[grid]\nnormal_bits = [1, 8]\n"),
            sweep(),
            vec!["sp.toml", "grid.normal_bits", "3..=16"],
        ),
        (
            "a sweep base value outside its field's range",
            space("scene = \"torus_caps\"\n[base]\nnormal_bits = 1\n[grid]\nlh_bits = [12, 16]\n"),
            sweep(),
            vec!["sp.toml:3", "base.normal_bits", "3..=16"],
        ),
        (
            "a key in both [base] and [grid]",
            space("scene = \"torus_caps\"\n[base]\nnormal_bits = 6\n[grid]\nnormal_bits = [6, 8]\n"),
            sweep(),
            vec!["sp.toml", "base.normal_bits", "both", "fix:"],
        ),
        (
            "fit --out on a file",
            vec![("afile", "a file".into())],
            vec!["fit", "--scene", "torus_caps", "--budget", "max<=2", "--no-regress", "--out", "afile"],
            vec!["afile is a file"],
        ),
        (
            "a colon in the work folder (make's rule separator)",
            vec![],
            vec!["regress", "--sim", "icarus", "--work", "w:c"],
            vec!["':'", "rule separator", "fix:"],
        ),
        (
            "claim --list with --out",
            vec![],
            vec!["claim", "--list", "--out", "x"],
            vec!["cannot be used with"],
        ),
        (
            "fit naming a scene twice",
            vec![],
            vec!["fit", "--scene", "torus_caps", "--scene", "torus_caps", "--budget", "max<=2", "--no-regress", "--out", "out"],
            vec!["--scene torus_caps", "more than once"],
        ),
        (
            "cosim --lib that is not a library",
            vec![("lib.so", "not a library".into())],
            vec!["cosim", "--lib", "lib.so", "--work", "w"],
            vec!["lib.so", "not a shared library", "fix:"],
        ),
        (
            "vectors into a folder that cannot be made",
            vec![],
            vec!["vectors", "--source", "corners", "--out", "/proc/gbump_out"],
            vec!["/proc/gbump_out", "--out", "cannot write in /proc", "fix:"],
        ),
        (
            "a configuration value out of range, at its line",
            vec![("c.toml", "normal_bits = 8\nlights = 99\n".into())],
            vec!["rtl", "--config", "c.toml", "--out", "out"],
            vec!["c.toml:2:1: field `lights`", "99 is out of range", "fix:"],
        ),
        (
            "rtl into an empty path (the working folder, unasked)",
            vec![],
            vec!["rtl", "--out", ""],
            vec!["--out: an empty value", "fix:"],
        ),
        (
            "vectors into --out= with no value",
            vec![],
            vec!["vectors", "--out="],
            vec!["--out: an empty value", "fix:"],
        ),
        (
            "rtl into a folder whose path the filelists would split",
            vec![],
            vec!["rtl", "--out", "sp ace/rtl"],
            vec!["--out sp ace/rtl", "' '", "fix:"],
        ),
        (
            // An ELF file without this gbump's source hash: a library of another build.
            "cosim --lib of another build",
            vec![("lib.so", "\u{7f}ELF a library of other sources, gbump_abi_version\0".into())],
            vec!["cosim", "--lib", "lib.so", "--work", "w"],
            vec!["lib.so", "built from other sources than this gbump", "gbump --version", "fix:"],
        ),
        (
            "a scene file given as --config",
            vec![("s.toml", TORUS.into())],
            vec!["rtl", "--config", "s.toml", "--out", "out"],
            vec!["s.toml", "this is a scene file", "--scene"],
        ),
        (
            "a configuration given as --scene",
            vec![("c.toml", "lights = 2\nlight_mode = \"parallel\"\n".into())],
            vec!["render", "--scene", "c.toml", "--out", "out"],
            vec!["c.toml", "pipeline configuration", "--config"],
        ),
        (
            "a vector set named twice",
            vec![],
            vec!["regress", "--vectors", "v.json", "--vectors", "./v.json", "--work", "w"],
            vec!["v.json", "given more than once", "fix:"],
        ),
        (
            // A program, not a library: named as such, not as a build of other sources.
            "cosim --lib given the gbump executable",
            vec![],
            vec!["cosim", "--lib", env!("CARGO_BIN_EXE_gbump"), "--work", "w"],
            vec!["an executable", "not the gbump C library", "libgbump.so", "fix:"],
        ),
        (
            "an engine named twice",
            vec![],
            vec!["engines", "--engine", "blinn", "--engine", "blinn", "--out", "out"],
            vec!["--engine blinn", "more than once"],
        ),
        (
            "--device off ice40",
            vec![],
            vec!["area", "--device", "up5k", "--work", "w"],
            vec!["--device", "no effect", "fix:"],
        ),
    ]
}

fn render_nosize() -> Vec<&'static str> {
    vec!["render", "--scene", "s.toml", "--out", "out"]
}

fn leftovers(dir: &Path) -> Vec<String> {
    let out = dir.join("out");
    if out.is_file() {
        return vec![];
    }
    std::fs::read_dir(&out)
        .map(|d| {
            d.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn every_bad_input_is_refused_cleanly() {
    let cases = cases();
    assert!(cases.len() >= 89, "{} cases", cases.len());
    let mut failures = Vec::new();
    // The README's claims table counts these cases.
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    assert!(
        readme.contains(&format!("`tests/bad_input.rs`: {} table-driven cases", cases.len())),
        "the README does not say `tests/bad_input.rs`: {} table-driven cases",
        cases.len()
    );
    for (name, files, args, needles) in cases {
        let dir = tempfile::tempdir().unwrap();
        // The case's folder is the parent of `out`: anything new beside `out` escaped it.
        let root = dir.path().join("case");
        std::fs::create_dir(&root).unwrap();
        for (f, text) in &files {
            std::fs::write(root.join(f), text).unwrap();
        }
        let out = Command::cargo_bin("gbump")
            .unwrap()
            .args(&args)
            .current_dir(&root)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        let escaped = std::fs::read_dir(dir.path())
            .unwrap()
            .chain(std::fs::read_dir(&root).unwrap())
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n != "case" && n != "out" && !files.iter().any(|f| f.0 == n));
        let problems: Vec<String> = [
            (out.status.success(), "exit status 0".to_string()),
            // The README's exit statuses: 1 for gbump's own errors, 2 for clap's usage errors.
            (
                out.status.code() != Some(if err.contains("gbump: error:") { 1 } else { 2 }),
                format!(
                    "exit status {:?} (the README: 1 for an error, 2 for a usage error)",
                    out.status.code()
                ),
            ),
            (err.contains("panicked"), "panic".to_string()),
            (!err.contains("error:"), "no error message".to_string()),
            (!out.stdout.is_empty(), "printed results before refusing".to_string()),
            // Every message, clap's usage errors too, shows an argument's control characters
            // escaped: a carriage return or an escape sequence could rewrite the terminal.
            (
                err.chars().any(|c| c.is_control() && c != '\n' && c != '\t'),
                "a raw control character in the message".to_string(),
            ),
        ]
        .into_iter()
        .filter(|(bad, _)| *bad)
        .map(|(_, m)| m)
        .chain(needles.iter().filter(|n| !err.contains(*n)).map(|n| format!("message lacks `{n}`")))
        .chain(leftovers(&root).into_iter().map(|f| format!("left output behind: {f}")))
        .chain(escaped.map(|f| format!("wrote outside the case folder: {f}")))
        .collect();
        if !problems.is_empty() {
            failures.push(format!("{name}: {}\n    stderr: {}", problems.join("; "), err.trim()));
        }
    }
    assert!(
        failures.is_empty(),
        "{} case(s) misbehaved:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn a_full_stdout_and_an_unwritable_folder_are_errors() {
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .arg("config")
        .stdout(full)
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("No space left"));
    // The help and the version too (clap's own exit had ignored the failed write).
    for flag in ["--help", "--version"] {
        let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
            .arg(flag)
            .stdout(full)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.code() == Some(1) && err.contains("No space left"), "{flag}: {err}");
    }
    // A reader that closed standard output (`gbump config | head -1`): quiet, with the
    // status of a tool killed by SIGPIPE, not an error.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .arg("config")
        .stdout(writer)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(141), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stderr.is_empty(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .args(["rtl", "--out", "/proc/gbump-no"])
        .output()
        .unwrap();
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("/proc/gbump-no"));
}

#[test]
fn writing_into_a_full_device_fails_and_removes_what_was_written() {
    // An output file that is a device: written in place (never renamed over), so /dev/full's
    // ENOSPC surfaces, and the files written before it are removed again.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    std::os::unix::fs::symlink("/dev/full", out.join("cg_wall_front_metrics.json")).unwrap();
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .args(["render", "--scene", "cg_wall_front", "--size", "16x8", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("No space left"), "{err}");
    let left: Vec<_> = std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left.len(), 1, "only the device link remains: {left:?}");
    assert!(std::fs::metadata("/dev/full").unwrap().file_type().is_char_device_like());
}

trait CharDev {
    fn is_char_device_like(&self) -> bool;
}
impl CharDev for std::fs::FileType {
    fn is_char_device_like(&self) -> bool {
        use std::os::unix::fs::FileTypeExt;
        self.is_char_device()
    }
}

#[test]
fn a_crashing_simulator_is_reported_as_a_crash() {
    let dir = tempfile::tempdir().unwrap();
    // A vvp that dies of SIGSEGV.
    let path = fake_tools::icarus(&dir.path().join("bin"), "kill -SEGV $$");
    let vectors = Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors/corners_top.json");
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .env("PATH", path)
        .args(["regress", "--sim", "icarus", "--work"])
        .arg(dir.path().join("w"))
        .arg("--vectors")
        .arg(vectors)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{text}");
    assert!(text.contains("crashed") && text.contains("signal 11"), "{text}");
}

/// A simulator that floods its output (a runaway `$display`) costs gbump a bounded amount of
/// memory: under a 3 GB address-space limit, which reading the output whole passed within
/// seconds (an allocation failure, an abort with a backtrace), the run is stopped at the tool
/// time limit and fails as a hung tool does.
#[test]
fn a_flooding_simulator_costs_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let path = fake_tools::icarus(
        &dir.path().join("bin"),
        "if [ \"$1\" = --version ]; then echo fake vvp; exit 0; fi\nexec yes 'MISMATCH a line the simulator repeats'",
    );
    let vectors = Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors/corners_top.json");
    let o = std::process::Command::new("sh")
        .env("PATH", path)
        .args(["-c", "ulimit -v 3000000; exec \"$0\" \"$@\""])
        .arg(env!("CARGO_BIN_EXE_gbump"))
        .args(["regress", "--sim", "icarus", "--tool-timeout", "4", "--work"])
        .arg(dir.path().join("w"))
        .arg("--vectors")
        .arg(vectors)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{}", &text[text.len().saturating_sub(3000)..]);
    assert!(
        !text.contains("memory allocation") && !text.contains("panicked"),
        "{}",
        &text[text.len().saturating_sub(3000)..]
    );
    // Stopped at the limit while flooding, not refused before it ran.
    assert!(
        text.contains("vvp ran for more than the tool time limit") && text.contains("MISMATCH a line the simulator repeats"),
        "{}",
        &text[text.len().saturating_sub(3000)..]
    );
}

/// A simulator that never ends (here a vvp whose own child sleeps) is stopped at the tool time
/// limit, with the processes it started, and the run fails naming the limit; a limit that is
/// not a positive number of seconds is refused before anything runs, from the flag or from
/// the environment.
#[test]
fn a_hung_simulator_is_stopped_at_the_tool_time_limit() {
    let dir = tempfile::tempdir().unwrap();
    let pid_file = dir.path().join("sleeper.pid");
    // Answers `--version` (the presence probe) unless HANG_PROBE is set; hangs on a run.
    let path = fake_tools::icarus(
        &dir.path().join("bin"),
        &format!(
            "if [ \"$1\" = --version ] && [ -z \"$HANG_PROBE\" ]; then echo fake vvp; exit 0; fi\nsleep 1000 &\necho $! > {}\nwait",
            pid_file.display()
        ),
    );
    let vectors = Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors/corners_top.json");
    let run = |limit: &[&str], env: Option<&str>| {
        let mut c = Command::cargo_bin("gbump").unwrap();
        c.env("PATH", &path).env_remove("GBUMP_TOOL_TIMEOUT");
        if let Some(v) = env {
            c.env("GBUMP_TOOL_TIMEOUT", v);
        }
        c.args(["regress", "--sim", "icarus", "--work"])
            .arg(dir.path().join("w"))
            .arg("--vectors")
            .arg(&vectors)
            .args(limit)
            .timeout(std::time::Duration::from_secs(120));
        let o = c.output().unwrap();
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr),
        )
    };
    for (limit, env) in [(&["--tool-timeout", "2"][..], None), (&[][..], Some("2"))] {
        let t = std::time::Instant::now();
        let (code, text) = run(limit, env);
        assert_eq!(code, Some(1), "{text}");
        assert!(text.contains("ran for more than the tool time limit (2 s"), "{text}");
        assert!(t.elapsed().as_secs() < 60, "stopped late: {text}");
        let sleeper = std::fs::read_to_string(&pid_file).unwrap();
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", sleeper.trim())).unwrap_or_default();
        // Gone, or a zombie waiting for init to reap it.
        assert!(
            stat.is_empty() || stat.rsplit_once(')').unwrap().1.trim_start().starts_with('Z'),
            "the tool's child still runs: {stat}"
        );
    }
    // A vvp that hangs on `--version` too is named as hung before anything is built.
    let t = std::time::Instant::now();
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .env("PATH", &path)
        .env("HANG_PROBE", "1")
        .args(["regress", "--sim", "icarus", "--work"])
        .arg(dir.path().join("w"))
        .arg("--vectors")
        .arg(&vectors)
        .timeout(std::time::Duration::from_secs(120))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.code() == Some(1) && text.contains("vvp did not answer `vvp --version` within"),
        "{text}"
    );
    assert!(t.elapsed() < gbump::tool::PROBE_LIMIT * 3, "the probe waited {:?}", t.elapsed());
    for (limit, env, says) in [
        (&["--tool-timeout", "0"][..], None, "--tool-timeout 0"),
        (&["--tool-timeout", "inf"][..], None, "--tool-timeout inf"),
        (&["--tool-timeout", "1e400"][..], None, "--tool-timeout 1e400"),
        // A limit that rounds to no time at all would stop every tool as it starts.
        (&["--tool-timeout", "1e-300"][..], None, "--tool-timeout 1e-300"),
        (&[][..], Some("0.0000001"), "GBUMP_TOOL_TIMEOUT=0.0000001"),
        (&[][..], Some("soon"), "GBUMP_TOOL_TIMEOUT=soon"),
    ] {
        let (code, text) = run(limit, env);
        assert!(code == Some(1) && text.contains(says) && text.contains("fix:"), "{text}");
        assert!(!text.contains("passed"), "a refused limit still ran: {text}");
    }
}

/// Ctrl-C, a CI runner's SIGTERM, a closed terminal's SIGHUP and every other signal whose
/// default ends a process each stop a dump midway with nothing left behind; so does the same signal sent twice a few milliseconds apart, as GNU
/// `timeout` sends it (to the process, then to its group), which had cut the cleanup short
/// and left the half-written set under its temporary name.
#[test]
fn an_interrupted_dump_leaves_nothing_behind() {
    let cases = [
        ("INT", false),
        ("TERM", false),
        ("HUP", false),
        ("INT", true),
        ("TERM", true),
        // Ctrl-\\, `ulimit -t`, a timer, a user signal: they had ended the run at once.
        ("QUIT", false),
        ("XCPU", false),
        ("ALRM", false),
        ("USR1", false),
    ];
    for (signal, twice) in cases {
        let dir = tempfile::tempdir().unwrap();
        let child = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
            .args([
                "vectors",
                "--source",
                "random:50000000",
                "--format",
                if twice { "both" } else { "bin" },
                "--target",
                "top",
                "--out",
            ])
            .arg(dir.path().join("out"))
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(1500));
        send(signal, child.id());
        if twice {
            // At once, as `timeout` does (`kill`, a process of its own, would space them).
            let sig = if signal == "INT" { libc::SIGINT } else { libc::SIGTERM };
            // SAFETY: a plain kill(2) of the child this test started and still waits for.
            unsafe {
                libc::kill(child.id() as libc::pid_t, sig);
            }
        }
        let o = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "SIG{signal}: {err}");
        // Every way a signal ends a run says so with one prefix.
        assert!(
            err.contains("gbump: interrupted: ") && !err.contains("gbump: error: "),
            "SIG{signal}: {err}"
        );
        let want = 128
            + match signal {
                "INT" => libc::SIGINT,
                "TERM" => libc::SIGTERM,
                "HUP" => libc::SIGHUP,
                "QUIT" => libc::SIGQUIT,
                "XCPU" => libc::SIGXCPU,
                "ALRM" => libc::SIGALRM,
                _ => libc::SIGUSR1,
            };
        assert_eq!(
            o.status.code(),
            Some(want),
            "SIG{signal}: a stopped run exits 128 + the signal's number whichever step noticed: {err}"
        );
        let left: Vec<_> = std::fs::read_dir(dir.path().join("out"))
            .map(|d| d.map(|e| e.unwrap().file_name()).collect())
            .unwrap_or_default();
        assert!(left.is_empty(), "SIG{signal} left behind: {left:?}");
    }
}

/// A dump larger than the free space under its folder is refused before a byte is written.
#[test]
fn a_dump_larger_than_the_disk_is_refused_first() {
    let dir = tempfile::tempdir().unwrap();
    let free = gbump::limits::free_bytes(dir.path()).expect("statvfs");
    let n = gbump::limits::MAX_RANDOM_VECTORS;
    let cfg = gbump::PipelineConfig::default();
    let need: u64 = gbump::vectors::targets::resolve(&cfg, &["all".to_string()])
        .unwrap()
        .iter()
        .map(|t| {
            let l = gbump::vectors::targets::layout(&cfg, t);
            (l.bytes() + l.hex_digits() + 1) as u64 * n
        })
        .sum();
    assert!(
        need > free,
        "this disk holds {free} bytes free, more than the {need} the test needs to exceed"
    );
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .args(["vectors", "--source", &format!("random:{n}"), "--out"])
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("B free") && err.contains("fix:"), "{err}");
    let left: Vec<_> = std::fs::read_dir(dir.path().join("out"))
        .map(|d| d.map(|e| e.unwrap().file_name()).collect())
        .unwrap_or_default();
    assert!(left.is_empty(), "left behind: {left:?}");
    // A regression dumps for itself into its work folder: its fix names its own options.
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .args(["regress", "--random", &n.to_string(), "--sim", "verilator", "--no-scenes", "--work"])
        .arg(dir.path().join("work"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("B free"), "{err}");
    assert!(err.contains("--work folder on a larger disk") && err.contains("--stream"), "{err}");
    assert!(!err.contains("--format") && !err.contains("--out"), "{err}");
}

/// One SIGTERM ends a run blocked where no loop looks (writing its JUnit report into a
/// named pipe nobody reads), within the grace period: a CI timeout sends no second one.
#[test]
fn one_signal_ends_a_run_blocked_on_a_named_pipe() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("junit.xml");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["regress", "--vectors", "vectors/corners_top.json", "--sim", "icarus", "--work"])
        .arg(dir.path().join("work"))
        .arg("--junit")
        .arg(&fifo)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Until the regression has run and the report's open blocks.
    let start = std::time::Instant::now();
    while !dir.path().join("work").exists() || start.elapsed().as_secs() < 3 {
        assert!(child.try_wait().unwrap().is_none(), "the run ended before it blocked");
        assert!(start.elapsed().as_secs() < 120, "the run never started");
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    std::thread::sleep(std::time::Duration::from_secs(2));
    let sent = std::time::Instant::now();
    send("TERM", child.id());
    let grace = gbump::interrupt::STOP_GRACE.as_secs();
    let st = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break st;
        }
        assert!(
            sent.elapsed().as_secs() < grace + 10,
            "still running {} s after one SIGTERM",
            grace + 10
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    assert_eq!(
        st.code(),
        Some(128 + libc::SIGTERM),
        "SIGTERM: 143, as the shell reports a process the signal ended"
    );
}

fn send(signal: &str, pid: u32) {
    std::process::Command::new("kill")
        .args([&format!("-{signal}"), &pid.to_string()])
        .status()
        .unwrap();
}

/// A vector manifest is checked field against field before anything runs: its data files'
/// checksums cannot see an edit of the manifest itself. An oversized or binary file given as
/// the manifest is refused as such.
#[test]
fn an_edited_manifest_is_refused_before_anything_runs() {
    let dir = tempfile::tempdir().unwrap();
    let gbump = || Command::cargo_bin("gbump").unwrap();
    gbump()
        .args(["vectors", "--source", "random:20", "--target", "top", "--out", "v"])
        .current_dir(dir.path())
        .assert()
        .success();
    let text = std::fs::read_to_string(dir.path().join("v/random20_top.json")).unwrap();
    let m: serde_json::Value = serde_json::from_str(&text).unwrap();
    let edits: Vec<(&str, Box<dyn Fn(&mut serde_json::Value)>, Vec<&str>)> = vec![
        (
            "the configuration",
            Box::new(|m| m["config"]["lights"] = 3.into()),
            vec!["field `config`", "config_hash", "fix: regenerate"],
        ),
        (
            "the record width",
            Box::new(|m| m["record_bits"] = 600.into()),
            vec!["field `columns`", "record layout", "fix: regenerate"],
        ),
        (
            "a column",
            Box::new(|m| m["columns"][0]["width"] = 9999.into()),
            vec!["field `columns`", "fix: regenerate"],
        ),
        (
            "the target",
            Box::new(|m| m["target"] = "nosuchunit".into()),
            vec!["field `target`", "nosuchunit", "fix: regenerate"],
        ),
        (
            "the target, to another unit of the configuration",
            Box::new(|m| m["target"] = "power_unit".into()),
            vec![
                "field `target`",
                "`power_unit` is not this set's target",
                "`top`'s",
                "fix: regenerate",
            ],
        ),
        (
            "the shininess",
            Box::new(|m| m["shininess"] = 100000.into()),
            vec!["field `shininess`", "MAX_SHININESS"],
        ),
    ];
    for (what, edit, needles) in edits {
        let mut e = m.clone();
        edit(&mut e);
        let path = dir.path().join("v/edited.json");
        std::fs::write(&path, serde_json::to_string(&e).unwrap()).unwrap();
        let o = gbump()
            .args(["regress", "--sim", "icarus", "--vectors"])
            .arg(&path)
            .args(["--work", "w"])
            .current_dir(dir.path())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{what}: {err}");
        for n in needles {
            assert!(err.contains(n), "{what}: message lacks `{n}`: {err}");
        }
        assert!(
            !dir.path().join("w").exists() || std::fs::read_dir(dir.path().join("w")).unwrap().next().is_none(),
            "{what}: ran before refusing"
        );
    }
    // A good set first and a broken one second, with no --config: the configuration comes
    // from the first, and nothing is said or written (its copy in the work folder) before
    // the second is refused.
    let o = gbump()
        .args([
            "regress",
            "--sim",
            "icarus",
            "--vectors",
            "v/random20_top.json",
            "--vectors",
            "v/edited.json",
            "--work",
            "w",
        ])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("edited.json"), "{err}");
    assert!(o.stdout.is_empty(), "said before refusing: {}", String::from_utf8_lossy(&o.stdout));
    assert!(
        !dir.path().join("w").exists() || std::fs::read_dir(dir.path().join("w")).unwrap().next().is_none(),
        "wrote before refusing the second set"
    );
    std::fs::write(dir.path().join("big.json"), vec![b' '; 2 << 20]).unwrap();
    for (file, needle) in [("big.json", "MAX_INPUT_BYTES"), ("v/random20_top.bin", "not UTF-8")] {
        let o = gbump()
            .args(["regress", "--sim", "icarus", "--vectors", file, "--work", "w"])
            .current_dir(dir.path())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains(needle) && err.contains(".json manifest"),
            "{file}: {err}"
        );
    }
}

/// With nothing written to clean up, a signal ends gbump at once, as the signal's default
/// would: a long computation is not finished only to be thrown away.
#[test]
fn a_signal_outside_any_cleanup_exits_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .args(["engines", "--size", "1600x1200", "--out"])
        .arg(dir.path().join("out"))
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the render ended before the signal: make it larger"
    );
    let sent = std::time::Instant::now();
    send("TERM", child.id());
    let st = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break st;
        }
        assert!(sent.elapsed().as_secs() < 5, "still running 5 s after SIGTERM");
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    assert!(!st.success());
    assert!(!dir.path().join("out").exists(), "an interrupted run left its output folder");
}

/// A signal ignored when gbump starts (`nohup`'s SIGHUP) stays ignored: the run completes.
#[test]
fn an_ignored_hangup_stays_ignored() {
    use std::os::unix::process::CommandExt;
    let dir = tempfile::tempdir().unwrap();
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"));
    cmd.args([
        "vectors",
        "--source",
        "random:8000000",
        "--target",
        "top",
        "--format",
        "bin",
        "--out",
    ])
    .arg(dir.path().join("out"))
    .stdout(std::process::Stdio::null())
    .stderr(std::process::Stdio::piped());
    // SAFETY: only async-signal-safe libc calls between fork and exec.
    unsafe {
        cmd.pre_exec(|| {
            libc::signal(libc::SIGHUP, libc::SIG_IGN);
            Ok(())
        });
    }
    let mut child = cmd.spawn().unwrap();
    // Long enough to start and install its handler; far shorter than the dump.
    std::thread::sleep(std::time::Duration::from_millis(150));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the dump ended before the hangup: make it longer"
    );
    send("HUP", child.id());
    let o = child.wait_with_output().unwrap();
    assert!(
        o.status.success(),
        "a hangup nohup ignores stopped the run: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(dir.path().join("out/random8000000_top.json").is_file());
}

/// A named pipe given as an input file is refused, not waited on forever.
#[test]
fn a_named_pipe_as_input_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("c.toml");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .args(["rtl", "--config"])
        .arg(&fifo)
        .arg("--out")
        .arg(dir.path().join("out"))
        .timeout(std::time::Duration::from_secs(20))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("named pipe") && err.contains("fix:"), "{err}");
    assert!(!dir.path().join("out").exists());
}

/// A named pipe in place of any file a vector set's manifest names (the records, the power
/// table) is refused when the set is checked, not waited on.
#[test]
fn a_named_pipe_in_a_vector_set_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    Command::cargo_bin("gbump")
        .unwrap()
        .args(["vectors", "--source", "random:20", "--target", "top", "--out", "v"])
        .current_dir(dir.path())
        .assert()
        .success();
    for file in ["random20_top.hex", "random20_top_power_table.hex"] {
        let set = dir.path().join(format!("s_{file}"));
        std::fs::create_dir(&set).unwrap();
        for e in std::fs::read_dir(dir.path().join("v")).unwrap() {
            let e = e.unwrap();
            std::fs::copy(e.path(), set.join(e.file_name())).unwrap();
        }
        std::fs::remove_file(set.join(file)).unwrap();
        assert!(std::process::Command::new("mkfifo").arg(set.join(file)).status().unwrap().success());
        let o = Command::cargo_bin("gbump")
            .unwrap()
            .args(["regress", "--sim", "icarus", "--vectors"])
            .arg(set.join("random20_top.json"))
            .arg("--work")
            .arg(dir.path().join("w"))
            .timeout(std::time::Duration::from_secs(60))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains("named pipe") && err.contains(file) && err.contains("fix:"),
            "{file}: {err}"
        );
    }
}

/// A sweep space may name `target = "cmos"`: gate equivalents, what every sweep measures.
#[test]
fn a_sweep_for_cmos_measures_gate_equivalents() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("sp.toml"),
        "scene = \"torus_caps\"\ntarget = \"cmos\"\n[grid]\nnormal_bits = [6, 8]\n",
    )
    .unwrap();
    Command::cargo_bin("gbump")
        .unwrap()
        .args(["sweep", "--space", "sp.toml", "--out", "so", "--work", "w"])
        .current_dir(dir.path())
        .assert()
        .success();
    assert!(dir.path().join("so/sp.csv").is_file());
}

/// While a simulator build runs: SIGINT to gbump alone (a runner's timeout, `kill`), or
/// SIGKILL to gbump's process group (a CI runner cancelling; gbump cannot handle SIGKILL, so
/// its tools must share its group): the build's whole process tree (Verilator, make, the
/// compiler) ends with gbump, nothing left writing into the work folder.
#[test]
fn a_signal_during_a_build_ends_the_builds_processes() {
    if let Some(why) = gbump::tool::unusable("verilator") {
        panic!("verilator is {why}: scripts/install-tools.sh installs it");
    }
    for signal in ["INT", "KILL"] {
        let dir = tempfile::tempdir().unwrap();
        let work = std::fs::canonicalize(dir.path()).unwrap().join("work");
        use std::os::unix::process::CommandExt;
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
            .args(["regress", "--sim", "verilator", "--random", "100", "--no-scenes", "--work"])
            .arg(&work)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            // Its own group, as a shell job or a runner's step is.
            .process_group(0)
            .spawn()
            .unwrap();
        // Wait for a build in progress: a temporary build folder under the work folder.
        let building =
            || std::fs::read_dir(work.join("build")).is_ok_and(|d| d.flatten().any(|e| e.file_name().to_string_lossy().contains(".tmp")));
        let t = std::time::Instant::now();
        while !building() {
            assert!(child.try_wait().unwrap().is_none(), "gbump ended before its build started");
            assert!(t.elapsed().as_secs() < 120, "no build started in 120 s");
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        std::thread::sleep(std::time::Duration::from_millis(1500));
        // SIGKILL goes to the group, as a runner's cancel does; SIGINT to gbump alone.
        let target = if signal == "KILL" {
            format!("-{}", child.id())
        } else {
            child.id().to_string()
        };
        std::process::Command::new("kill")
            .args([&format!("-{signal}"), "--", &target])
            .status()
            .unwrap();
        let st = child.wait().unwrap();
        assert!(!st.success());
        // Every process still working in the work folder (the build's cwd) after a grace period
        // (a compiler left orphaned would go on for seconds, until its file is done).
        let mut left = Vec::new();
        for _ in 0..10 {
            std::thread::sleep(std::time::Duration::from_millis(100));
            left = std::fs::read_dir("/proc")
                .unwrap()
                .flatten()
                .filter_map(|e| {
                    let cwd = std::fs::read_link(e.path().join("cwd")).ok()?;
                    let cmd = std::fs::read_to_string(e.path().join("cmdline")).unwrap_or_default();
                    cwd.starts_with(&work)
                        .then(|| format!("{}: {}", e.file_name().to_string_lossy(), cmd.replace('\0', " ")))
                })
                .collect();
            if left.is_empty() {
                break;
            }
        }
        assert!(
            left.is_empty(),
            "SIG{signal}: processes left running in {}:\n{}",
            work.display(),
            left.join("\n")
        );
    }
}

/// A work folder reached through a symbolic link is checked where it really is: make cannot
/// build in a path with a space, and the link must not hide one (refused before anything is
/// written, the link and its target named).
#[test]
fn a_link_to_a_path_with_a_space_is_refused_as_the_path_is() {
    let d = tempfile::tempdir().unwrap();
    let real = d.path().join("real sp");
    std::fs::create_dir(&real).unwrap();
    std::os::unix::fs::symlink(&real, d.path().join("link")).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "regress",
            "--config",
            "tests/configs/one_light_parallel.toml",
            "--sim",
            "verilator",
            "--target",
            "top",
            "--work",
        ])
        .arg(d.path().join("link").join("w"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("through a link") && err.contains("real sp") && err.contains("fix:"),
        "{err}"
    );
    assert_eq!(std::fs::read_dir(&real).unwrap().count(), 0, "written before the refusal");
}

/// An argument that is not UTF-8 is named (the option it is the value of, or its place), not
/// only "invalid UTF-8 was detected in one or more arguments".
#[test]
fn an_argument_that_is_not_utf8_is_named() {
    use std::os::unix::ffi::OsStrExt;
    let bad = std::ffi::OsStr::from_bytes(b"a\xffb.toml");
    let dir = tempfile::tempdir().unwrap();
    for (args, needle) in [
        (
            vec!["render".as_ref(), "--scene".as_ref(), bad, "--out".as_ref(), "out".as_ref()],
            "--scene \"a\u{fffd}b.toml\"",
        ),
        (vec!["render".as_ref(), bad], "argument 2 \"a\u{fffd}b.toml\""),
    ] {
        let out = Command::cargo_bin("gbump")
            .unwrap()
            .args(&args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{err}");
        for n in [needle, "not UTF-8", "fix:"] {
            assert!(err.contains(n), "`{n}` missing from: {err}");
        }
        assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none(), "left output behind");
    }
}

/// An output that is a symbolic link into a folder that does not exist is refused, naming the
/// link, where it leads and the fix, and no folder is made for it: a link is written through,
/// never used to make folders (a `--junit` link to /nonexistent/j.xml had created /nonexistent).
#[test]
fn a_link_into_a_missing_folder_is_refused_without_making_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let gone = d.join("gone");
    let link = |at: &Path, name: &str| {
        std::fs::create_dir_all(at).unwrap();
        std::os::unix::fs::symlink(gone.join(name), at.join(name)).unwrap();
    };
    let cfg = gbump::PipelineConfig::default();
    let top = format!("{}.v", gbump::rtlgen::units_v::module_name(&cfg, "gbump_pipeline"));
    link(&d.join("rtl"), &top);
    link(&d.join("v"), "random10_top.hex");
    link(d, "j.xml");
    let runs: [Vec<String>; 3] = [
        vec!["rtl".into(), "--out".into(), d.join("rtl").display().to_string()],
        vec![
            "vectors".into(),
            "--source".into(),
            "random:10".into(),
            "--target".into(),
            "top".into(),
            "--out".into(),
            d.join("v").display().to_string(),
        ],
        vec![
            "regress".into(),
            "--sim".into(),
            "icarus".into(),
            "--vectors".into(),
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("vectors/corners_top.json")
                .display()
                .to_string(),
            "--work".into(),
            d.join("w").display().to_string(),
            "--junit".into(),
            d.join("j.xml").display().to_string(),
        ],
    ];
    for args in runs {
        let o = Command::cargo_bin("gbump").unwrap().args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains("a symbolic link to") && err.contains("gone") && err.contains("fix:"),
            "{}: {err}",
            args[0]
        );
        assert!(
            !err.contains(".gbump.tmp"),
            "{}: the message names a temporary file: {err}",
            args[0]
        );
        assert!(!gone.exists(), "{} made the link's missing folder", args[0]);
    }
}

/// An output folder that is a loop of symbolic links (a -> b -> a) is named as a loop, not
/// as a link to something missing to be created.
#[test]
fn an_output_folder_in_a_loop_of_links_is_named_as_a_loop() {
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink("b", dir.path().join("a")).unwrap();
    std::os::unix::fs::symlink("a", dir.path().join("b")).unwrap();
    for args in [
        vec!["vectors", "--source", "random:10", "--target", "top", "--out", "a"],
        vec!["rtl", "--out", "a"],
    ] {
        let o = Command::cargo_bin("gbump")
            .unwrap()
            .args(&args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains("a: a loop of symbolic links") && err.contains("fix:"),
            "{}: {err}",
            args[0]
        );
        assert!(!err.contains("does not exist"), "{}: {err}", args[0]);
    }
}

/// A folder `gbump vectors` writes but `gbump regress` refuses (make reads `=` and `:`) is
/// written with a note saying so, and regress then refuses it, as the note said.
#[test]
fn a_folder_regress_refuses_is_named_when_the_vectors_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("e=q");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .args(["vectors", "--source", "random:5", "--target", "top", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("will refuse this folder") && err.contains("'='"), "{err}");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .args(["regress", "--sim", "icarus", "--vectors"])
        .arg(&out)
        .arg("--work")
        .arg(dir.path().join("w"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("'='") && err.contains("fix:"), "{err}");
}

/// A Verilator or a Yosys that exits 0 having printed and made nothing, or a make that fails
/// without a word on Verilator's output: the message says it printed nothing, names the tool
/// that ran and says to reinstall it, where it pointed at "the reasons above" (none) and
/// called it a gbump bug, or blamed Verilator for make.
#[test]
fn a_silent_tool_that_makes_nothing_is_named_as_broken() {
    let regress = vec!["regress", "--sim", "verilator", "--random", "10", "--no-scenes", "--target", "top"];
    for (tool, args) in [("verilator", regress.clone()), ("yosys", vec!["area"]), ("make", regress)] {
        let dir = tempfile::tempdir().unwrap();
        // A real answer to the version probe (and to make's dry run, which lists Verilator's
        // runtime objects), silence for the work.
        let body = if tool == "make" {
            "for a in \"$@\"; do if [ \"$a\" = -n ]; then exec /usr/bin/make \"$@\"; fi; done\nexit 1".to_string()
        } else {
            format!("if [ \"$1\" = --version ] || [ \"$1\" = -V ]; then exec /usr/bin/{tool} \"$@\"; fi\nexit 0")
        };
        let path = fake_tools::tool(&dir.path().join("bin"), tool, &body);
        let o = Command::cargo_bin("gbump")
            .unwrap()
            .env("PATH", path)
            .env("GBUMP_CACHE", "")
            .args(&args)
            .arg("--work")
            .arg(dir.path().join("w"))
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{tool}: {text}");
        assert!(
            text.contains(&format!("({tool} printed nothing)")) && text.contains(&format!("it is not a working {tool}")),
            "{tool}: {text}"
        );
        assert!(
            text.contains(&dir.path().join("bin").join(tool).display().to_string()),
            "{tool}: {text}"
        );
    }
}

/// A work folder whose lock file is a folder or a link to nowhere: the message names the
/// work folder's lock (a path the user never gave) and says to remove it.
#[test]
fn a_lock_file_that_is_not_a_file_is_named_as_the_work_folders() {
    for make in ["folder", "dangling link"] {
        let dir = tempfile::tempdir().unwrap();
        let work = dir.path().join("w");
        std::fs::create_dir(&work).unwrap();
        let lock = work.join(".gbump.lock");
        if make == "folder" {
            std::fs::create_dir(&lock).unwrap();
        } else {
            std::os::unix::fs::symlink(dir.path().join("nowhere/x"), &lock).unwrap();
        }
        let o = Command::cargo_bin("gbump")
            .unwrap()
            .args(["regress", "--sim", "icarus", "--work"])
            .arg(&work)
            .arg("--vectors")
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors/corners_top.json"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{make}: {err}");
        assert!(
            err.contains("the work folder's lock file") && err.contains("fix: remove it"),
            "{make}: {err}"
        );
    }
}

/// `gbump regress` on the checked-in corner set with a fake `vvp` whose body, past its version
/// answer, is `body` (which writes a pid into `pid_file`); returned once that file exists.
fn regress_on_a_fake_simulator(dir: &Path, body: &str, pid_file: &Path) -> std::process::Child {
    let path = fake_tools::icarus(
        &dir.join("bin"),
        &format!("if [ \"$1\" = --version ]; then echo fake vvp; exit 0; fi\n{body}"),
    );
    let vectors = Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors/corners_top.json");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_gbump"))
        .env("PATH", &path)
        .env_remove("GBUMP_TOOL_TIMEOUT")
        .args(["regress", "--sim", "icarus", "--work"])
        .arg(dir.join("w"))
        .arg("--vectors")
        .arg(&vectors)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let t = std::time::Instant::now();
    while !pid_file.exists() {
        assert!(child.try_wait().unwrap().is_none(), "gbump ended before the simulator ran");
        assert!(t.elapsed().as_secs() < 60, "the simulator did not start in 60 s");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    child
}

/// Wait up to `tenths` tenths of a second for the process whose pid `pid_file` holds to end
/// (gone, or a zombie for init to reap); kill it and fail with `what` if it does not.
fn assert_ends(pid_file: &Path, tenths: u32, what: &str) {
    let pid = std::fs::read_to_string(pid_file).unwrap();
    let mut stat = String::new();
    for _ in 0..tenths {
        stat = std::fs::read_to_string(format!("/proc/{}/stat", pid.trim())).unwrap_or_default();
        if stat.is_empty() || stat.rsplit_once(')').unwrap().1.trim_start().starts_with('Z') {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    let _ = std::process::Command::new("kill").args(["-KILL", pid.trim()]).status();
    panic!("{what}: {stat}");
}

/// A simulator that ignores SIGTERM does not outlive a run stopped by a signal: the run
/// sends SIGTERM at the signal and SIGKILL to whatever is left as it exits.
#[test]
fn a_simulator_that_ignores_sigterm_is_killed_when_a_signal_stops_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let pid_file = dir.path().join("sleeper.pid");
    let body = format!(
        "trap '' TERM INT HUP\nsleep 300 &\necho $! > {}.tmp && mv {0}.tmp {0}\nwait",
        pid_file.display()
    );
    let child = regress_on_a_fake_simulator(dir.path(), &body, &pid_file);
    send("INT", child.id());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130), "{}", String::from_utf8_lossy(&out.stderr));
    assert_ends(&pid_file, 20, "the simulator's child outlived the run");
}

/// A simulator does not outlive a gbump ended by SIGKILL, which no handler sees: the kernel
/// ends it (it had run on at full speed with no one reading it).
#[test]
fn a_simulator_dies_with_a_gbump_killed_outright() {
    let dir = tempfile::tempdir().unwrap();
    let pid_file = dir.path().join("sim.pid");
    let body = format!("echo $$ > {}.tmp && mv {0}.tmp {0}\nexec sleep 300", pid_file.display());
    let mut child = regress_on_a_fake_simulator(dir.path(), &body, &pid_file);
    child.kill().unwrap();
    child.wait().unwrap();
    assert_ends(&pid_file, 50, "the simulator outlived a gbump killed with SIGKILL");
}

/// Under an address-space limit (`ulimit -v`) a dump either fits or ends with gbump's own
/// error, exit 1 and no temporary file: per-thread allocator arenas had used up 400 MB
/// before any record was made, and the failed allocation aborted the process with its
/// temporary files left behind.
#[test]
fn a_dump_under_an_address_space_limit_fits_or_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let run = |limit_kb: u64, source: &str, out: &str| {
        std::process::Command::new("sh")
            .arg("-c")
            .arg(format!(
                "ulimit -v {limit_kb}; exec '{}' vectors --source {source} --out {out}",
                env!("CARGO_BIN_EXE_gbump")
            ))
            .current_dir(dir.path())
            .output()
            .unwrap()
    };
    let o = run(400_000, "random:20000", "fits");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Too little for the binary's own start: gbump's error, never an abort.
    let o = run(60_000, "random:2000000 --target top --format both", "short");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("gbump: error: out of memory") && err.contains("fix:"), "{err}");
    // Its files and the folder it made for them are gone.
    assert!(
        !dir.path().join("short").exists(),
        "{:?}",
        std::fs::read_dir(dir.path().join("short")).map(|d| d.flatten().map(|e| e.file_name()).collect::<Vec<_>>())
    );
}

/// Past a file-size limit (`ulimit -f`) a write fails with a message naming the file and
/// the limit, and the run removes what it wrote (SIGXFSZ had ended it without a word).
#[test]
fn a_file_size_limit_is_an_error_that_names_it() {
    let dir = tempfile::tempdir().unwrap();
    let o = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -f 8; exec '{}' rtl --out out", env!("CARGO_BIN_EXE_gbump")))
        .current_dir(dir.path())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("File too large") && err.contains("ulimit -f"), "{err}");
    let left: Vec<String> = std::fs::read_dir(dir.path().join("out"))
        .map(|d| d.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect())
        .unwrap_or_default();
    assert!(left.iter().all(|n| !n.contains(".gbump.tmp")), "{left:?}");
}

/// Whether `text` names `tool` (with its path) as having exited 0 without its work, with a fix.
fn did_not_run(tool: &str, text: &str) -> bool {
    text.contains(&format!("{tool} (")) && text.contains("did not do its work") && text.contains("fix:")
}

/// A `tool` in a fresh folder's `bin` that answers its version as the real one and otherwise
/// exits 0 having done nothing; the folder and the PATH to run gbump with.
fn idle_tool(tool: &str) -> (tempfile::TempDir, String) {
    let real = gbump::tool::on_path(tool).unwrap_or_else(|| panic!("{tool} missing: scripts/install-tools.sh"));
    let dir = tempfile::tempdir().unwrap();
    let path = fake_tools::tool(
        &dir.path().join("bin"),
        tool,
        &format!("case \"$1\" in -V|--version) exec '{}' \"$@\";; esac\nexit 0", real.display()),
    );
    (dir, path)
}

/// `gbump lint` is clean only when each linter shows it read the design: a Verilator, Icarus
/// or Yosys that exits 0 without doing its work (here: answers its version, then does
/// nothing) makes the lint fail, naming the tool, instead of reporting a clean design.
#[test]
fn a_linter_that_does_nothing_is_not_a_clean_lint() {
    for tool in ["verilator", "iverilog", "yosys"] {
        let (dir, path) = idle_tool(tool);
        let o = Command::cargo_bin("gbump")
            .unwrap()
            .env("PATH", &path)
            .args(["lint", "--work"])
            .arg(dir.path().join("w"))
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{tool}: {text}");
        assert!(did_not_run(tool, &text), "{tool}: {text}");
        assert!(!text.contains(": clean"), "{tool}: {text}");
    }
}

/// A closed standard input, output or error is not taken over by a file gbump opens (the
/// lowest free descriptor; Rust's start-up points a closed one at /dev/null): the run succeeds
/// and writes what a run with all three open writes.
#[test]
fn closed_standard_descriptors_leave_the_outputs_alone() {
    let dir = tempfile::tempdir().unwrap();
    let run = |at: &str, redirect: &str| {
        let cwd = dir.path().join(at);
        std::fs::create_dir(&cwd).unwrap();
        let o = std::process::Command::new("sh")
            .args([
                "-c",
                &format!("exec \"$0\" vectors --source random:300 --target all --seed 3 --out d {redirect}"),
                env!("CARGO_BIN_EXE_gbump"),
            ])
            .current_dir(&cwd)
            .output()
            .unwrap();
        assert!(o.status.success(), "{redirect}: {}", String::from_utf8_lossy(&o.stderr));
        cwd.join("d")
    };
    let open = run("open", "");
    let closed = run("closed", ">&- 2>&- <&-");
    let mut names: Vec<_> = std::fs::read_dir(&open).unwrap().map(|e| e.unwrap().file_name()).collect();
    names.sort();
    assert!(names.len() > 10, "{names:?}");
    for n in &names {
        let a = std::fs::read(open.join(n)).unwrap();
        let b = std::fs::read(closed.join(n)).unwrap();
        assert!(a == b, "{n:?} differs with the standard descriptors closed");
    }
}

/// A build tool that exits 0 without making its output (iverilog with no image, make with no
/// linked model) is named with its path and a fix, not as "the build did not produce" inside
/// a temporary folder that is gone by the time the message is read.
#[test]
fn a_build_tool_that_makes_nothing_is_named() {
    let vectors = Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors/corners_top.json");
    for (sim, tool) in [("icarus", "iverilog"), ("verilator", "make")] {
        let (dir, path) = idle_tool(tool);
        let o = Command::cargo_bin("gbump")
            .unwrap()
            .env("PATH", &path)
            .args(["regress", "--sim", sim, "--vectors"])
            .arg(&vectors)
            .arg("--work")
            .arg(dir.path().join("w"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{sim}: {err}");
        assert!(did_not_run(tool, &err), "{sim}: {err}");
        assert!(!err.contains(".gbump.tmp"), "{sim}: the message names a temporary folder: {err}");
    }
}

/// `cosim --lib` with a damaged copy of the real library says what is wrong with it: cut
/// short (the headers place data past its end), or a library without gbump's entry points;
/// neither is "built from other sources".
#[test]
fn a_damaged_or_foreign_library_is_named_for_what_it_is() {
    // Beside the binary, or in deps/ where a test build leaves it.
    let real =
        gbump::cosim::library_beside(Path::new(env!("CARGO_BIN_EXE_gbump"))).expect("cargo builds libgbump.so with the gbump binary");
    let image = std::fs::read(&real).unwrap_or_else(|e| panic!("{}: {e}", real.display()));
    let dir = tempfile::tempdir().unwrap();
    let foreign = {
        let mut b = image.clone();
        let name = b"gbump_abi_version";
        let mut i = 0;
        while i + name.len() <= b.len() {
            if &b[i..i + name.len()] == name {
                b[i] = b'x';
            }
            i += 1;
        }
        b
    };
    for (file, bytes, says) in [
        ("cut.so", image[..image.len() / 2].to_vec(), "cut short"),
        ("foreign.so", foreign, "not the gbump C library (it defines no gbump_abi_version)"),
    ] {
        std::fs::write(dir.path().join(file), &bytes).unwrap();
        let o = Command::cargo_bin("gbump")
            .unwrap()
            .args(["cosim", "--lib", file, "--work", "w"])
            .current_dir(dir.path())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(says) && err.contains("fix:"), "{file}: {err}");
        assert!(!err.contains("other sources"), "{file}: {err}");
    }
}

/// A Verilator too old for the benches (4.x: no --timing, no --main) is refused by its
/// version before any build, naming it, where it had failed on an option error.
#[test]
fn a_verilator_too_old_for_the_benches_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = fake_tools::tool(
        &dir.path().join("bin"),
        "verilator",
        "case \"$1\" in -V|--version) echo 'Verilator 4.038 2020-07-11 rev v4.036-114-g0cd4a57ad';; esac\nexit 0",
    );
    let vectors = Path::new(env!("CARGO_MANIFEST_DIR")).join("vectors/corners_top.json");
    let o = Command::cargo_bin("gbump")
        .unwrap()
        .env("PATH", &path)
        .args(["regress", "--sim", "verilator", "--vectors"])
        .arg(&vectors)
        .arg("--work")
        .arg(dir.path().join("w"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("Verilator 4.038") && err.contains("need Verilator 5 or later") && err.contains("fix:"),
        "{err}"
    );
    assert!(!dir.path().join("w").exists(), "the work folder was taken before the refusal");
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let want = format!("The benches need Verilator {} or later", gbump::sim::MIN_VERILATOR_MAJOR);
    assert!(readme.contains(&want), "README should say: {want}");
    for ok in [
        "Verilator 5.006 2023-01-22 rev (Debian 5.006-3)",
        "Verilator 6.0 devel",
        "verilator (custom build)",
    ] {
        gbump::sim::verilator_recent_enough(ok).unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
}
