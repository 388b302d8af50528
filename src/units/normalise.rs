//! normalise: an interpolated L or H scaled back to unit length per fragment (a reciprocal
//! square root from a table and Newton steps; `model::normalise` holds the arithmetic).
//! Present with `renormalise = true`, one instance per interpolated vector the top uses,
//! between the fragment port and the dot products. normalise_b: the same arithmetic on the
//! fetched bump normal (`renormalise_bump = true`), one instance after the fetch.

use super::{lanes, p, Dir, Lanes, Memories, Port, Unit};
use crate::config::PipelineConfig;
use crate::model::normalise::{normalise_exact_shape, normalise_shape, params_of, Shape};
use crate::units::timing::{cut, NORMALISE as NORMALISE_CUTS};

/// One normalise unit: which vector it scales (its [`Shape`]), where it is and what it needs.
pub struct Normalise {
    name: &'static str,
    source: &'static str,
    shape: fn(&PipelineConfig) -> Shape,
    included: fn(&PipelineConfig) -> bool,
    requires: fn(&PipelineConfig) -> Vec<(&'static str, &'static str)>,
    /// The input port's description.
    v_doc: &'static str,
    /// Whether it scales an interpolated vector (else the fetched bump normal): its corners'
    /// wording.
    interpolated: bool,
    /// When its sweep is exhaustive: the vector's width field up to 6 bits.
    exhaustive_when: &'static str,
}

/// An interpolated L or H (`renormalise`).
pub static NORMALISE: Normalise = Normalise {
    name: "normalise",
    source: "per-pixel renormalisation of interpolated vectors (paper §2 N'/|N'|, §6; Cg §8.2 normalisation cube map), by a reciprocal-square-root table and Newton steps",
    shape: Shape::lh,
    included: |cfg| cfg.renormalise && cfg.cube_map_face == 0,
    requires: |cfg| {
        let interpolate = match cfg.interpolate {
            crate::config::Interpolate::Hl => "\"hl\"",
            _ => "\"h\"",
        };
        vec![
            ("renormalise", "true"),
            ("interpolate", interpolate),
            ("bump_state", "\"fragment\""),
            ("light_mode", "\"parallel\""),
            ("cube_map_face", "0"),
        ]
    },
    v_doc: "an interpolated L or H, any length",
    interpolated: true,
    exhaustive_when: "lh_bits <= 6 (2^18 inputs at most)",
};

/// The fetched bump normal (`renormalise_bump`): the same arithmetic at the normal's width.
pub static NORMALISE_B: Normalise = Normalise {
    name: "normalise_b",
    source: "the fetched bump normal scaled back to unit length after the texture filter shortened it (paper §2 N'/|N'|; gbump claim map-filter), the normalise unit's arithmetic at the normal's width",
    shape: Shape::bump,
    included: |cfg| cfg.renormalise_bump,
    requires: |_| vec![("renormalise_bump", "true"), ("palette", "false")],
    v_doc: "the fetched bump normal B, any length (a filter shortens it)",
    interpolated: false,
    exhaustive_when: "normal_bits <= 6 (2^18 inputs at most)",
};

/// What both units share, given the vector's shape.
fn ports(shape: &Shape, what: &'static str) -> Vec<Port> {
    vec![
        p("v", Dir::In, shape.fmt(), 3, what),
        p(
            "n",
            Dir::Out,
            shape.fmt(),
            3,
            "v scaled to the length it carries at unit length (the normals' scale); zero stays zero",
        ),
    ]
}

pub(super) fn resources(cfg: &PipelineConfig, shape: &Shape) -> crate::units::resources::Resources {
    use crate::units::resources::{requant_clamp, signed, sum_of_products, unsigned, Resources};
    let pr = params_of(shape);
    let (lh, rw, mb, l) = (shape.width, pr.word_bits(), pr.m_bits, pr.window);
    let zw = pr.shift_bits();
    let m = cfg.multipliers;
    let mut r = sum_of_products(m, &[(signed(lh), signed(lh)); 3], false, 2 * lh);
    if pr.pre_bits > 0 {
        r += Resources::adders(2 * l);
    }
    r += Resources::stage(cut(cfg, NORMALISE_CUTS, 0), l + 3 * lh);
    // The leading-pair search and the shift (a barrel shifter of l bits, zw levels), and
    // the table: a word per entry, selected by the index.
    r += Resources::compares(l / 2) + Resources::muxes(l * zw);
    r += Resources::muxes(pr.entries() * rw);
    for _ in 0..pr.steps {
        r += sum_of_products(m, &[(unsigned(rw), unsigned(rw))], false, 2 * rw);
        r += sum_of_products(m, &[(unsigned(mb), unsigned(rw + 2))], false, mb + rw + 2);
        r += Resources::adders(rw);
        r += sum_of_products(m, &[(unsigned(rw), unsigned(rw))], false, 2 * rw);
    }
    r += Resources::stage(cut(cfg, NORMALISE_CUTS, 1), rw + zw + 3 * lh);
    let xw = lh + rw + 1;
    let pw = xw + pr.post_bits;
    r += sum_of_products(m, &[(signed(lh), unsigned(rw))], false, xw).scaled(3.0);
    if pr.post_bits > 0 {
        r += Resources::adders(pw).scaled(3.0);
    }
    r += Resources::stage(cut(cfg, NORMALISE_CUTS, 2), 3 * pw + zw);
    let sw = crate::rtlgen::normalise_v::scaled_width(shape);
    let fmt = crate::fixed::Format {
        width: sw,
        frac: pr.r_frac + 2 + pr.post_bits,
        signed: true,
    };
    r += (Resources::muxes(sw * zw) + requant_clamp(fmt, 0, crate::model::normalise::ROUNDING, lh)).scaled(3.0);
    r + Resources::regs(3 * lh)
}

pub(super) fn exhaustive_input(shape: &Shape, i: u64) -> Lanes {
    let w = shape.width;
    let f = shape.fmt();
    let lane = |k: u32| crate::fixed::fit(((i >> (k * w)) & ((1 << w) - 1)) as i128, f, crate::fixed::Overflow::Wrap);
    vec![vec![lane(0), lane(1), lane(2)]]
}

fn corners(shape: &Shape, interpolated: bool) -> Vec<(String, Lanes)> {
    let f = shape.fmt();
    let (lo, hi) = (f.min_raw(), f.max_raw());
    let one = (1i64 << shape.frac).min(hi);
    let mut c = vec![
        ("a zero vector stays zero".to_string(), vec![vec![0, 0, 0]]),
        ("a unit axis is a fixed point".into(), vec![vec![0, 0, one]]),
        ("the shortest vector: the largest shift".into(), vec![vec![1, 0, 0]]),
        ("the shortest negative vector".into(), vec![vec![0, -1, 0]]),
        ("the longest vector: no shift, the largest S".into(), vec![vec![lo, lo, lo]]),
        ("the largest positive components".into(), vec![vec![hi, hi, hi]]),
        (
            if interpolated {
                "an interpolated unit vector at 70 % length (the dihedral of a coarse mesh)"
            } else {
                "a filtered normal at 70 % length (the average of two texels 90 degrees apart)"
            }
            .into(),
            vec![vec![one * 7 / 10 * 3 / 5, -(one * 7 / 10 * 4 / 5), 0]],
        ),
        (
            "a length just under 1: m just under 1, the table's last word".into(),
            vec![vec![0, one - 1, 0]],
        ),
        (
            "a length of 1/2: m = 1/4 exactly with binary normals, the table's first word".into(),
            vec![vec![one / 2, 0, 0]],
        ),
    ];
    // Every shift the unit can take: lengths 2^k and 2^k - 1 for every k the format holds.
    for k in 0..shape.width - 1 {
        let x = 1i64 << k;
        c.push((format!("length 2^{k}: shift for S = 4^{k}"), vec![vec![x, 0, 0]]));
        c.push((format!("length 2^{k} - 1 on two axes"), vec![vec![0, -(x - 1).max(1), x - 1]]));
    }
    c
}

impl Unit for Normalise {
    fn name(&self) -> &'static str {
        self.name
    }
    fn source(&self) -> &'static str {
        self.source
    }
    fn requires(&self, cfg: &PipelineConfig) -> Vec<(&'static str, &'static str)> {
        (self.requires)(cfg)
    }
    fn included(&self, cfg: &PipelineConfig) -> bool {
        (self.included)(cfg)
    }
    fn ports(&self, cfg: &PipelineConfig) -> Vec<Port> {
        ports(&(self.shape)(cfg), self.v_doc)
    }
    fn latency(&self, cfg: &PipelineConfig) -> u32 {
        crate::units::timing::latency(cfg, NORMALISE_CUTS)
    }
    fn eval(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Lanes {
        vec![normalise_shape(&(self.shape)(cfg), lanes(&i[0])).to_vec()]
    }
    fn exact(&self, cfg: &PipelineConfig, _: &Memories, i: &[Vec<i64>]) -> Vec<Vec<f64>> {
        vec![normalise_exact_shape(&(self.shape)(cfg), lanes(&i[0])).to_vec()]
    }
    fn resources(&self, cfg: &PipelineConfig) -> crate::units::resources::Resources {
        resources(cfg, &(self.shape)(cfg))
    }
    fn verilog(&self, cfg: &PipelineConfig) -> Vec<(&'static str, String)> {
        vec![(self.name, crate::rtlgen::normalise_v::normalise(cfg, &(self.shape)(cfg), self.name))]
    }
    fn exhaustive_count(&self, cfg: &PipelineConfig) -> Option<u64> {
        let w = (self.shape)(cfg).width;
        (w <= 6).then(|| 1u64 << (3 * w))
    }
    fn exhaustive_when(&self) -> Option<&'static str> {
        Some(self.exhaustive_when)
    }
    fn exhaustive_input(&self, cfg: &PipelineConfig, i: u64) -> Lanes {
        exhaustive_input(&(self.shape)(cfg), i)
    }
    fn corners(&self, cfg: &PipelineConfig) -> Vec<(String, Lanes)> {
        corners(&(self.shape)(cfg), self.interpolated)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::normalise::{newton_step, params, table_word};

    /// Every Newton step stays inside the widths the Verilog gives it: 0 < 3 - m r^2 and
    /// every r below 2^(Y+2), for every table word at both ends of its interval of m.
    #[test]
    fn newton_steps_fit_their_words_for_every_table_entry() {
        for lh in 4..=24 {
            for range in [crate::config::NormalRange::Binary, crate::config::NormalRange::Symmetric] {
                let cfg = PipelineConfig {
                    lh_bits: lh,
                    normal_range: range,
                    ..Default::default()
                };
                let p = params(&cfg);
                for k in 0..p.entries() {
                    assert!(table_word(&p, k) < 1 << p.word_bits());
                    for end in [0i128, (1i128 << (p.m_bits - p.table_bits)) - 1] {
                        let m = (((p.first_index() + k) as i128) << (p.m_bits - p.table_bits)) + end;
                        let mut r = table_word(&p, k) as i128;
                        for _ in 0..p.steps {
                            let (e, next) = newton_step(&p, m, r);
                            assert!(e > 0 && e < 1 << p.word_bits(), "lh {lh} entry {k}: e {e}");
                            r = next;
                            assert!(r < 1 << p.word_bits());
                        }
                    }
                }
            }
        }
    }
}
