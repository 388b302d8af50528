//! Golden-model throughput: fragments per second for a 1024×1024 render with 1 and with 4
//! bump lights, beside the f64 reference on the same fragments (`cargo bench`). Under
//! `cargo test --all-targets` it runs as a quick smoke test at 128×128. `gbump bench` adds
//! the vector-dump and simulator figures.

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
    for lights in [1, 4] {
        let (g, r, n) = gbump::measure::bench::model_rate(lights, side);
        println!(
            "golden model   {lights} light(s): {g:8.2} Mfragments/s ({n} fragments, {} threads)",
            rayon::current_num_threads()
        );
        println!("f64 reference  {lights} light(s): {r:8.2} Mfragments/s (interpolation + shading)");
    }
}
