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

/// colour_round without its rounding half in the first channel (it truncates): the constant
/// added on the `r0 =` line becomes 0. None when the design has no such line.
pub fn colour_round_truncates(text: &str) -> Option<String> {
    let line = text.lines().find(|l| l.starts_with("wire [") && l.contains(" r0 = "))?;
    let at = line.rfind("'d")? + 2;
    let end = at + line[at..].find(|c: char| !c.is_ascii_digit())?;
    (line[at..end] != *"0").then(|| text.replacen(line, &format!("{}0{}", &line[..at], &line[end..]), 1))
}

/// The guard-bit texture divider with one shifted add fewer in the first channel (the
/// reciprocal constant loses its lowest set bit): the last `+ (...)` term of the `q0 =` line
/// goes. None when the line has a single term.
pub fn texture_divider_term(text: &str) -> Option<String> {
    let line = text
        .lines()
        .find(|l| l.starts_with("wire [") && l.contains(" q0 = ") && l.contains(" << "))?;
    let cut = line.rfind(" + (")?;
    Some(text.replacen(line, &format!("{};", &line[..cut]), 1))
}

/// A white-light `light_term` that multiplies f·k by 2^c instead of 2^c - 1 (its subtract
/// gone). None when the design has no such line.
pub fn white_term_no_subtract(text: &str) -> Option<String> {
    let line = text.lines().find(|l| l.contains(" tw0 = ") && l.contains(" - "))?;
    let cut = line.find(" - ")?;
    Some(text.replacen(line, &format!("{};", &line[..cut]), 1))
}

/// normalise with its last Newton step skipped: the reciprocal the products use is the one
/// before it (the table's, with one step). None when the unit takes no Newton step.
pub fn normalise_step_fewer(text: &str) -> Option<String> {
    let steps = (1..=4).take_while(|k| text.contains(&format!(" nr{k} = "))).count();
    if steps == 0 {
        return None;
    }
    let before = if steps == 1 { "r0".to_string() } else { format!("nr{}", steps - 1) };
    let last = format!("nr{steps}");
    let line = text.lines().find(|l| l.contains("r_s2") && (l.ends_with(&format!(" {last};"))))?;
    Some(text.replacen(line, &line.replace(&format!(" {last};"), &format!(" {before};")), 1))
}

/// normalise_cube without its last-texel clamp on the first minor: a minor equal to the
/// major (quotient `face`) wraps to texel 0 instead of staying in the last one. None when the
/// unit has no such line.
pub fn cube_unclamped(text: &str) -> Option<String> {
    let line = text.lines().find(|l| l.contains(" i_t = i_q["))?;
    let (head, tail) = line.split_once(" ? ")?;
    let select = tail.split_once(" : ")?.1;
    let bit = head.rsplit_once(" = ")?;
    Some(text.replacen(line, &format!("{} = {select}", bit.0), 1))
}

/// The top's self-shadowing gate always open for light 0: `lit0` tied high. None when the
/// top does not self-shadow.
pub fn self_shadow_open(text: &str) -> Option<String> {
    let line = text.lines().find(|l| l.contains(" lit0 = "))?;
    let (head, _) = line.split_once(" = ")?;
    Some(text.replacen(line, &format!("{head} = 1'b1;"), 1))
}

/// The squaring power unit with its last squaring skipped: the result rounds the product
/// before it. None when the unit has no such chain.
pub fn squaring_one_fewer(text: &str) -> Option<String> {
    let line = text.lines().find(|l| l.contains(" fin = sq"))?;
    let at = line.find(" fin = sq")? + " fin = sq".len();
    let end = at + line[at..].find(|c: char| !c.is_ascii_digit())?;
    let k: u32 = line[at..end].parse().ok()?;
    (k > 0).then(|| text.replacen(line, &format!("{}{}{}", &line[..at], k - 1, &line[end..]), 1))
}

/// frame_transform with one pair of frame elements transposed: the product that should read
/// B_x (lane 3) reads T_y (lane 1) and the one that should read T_y reads B_x. None when the
/// unit has no such products.
pub fn frame_transposed(text: &str) -> Option<String> {
    // The frame slices in the emitter's order: component 0's b_x T_x, b_y B_x, b_z N_x, then
    // component 1's b_x T_y, ...
    let slices: Vec<&str> = text
        .lines()
        .filter_map(|l| l.split_once("= frame[").map(|(_, r)| r.split(']').next().unwrap_or("")))
        .collect();
    let (bx, ty) = (format!("frame[{}]", slices.get(1)?), format!("frame[{}]", slices.get(3)?));
    Some(text.replace(&bx, "@SWAP@").replace(&ty, &bx).replace("@SWAP@", &ty))
}

/// frame_build: the first cross product turned round, m × N for N × m, so B and T point the
/// other way (a left-handed reading of the paper's e1).
pub fn frame_cross_reversed(text: &str) -> Option<String> {
    let mut out = text.to_string();
    for c in 0..3 {
        let (from, to) = (format!("c{c}_d = c{c}_p - c{c}_n;"), format!("c{c}_d = c{c}_n - c{c}_p;"));
        if !out.contains(&from) {
            return None;
        }
        out = out.replace(&from, &to);
    }
    Some(out)
}

/// `pixel_lh`'s half sum for light 0 not halved: H's normalise reads the low bits of L + V.
/// None when the top forms no H at the pixel.
pub fn half_sum_not_halved(text: &str) -> Option<String> {
    let line = text.lines().find(|l| l.contains(" hh0 = "))?;
    // Each lane is `hs0_<c>[W:1]`; the mutant takes `[W-1:0]`.
    let mut out = String::new();
    let mut rest = line;
    while let Some(at) = rest.find('[') {
        let end = at + rest[at..].find(']')?;
        let (hi, lo) = rest[at + 1..end].split_once(':')?;
        let hi: u32 = hi.parse().ok()?;
        out += &rest[..at];
        out += &if lo == "1" {
            format!("[{}:0]", hi - 1)
        } else {
            rest[at..=end].to_string()
        };
        rest = &rest[end + 1..];
    }
    out += rest;
    (out != line).then(|| text.replacen(line, &out, 1))
}

/// env_fetch reading the block's first texel where its second, (x0 + 1, y0), belongs: the
/// second RAM copy's address loses its increment. None when the design has no such read.
pub fn env_fetch_second_texel(text: &str) -> Option<String> {
    let from = ".raddr({y0, x1})";
    text.contains(from).then(|| text.replacen(from, ".raddr({y0, x0})", 1))
}

/// env_coords with the last texel's fraction one sixteenth short: at the map's far edge
/// the block's far texel weighs 15/16 instead of 1. None when the line is not there.
pub fn env_coords_edge_fraction(text: &str) -> Option<String> {
    let from = "lx ? 5'd16";
    text.contains(from).then(|| text.replacen(from, "lx ? 5'd15", 1))
}

/// The top's handshake output `ready` (`in_ready`, `tri_ready`) tied low: a top that stops
/// taking beats. None when the top assigns no such port.
pub fn ready_stuck_low(text: &str, ready: &str) -> Option<String> {
    let line = text.lines().find(|l| l.starts_with(&format!("assign {ready} = ")))?;
    Some(text.replacen(line, &format!("assign {ready} = 1'b0;"), 1))
}

/// The top's output gate removed: `out_c` holds its last result while `out_valid` is low,
/// where the integration notes promise 0. The gate is `valid ? colour : 0`, the colour
/// itself possibly a conditional (the output buffer). None when the top has no such line.
pub fn output_ungated(text: &str) -> Option<String> {
    let gated = text.lines().find(|l| l.starts_with("assign out_c = "))?;
    let (_, rhs) = gated.split_once(" ? ")?;
    let bare = format!("assign out_c = {};", rhs.rsplit_once(" : ")?.0);
    Some(text.replacen(gated, &bare, 1))
}
