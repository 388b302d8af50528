//! normalise_cube: an interpolated L or H scaled to unit length by reading a normalisation
//! cube map (Cg Tutorial §8.2; `model::cube_normalise` holds the arithmetic). Present with
//! `renormalise = true` and `cube_map_face` set, in place of every `normalise` instance.

use super::{p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::cube_normalise::{component_bits, cube_normalise, cube_normalise_exact, words};
use crate::model::normalise::Shape;
use crate::rtlgen::normalise_cube_v::{dividend_bits, index_bits};
use crate::units::timing::{cut, NORMALISE_CUBE};

pub struct NormaliseCube;

impl Unit for NormaliseCube {
    fn name(&self) -> &'static str {
        "normalise_cube"
    }
    fn source(&self) -> &'static str {
        "Cg Tutorial §8.2: renormalising an interpolated vector with a normalisation cube map (the texel it pierces holds the unit vector through its centre)"
    }
    fn requires(&self, cfg: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        let mut r = super::unit("normalise").expect("unit").requires(cfg);
        r.retain(|f| f.0 != "cube_map_face");
        if cfg.cube_map_face == 0 {
            r.push(("cube_map_face", "32"));
        }
        r
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.renormalise && cfg.cube_map_face > 0
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        let f = Shape::lh(cfg).fmt();
        vec![
            p("v", Dir::In, f, 3, "an interpolated L or H, any length"),
            p(
                "n",
                Dir::Out,
                f,
                3,
                "the unit vector through the centre of the map texel v pierces, at the normals' scale; zero stays zero",
            ),
        ]
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        crate::units::timing::latency(cfg, NORMALISE_CUBE)
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![cube_normalise(cfg, [i[0][0], i[0][1], i[0][2]]).to_vec()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        vec![cube_normalise_exact(cfg, [i[0][0], i[0][1], i[0][2]]).to_vec()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::Resources;
        let shape = Shape::lh(cfg);
        let face = cfg.cube_map_face;
        let (lh, c, cw) = (shape.width, index_bits(face), component_bits(&shape));
        let dw = dividend_bits(lh, face);
        // Magnitudes, the major axis (three comparisons) and the minors picked.
        let mut r = (Resources::adders(lh) + Resources::muxes(lh)).scaled(3.0) + Resources::compares(3 * lh);
        r += Resources::muxes(4 * lh + 2);
        r += Resources::stage(cut(cfg, NORMALISE_CUBE, 0), 3 * lh + 3);
        // Two divisions: the dividend, then a compare, subtract and select a quotient bit.
        r += (Resources::adders(lh + 1)
            + Resources::compares(dw).scaled((c + 1) as f64)
            + (Resources::adders(dw) + Resources::muxes(dw)).scaled(c as f64)
            + Resources::muxes(c))
        .scaled(2.0);
        r += Resources::compares(lh);
        r += Resources::stage(cut(cfg, NORMALISE_CUBE, 1), 2 * c + 4);
        // The quarter-face map, its index, the signs and the axes' order.
        r += Resources::muxes(words(face) * 3 * cw) + Resources::muxes(2 * (c - 1));
        r += (Resources::adders(lh) + Resources::muxes(lh)).scaled(3.0);
        r += Resources::muxes(4 * lh + 3 * lh);
        r + Resources::regs(3 * lh)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![("normalise_cube", crate::rtlgen::normalise_cube_v::normalise_cube(cfg))]
    }
    fn exhaustive_count(&self, cfg: &PipelineConfig) -> Option<u64> {
        let w = cfg.lh_bits;
        (w <= 6).then(|| 1u64 << (3 * w))
    }
    fn exhaustive_when(&self) -> Option<&'static str> {
        Some("lh_bits <= 6 (2^18 inputs at most)")
    }
    fn exhaustive_input(&self, cfg: &PipelineConfig, i: u64) -> Lanes {
        super::normalise::exhaustive_input(&Shape::lh(cfg), i)
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let f = Shape::lh(cfg).fmt();
        let (lo, hi) = (f.min_raw(), f.max_raw());
        let one = 1i64 << (cfg.lh_bits - 2);
        let face = cfg.cube_map_face as i64;
        // A minor component on the edge between texels k - 1 and k of a face of major m.
        let edge = |k: i64, m: i64| 2 * k * m / face - m;
        let mut c: Vec<(String, Lanes)> = vec![
            ("a zero vector stays zero".into(), vec![vec![0, 0, 0]]),
            ("+z: the face's four central texels meet".into(), vec![vec![0, 0, one]]),
            ("-x: the major's sign".into(), vec![vec![-one, 0, 0]]),
            ("the shortest vector: a major of one LSB".into(), vec![vec![0, 1, 0]]),
            ("|x| = |y| = |z|: the tie goes to x".into(), vec![vec![one / 2, -one / 2, one / 2]]),
            ("|y| = |z| > |x|: the tie goes to y".into(), vec![vec![1, one / 2, -one / 2]]),
            ("the most negative components: magnitude 2^(w-1)".into(), vec![vec![lo, lo, lo]]),
            ("the largest positive components".into(), vec![vec![hi, hi, hi]]),
            (
                "a minor equal to the major: the last texel, not past it".into(),
                vec![vec![one, one - 1, one]],
            ),
            (
                "a minor equal to minus the major: the first texel".into(),
                vec![vec![-one + 1, -one, one]],
            ),
            (
                "an interpolated unit vector at 70 % length".into(),
                vec![vec![one * 7 / 10 * 3 / 5, -(one * 7 / 10 * 4 / 5), 0]],
            ),
        ];
        // Each side of the centre line and of a texel edge near the face's rim.
        let m = one;
        for k in [face / 2, face / 2 + 1, face - 1] {
            let p = edge(k, m);
            c.push((format!("a minor on the edge into texel {k}"), vec![vec![m, p, 0]]));
            c.push((format!("a minor just below the edge into texel {k}"), vec![vec![m, p - 1, 0]]));
        }
        c
    }
}
