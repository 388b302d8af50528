//! ARCHITECTURE.md's figures that describe today's design, read from the sources that hold
//! them: the default top's interface and docs/REPORT.md, which `gbump report` regenerates.
//! (Figures measured at a change, before and after, are stated as such and not re-checked.)

fn read(rel: &str) -> String {
    std::fs::read_to_string(format!("{}/{rel}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

#[test]
fn the_default_tops_state_bits_are_its_triangle_ports() {
    let arch = read("ARCHITECTURE.md");
    let json = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/rtl"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|x| x == "json") && p.to_string_lossy().contains("gbump_pipeline_"))
        .unwrap();
    let j: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let bits: u64 = j["ports"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| {
            let n = p["name"].as_str().unwrap();
            n.starts_with("tri_") && n != "tri_valid" && n != "tri_ready"
        })
        .map(|p| p["width"].as_u64().unwrap())
        .sum();
    let want = format!("the {bits} state bits of the default four-light top");
    assert!(arch.replace("\n  ", " ").contains(&want), "ARCHITECTURE.md should say: {want}");
}

/// The area model's held-out errors, as the report states them.
#[test]
fn the_area_models_figures_are_the_reports() {
    let (arch, report) = (read("ARCHITECTURE.md").replace("\n  ", " "), read("docs/REPORT.md"));
    let at = report.find("held out: ").expect("REPORT.md: no held-out figures") + "held out: ".len();
    let words: Vec<&str> = report[at..].split_whitespace().take(9).collect();
    // "30 configurations, mean error 6.4 %, max 17.5 %"
    let (n, mean, max) = (words[0], words[4], words[7]);
    let want = format!("On the {n} held-out random configurations of `tests/area_model/samples.jsonl` the top is {mean} % off Yosys on average, {max} % at worst");
    assert!(arch.contains(&want), "ARCHITECTURE.md should say: {want}");
}

/// `pipeline_depth = 3` is the default because the report's depth table says so: on each
/// configuration it measures, 3 is the first depth past twice the 31.6 MHz of the top before
/// it had a depth, and 4 places no faster beyond placement noise (10 %).
#[test]
fn the_default_depth_is_where_the_reports_fmax_stops_rising() {
    let report = read("docs/REPORT.md");
    let at = report.find("## Timing as a parameter").expect("REPORT.md: no depth table");
    let mut fmax: std::collections::BTreeMap<String, Vec<(u32, f64)>> = Default::default();
    for line in report[at..].lines().skip(1).take_while(|l| !l.starts_with("## ")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let (Some(depth), Some(mhz)) = (
            cells.get(2).and_then(|c| c.parse().ok()),
            cells.get(11).and_then(|c| c.parse().ok()),
        ) else {
            continue;
        };
        fmax.entry(cells[1].to_string()).or_default().push((depth, mhz));
    }
    assert!(fmax.len() >= 2, "{fmax:?}");
    let default = gbump::config::PipelineConfig::default().pipeline_depth;
    for (cfg, rows) in &fmax {
        let f = |d: u32| rows.iter().find(|r| r.0 == d).unwrap_or_else(|| panic!("{cfg}: no depth {d}")).1;
        let first_past = rows.iter().find(|r| r.1 > 2.0 * 31.6).map(|r| r.0);
        assert_eq!(first_past, Some(default), "{cfg}: {rows:?}");
        assert!(
            f(default + 1) < 1.1 * f(default),
            "{cfg}: depth {} gains more than placement noise: {rows:?}",
            default + 1
        );
    }
}

/// The fast model's check against the readable model, as the constants of
/// `vectors::top_records` set it.
#[test]
fn the_fast_models_check_is_stated_by_its_constants() {
    use gbump::vectors::sources::RANDOM_CHUNK;
    use gbump::vectors::top_records::{CHECK_SAMPLE, FULL_CHECK_RECORDS};
    let flat = read("ARCHITECTURE.md").split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(FULL_CHECK_RECORDS.is_power_of_two() && RANDOM_CHUNK % 1024 == 0);
    let share = 100.0 * CHECK_SAMPLE as f64 / RANDOM_CHUNK as f64;
    let want = format!(
        "every record of the first 2^{e} of a set and on the first {CHECK_SAMPLE} of every later {}k-record chunk (so a set of up to 2^{e} records is checked whole, and a longer one on its first 2^{e} and a sample of {share:.1} % after them)",
        RANDOM_CHUNK / 1024,
        e = FULL_CHECK_RECORDS.ilog2()
    );
    assert!(flat.contains(&want), "ARCHITECTURE.md should say: {want}");
}
