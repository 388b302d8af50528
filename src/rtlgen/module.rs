//! A structured Verilog module builder: ports, wires, registers and unit instances, each
//! declared once with its width, so an instance is checked against its unit's ports (every
//! port connected once, no unknown port, output widths equal) when it is built, not when a
//! simulator first reads the text. The top pipeline is written through it.

use super::units_v::module_name;
use super::writer::{range, VWriter};
use crate::config::PipelineConfig;
use crate::units::{Dir, Unit};
use std::collections::BTreeMap;

pub struct ModuleBuilder {
    name: String,
    params: Vec<(String, String)>,
    ports: Vec<(String, Dir, u32)>,
    body: VWriter,
    widths: BTreeMap<String, u32>,
}

impl ModuleBuilder {
    pub fn new(name: impl Into<String>) -> ModuleBuilder {
        ModuleBuilder {
            name: name.into(),
            params: Vec::new(),
            ports: Vec::new(),
            body: VWriter::new(),
            widths: BTreeMap::new(),
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

    pub fn param(&mut self, name: &str, default: String) {
        self.params.push((name.to_string(), default));
    }

    pub fn port(&mut self, name: &str, dir: Dir, width: u32) {
        self.declare(name, width);
        self.ports.push((name.to_string(), dir, width));
    }

    pub fn comment(&mut self, text: impl AsRef<str>) {
        self.body.line(format!("// {}", text.as_ref()));
    }

    /// A line of hand-written logic (the light sequencer), whose signals it declares itself
    /// through [`ModuleBuilder::wire`]/[`ModuleBuilder::reg_decl`].
    pub fn raw(&mut self, text: impl AsRef<str>) {
        self.body.line(text);
    }

    /// `wire [w-1:0] name = expr;` (or a bare declaration without an expression).
    pub fn wire(&mut self, name: &str, width: u32, expr: Option<&str>) {
        self.declare(name, width);
        match expr {
            Some(e) => self.body.line(format!("wire {}{name} = {e};", range(width))),
            None => self.body.line(format!("wire {}{name};", range(width))),
        };
    }

    /// A register declared here and driven by hand-written logic.
    pub fn reg_decl(&mut self, name: &str, width: u32) {
        self.declare(name, width);
        self.body.line(format!("reg {}{name};", range(width)));
    }

    /// A register loaded with `next` at every rising edge (cleared by `rst` when `reset`).
    pub fn reg(&mut self, name: &str, width: u32, next: &str, reset: bool) {
        self.reg_decl(name, width);
        let next = if reset {
            format!("rst ? {width}'d0 : {next}")
        } else {
            next.to_string()
        };
        self.body.line(format!("always @(posedge clk) {name} <= {next};"));
    }

    /// Drive an output port.
    pub fn assign(&mut self, name: &str, expr: &str) {
        assert!(
            self.ports.iter().any(|p| p.0 == name && p.1 == Dir::Out),
            "{name} is not an output of {}",
            self.name
        );
        self.body.line(format!("assign {name} = {expr};"));
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
        self.body
            .line(format!("{}{p} {inst} ({});", module_name(cfg, unit.name()), list.join(", ")));
    }

    /// Instantiate a helper module that is not a unit (its ports are checked by the unit
    /// that emits it: `light_term`, `bump_fetch_comb`).
    pub fn inst_helper(&mut self, module: &str, inst: &str, conns: &[(&str, String)]) {
        let list: Vec<String> = conns.iter().map(|(p, e)| format!(".{p}({e})")).collect();
        self.body.line(format!("{module} {inst} ({});", list.join(", ")));
    }

    pub fn finish(self) -> String {
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
        s
    }
}
