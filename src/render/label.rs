//! Text on an RGB image: labels for contact sheets, drawn from the public-domain 8×8 font
//! (`font8x8`), so a sheet names its own columns and rows without a font on the machine.

/// Pixels a character advances.
pub const CHAR_W: u32 = 8;
/// Pixels of a line of text.
pub const LINE_H: u32 = 8;

/// Draw `text` into `px` (an image `w` pixels wide) with its top-left at (`x`, `y`), in
/// `colour`, cut at `max_w` pixels (a cut label ends in `~`, so it is not read as whole).
/// Characters beyond ASCII draw as `?`.
pub fn draw(px: &mut [[u8; 3]], w: u32, x: u32, y: u32, text: &str, max_w: u32, colour: [u8; 3]) {
    let h = px.len() as u32 / w.max(1);
    let fit = (max_w / CHAR_W) as usize;
    let chars: Vec<char> = text.chars().collect();
    let shown: Vec<char> = if chars.len() <= fit {
        chars
    } else if fit == 0 {
        Vec::new()
    } else {
        chars[..fit - 1].iter().copied().chain(['~']).collect()
    };
    for (i, c) in shown.into_iter().enumerate() {
        let glyph = font8x8::legacy::BASIC_LEGACY[if c.is_ascii() { c as usize } else { '?' as usize }];
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8u32 {
                // Bit n of a row is the n-th pixel from the left.
                if bits >> col & 1 == 1 {
                    let (px_x, px_y) = (x + i as u32 * CHAR_W + col, y + row as u32);
                    if px_x < w && px_y < h {
                        px[(px_y * w + px_x) as usize] = colour;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const INK: [u8; 3] = [255, 255, 255];

    fn lit(px: &[[u8; 3]]) -> usize {
        px.iter().filter(|p| **p == INK).count()
    }

    /// A glyph lands where it is put and nowhere else; a long label is cut with `~`; nothing
    /// is drawn outside the image.
    #[test]
    fn labels_draw_inside_their_box() {
        let w = 40;
        let mut px = vec![[0u8; 3]; (w * 10) as usize];
        draw(&mut px, w, 0, 0, "I", 40, INK);
        let one = lit(&px);
        assert!(one > 5, "an I has ink");
        assert!(px
            .iter()
            .enumerate()
            .filter(|(_, p)| **p == INK)
            .all(|(i, _)| (i as u32 % w) < CHAR_W && (i as u32 / w) < LINE_H));
        let mut cut = vec![[0u8; 3]; (w * 10) as usize];
        draw(&mut cut, w, 0, 0, "gouraud_hl", 24, INK);
        let mut want = vec![[0u8; 3]; (w * 10) as usize];
        draw(&mut want, w, 0, 0, "go~", 24, INK);
        assert_eq!(cut, want);
        let mut edge = vec![[0u8; 3]; (w * 10) as usize];
        draw(&mut edge, w, 36, 6, "WW", 80, INK);
        assert!(lit(&edge) > 0 && edge.len() == (w * 10) as usize);
    }
}
