//! Golden-model throughput: fragments per second for a 1024×1024 render with 1 and with 4
//! bump lights, beside the f64 reference on the same fragments (`cargo bench`). Under
//! `cargo test --all-targets` it runs as a quick smoke test at 128×128. `gbump bench` adds
//! the simulator figures; the vector encoder's rate (records made and encoded into memory, as
//! `gbump bench` measures it) is here too, so it can be watched on its own.

fn main() {
    let args: Vec<String> = std::env::args().collect();
    // cargo-nextest lists a target's tests with libtest's flags first: this one is one smoke
    // test (and no ignored one), which it then runs by name.
    if args.iter().any(|a| a == "--list") {
        if !args.iter().any(|a| a == "--ignored") {
            println!("model_throughput: test");
        }
        return;
    }
    let full = args.iter().any(|a| a == "--bench");
    let side = if full { 1024 } else { 128 };
    // `cargo bench --bench model_throughput -- encoder` runs only the sections so named; other
    // arguments (a test runner's own, such as the test's name) select nothing.
    const SECTIONS: [&str; 2] = ["model", "encoder"];
    let only: Vec<&str> = args[1..].iter().map(|a| a.as_str()).filter(|a| SECTIONS.contains(a)).collect();
    let run = |name: &str| only.is_empty() || only.contains(&name);
    for lights in [1, 4].into_iter().filter(|_| run("model")) {
        let (g, r, n) = gbump::measure::bench::model_rate(lights, side);
        println!(
            "golden model   {lights} light(s): {g:8.2} Mfragments/s ({n} fragments, {} threads)",
            rayon::current_num_threads()
        );
        println!("f64 reference  {lights} light(s): {r:8.2} Mfragments/s (interpolation + shading)");
    }
    if !run("encoder") {
        return;
    }
    let cfg = gbump::PipelineConfig::default();
    let (fast, readable) = gbump::measure::bench::model_speed(&cfg);
    println!(
        "fast model, default config: {:8.2} Mfragments/s (readable model {:.2}), random runs",
        fast / 1e6,
        readable / 1e6
    );
    let records = if full { gbump::measure::bench::DUMP_RECORDS } else { 1 << 16 };
    let rate = gbump::measure::bench::made_rate(&cfg, records).expect("encoder");
    let bytes = gbump::vectors::targets::top_layout(&cfg).bytes() as f64;
    println!(
        "vector encoder, default config: {:8.2} Mrecords/s, {:.0} MB/s ({records} random records of {bytes} bytes)",
        rate / 1e6,
        rate * bytes / 1e6
    );
}
