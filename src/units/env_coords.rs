//! env_coords: EMBM's map coordinates (paper §3.3, Direct3D 6): s = st + M·(du, dv) with
//! (du, dv) the fetched bump normal's x and y, then the texel (x0, y0) of the bilinear block
//! and its four weights (`model::env_map`).

use super::{lanes, p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::fixed::Format;
use crate::model::env_map::{env_coords, SUBTEXEL_BITS, WEIGHT_FRAC_BITS};
use crate::rtlgen::env_v::{coord_width, WEIGHT_BITS};

pub struct EnvCoords;

impl Unit for EnvCoords {
    fn name(&self) -> &'static str {
        "env_coords"
    }
    fn source(&self) -> &'static str {
        "paper §3.3 (Direct3D 6 EMBM): (du, dv) through a 2x2 matrix perturbs the environment-map coordinates"
    }
    fn requires(&self, _: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        vec![("env_map_bits", "6")]
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        cfg.embm()
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        let e = Format::u(cfg.env_map_bits, 0);
        vec![
            p("b", Dir::In, cfg.normal_fmt(), 2, "x and y of the fetched bump normal: (du, dv)"),
            p("st", Dir::In, cfg.lh_fmt(), 2, "interpolated sphere-map coordinates (s, t)"),
            p(
                "m",
                Dir::In,
                cfg.lh_fmt(),
                4,
                "the 2x2 matrix: lanes 0, 1 = ds/ddu, lanes 2, 3 = ds/ddv",
            ),
            p("x0", Dir::Out, e, 1, "texel column of the bilinear block's first texel"),
            p("y0", Dir::Out, e, 1, "texel row of the bilinear block's first texel"),
            p(
                "w",
                Dir::Out,
                Format::u(WEIGHT_BITS, WEIGHT_FRAC_BITS),
                4,
                "bilinear weights of (x0, y0), (x0+1, y0), (x0, y0+1), (x0+1, y0+1)",
            ),
        ]
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        super::timing::latency(cfg, super::timing::ENV_COORDS)
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        let s = env_coords(cfg, lanes(&i[0]), lanes(&i[1]), lanes(&i[2]));
        vec![vec![s.x0], vec![s.y0], s.w.to_vec()]
    }
    fn exact(&self, cfg: &PipelineConfig, mem: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        // The texel coordinate without the sub-texel truncation: weights of the exact
        // fractions (the texel itself is the model's, which the truncation never moves).
        let n = cfg.env_map_side() as f64;
        let (lf, nf) = (cfg.lh_fmt(), cfg.normal_fmt());
        let m: Vec<f64> = i[2].iter().map(|&v| lf.to_f64(v)).collect();
        let b = [nf.to_f64(i[0][0]), nf.to_f64(i[0][1])];
        let axis = |st: i64, mx: f64, my: f64, x0: i64| {
            let s = lf.to_f64(st) + mx * b[0] + my * b[1];
            let x = ((s + 1.0) * n / 2.0 - 0.5).clamp(0.0, n - 1.0);
            (x - x0 as f64) * (1 << SUBTEXEL_BITS) as f64
        };
        let model = self.eval(cfg, mem, i);
        let (x0, y0) = (model[0][0], model[1][0]);
        let (fx, fy) = (axis(i[1][0], m[0], m[2], x0), axis(i[1][1], m[1], m[3], y0));
        let one = (1 << SUBTEXEL_BITS) as f64;
        vec![
            vec![x0 as f64],
            vec![y0 as f64],
            vec![(one - fx) * (one - fy), fx * (one - fy), (one - fx) * fy, fx * fy],
        ]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        use crate::units::resources::{form, signed, sum_of_products, unsigned, Resources};
        use crate::units::timing::{cut, ENV_COORDS};
        let (nb, lh, e) = (cfg.normal_bits, cfg.lh_bits, cfg.env_map_bits);
        let (sw, fb) = (coord_width(cfg), SUBTEXEL_BITS + 1);
        let xw = sw + e;
        let axis = sum_of_products(form(cfg), &[(signed(lh), signed(nb)), (signed(lh), signed(nb))], true, sw)
            + Resources::stage(cut(cfg, ENV_COORDS, 0), sw)
            + Resources::adders(2 * xw)
            + Resources::compares(2 * xw)
            + Resources::muxes(xw + e + fb)
            + Resources::stage(cut(cfg, ENV_COORDS, 1), e + fb)
            + Resources::adders(fb);
        let weight = sum_of_products(form(cfg), &[(unsigned(fb), unsigned(fb))], false, WEIGHT_BITS);
        axis.scaled(2.0) + weight.scaled(4.0) + Resources::regs(2 * e + 4 * WEIGHT_BITS)
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![("env_coords", crate::rtlgen::env_v::env_coords(cfg))]
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        let (nf, lf) = (cfg.normal_fmt(), cfg.lh_fmt());
        let one = 1i64 << (cfg.lh_bits - 2);
        let n = cfg.env_map_side() as i64;
        // st of texel i's centre, (i + 1/2)·2/n − 1, exactly when n divides the scale.
        let centre = |i: i64| ((2 * i + 1) * one) / n - one;
        let id = vec![one, 0, 0, one];
        let flat = vec![0, 0];
        let mut v = vec![
            (
                "flat normal at the map's centre: the middle texels, no perturbation".into(),
                vec![flat.clone(), vec![0, 0], id.clone()],
            ),
            (
                "flat normal at texel (1, 2)'s centre: that texel alone, weight 1".into(),
                vec![flat.clone(), vec![centre(1), centre(2)], id.clone()],
            ),
            (
                "flat normal at the last texel's centre: the block before it, weight 1 on its far texel".into(),
                vec![flat.clone(), vec![centre(n - 1), centre(n - 1)], id.clone()],
            ),
            (
                "coordinates below the map: clamp to the first texel".into(),
                vec![flat.clone(), vec![lf.min_raw(), lf.min_raw()], id.clone()],
            ),
            (
                "coordinates above the map: clamp to the last texel".into(),
                vec![flat.clone(), vec![lf.max_raw(), lf.max_raw()], id.clone()],
            ),
            (
                "the largest s: st at its top and M b at its most positive (both negative extremes), clamps to the last texel".into(),
                vec![vec![nf.min_raw(); 2], vec![lf.max_raw(); 2], vec![lf.min_raw(); 4]],
            ),
            (
                "the most negative s: st at its bottom and M b at its most negative, clamps to the first texel".into(),
                vec![vec![nf.max_raw(); 2], vec![lf.min_raw(); 2], vec![lf.min_raw(); 4]],
            ),
            (
                "most negative codes everywhere: st and M b pull against each other".into(),
                vec![vec![nf.min_raw(); 2], vec![lf.min_raw(); 2], vec![lf.min_raw(); 4]],
            ),
            (
                "a tilt of half a texel (where the L/H word resolves 2/n): equal weights across the block".into(),
                vec![
                    vec![1 << (cfg.normal_bits - 2), 1 << (cfg.normal_bits - 2)],
                    vec![centre(2), centre(2)],
                    {
                        // ds/ddu such that b_x = 1/2 moves s by half a texel (1/n): m = 2/n.
                        let m = 2 * one / n;
                        vec![m, 0, 0, m]
                    },
                ],
            ),
        ];
        // The sub-texel truncation: just below and at a sixteenth of a texel.
        let step = 2 * one / (n * (1 << SUBTEXEL_BITS));
        if step > 1 {
            for (k, why) in [
                (step - 1, "just below a sixteenth of a texel: fraction 0"),
                (step, "a sixteenth of a texel: fraction 1"),
            ] {
                v.push((why.into(), vec![flat.clone(), vec![centre(3) + k, centre(3)], id.clone()]));
            }
        }
        v
    }
}
