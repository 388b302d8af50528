//! A structured Verilog module builder: ports, wires, registers and unit instances, each
//! declared once with its width, so an instance is checked against its unit's ports (every
//! port connected once, no unknown port, output widths equal) when it is built, not when a
//! simulator first reads the text. The top pipeline is written through it.

use super::units_v::module_name;
use super::writer::{range, VWriter};
use crate::config::PipelineConfig;
use crate::units::resources::Resources;
use crate::units::{Dir, Unit};
use std::collections::BTreeMap;

/// What the module is built of, counted as it is built (the area model's view of the top):
/// its own logic, and the units it instantiates with their copies.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    pub glue: Resources,
    pub instances: Vec<Instance>,
}

/// A unit instance as the area model sees it.
#[derive(Clone, Debug)]
pub struct Instance {
    pub unit: &'static str,
    pub copies: u32,
    /// The fraction bits its blend factor really carries, when fewer than the configuration's
    /// `factor_frac` (a blend fed by the dot product or the power unit alone): the factor's
    /// low bits are zero there, and synthesis removes what they would drive.
    pub factor_frac: Option<u32>,
}

pub struct ModuleBuilder {
    name: String,
    params: Vec<(String, String)>,
    ports: Vec<(String, Dir, u32)>,
    body: VWriter,
    widths: BTreeMap<String, u32>,
    /// Register arrays (width, depth, read yet).
    arrays: BTreeMap<String, (u32, u32, bool)>,
    pub tally: Tally,
    /// False when only the tally is wanted (the area model): no text is written.
    text: bool,
}

/// Binary `+`/`-` and `?` operators of an expression, outside index brackets and replication
/// counts (a sign after `(`, `{`, `,`, `=`, `?` or `:` is no adder; `+:` is a part select).
fn operators(expr: &str) -> (u32, u32) {
    let mut depth = 0;
    let (mut add, mut mux) = (0, 0);
    let b = expr.as_bytes();
    for (i, &c) in b.iter().enumerate() {
        match c {
            b'[' => depth += 1,
            b']' => depth -= 1,
            b'+' | b'-' if depth == 0 => {
                let next = b.get(i + 1).copied().unwrap_or(b' ');
                let prev = b[..i].iter().rev().find(|c| !c.is_ascii_whitespace()).copied().unwrap_or(b'(');
                if next != b':' && !matches!(prev, b'(' | b'{' | b',' | b'=' | b'?' | b':') {
                    add += 1;
                }
            }
            b'?' if depth == 0 => mux += 1,
            _ => {}
        }
    }
    (add, mux)
}

impl ModuleBuilder {
    pub fn new(name: impl Into<String>) -> ModuleBuilder {
        ModuleBuilder {
            name: name.into(),
            params: Vec::new(),
            ports: Vec::new(),
            body: VWriter::new(),
            widths: BTreeMap::new(),
            arrays: BTreeMap::new(),
            tally: Tally::default(),
            text: true,
        }
    }

    /// A builder that only counts (`tally`) and writes no text.
    pub fn counting(name: impl Into<String>) -> ModuleBuilder {
        ModuleBuilder {
            text: false,
            ..ModuleBuilder::new(name)
        }
    }

    /// Write a line of the body, built only when text is wanted.
    fn emit(&mut self, line: impl FnOnce() -> String) {
        if self.text {
            self.body.line(line());
        }
    }

    /// Count the logic of `expr` driving `width` bits, and the read multiplexers of every
    /// register array it indexes (an array's registers count from its first read: synthesis
    /// drops an array nothing reads).
    fn count(&mut self, expr: &str, width: u32) {
        let (a, m) = operators(expr);
        self.tally.glue += Resources::adders(a * width) + Resources::muxes(m * width);
        for (name, (w, depth, read)) in self.arrays.iter_mut() {
            // `name[`, found without building the pattern: this runs for every expression.
            if expr
                .match_indices(name.as_str())
                .any(|(at, _)| expr[at + name.len()..].starts_with('['))
            {
                // Each read selects among every bank; the registers count at the first read.
                self.tally.glue.array += (*w * *depth) as f64;
                if !*read {
                    *read = true;
                    self.tally.glue += Resources::regs(*w * *depth);
                }
            }
        }
    }

    /// `reg [w-1:0] name [0:depth-1];`, written by hand-written logic.
    pub fn array(&mut self, name: &str, width: u32, depth: u32) {
        self.emit(|| format!("reg {}{name} [0:{}];", range(width), depth - 1));
        self.arrays.insert(name.to_string(), (width, depth, false));
    }

    /// `copies` instances of `unit` written as a helper (a unit with a read-port parameter).
    pub fn count_instances(&mut self, unit: &'static str, copies: u32) {
        self.tally.instances.push(Instance {
            unit,
            copies,
            factor_frac: None,
        });
    }

    /// The blend factor of the instance built last carries `frac` fraction bits.
    pub fn factor_frac(&mut self, frac: u32) {
        if let Some(i) = self.tally.instances.last_mut() {
            i.factor_frac = Some(frac);
        }
    }

    fn declare(&mut self, name: &str, width: u32) {
        assert!(width > 0, "{name}: zero width");
        let old = self.widths.insert(name.to_string(), width);
        assert!(old.is_none(), "{name} declared twice in {}", self.name);
    }

    /// Width of a declared signal.
    pub fn width(&self, name: &str) -> u32 {
        *self
            .widths
            .get(name)
            .unwrap_or_else(|| panic!("{name} is not declared in {}", self.name))
    }

    pub fn has(&self, name: &str) -> bool {
        self.widths.contains_key(name)
    }

    pub fn param(&mut self, name: &str, default: impl FnOnce() -> String) {
        if self.text {
            self.params.push((name.to_string(), default()));
        }
    }

    pub fn port(&mut self, name: &str, dir: Dir, width: u32) {
        self.declare(name, width);
        self.ports.push((name.to_string(), dir, width));
    }

    pub fn comment(&mut self, text: impl AsRef<str>) {
        self.emit(|| format!("// {}", text.as_ref()));
    }

    /// A line of hand-written logic (the light sequencer), whose signals it declares itself
    /// through [`ModuleBuilder::wire`]/[`ModuleBuilder::reg_decl`].
    pub fn raw(&mut self, text: impl AsRef<str>) {
        self.emit(|| text.as_ref().to_string());
    }

    /// `wire [w-1:0] name = expr;` (or a bare declaration without an expression).
    pub fn wire(&mut self, name: &str, width: u32, expr: Option<&str>) {
        self.declare(name, width);
        if let Some(e) = expr {
            self.count(e, width);
        }
        self.emit(|| match expr {
            Some(e) => format!("wire {}{name} = {e};", range(width)),
            None => format!("wire {}{name};", range(width)),
        });
    }

    /// A register declared here and driven by hand-written logic.
    pub fn reg_decl(&mut self, name: &str, width: u32) {
        self.declare(name, width);
        self.tally.glue += Resources::regs(width);
        self.emit(|| format!("reg {}{name};", range(width)));
    }

    /// A register loaded with `next` at every rising edge (cleared by `rst` when `reset`).
    pub fn reg(&mut self, name: &str, width: u32, next: &str, reset: bool) {
        self.reg_decl(name, width);
        self.count(next, width);
        if reset {
            self.tally.glue += Resources::muxes(width);
        }
        self.emit(|| {
            if reset {
                format!("always @(posedge clk) {name} <= rst ? {width}'d0 : {next};")
            } else {
                format!("always @(posedge clk) {name} <= {next};")
            }
        });
    }

    /// Drive an output port.
    pub fn assign(&mut self, name: &str, expr: &str) {
        assert!(
            self.ports.iter().any(|p| p.0 == name && p.1 == Dir::Out),
            "{name} is not an output of {}",
            self.name
        );
        let w = self.width(name);
        self.count(expr, w);
        self.emit(|| format!("assign {name} = {expr};"));
    }

    /// Instantiate `unit`'s own module. `conns` must name every data port of the unit once
    /// (an output must be a declared wire of the port's width); a unit with a memory also
    /// gets its load port from the top's `<prefix>_we/_waddr/_wdata` and its init parameter.
    pub fn inst(&mut self, cfg: &PipelineConfig, unit: &dyn Unit, inst: &str, conns: &[(&str, String)], params: &[(&str, String)]) {
        let ports = unit.ports(cfg);
        for (pname, _) in conns {
            assert!(
                ports.iter().any(|p| p.name == *pname),
                "{inst}: {} has no port {pname}",
                unit.name()
            );
        }
        self.count_instances(unit.name(), 1);
        let mut list = vec![".clk(clk)".to_string()];
        if let Some(m) = unit.memory(cfg) {
            for (up, tp) in [("we", "we"), ("waddr", "waddr"), ("wdata", "wdata")] {
                list.push(format!(".{up}({}_{tp})", m.prefix));
            }
        }
        for port in &ports {
            let matches: Vec<&String> = conns.iter().filter(|c| c.0 == port.name).map(|c| &c.1).collect();
            assert_eq!(
                matches.len(),
                1,
                "{inst}: port {} of {} connected {} times",
                port.name,
                unit.name(),
                matches.len()
            );
            if port.dir == Dir::Out {
                assert_eq!(self.width(matches[0]), port.bits(), "{inst}: output {} width", port.name);
            }
            list.push(format!(".{}({})", port.name, matches[0]));
        }
        let p = if params.is_empty() {
            String::new()
        } else {
            let ps: Vec<String> = params.iter().map(|(k, v)| format!(".{k}({v})")).collect();
            format!(" #({})", ps.join(", "))
        };
        self.emit(|| format!("{}{p} {inst} ({});", module_name(cfg, unit.name()), list.join(", ")));
    }

    /// Instantiate a helper module that is not a unit (its ports are checked by the unit
    /// that emits it: `light_term`, `bump_fetch_comb`).
    /// `module` is the helper's base name (`module_name` adds the hash).
    pub fn inst_helper(&mut self, cfg: &PipelineConfig, module: &str, inst: &str, conns: &[(&str, String)]) {
        self.emit(|| {
            let list: Vec<String> = conns.iter().map(|(p, e)| format!(".{p}({e})")).collect();
            format!("{} {inst} ({});", module_name(cfg, module), list.join(", "))
        });
    }

    pub fn finish(self) -> (String, Tally) {
        let mut w = VWriter::new();
        let params = if self.params.is_empty() {
            String::new()
        } else {
            let ps: Vec<String> = self.params.iter().map(|(k, v)| format!("    parameter {k} = {v}")).collect();
            format!(" #(\n{}\n)", ps.join(",\n"))
        };
        let ports: Vec<String> = self
            .ports
            .iter()
            .map(|(n, d, wd)| {
                let dir = if *d == Dir::In { "input " } else { "output" };
                format!("    {dir} wire {}{n}", range(*wd))
            })
            .collect();
        w.line(format!("module {}{params} (\n{}\n);", self.name, ports.join(",\n")));
        let mut s = w.finish();
        s += &self.body.finish();
        s += "endmodule\n";
        (s, self.tally)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operators_skip_part_selects_signs_and_indices() {
        assert_eq!(operators(" a + b - c;"), (2, 0));
        assert_eq!(operators(" x[j*4 +: 4] + {1'b0, y[3:0]};"), (1, 0));
        assert_eq!(operators(" s ? a + b : -c;"), (1, 1));
    }
}
