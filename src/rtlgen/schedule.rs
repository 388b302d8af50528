//! The pipeline scheduler: every signal has the stage (rising edges after the accepting one)
//! at which it is valid; a unit starts when its last input is ready, a combinational
//! expression sits at the stage of its latest input, and an earlier input is carried to the
//! later stage by delay registers inserted only as far as its last use. The latency is the
//! stage of the output, so no other place states it.
//!
//! Expressions are Verilog templates whose signals are written `{name}`; the scheduler
//! replaces each with the name of that signal's copy at the expression's stage.

use super::module::ModuleBuilder;
use crate::config::PipelineConfig;
use crate::units::{outputs, Unit};
use std::collections::{BTreeMap, BTreeSet};

pub struct Scheduler<'m> {
    pub m: &'m mut ModuleBuilder,
    /// Stage at which each signal (by its base name) is valid.
    ready: BTreeMap<String, u32>,
    /// Signals whose delay registers are cleared by reset (valid bits).
    reset: BTreeSet<String>,
    /// Late signals: recomputed from their template at every stage that uses them (width,
    /// template), instead of being carried by delay registers.
    late: BTreeMap<String, (u32, String)>,
    /// The latest stage at which a late signal is read.
    late_max: Option<u32>,
}

/// Names `{x}` in a template.
fn names(tpl: &str) -> Vec<String> {
    let mut v = Vec::new();
    let mut rest = tpl;
    while let Some(a) = rest.find('{') {
        let Some(b) = rest[a..].find('}') else { break };
        let inner = &rest[a + 1..a + b];
        // Verilog concatenations also use braces; a signal name is a bare identifier.
        if !inner.is_empty()
            && inner.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !inner.starts_with(|c: char| c.is_ascii_digit())
        {
            v.push(inner.to_string());
        }
        rest = &rest[a + 1..];
    }
    v
}

impl<'m> Scheduler<'m> {
    pub fn new(m: &'m mut ModuleBuilder) -> Scheduler<'m> {
        Scheduler {
            m,
            ready: BTreeMap::new(),
            reset: BTreeSet::new(),
            late: BTreeMap::new(),
            late_max: None,
        }
    }

    /// A late signal `name = tpl`: at every stage that uses it, it is recomputed from its
    /// inputs' copies at that stage (`name_s<stage>`), so only its inputs are delayed. This is
    /// how a narrow index (a triangle's bank tag) reads a wide register that holds still (the
    /// bank) where the value is needed, instead of the value travelling with the fragment.
    pub fn late(&mut self, name: &str, width: u32, tpl: &str) {
        let st = self.stage_of(&[tpl]);
        self.ready.insert(name.to_string(), st);
        self.late.insert(name.to_string(), (width, tpl.to_string()));
    }

    /// The latest stage at which any late signal is read (None: none is).
    pub fn late_max(&self) -> Option<u32> {
        self.late_max
    }

    /// A signal of the module (a port, or hand-written logic) valid at `stage`.
    pub fn source(&mut self, name: &str, stage: u32) {
        assert!(self.m.has(name), "{name} is not declared");
        self.ready.insert(name.to_string(), stage);
    }

    /// Mark a valid bit: its delay registers are cleared by reset.
    pub fn valid_bit(&mut self, name: &str) {
        self.reset.insert(name.to_string());
    }

    pub fn ready(&self, name: &str) -> u32 {
        *self.ready.get(name).unwrap_or_else(|| panic!("{name} has no stage"))
    }

    /// The copy of `name` valid at `stage`, with delay registers `name_d<s>` added as needed.
    pub fn at(&mut self, name: &str, stage: u32) -> String {
        let r = self.ready(name);
        assert!(stage >= r, "{name} is needed at stage {stage} but ready only at {r}");
        if let Some((w, tpl)) = self.late.get(name).cloned() {
            let wire = format!("{name}_s{stage}");
            if !self.m.has(&wire) {
                let e = self.fill(&tpl, stage);
                self.m.wire(&wire, w, Some(&e));
            }
            self.late_max = Some(self.late_max.map_or(stage, |m| m.max(stage)));
            return wire;
        }
        let w = self.m.width(name);
        let mut prev = name.to_string();
        for s in r + 1..=stage {
            let d = format!("{name}_d{s}");
            if !self.m.has(&d) {
                self.m.reg(&d, w, &prev, self.reset.contains(name));
            }
            prev = d;
        }
        prev
    }

    /// The stage at which every signal of `tpl` is ready.
    pub fn stage_of(&self, tpl: &[&str]) -> u32 {
        tpl.iter().flat_map(|t| names(t)).map(|n| self.ready(&n)).max().unwrap_or(0)
    }

    /// Fill a template at `stage`.
    pub fn fill(&mut self, tpl: &str, stage: u32) -> String {
        let mut out = tpl.to_string();
        for n in names(tpl) {
            let s = self.at(&n, stage);
            out = out.replace(&format!("{{{n}}}"), &s);
        }
        out
    }

    /// `name = expr` combinationally, at the stage of its latest input.
    pub fn comb(&mut self, name: &str, width: u32, tpl: &str) -> u32 {
        let st = self.stage_of(&[tpl]);
        let e = self.fill(tpl, st);
        self.m.wire(name, width, Some(&e));
        self.ready.insert(name.to_string(), st);
        st
    }

    /// Instantiate `unit` once all of its inputs are ready; each output port is the wire
    /// named in `outs`, ready `unit.latency()` stages later. Returns the start stage.
    pub fn unit(
        &mut self,
        cfg: &PipelineConfig,
        unit: &dyn Unit,
        inst: &str,
        ins: &[(&str, &str)],
        outs: &[(&str, &str)],
        params: &[(&str, String)],
    ) -> u32 {
        let tpls: Vec<&str> = ins.iter().map(|i| i.1).collect();
        let st = self.stage_of(&tpls);
        let mut conns: Vec<(&str, String)> = ins.iter().map(|(p, t)| (*p, self.fill(t, st))).collect();
        let ports = outputs(unit, cfg);
        for (p, wire) in outs {
            let port = ports
                .iter()
                .find(|x| x.name == *p)
                .unwrap_or_else(|| panic!("{inst}: no output {p}"));
            self.m.wire(wire, port.bits(), None);
            self.ready.insert(wire.to_string(), st + unit.latency(cfg));
            conns.push((p, wire.to_string()));
        }
        self.m.inst(cfg, unit, inst, &conns, params);
        st
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::Dir;

    #[test]
    fn delays_reach_only_as_far_as_the_last_use() {
        let mut m = ModuleBuilder::new("t");
        m.port("clk", Dir::In, 1);
        m.port("rst", Dir::In, 1);
        m.port("a", Dir::In, 4);
        m.port("v", Dir::In, 1);
        let mut s = Scheduler::new(&mut m);
        s.source("a", 0);
        s.source("v", 0);
        s.valid_bit("v");
        assert_eq!(s.at("a", 2), "a_d2");
        assert_eq!(s.at("a", 1), "a_d1");
        assert_eq!(s.at("v", 1), "v_d1");
        let st = s.comb("x", 4, "{a} + {a}");
        assert_eq!(st, 0);
        assert_eq!(names("{a, b} | {c}"), vec!["c".to_string()]);
        let text = m.finish().0;
        assert!(text.contains("a_d2 <= a_d1;"), "{text}");
        assert!(text.contains("v_d1 <= rst ? 1'd0 : v;"), "{text}");
        assert!(!text.contains("a_d3"));
    }

    #[test]
    fn a_late_signal_delays_its_index_not_its_value() {
        let mut m = ModuleBuilder::new("t");
        m.port("clk", Dir::In, 1);
        m.port("rst", Dir::In, 1);
        m.port("tag", Dir::In, 1);
        m.raw("reg [31:0] bank [0:1];");
        let mut s = Scheduler::new(&mut m);
        s.source("tag", 0);
        s.late("val", 32, "bank[{tag}]");
        assert_eq!(s.fill("{val}[3:0]", 2), "val_s2[3:0]");
        assert_eq!(s.late_max(), Some(2));
        let text = m.finish().0;
        assert!(text.contains("tag_d2 <= tag_d1;"), "{text}");
        assert!(text.contains("bank[tag_d2]"), "{text}");
        assert!(!text.contains("val_d"), "{text}");
    }
}
