//! A ROM init file's header must state what its contents were built from: `gbump rom
//! --shininess 8` once wrote a table for n = 8 whose header said `shininess = 16` (the
//! config's). Each header is read back here and checked against the file name and the words.

#[path = "common/file_names.rs"]
mod file_names;

use gbump::cli::ConfigPick;
use gbump::config::PowerUnitKind;
use gbump::rtlgen::rom::{parse, RomFormat};
use gbump::PipelineConfig;
use std::collections::BTreeMap;
use std::path::Path;

/// `key = value` lines of a header (comment markers stripped), failing on a key stated twice
/// with different values: a header that contradicts itself.
fn header_params(text: &str) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    for l in text.lines().filter(|l| l.starts_with("// ")) {
        if let Some((k, v)) = l.trim_start_matches("// ").trim().split_once(" = ") {
            if let Some(old) = m.insert(k.to_string(), v.to_string()) {
                assert_eq!(old, v, "header states {k} twice:\n{text}");
            }
        }
    }
    m
}

fn configs() -> Vec<PipelineConfig> {
    let d = PipelineConfig::default();
    vec![
        d.clone(),
        PipelineConfig {
            dot_frac_bits: 12,
            power_entries: 1024,
            power_frac_bits: 12,
            shininess: 3,
            ..d.clone()
        },
        PipelineConfig {
            dot_frac_bits: 10,
            power_unit: PowerUnitKind::Segmented,
            power_entries: 16,
            power_segments: 5,
            ..d.clone()
        },
        PipelineConfig {
            normal_bits: 11,
            power_unit: PowerUnitKind::Lerp,
            power_entries: 64,
            ..d
        },
    ]
}

/// Each case's shininess and cube-map size.
const CASES: [(u32, usize); 6] = [(0, 1), (1, 4), (8, 32), (16, 32), (255, 7), (1024, 2)];

/// The README's guarantee table names the shininesses and the number of configurations.
#[test]
fn the_readme_states_the_cases_checked_here() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
    let ns: Vec<String> = CASES.iter().map(|c| c.0.to_string()).collect();
    let words = ["no", "one", "two", "three", "four", "five", "six"];
    let want = format!(
        "power tables for n = {} and {} under {} configurations",
        ns[..ns.len() - 1].join(", "),
        ns[ns.len() - 1],
        words[configs().len()]
    );
    assert!(flat.contains(&want), "README should say: {want}");
}

#[test]
fn every_rom_header_states_the_parameters_of_its_contents() {
    let pick = ConfigPick { config: None, scene: None };
    for cfg in configs() {
        for (n, cube) in CASES {
            let files = rom_files(&cfg, &pick, Some(n), cube, Path::new("rom")).unwrap();
            for (name, text) in files.iter().filter(|(f, _)| f.ends_with(".hex")) {
                let p = header_params(text);
                let words = parse(text, RomFormat::Hex).unwrap();
                let ctx = format!("{name} (config {}, n = {n})", cfg.hash());
                if name.starts_with("power_table_") {
                    assert!(name.starts_with(&format!("power_table_n{n}_{}", &cfg.hash()[..8])), "{ctx}");
                    assert_eq!(p["shininess"], n.to_string(), "{ctx}");
                    assert_eq!(p["power_entries"], cfg.power_entries.to_string(), "{ctx}");
                    assert_eq!(p["power_frac_bits"], cfg.power_frac_bits.to_string(), "{ctx}");
                    let want = gbump::model::PowerTable::build(&cfg, n);
                    assert_eq!(words, want.entries.iter().map(|&e| e as u64).collect::<Vec<_>>(), "{ctx}");
                } else if name.starts_with("bump_palette_") {
                    assert!(name.starts_with(&format!("bump_palette_{}_", p["palette_source"])), "{ctx}");
                    assert_eq!(p["normal_bits"], cfg.normal_bits.to_string(), "{ctx}");
                    assert_eq!(words.len(), 256, "{ctx}");
                } else {
                    assert_eq!(name, &format!("cube_map_{cube}x{cube}x6_rgb8.hex"));
                    assert_eq!(p["cube_size"], cube.to_string(), "{ctx}");
                    assert_eq!(words.len(), 6 * cube * cube, "{ctx}");
                    // The cube map is the same for every configuration, so it names none.
                    assert!(!text.contains("config hash") && !p.contains_key("shininess"), "{ctx}:\n{text}");
                }
            }
        }
    }
}

/// The pipeline's own reset table and a vector set's table, for a config whose shininess
/// differs from the default: the header agrees with the words.
#[test]
fn reset_and_vector_tables_state_their_shininess() {
    let cfg = PipelineConfig {
        shininess: 5,
        ..PipelineConfig::default()
    };
    let want: Vec<u64> = gbump::model::PowerTable::build(&cfg, 5).entries.iter().map(|&e| e as u64).collect();
    let rtl = gbump::rtlgen::generate(&cfg, "gbump rtl --out rtl");
    let (_, text) = rtl
        .iter()
        .find(|(n, _)| n.starts_with("power_table_") && n.ends_with(".hex"))
        .unwrap();
    assert_eq!(header_params(text)["shininess"], "5");
    assert_eq!(parse(text, RomFormat::Hex).unwrap(), want);
    let tmp = tempfile::tempdir().unwrap();
    let o = gbump::vectors::DumpOptions {
        shininess: Some(9),
        ..gbump::vectors::DumpOptions::formats("test", true, false)
    };
    gbump::vectors::dump(&cfg, &gbump::vectors::Source::Random(4), &["top".to_string()], tmp.path(), &o).unwrap();
    let table = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.to_string_lossy().ends_with("_power_table.hex"))
        .unwrap();
    let text = std::fs::read_to_string(table).unwrap();
    assert_eq!(header_params(&text)["shininess"], "9", "{text}");
    let nine: Vec<u64> = gbump::model::PowerTable::build(&cfg, 9).entries.iter().map(|&e| e as u64).collect();
    assert_eq!(parse(&text, RomFormat::Hex).unwrap(), nine);
}

/// `gbump rom`'s files for a configuration picked as on the command line.
fn rom_files(
    cfg: &gbump::PipelineConfig,
    pick: &gbump::cli::ConfigPick,
    n: Option<u32>,
    cube: usize,
    out: &std::path::Path,
) -> gbump::Result<Vec<(String, String)>> {
    gbump::rtlgen::rom_files::rom_files(cfg, pick.scene.as_deref(), &pick.args(), n, Some(cube), out)
}

/// `gbump rom` writes what the configuration's hardware reads and refuses what it cannot:
/// no power table for a squaring unit or EMBM (whose maps it writes), the configuration's own
/// shininess for a power ROM or squaring unit, none under EMBM, its own cube map size.
#[test]
fn rom_files_follow_the_configurations_memories() {
    use gbump::config::PowerUnitKind;
    let pick = ConfigPick { config: None, scene: None };
    let rom = PipelineConfig {
        power_rom: true,
        shininess: 24,
        ..Default::default()
    };
    let squaring = PipelineConfig {
        power_unit: PowerUnitKind::Squaring,
        ..Default::default()
    };
    for cfg in [&rom, &squaring] {
        let e = rom_files(cfg, &pick, Some(cfg.shininess + 1), 32, Path::new("rom"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&format!("--shininess {}", cfg.shininess + 1)) && e.contains("fix:"),
            "{e}"
        );
    }
    let names = |cfg: &PipelineConfig, cube: Option<usize>| -> Vec<String> {
        gbump::rtlgen::rom_files::rom_files(cfg, None, "", None, cube, Path::new("rom"))
            .unwrap()
            .into_iter()
            .map(|f| f.0)
            .collect()
    };
    assert!(names(&rom, None).iter().any(|n| n.starts_with("power_table_n24_")));
    assert!(
        !names(&squaring, None).iter().any(|n| n.starts_with("power_table")),
        "a squaring unit has no table"
    );
    let cube = PipelineConfig {
        bump_state: gbump::config::BumpStateAt::Fragment,
        light_mode: gbump::config::LightMode::Parallel,
        interpolate: gbump::config::Interpolate::Hl,
        renormalise: true,
        cube_map_face: 16,
        ..Default::default()
    };
    cube.validate("t").unwrap();
    assert!(
        names(&cube, None).iter().any(|n| n.starts_with("cube_map_16x16x6")),
        "the config's own size by default"
    );
    assert!(names(&PipelineConfig::default(), None)
        .iter()
        .any(|n| n.starts_with("cube_map_32x32x6")));
    let e = gbump::rtlgen::rom_files::rom_files(&cube, None, "", None, Some(32), Path::new("rom"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("cube_map_face = 16") && e.contains("fix:"), "{e}");
    // EMBM reads no power table: its maps instead, one per blend it has (the power-up maps,
    // or each object's of a scene, the words `gbump rtl`'s init files and a scene set's map
    // files hold), and a shininess is refused.
    let embm = PipelineConfig::load(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/configs/embm.toml"))).unwrap();
    let no_specular = PipelineConfig {
        specular: false,
        ..embm.clone()
    };
    no_specular.validate("t").unwrap();
    let maps = gbump::model::env_map::default_maps(&embm);
    for (cfg, have) in [(&embm, vec!["diffuse", "specular"]), (&no_specular, vec!["diffuse"])] {
        let files = gbump::rtlgen::rom_files::rom_files(cfg, None, "", None, None, Path::new("rom")).unwrap();
        assert!(!files.iter().any(|f| f.0.starts_with("power_table")), "EMBM reads no power table");
        for which in ["diffuse", "specular"] {
            let name = format!("env_{which}_default_{}.hex", &cfg.hash()[..8]);
            let file = files.iter().find(|f| f.0 == name);
            assert_eq!(file.is_some(), have.contains(&which), "{name}");
            if let Some((_, text)) = file {
                let map = if which == "diffuse" { &maps.diffuse } else { &maps.specular };
                let words = parse(text, RomFormat::Hex).unwrap();
                let texels = gbump::model::env_map::texels_of_words(cfg, &words, &name).unwrap();
                assert!(&texels == map, "{name}: not the power-up map");
            }
        }
        let e = rom_files(cfg, &pick, Some(8), 32, Path::new("rom")).unwrap_err().to_string();
        assert!(e.contains("--shininess 8: EMBM has no power unit") && e.contains("fix:"), "{e}");
    }
    // A scene's objects each with their own maps: the maps its vector sets carry.
    let scene = gbump::rtlgen::rom_files::rom_files(&embm, Some("cg_wall_floor"), "", None, None, Path::new("rom")).unwrap();
    let wall = gbump::scene::Scene::load("cg_wall_floor").unwrap();
    let prepared = gbump::raster::Prepared::new(&wall, &embm, 1, 1).unwrap();
    for (i, o) in prepared.objects.iter().enumerate() {
        for (which, map) in [("diffuse", &o.env.diffuse), ("specular", &o.env.specular)] {
            let name = format!("env_{which}_cg_wall_floor_o{i}_{}.hex", &embm.hash()[..8]);
            let (_, text) = scene.iter().find(|f| f.0 == name).unwrap_or_else(|| panic!("no {name}"));
            let words = parse(text, RomFormat::Hex).unwrap();
            assert!(
                &gbump::model::env_map::texels_of_words(&embm, &words, &name).unwrap() == map,
                "{name}"
            );
        }
    }
}

/// `gbump rom --scene S --engine embm`, the command line's way to a scene under EMBM, writes
/// each object's maps (the words the library gives for that configuration and scene) and no
/// power table; `gbump rom --scene S` alone is the scene's own Gouraud configuration.
#[test]
fn rom_of_a_scene_under_an_engine_writes_its_objects_maps() {
    let dir = tempfile::tempdir().unwrap();
    let o = assert_cmd::Command::cargo_bin("gbump")
        .unwrap()
        .args(["rom", "--scene", "cg_wall_floor", "--engine", "embm", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let wall = gbump::scene::Scene::load("cg_wall_floor").unwrap();
    let embm = gbump::engines::fixed_engine("embm").unwrap().fixed_config(&wall).unwrap().unwrap();
    let want = gbump::rtlgen::rom_files::rom_files(&embm, Some("cg_wall_floor"), "", None, None, Path::new("rom")).unwrap();
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.starts_with("power_table")), "{names:?}");
    for i in 0..wall.objects.len() {
        for which in ["diffuse", "specular"] {
            let name = format!("env_{which}_cg_wall_floor_o{i}_{}.hex", &embm.hash()[..8]);
            let got = std::fs::read_to_string(dir.path().join(&name)).unwrap_or_else(|_| panic!("no {name} in {names:?}"));
            let (_, text) = want.iter().find(|f| f.0 == name).unwrap();
            assert_eq!(parse(&got, RomFormat::Hex).unwrap(), parse(text, RomFormat::Hex).unwrap(), "{name}");
        }
    }
}

/// `gbump rom --scene` writes each object's bump map as the texture memory holds it, with the
/// addressing its header states: decoded as the header says, word y·w + x is the model's
/// stored texel (x, y) (the model's sampler at that texel's centre gives it, whatever the
/// filter); under a palette each object's map indexes its own palette, written beside it.
#[test]
fn a_scenes_bump_maps_are_its_objects_texture_memory() {
    use gbump::bumpmap::sample::sample_bump;
    use gbump::bumpmap::Filter;
    use gbump::model::BumpTexel;
    for (scene, palette) in [
        ("blend_split", false),
        ("torus_caps", false),
        ("cg_wall_floor", false),
        ("cg_wall_floor", true),
    ] {
        let (s, mut cfg) = gbump::render::report::scene_and_config(scene, None).unwrap();
        cfg.palette = palette;
        let files = gbump::rtlgen::rom_files::rom_files(&cfg, Some(scene), "", None, None, Path::new("rom")).unwrap();
        let text_of = |name: &str| files.iter().find(|(f, _)| f == name).map(|(_, t)| t.clone());
        let maps: Vec<&(String, String)> = files
            .iter()
            .filter(|(f, _)| f.starts_with(&format!("bump_map_{scene}_o")) && f.ends_with(".hex"))
            .collect();
        assert_eq!(maps.len(), s.objects.len(), "{scene}: one map per object");
        let p = gbump::raster::Prepared::new(&s, &cfg, 1, 1).unwrap();
        let nb = cfg.normal_bits;
        let mask = (1u64 << nb) - 1;
        for (i, (name, text)) in maps.iter().enumerate() {
            assert!(name.starts_with(&format!("bump_map_{scene}_o{i}_")), "{name}");
            let h = header_params(text);
            assert_eq!(h["object"], format!("{scene} object {i}"));
            // "texel (x, y) of the WxH map at word y*W + x (texel centres at ((x + 0.5)/W, ...".
            let dims = text.split(" of the ").nth(1).and_then(|t| t.split(" map").next()).unwrap();
            let (w, hh) = dims
                .split_once('x')
                .map(|(a, b)| (a.parse::<usize>().unwrap(), b.parse::<usize>().unwrap()))
                .unwrap();
            let words = parse(text, RomFormat::Hex).unwrap();
            assert_eq!(words.len(), w * hh, "{name}");
            let stored = &p.objects[i].stored;
            assert_eq!(stored.size(), (w, hh), "{name}");
            let mut differ = 0;
            for y in 0..hh {
                for x in 0..w {
                    let uv = glam::DVec2::new((x as f64 + 0.5) / w as f64, (y as f64 + 0.5) / hh as f64);
                    let v = words[y * w + x];
                    let want = if palette {
                        BumpTexel::Index(v as u8)
                    } else {
                        BumpTexel::Rgb([0, 1, 2].map(|c| ((v >> (c * nb)) & mask) as u32))
                    };
                    for f in [Filter::Nearest, Filter::Bilinear] {
                        differ += usize::from(sample_bump(stored, uv, f) != want);
                    }
                }
            }
            assert_eq!(differ, 0, "{name}: texels differ from the model's stored map");
            if palette {
                // Its palette: object 0's is the scene's, each other object's its own.
                let pal = if i == 0 {
                    format!("bump_palette_{scene}_{}.hex", &cfg.hash()[..8])
                } else {
                    format!("bump_palette_{scene}_o{i}_{}.hex", &cfg.hash()[..8])
                };
                assert!(h["filter"].contains(pal.trim_end_matches(".hex")), "{name}: {}", h["filter"]);
                let want: Vec<u64> = stored
                    .palette()
                    .unwrap()
                    .0
                    .iter()
                    .map(|e| e[0] as u64 | (e[1] as u64) << nb | (e[2] as u64) << (2 * nb))
                    .collect();
                assert_eq!(
                    parse(&text_of(&pal).unwrap_or_else(|| panic!("{pal} not written")), RomFormat::Hex).unwrap(),
                    want,
                    "{pal}"
                );
            } else if s.objects[i].bump.strength > 0.0 {
                assert!(words.iter().any(|v| *v != words[0]), "{name}: every texel the same");
            }
        }
    }
}

/// `gbump rom --scene` writes a power table for each shininess the scene's objects read (a
/// vector dump makes one set per table), and a scene that lost an object since an earlier
/// run into the same folder leaves no map of that object behind.
#[test]
fn a_scenes_roms_follow_its_objects() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes_doc/mixed.toml")).unwrap();
    let scene = dir.path().join("mx.toml");
    std::fs::write(&scene, &text).unwrap();
    let out = dir.path().join("rom");
    let rom = || {
        assert_cmd::Command::cargo_bin("gbump")
            .unwrap()
            .args(["rom", "--out"])
            .arg(&out)
            .arg(format!("--scene={}", scene.display()))
            .assert()
            .success()
    };
    rom();
    let names = || file_names::file_names(&out);
    let tables: Vec<String> = names()
        .into_iter()
        .filter(|n| n.starts_with("power_table_n") && n.ends_with(".hex"))
        .collect();
    assert_eq!(tables.len(), 2, "{tables:?}");
    assert!(
        tables[0].starts_with("power_table_n12_") && tables[1].starts_with("power_table_n30_"),
        "{tables:?}"
    );
    assert_eq!(names().iter().filter(|n| n.starts_with("bump_map_mixed_o2_")).count(), 3);
    // The last object dropped: its three map files go, the others stay.
    let last = text.rfind("[[objects]]").unwrap();
    std::fs::write(&scene, &text[..last]).unwrap();
    let o = rom();
    assert!(String::from_utf8_lossy(&o.get_output().stdout).contains("removed 3 ROM file(s)"));
    assert_eq!(
        names().iter().filter(|n| n.starts_with("bump_map_mixed_o2_")).count(),
        0,
        "{:?}",
        names()
    );
    assert_eq!(names().iter().filter(|n| n.starts_with("bump_map_mixed_o")).count(), 6);
}
