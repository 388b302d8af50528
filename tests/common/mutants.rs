//! RTL mutants the tests substitute to prove a bench catches a wrong design.

// Each test binary includes this file and uses some of the mutants.
#![allow(dead_code)]

/// texture_modulate with its rounding half one less in the first channel (127 for 128): the
/// half is folded into the product's constant term (the Booth rows' sign corrections), so
/// the last constant of the `p0 <=` (or `p0 =`) line is decremented. None when no such line.
pub fn texture_rounding(text: &str) -> Option<String> {
    let line = text.lines().find(|l| l.contains("p0 <=") || l.contains("wire [16:0] p0 ="))?;
    let at = line.rfind("17'd")? + 4;
    let c: u64 = line[at..line.len() - 1].parse().ok()?;
    Some(text.replacen(line, &format!("{}{};", &line[..at], c - 1), 1))
}

/// The top's output buffer without its bypass: the head is always the RAM's read, so an
/// entry that becomes the head at the edge that writes it shows the RAM's old word. None when
/// the top has no such buffer.
pub fn output_bypass(text: &str) -> Option<String> {
    let from = "(obuf_use_byp ? obuf_byp : obuf_q)";
    text.contains(from).then(|| text.replacen(from, "obuf_q", 1))
}
