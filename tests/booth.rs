//! The Booth rows the units' multipliers are emitted as (`rtlgen::booth`), in both forms, equal
//! Verilog's own `*` under Icarus: exhaustively on small widths of every signedness, a sum of two products
//! with an addend, a result narrower than the product (wrapping), and random 8 x 16 signed
//! operands (the dot product's).

use gbump::rtlgen::booth::{sum_of_products, Factor, Form};
use gbump::rtlgen::writer::VWriter;
use gbump::sim::Simulator;

struct Case {
    /// (width, signed) of each factor, in product order: [a0, b0, a1, b1, ...].
    factors: Vec<(u32, bool)>,
    addend: u128,
    out: u32,
    /// Every input when None; else this many random inputs.
    random: Option<u32>,
}

fn input_width(c: &Case) -> u32 {
    c.factors.iter().map(|f| f.0).sum()
}

/// The factor slices of the case's input vector `x`, as (expression, width, signed).
fn slices(c: &Case) -> Vec<(String, u32, bool)> {
    let mut lo = 0;
    c.factors
        .iter()
        .map(|&(w, s)| {
            let e = format!("x[{}:{lo}]", lo + w - 1);
            lo += w;
            (e, w, s)
        })
        .collect()
}

fn module(i: usize, c: &Case, form: Form) -> String {
    let mut w = VWriter::new();
    w.line(format!(
        "module c{i} (input wire [{}:0] x, output wire [{}:0] y);",
        input_width(c) - 1,
        c.out - 1
    ));
    let f = |(e, wd, s): &(String, u32, bool)| Factor {
        expr: e.clone(),
        width: *wd,
        signed: *s,
    };
    let sl = slices(c);
    let products: Vec<(Factor, Factor)> = sl.chunks(2).map(|p| (f(&p[0]), f(&p[1]))).collect();
    let e = sum_of_products(&mut w, form, "s", &products, c.addend, c.out);
    w.line(format!("assign y = {e};"));
    w.line("endmodule");
    w.finish()
}

/// Verilog's own value of the same sum, as the bench computes it.
fn reference(c: &Case) -> String {
    let sl = slices(c);
    let term = |(e, _, s): &(String, u32, bool)| {
        if *s {
            format!("$signed({e})")
        } else {
            format!("$signed({{1'b0, {e}}})")
        }
    };
    let mut parts: Vec<String> = sl.chunks(2).map(|p| format!("{} * {}", term(&p[0]), term(&p[1]))).collect();
    parts.push(format!("{}'sd{}", 100, c.addend));
    format!("({})", parts.join(" + "))
}

fn bench(cases: &[Case]) -> String {
    let mut s = String::from("`timescale 1ns / 1ps\nmodule tb;\ninteger i, bad, n;\nreg signed [99:0] want;\n");
    for (i, c) in cases.iter().enumerate() {
        s += &format!(
            "reg [{w}:0] x{i}; wire [{o}:0] y{i};\nc{i} d{i} (.x(x{i}), .y(y{i}));\n",
            w = input_width(c) - 1,
            o = c.out - 1
        );
    }
    s += "initial begin\n";
    for (i, c) in cases.iter().enumerate() {
        let count = c.random.map_or(1u64 << input_width(c), u64::from);
        let draw = if c.random.is_some() {
            format!("x{i} = {{$random, $random}};")
        } else {
            format!("x{i} = i;")
        };
        let r = reference(c).replace("x[", &format!("x{i}["));
        s += &format!(
            "  bad = 0; n = 0;\n  for (i = 0; i < {count}; i = i + 1) begin\n    {draw} #1;\n    want = {r};\n    if (y{i} !== want[{o}:0]) bad = bad + 1;\n    n = n + 1;\n  end\n  $display(\"case {i} checked %0d bad %0d\", n, bad);\n",
            o = c.out - 1
        );
    }
    s += "  $finish;\nend\nendmodule\n";
    s
}

#[test]
fn booth_rows_as_wires_equal_verilog_multiplication() {
    check(Form::Wires);
}

#[test]
fn booth_rows_in_functions_equal_verilog_multiplication() {
    check(Form::Function);
}

fn check(form: Form) {
    let cases = vec![
        Case {
            factors: vec![(5, true), (4, true)],
            addend: 0,
            out: 9,
            random: None,
        },
        Case {
            factors: vec![(4, false), (5, false)],
            addend: 0,
            out: 9,
            random: None,
        },
        Case {
            factors: vec![(6, true), (3, false)],
            addend: 0,
            out: 9,
            random: None,
        },
        Case {
            factors: vec![(3, false), (6, true)],
            addend: 0,
            out: 9,
            random: None,
        },
        Case {
            factors: vec![(1, false), (1, true)],
            addend: 0,
            out: 2,
            random: None,
        },
        // A one-bit unsigned factor is a gate (k_i with no fraction bits), on either side,
        // against an unsigned and a signed factor, at the product's width and cut below it.
        Case {
            factors: vec![(7, false), (1, false)],
            addend: 0,
            out: 8,
            random: None,
        },
        Case {
            factors: vec![(1, false), (6, true), (5, true), (2, false)],
            addend: 3,
            out: 9,
            random: None,
        },
        Case {
            factors: vec![(6, true), (1, false)],
            addend: 0,
            out: 4,
            random: None,
        },
        Case {
            factors: vec![(4, true), (4, true), (3, false), (3, false)],
            addend: 5,
            out: 10,
            random: None,
        },
        Case {
            factors: vec![(6, false), (6, false)],
            addend: 3,
            out: 8,
            random: None,
        },
        Case {
            factors: vec![(8, true), (16, true)],
            addend: 0,
            out: 24,
            random: Some(20000),
        },
        Case {
            factors: vec![(18, false), (8, false)],
            addend: 0,
            out: 26,
            random: Some(20000),
        },
    ];
    let dir = tempfile::tempdir().unwrap();
    let mut sources = Vec::new();
    for (i, c) in cases.iter().enumerate() {
        let p = dir.path().join(format!("c{i}.v"));
        std::fs::write(&p, module(i, c, form)).unwrap();
        sources.push(p);
    }
    let rtl = gbump::sim::rtl_files::Rtl {
        dir: dir.path().to_path_buf(),
        init_file: dir.path().join("none.hex"),
        sources,
        waivers: vec![],
        memory_inits: vec![],
    };
    let sim = gbump::sim::Icarus;
    let exe = sim
        .build(dir.path(), &gbump::sim::Testbench::new("tb", &bench(&cases)), &rtl)
        .unwrap_or_else(|e| panic!("Icarus could not build the Booth bench (scripts/install-tools.sh installs it): {e}"));
    let (_, out, _) = sim.run_log(&exe, &[], None, dir.path(), "vvp").unwrap();
    for (i, c) in cases.iter().enumerate() {
        let count = c.random.map_or(1u64 << input_width(c), u64::from);
        let line = out
            .lines()
            .find(|l| l.starts_with(&format!("case {i} ")))
            .unwrap_or_else(|| panic!("no result for case {i}:\n{out}"));
        assert_eq!(line, format!("case {i} checked {count} bad 0"), "{}", module(i, c, form));
    }
}
