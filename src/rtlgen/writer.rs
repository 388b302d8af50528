//! A small structured Verilog writer: lines at the current indent, and blocks that indent
//! their body (after Amaranth's emitter), so no emitter assembles HDL from tab strings.

#[derive(Default)]
pub struct VWriter {
    out: String,
    depth: usize,
}

impl VWriter {
    pub fn new() -> VWriter {
        VWriter::default()
    }

    /// One line at the current indent.
    pub fn line(&mut self, s: impl AsRef<str>) -> &mut Self {
        let s = s.as_ref();
        if s.is_empty() {
            self.out.push('\n');
        } else {
            for _ in 0..self.depth {
                self.out.push_str("    ");
            }
            self.out.push_str(s);
            self.out.push('\n');
        }
        self
    }

    /// Several lines.
    pub fn lines<I: IntoIterator<Item = S>, S: AsRef<str>>(&mut self, it: I) -> &mut Self {
        for l in it {
            self.line(l);
        }
        self
    }

    /// `open`, the body one level deeper, then `close`.
    pub fn block(&mut self, open: impl AsRef<str>, close: impl AsRef<str>, body: impl FnOnce(&mut VWriter)) -> &mut Self {
        self.line(open);
        self.depth += 1;
        body(self);
        self.depth -= 1;
        self.line(close)
    }

    /// `name = expr`, declared `decl` (`signed [7:0]`, or empty): a register loaded at the
    /// rising edge of `clk` when `registered` (a pipeline cut), a wire otherwise.
    pub fn stage(&mut self, registered: bool, decl: &str, name: &str, expr: &str) -> &mut Self {
        let sp = if decl.is_empty() { "" } else { " " };
        if registered {
            self.line(format!("reg {decl}{sp}{name};"));
            self.line(format!("always @(posedge clk) {name} <= {expr};"))
        } else {
            self.line(format!("wire {decl}{sp}{name} = {expr};"))
        }
    }

    /// The text, in ASCII: every tool in the flow (Verilator's config parser among them)
    /// reads ASCII, so the paper's symbols in comments are spelled out.
    pub fn finish(self) -> String {
        ascii(&self.out)
    }
}

/// `[w-1:0]` range text for a width (empty for 1 bit).
pub fn range(w: u32) -> String {
    if w <= 1 {
        String::new()
    } else {
        format!("[{}:0] ", w - 1)
    }
}

/// Spell out the non-ASCII symbols the emitters' comments use.
pub fn ascii(s: &str) -> String {
    s.replace('§', "sec. ")
        .replace('→', "->")
        .replace('·', "*")
        .replace('≥', ">=")
        .replace('≤', "<=")
        .replace('×', "x")
        .replace('—', "-")
        .chars()
        .map(|c| if c.is_ascii() { c } else { '?' })
        .collect()
}

/// `s` as a Verilog string literal.
pub fn verilog_string(s: &str) -> String {
    format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""))
}

/// Lane `index` (an expression) of `lanes` lanes of `width` bits each in `signal`. One lane is
/// the whole signal, which may be a single bit declared without a range, so it is not selected.
pub fn lane(signal: &str, lanes: u32, index: &str, width: u32) -> String {
    if lanes == 1 {
        signal.to_string()
    } else {
        format!("{signal}[{index}*{width} +: {width}]")
    }
}

/// Zero-extend `e` by `pad` bits (no concatenation when there is nothing to add).
pub fn zext(e: &str, pad: u32) -> String {
    if pad == 0 {
        e.to_string()
    } else {
        format!("{{{pad}'d0, {e}}}")
    }
}
