//! `PipelineConfig`: the single source of truth for every width, table size, light count,
//! rounding and ordering choice of the Gouraud bump pipeline.
//!
//! Number conventions (chosen so that 1.0 is exact wherever the paper multiplies by it):
//! - bump-normal components: signed `normal_bits`, value `b / 2^(normal_bits-1)` (or
//!   `b / (2^(normal_bits-1)-1)` under `normal_range = "symmetric"`, the factor carried by the
//!   per-triangle L and H), stored range-compressed as offset binary
//!   (`b + 2^(normal_bits-1)`), so expanding is an MSB flip;
//! - L and H components: signed `lh_bits` words `s1.(lh_bits-2)` (paper §4.2: 16-bit words);
//! - fd, fs and k: unsigned `u1.F`, codes `0..=2^F`, so a full-intensity term is exact;
//! - colours: unsigned normalised codes, `2^colour_bits - 1` is 1.0 (as in a frame buffer).

use crate::error::{toml_error, Error, Result};
use crate::fixed::{Format, Overflow, Rounding};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

/// How the power table is indexed by the dot product.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PowerIndex {
    /// Nearest table entry: `round(fd * (N-1))`.
    Nearest,
    /// The entry below: `floor(fd * (N-1))`, one adder fewer.
    Truncate,
}

/// How the power unit computes x^n (see `model::power_unit` and `gbump power-space`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PowerUnitKind {
    /// The paper's table: `power_entries` entries, indexed as `power_index` says.
    Table,
    /// `power_entries` uniform knots with linear interpolation.
    Lerp,
    /// `power_segments` segments halving towards x = 1, `power_entries` interpolated
    /// entries each: dense where x^n changes fastest.
    Segmented,
    /// No table: the Cg Tutorial's specular power (§8.3), x^e by successive squarings, e the
    /// power of two nearest the shininess on a log scale (`model::power_unit::squarings_exponent`: three
    /// squarings for 8, four for 20), each product rounded on u1.(power_frac_bits +
    /// SQUARING_GUARD_BITS). The exponent is fixed when the hardware is built, so the top
    /// serves one shininess, as a ROM table does; its table load port stays, unused.
    Squaring,
}

/// Guard bits of the squaring power unit's products: with 4 the result stays within an LSB
/// of x^e for every exponent the unit can be built for at the default formats
/// (`model::power_unit`'s test: 0.993 at worst); `gbump power-space` measures other guards.
pub const SQUARING_GUARD_BITS: u32 = 4;

/// Hardware that holds one shininess, fixed when it is built (a ROM table, or a squaring
/// power unit): what to say when a scene, a vector set or a caller asks for another.
pub struct FixedShininess {
    /// The field that fixes it.
    pub field: &'static str,
    /// The setting that fixes it (`power_rom = true`, `power_unit = "squaring"`).
    pub setting: &'static str,
    /// "the power table is a ROM holding shininess 16", or the squaring unit's equivalent.
    pub what: String,
    /// The setting that would lift the restriction.
    pub release: &'static str,
}

impl FixedShininess {
    /// The refusal of `--shininess n` for another shininess than the one the hardware serves.
    /// `choice` is how the caller spells it: `--shininess`, `shininess=`.
    pub fn refuse(&self, choice: &str, n: u32) -> Error {
        Error::Other(format!(
            "{}: the configuration's {}\n  fix: drop {choice}, or use a configuration with {}",
            crate::names::choice(choice, n),
            self.what,
            self.release
        ))
    }
}

/// One light per clock (paper §4.2: "n light sources are blended in n clock cycles") or all at once.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LightMode {
    Serial,
    Parallel,
}

/// Where the top holds a triangle's bump state (L_i, H_i, Lc_i, k_i).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BumpStateAt {
    /// Loaded once per triangle through the triangle-setup port into `triangle_banks`
    /// register banks; fragments carry a bank tag only (the paper's per-triangle setup).
    Triangle,
    /// Enters with every fragment and travels with it through the stage registers.
    Fragment,
}

/// What the rasteriser interpolates of the bump state (paper §6's improvements): nothing
/// (the paper's engine: L and H per triangle), the half vectors, or the half vectors and the
/// light directions. An interpolated vector is formed at each vertex in that vertex's own
/// frame and interpolated over the triangle, so it reaches the pipeline per fragment: it needs
/// `bump_state = "fragment"`. The generated RTL is the per-fragment top's; the vectors and
/// golden images carry each fragment's own L and H.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Interpolate {
    #[default]
    None,
    H,
    Hl,
}

impl Interpolate {
    /// Whether nothing is interpolated (the field is then left out of the TOML, so the
    /// hashes of configurations from before the field are unchanged).
    pub fn is_none(&self) -> bool {
        *self == Interpolate::None
    }
}

/// How the units' multipliers are written in the Verilog.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Multipliers {
    /// Radix-4 Booth partial-product rows in logic (`rtlgen::booth`): smaller in gate
    /// equivalents and on FPGAs without multiplier blocks (iCE40 HX/LP), which the default
    /// four-light top needs to fit an HX8K.
    Booth,
    /// A Verilog `*` per product, left to synthesis: DSP blocks on ECP5, Xilinx and the iCE40
    /// UltraPlus, an AND array elsewhere.
    Inferred,
}

/// What a bump-normal code b means. Both store b as offset binary and feed the same dot
/// product; they differ in the scale the per-triangle L and H carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalRange {
    /// b / 2^(w-1): +1.0 saturates to (2^(w-1)-1) / 2^(w-1), 127/128 at 8 bits, so a flat
    /// normal's diffuse term is scaled by that and its highlight by its n-th power.
    Binary,
    /// b / (2^(w-1)-1): ±1.0 exact (the SNORM convention). The hardware still computes B·L
    /// with b / 2^(w-1); the per-triangle L and H are sent multiplied by
    /// 2^(w-1) / (2^(w-1)-1), so the product is the same at no per-fragment cost.
    Symmetric,
}

/// The order of the blend units around texture modulation (paper §5.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BlendOrder {
    /// DiffuseBlend → Texture → SpecularBlend (Fig. 2, the paper's recommendation).
    DiffuseTextureSpecular,
    /// DiffuseBlend → SpecularBlend → Texture (Fig. 3: highlights vanish on dark texels).
    TextureLast,
}

/// Every parameter of one pipeline instance.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PipelineConfig {
    /// Bits per bump-normal component (signed after expansion).
    pub normal_bits: u32,
    /// What a bump-normal code means: `binary` (b / 2^(w-1)) or `symmetric` (b / (2^(w-1)-1),
    /// the scale folded into the per-triangle L and H).
    pub normal_range: NormalRange,
    /// Bits per L or H component word (paper: 16).
    pub lh_bits: u32,
    /// Fraction bits of the clamped dot products fd and of the power-table index.
    #[serde(alias = "dot_bits")]
    pub dot_frac_bits: u32,
    /// Power-table entries (a power of two; paper: 256, the size of a colour LUT).
    pub power_entries: u32,
    /// Fraction bits of a power-table entry (u1.P, so x^n = 1 is exact).
    #[serde(alias = "power_bits")]
    pub power_frac_bits: u32,
    pub power_index: PowerIndex,
    pub power_unit: PowerUnitKind,
    /// Segments of a segmented power unit.
    pub power_segments: u32,
    /// Shininess n whose table the power ROM holds at reset (reloadable through its load port).
    pub shininess: u32,
    /// Colour channel bits (paper: 8).
    pub colour_bits: u32,
    /// Fraction bits the colour keeps between the three colour stages (0: each stage rounds to
    /// `colour_bits`, as the paper's units do). With g > 0 the diffuse blend, the texture
    /// modulation and the specular blend pass colours of `colour_bits + g` bits and
    /// `colour_round` rounds once at the end, so the stages' roundings add 2^-g LSB each
    /// instead of half an LSB (left out of the TOML when 0, so older hashes are unchanged).
    #[serde(skip_serializing_if = "is_zero")]
    pub colour_guard_bits: u32,
    /// Fraction bits of the per-light modulation k_i (u1.K).
    #[serde(alias = "k_bits")]
    pub k_frac_bits: u32,
    /// Light slots in hardware (1–8; paper: "usually two to four").
    pub lights: u32,
    pub light_mode: LightMode,
    pub blend_order: BlendOrder,
    /// Rounding of the dot-product requantisation and of each blend sum.
    pub rounding: Rounding,
    /// Bump map holds 8-bit indices into a 256-entry normal palette (paper §6).
    pub palette: bool,
    /// Hardware has a diffuse blend unit.
    pub diffuse: bool,
    /// Hardware has a specular path (dot, power table, specular blend).
    pub specular: bool,
    /// Leave fragments whose bump normal is unperturbed (0,0,1) untouched (paper §5.4.2).
    pub skip_flat: bool,
    /// Where the top holds the bump state: per triangle (setup port, register banks) or per
    /// fragment (on the fragment port).
    pub bump_state: BumpStateAt,
    /// The top has `out_ready` and an output buffer that holds every result in flight, so a
    /// downstream stage may stall it (credit-based: `in_ready` is low while the buffer could
    /// fill; no pipeline register stalls).
    pub backpressure: bool,
    /// Register banks of a per-triangle top: how many triangles may have fragments in flight
    /// at once (a setup waits while its bank is still read by an earlier triangle's fragment).
    pub triangle_banks: u32,
    /// Register stages of each arithmetic unit (1 = every unit computes in one cycle). Each
    /// step adds the next register cut of `units::timing`; from 2 on no register-to-register
    /// path holds more than one multiplier, from 3 on none holds a multiplier and the adders
    /// after it. Latencies grow with it; results do not change.
    pub pipeline_depth: u32,
    /// How the multipliers are written: Booth rows in logic, or `*` for synthesis to map
    /// (DSP blocks where the FPGA has them). Results do not change.
    pub multipliers: Multipliers,
    /// What the rasteriser interpolates of the bump state per fragment (`none`, `h`, `hl`).
    #[serde(skip_serializing_if = "Interpolate::is_none")]
    pub interpolate: Interpolate,
    /// Every bump light is white (Lc = 1, 1, 1): the blends drop the light-colour multiply
    /// (f·k·Lc is f·k in colour units, a shift and a subtract) and the banks drop Lc; the
    /// light-colour port (`tri_lc`, or `in_lc`) stays and is ignored (left out of the TOML
    /// when false, so older hashes are unchanged).
    #[serde(skip_serializing_if = "is_false")]
    pub white_lights: bool,
    /// The power table is a ROM holding x^shininess (its INIT_FILE) for a scene whose
    /// specular objects share one shininess: the table is never reloaded, so its write port
    /// is tied off (`power_table_we/_waddr/_wdata` stay on the interface, unused). Left out of
    /// the TOML when false, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub power_rom: bool,
    /// The pipeline scales every interpolated L and H back to unit length per fragment (the
    /// `normalise` unit: a reciprocal-square-root table and Newton steps), as per-pixel
    /// engines do: interpolating unit vectors shortens them. Needs `interpolate` and parallel
    /// lights. Left out of the TOML when false, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub renormalise: bool,
    /// The rasteriser interpolates each bump light's k (its intensity times its spot factor,
    /// taken at the vertices) per fragment instead of holding the triangle's, as SGI's and
    /// Harmony's per-vertex lighting does. The pipeline is unchanged: k reaches it on the
    /// fragment port with the rest of the bump state, so this needs bump_state = "fragment".
    /// Left out of the TOML when false, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub interpolate_k: bool,
    /// The pipeline scales the fetched bump normal back to unit length per fragment (a
    /// `normalise_b` unit after the fetch, the `normalise` unit's arithmetic at the normal's
    /// width): a texture unit's bilinear filter averages unit normals, and between texels that
    /// disagree the average is short, which darkens the diffuse light and dims the highlight
    /// (`gbump claim map-filter`). The flat bypass still compares the fetched normal. Left out
    /// of the TOML when false, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub renormalise_bump: bool,
    /// Texels along a face edge of the normalisation cube map (Cg Tutorial §8.2) that the
    /// `normalise_cube` units read instead of computing 1/|v| (0: the `normalise` unit's table
    /// and Newton steps). The six faces are one face turned, so the unit holds a quarter of one
    /// face and finds the texel by dividing the two minor components by the major one. Needs
    /// `renormalise`. Left out of the TOML when 0, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_zero")]
    pub cube_map_face: u32,
    /// Geometric self-shadowing (Cg Tutorial §8.5.3): a light whose direction L (as the dot
    /// products see it) points below the surface adds nothing, and its highlight is cut where
    /// the bump normal faces away from it (its fd, B·L as `dot_clamp` rounds and clamps it, is 0,
    /// read before `in_diffuse_en` masks it), so no highlight shows on a bump
    /// the light cannot reach. Below the surface is L_z <= 0 in bump space; under
    /// `frame_transform` it is N·L clamped to 0, N the unperturbed normal (0, 0, 1) placed in
    /// the fragment's frame by a second `frame_transform` instance and N·L one more
    /// `dot_clamp` per light. Gates on each light's factors; needs the diffuse path (its B·L).
    /// Left out of the TOML when false, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub self_shadow: bool,
    /// The bump normal placed in a frame that enters with every fragment (Harmony, paper
    /// §3.5): the `frame_transform` unit forms `T b_x + B b_y + N b_z` from the fetched
    /// normal and the fragment's frame (`in_frame`: the rasteriser's interpolated vertex
    /// frames, not re-orthonormalised), so L and H are given in the frame's space (eye space)
    /// instead of bump space. Needs `bump_state = "fragment"`. Left out of the TOML when
    /// false, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub frame_transform: bool,
    /// The frame built per fragment from two interpolated vectors (TexRam, paper §3.1):
    /// `in_frame` carries the main direction m (the T lanes) and the interpolated normal N_i
    /// (the N lanes; the B lanes are not read), and the `frame_build` unit forms
    /// N = N_i/|N_i|, B = N×m/|N×m| and T = B×N (the paper's e2 and −e1) for the
    /// `frame_transform` unit. Needs `frame_transform`. Left out of the TOML when false, so
    /// older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub frame_build: bool,
    /// The frame's T and B held per triangle (VISA+'s alignment matrix, paper §3.2): the
    /// rasteriser sends the triangle's plane T and B with the interpolated normal N_i, so
    /// the `frame_transform` unit forms `T b_x + B b_y + N_i b_z` = b_z (N_i + A·V) with V
    /// the map's offsets (b_x/b_z, b_y/b_z). A rasteriser choice: no RTL changes. Needs
    /// `frame_transform`, not with `frame_build`. Left out of the TOML when false, so older
    /// hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub triangle_frame: bool,
    /// The frame from an interpolated vertex quaternion (VISA+ with quaternions, paper §3.2
    /// and its [5]): `in_frame`'s lanes 0 to 3 carry q = (w, x, y, z), any length, lanes 6
    /// to 8 the interpolated normal N_i (lanes 4 and 5 are not read), and the `quat_frame`
    /// unit forms T and B as the rotation's columns in the homogeneous form, |q|² times the
    /// rotation of q/|q|, and N = |q|² N_i, for `frame_transform`. Needs
    /// `frame_transform`; not with `frame_build` or `triangle_frame`. Left out of the TOML
    /// when false, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub frame_quaternion: bool,
    /// L and H formed at the pixel (Blinn, paper §2, lit per pixel): the rasteriser sends on
    /// each light's L lanes its vector to the light unnormalised (a directional light's
    /// direction), scaled per triangle so the longest is unit, which interpolates exactly; and
    /// on its H lanes the viewer direction V. The `normalise` unit turns L into the pixel's
    /// unit L, and H = normalise((L + V)/2) is a second `normalise` in series fed the halved
    /// sum (the sum rounded down one bit). Needs `frame_transform` (V is constant only in eye
    /// space), `interpolate = "hl"` and `renormalise`. Left out of the TOML when false, so
    /// older hashes are unchanged.
    #[serde(skip_serializing_if = "is_false")]
    pub pixel_lh: bool,
    /// Environment-mapped bump mapping (Direct3D 6 EMBM, paper §3.3) with two maps of
    /// 2^env_map_bits texels a side (0: none). The fragment port carries the interpolated
    /// sphere-map coordinates `in_st` and the triangle's 2×2 matrix `in_m` in place of the
    /// light state; the `env_coords` unit forms s = st + M·(b_x, b_y) from the fetched
    /// normal, the texel (x0, y0) and the bilinear weights (4 sub-texel bits a side), the
    /// `env_fetch_*` units read the four texels of the diffuse and the specular map, and the
    /// blend units filter them: D = Σ w_i·texel_i into the diffuse blend, S likewise into the
    /// specular blend, each rounded once. The four light slots are the four texels (lights =
    /// 4, parallel, per fragment). Left out of the TOML when 0, so older hashes are unchanged.
    #[serde(skip_serializing_if = "is_zero")]
    pub env_map_bits: u32,
}

/// What the rasteriser and the pipeline do per fragment beyond the paper's per-triangle
/// engine: the choices `gbump engines` sets, every one of them, to turn a scene's
/// configuration into an engine's bit-accurate path, and the f64 model of that path reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PerFragment {
    /// What the rasteriser interpolates of L and H.
    pub interpolate: Interpolate,
    /// Whether the pipeline renormalises the interpolated vectors (the `normalise` unit).
    pub renormalise: bool,
    /// Whether the rasteriser interpolates each light's k.
    pub interpolate_k: bool,
    /// Whether the pipeline renormalises the fetched bump normal (the `normalise_b` unit).
    pub renormalise_bump: bool,
    /// Texels along a face edge of the cube map that renormalises L and H (0: computed).
    pub cube_map_face: u32,
    /// Whether the specular power comes from successive squarings (`power_unit =
    /// "squaring"`) rather than the scene's table.
    pub squaring: bool,
    /// Whether the pipeline self-shadows (`self_shadow`) where the scene asks for it.
    pub self_shadow: bool,
    /// Whether the bump normal is placed in the fragment's interpolated frame
    /// (`frame_transform`), L and H interpolated in eye space.
    pub frame_transform: bool,
    /// Whether that frame is built per fragment from the interpolated normal and main
    /// direction (`frame_build`, TexRam) rather than interpolated whole (Harmony).
    pub frame_build: bool,
    /// Whether the frame's T and B are the triangle's (`triangle_frame`, VISA+).
    pub triangle_frame: bool,
    /// Whether the frame comes from an interpolated quaternion (`frame_quaternion`, VISA+
    /// with quaternions).
    pub frame_quaternion: bool,
    /// Whether L is formed at the pixel from the interpolated vector to the light and H from
    /// it and the viewer direction (`pixel_lh`, Blinn's per-pixel lighting).
    pub pixel_lh: bool,
    /// Environment-map address bits per axis (`env_map_bits`, EMBM: the lighting read from
    /// per-object maps at perturbed coordinates); 0: none.
    pub env_map_bits: u32,
}

impl PerFragment {
    /// The paper's engine: nothing per fragment beyond its fetch (the base the engines'
    /// choices are written over).
    pub const PER_TRIANGLE: PerFragment = PerFragment {
        interpolate: Interpolate::None,
        renormalise: false,
        interpolate_k: false,
        renormalise_bump: false,
        cube_map_face: 0,
        squaring: false,
        self_shadow: false,
        frame_transform: false,
        frame_build: false,
        triangle_frame: false,
        frame_quaternion: false,
        pixel_lh: false,
        env_map_bits: 0,
    };
}

impl std::fmt::Display for PerFragment {
    /// As the configuration's TOML fields.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let i = match self.interpolate {
            Interpolate::None => "none",
            Interpolate::H => "h",
            Interpolate::Hl => "hl",
        };
        write!(
            f,
            "interpolate = \"{i}\", renormalise = {}, interpolate_k = {}, renormalise_bump = {}",
            self.renormalise, self.interpolate_k, self.renormalise_bump
        )?;
        if self.cube_map_face > 0 {
            write!(f, ", cube_map_face = {}", self.cube_map_face)?;
        }
        if self.squaring {
            write!(f, ", power_unit = \"squaring\"")?;
        }
        if self.self_shadow {
            write!(f, ", self_shadow as the scene asks")?;
        }
        if self.frame_transform {
            write!(f, ", frame_transform = true")?;
        }
        if self.frame_build {
            write!(f, ", frame_build = true")?;
        }
        if self.triangle_frame {
            write!(f, ", triangle_frame = true")?;
        }
        if self.frame_quaternion {
            write!(f, ", frame_quaternion = true")?;
        }
        if self.env_map_bits > 0 {
            write!(f, ", env_map_bits = {}", self.env_map_bits)?;
        }
        if self.pixel_lh {
            write!(f, ", pixel_lh = true")?;
        }
        Ok(())
    }
}

impl PipelineConfig {
    /// This configuration's per-fragment choices.
    pub fn per_fragment(&self) -> PerFragment {
        PerFragment {
            interpolate: self.interpolate,
            renormalise: self.renormalise,
            interpolate_k: self.interpolate_k,
            renormalise_bump: self.renormalise_bump,
            cube_map_face: self.cube_map_face,
            squaring: self.power_unit == PowerUnitKind::Squaring,
            self_shadow: self.self_shadow,
            frame_transform: self.frame_transform,
            frame_build: self.frame_build,
            triangle_frame: self.triangle_frame,
            frame_quaternion: self.frame_quaternion,
            pixel_lh: self.pixel_lh,
            env_map_bits: self.env_map_bits,
        }
    }
}

/// Where this run's configuration came from, for a message that finds a clash with it later,
/// away from where it was read (a scene's needs, say). None: the default.
enum Origin {
    /// A `--config` file.
    File(String),
    /// The configuration a `--scene` derives, by the name given.
    Scene(String),
}

static ORIGIN: std::sync::Mutex<Option<Origin>> = std::sync::Mutex::new(None);

fn set_origin(o: Origin) {
    *ORIGIN.lock().unwrap_or_else(|e| e.into_inner()) = Some(o);
}

/// Record `file` as the run's configuration file ([`origin`]).
pub fn note_origin(file: &str) {
    set_origin(Origin::File(file.to_string()));
}

/// Record that this run's configuration is the one scene `name` derives (`--scene`).
pub fn note_derived(name: &str) {
    set_origin(Origin::Scene(name.to_string()));
}

/// Whether this run's configuration is the one a `--scene` derives ([`note_derived`]).
pub fn from_scene() -> bool {
    matches!(*ORIGIN.lock().unwrap_or_else(|e| e.into_inner()), Some(Origin::Scene(_)))
}

/// Whether this run's configuration was read from a file (`--config`): only then can a
/// message say to edit a field of it.
pub fn from_file() -> bool {
    matches!(*ORIGIN.lock().unwrap_or_else(|e| e.into_inner()), Some(Origin::File(_)))
}

/// The run's configuration as messages name it: the `--config` file, the one a `--scene`
/// derives, else "the default configuration".
pub fn origin() -> String {
    match &*ORIGIN.lock().unwrap_or_else(|e| e.into_inner()) {
        Some(Origin::File(f)) => f.clone(),
        Some(Origin::Scene(name)) => format!("the configuration --scene {} derives", crate::shell::quoted(name)),
        None => "the default configuration".into(),
    }
}

impl Default for PipelineConfig {
    fn default() -> Self {
        PipelineConfig {
            normal_bits: 8,
            normal_range: NormalRange::Binary,
            lh_bits: 16,
            dot_frac_bits: 8,
            power_entries: 256,
            power_frac_bits: 8,
            power_index: PowerIndex::Nearest,
            power_unit: PowerUnitKind::Table,
            power_segments: 6,
            shininess: 16,
            colour_bits: 8,
            colour_guard_bits: 0,
            k_frac_bits: 8,
            lights: 4,
            light_mode: LightMode::Serial,
            blend_order: BlendOrder::DiffuseTextureSpecular,
            rounding: Rounding::HalfUp,
            palette: false,
            diffuse: true,
            specular: true,
            skip_flat: false,
            bump_state: BumpStateAt::Triangle,
            backpressure: true,
            triangle_banks: 2,
            pipeline_depth: DEFAULT_PIPELINE_DEPTH,
            multipliers: Multipliers::Booth,
            interpolate: Interpolate::None,
            white_lights: false,
            power_rom: false,
            renormalise: false,
            interpolate_k: false,
            renormalise_bump: false,
            cube_map_face: 0,
            self_shadow: false,
            frame_transform: false,
            frame_build: false,
            triangle_frame: false,
            frame_quaternion: false,
            pixel_lh: false,
            env_map_bits: 0,
        }
    }
}

fn is_zero(v: &u32) -> bool {
    *v == 0
}

fn is_false(v: &bool) -> bool {
    !*v
}

/// The default `pipeline_depth` (see ARCHITECTURE.md, "Timing as a parameter").
pub const DEFAULT_PIPELINE_DEPTH: u32 = 3;

/// Valid range of each numeric field, with the reason for its bounds.
pub const LIMITS: &[(&str, u32, u32, &str)] = &[
    (
        "normal_bits",
        3,
        16,
        "3 bits give a sign and 2 magnitude bits; 16 covers 16-bit normal maps",
    ),
    (
        "lh_bits",
        4,
        24,
        "s1.(w-2): at least 2 fraction bits; 24 keeps dot sums within 62 bits",
    ),
    (
        "dot_frac_bits",
        2,
        16,
        "fd index bits; more than 16 cannot address a practical table",
    ),
    ("power_entries", 2, 65536, "a power of two; at most 2^dot_frac_bits + 1 useful"),
    ("power_frac_bits", 2, 16, "entry fraction bits"),
    (
        "power_segments",
        2,
        15,
        "segments of a segmented power unit; fewer than dot_frac_bits",
    ),
    ("shininess", 0, 1024, "the largest exponent the table generator supports"),
    ("colour_bits", 2, 12, "frame-buffer channel width"),
    (
        "colour_guard_bits",
        0,
        4,
        "fraction bits kept between the colour stages; 4 leave 1/16 LSB per stage, below any output's resolution",
    ),
    (
        "k_frac_bits",
        0,
        12,
        "modulation fraction bits; 0 makes k_i an on/off enable (the paper's sample implementation, where k has no effect)",
    ),
    ("lights", 1, 8, "light slots in hardware"),
    (
        "triangle_banks",
        2,
        16,
        "two let a setup load while the previous triangle drains; a bank tag wider than 4 bits buys nothing at these latencies",
    ),
    (
        "cube_map_face",
        0,
        128,
        "a power of two, texels along a cube-map face edge (0: no cube map); 128 keeps the quarter face at 4096 words",
    ),
    (
        "env_map_bits",
        0,
        8,
        "texels a side of each EMBM environment map as a power of two, 2 (4x4) to 8 (256x256); 0: no EMBM",
    ),
    (
        "pipeline_depth",
        1,
        crate::limits::MAX_PIPELINE_DEPTH,
        "register stages per unit; beyond the last cut of every unit a stage adds nothing",
    ),
];

/// [`LIMITS`] as a Markdown table, each key with its default (`gbump limits` prints it after
/// the size limits; the README's Limits section holds it).
pub fn limits_markdown() -> String {
    let d = toml::Value::try_from(PipelineConfig::default()).ok();
    let default = |k: &str| d.as_ref().and_then(|t| t.get(k)).map_or("0".to_string(), |v| v.to_string());
    let mut s = String::from("| configuration key | range | default | why |\n|---|---|---:|---|\n");
    for (k, lo, hi, why) in LIMITS {
        s += &format!("| `{k}` | {lo}..={hi} | {} | {why} |\n", default(k));
    }
    s
}

/// The valid range `(lo, hi)` of numeric field `name`, from [`LIMITS`].
///
/// # Panics
/// If `LIMITS` has no such field.
pub fn limit(name: &str) -> (u32, u32) {
    LIMITS
        .iter()
        .find(|l| l.0 == name)
        .map(|&(_, lo, hi, _)| (lo, hi))
        .unwrap_or_else(|| panic!("no limit for {name}"))
}

/// Fields renamed so that a name says what it counts (`_bits`: a width; `_frac_bits`: fraction
/// bits), as (old, new). The old names are still read, with a warning.
pub const RENAMED_FIELDS: &[(&str, &str)] = &[
    ("dot_bits", "dot_frac_bits"),
    ("power_bits", "power_frac_bits"),
    ("k_bits", "k_frac_bits"),
];

/// Warn about every renamed key `text` holds under its old name, however it is written
/// (quoted, bare), at its own line; refuse one written under both names. The parser reads
/// the old names as the new ones (each field's `serde(alias)`, which
/// `old_field_names_read_as_the_new_ones` ties to this list).
fn check_renamed(file: &str, text: &str) -> Result<()> {
    // Text that does not parse is reported by the parse that follows.
    let Ok(table) = text.parse::<toml::Table>() else {
        return Ok(());
    };
    let at = |key: &str| crate::toml_line::place(text, key).map_or(String::new(), |(l, c)| format!(":{l}:{c}"));
    for &(old, new) in RENAMED_FIELDS {
        if !table.contains_key(old) {
            continue;
        }
        let at = format!("{file}{}", at(old));
        if table.contains_key(new) {
            return Err(renamed_twice(&at, old, new));
        }
        crate::warn::warn(renamed_warning(&at, old, new));
    }
    Ok(())
}

/// The warning for renamed field `old` read as `new`, written at `at` (`file:LINE:COL`).
pub fn renamed_warning(at: &str, old: &str, new: &str) -> String {
    format!(
        "warning: {at}: `{old}` is deprecated: it counts fraction bits, not a width\n  fix: write `{new}` (the old name will be removed)"
    )
}

/// The refusal of a renamed field written under both its names, the old one at `at`.
pub fn renamed_twice(at: &str, old: &str, new: &str) -> Error {
    Error::Other(format!(
        "{at}: `{old}` and `{new}` are one field (`{old}` is its old name), given twice\n  fix: keep `{new}` only"
    ))
}

impl PipelineConfig {
    /// Parse a TOML config; `file` names it in errors. Renamed fields are read under their
    /// old names too, with a warning ([`RENAMED_FIELDS`]).
    pub fn from_toml(file: &str, text: &str) -> Result<PipelineConfig> {
        // Text handed over by the C ABI or Python has the cap a file read has (in parse).
        let cfg = Self::parse(file, text)?;
        cfg.validate(file).map_err(|e| at_line(text, e))?;
        Ok(cfg)
    }

    /// [`from_toml`](Self::from_toml) for a configuration a program composed (a sweep's grid
    /// point): a field that does nothing beside another's value is set to its default instead
    /// of refused, so the point is the hardware it describes.
    pub fn from_toml_canonical(file: &str, text: &str) -> Result<PipelineConfig> {
        let cfg = Self::parse(file, text)?.canonical();
        cfg.validate(file)?;
        Ok(cfg)
    }

    /// The fields of `text`, unchecked.
    fn parse(file: &str, text: &str) -> Result<PipelineConfig> {
        if text.len() as u64 > crate::limits::MAX_INPUT_BYTES {
            return Err(Error::Other(format!(
                "{file}: {} bytes of TOML, larger than MAX_INPUT_BYTES = {}; not a configuration\n  fix: give the configuration's TOML text",
                text.len(),
                crate::limits::MAX_INPUT_BYTES
            )));
        }
        if text.trim_start().starts_with('{') {
            // An interface file or a vector manifest handed over as the configuration.
            return Err(Error::Other(format!(
                "{file}: JSON, not a configuration's TOML (an interface file or a vector manifest?)\n  fix: give the configuration's TOML: `gbump config` prints the default, and a manifest's `config` table holds its set's fields"
            )));
        }
        check_renamed(file, text)?;
        toml::from_str(text).map_err(|e| {
            let err = toml_error(
                file,
                text,
                &e,
                "`gbump config` prints every field with its default (the optional ones as `#` comments)",
            );
            // A counted field given a value of the wrong type (-1, 1e9, nan, "two"): its range.
            match err {
                Error::Input { file, line, col, msg, fix } => {
                    let key = msg
                        .strip_prefix('`')
                        .and_then(|m| m.split_once('`'))
                        .map(|(k, _)| k.rsplit('.').next().unwrap_or(k));
                    let typed = ["invalid type", "invalid value", "number", "floating-point"]
                        .iter()
                        .any(|w| msg.contains(w));
                    let fix = match key.filter(|_| typed).and_then(|k| LIMITS.iter().find(|l| l.0 == k)) {
                        Some(&(k, lo, hi, why)) => format!("`{k}` is a whole number in {lo}..={hi} ({why})"),
                        None => crate::error::wrong_kind(text, "configuration").unwrap_or(fix),
                    };
                    Error::Input { file, line, col, msg, fix }
                }
                other => other,
            }
        })
    }

    /// Load from a file.
    pub fn load(path: &std::path::Path) -> Result<PipelineConfig> {
        let text = crate::limits::read_text(path)?;
        Self::from_toml(&path.display().to_string(), &text)
    }

    /// Canonical TOML (field order fixed by the struct), the input of [`Self::hash`].
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("config serialises")
    }

    /// Stable 16-hex-digit hash of the canonical TOML.
    pub fn hash(&self) -> String {
        // Every module name and file name of a generated set asks for it, so the last
        // configuration's hash is kept per thread (the TOML and SHA-256 cost 20 µs a call).
        thread_local! {
            static LAST: std::cell::RefCell<Option<(PipelineConfig, String)>> = const { std::cell::RefCell::new(None) };
        }
        LAST.with(|last| {
            let mut last = last.borrow_mut();
            if let Some((c, h)) = last.as_ref() {
                if c == self {
                    return h.clone();
                }
            }
            let d = Sha256::digest(self.to_toml().as_bytes());
            let h: String = d.iter().take(8).map(|b| format!("{b:02x}")).collect();
            *last = Some((self.clone(), h.clone()));
            h
        })
    }

    /// A field away from its default that no unit reads under the other settings, and why:
    /// two configurations differing only there would generate the same hardware under two
    /// hashes. [`canonical`](Self::canonical) puts such fields back.
    pub fn inert_field(&self) -> Option<(&'static str, &'static str)> {
        let d = PipelineConfig::default();
        if self.bump_state == BumpStateAt::Fragment && self.triangle_banks != d.triangle_banks {
            return Some((
                "triangle_banks",
                "with bump_state = \"fragment\" the state comes with each fragment: there are no triangle banks",
            ));
        }
        if self.power_unit != PowerUnitKind::Segmented && self.power_segments != d.power_segments {
            return Some(("power_segments", "only power_unit = \"segmented\" has segments"));
        }
        if !self.renormalise && self.cube_map_face != d.cube_map_face {
            return Some((
                "cube_map_face",
                "with renormalise = false there is no normalise unit to read a cube map",
            ));
        }
        None
    }

    /// This configuration with every field [`inert_field`](Self::inert_field) names at its
    /// default: the one hash of its hardware (for configurations drawn or searched, not
    /// written by a user, whose stray value is refused instead).
    pub fn canonical(mut self) -> PipelineConfig {
        let d = PipelineConfig::default();
        if self.bump_state == BumpStateAt::Fragment {
            self.triangle_banks = d.triangle_banks;
        }
        if self.power_unit != PowerUnitKind::Segmented {
            self.power_segments = d.power_segments;
        }
        if !self.renormalise {
            self.cube_map_face = d.cube_map_face;
        }
        self
    }

    /// Check every field against [`LIMITS`] and the cross-field rules.
    pub fn validate(&self, file: &str) -> Result<()> {
        for &(name, lo, hi, why) in LIMITS {
            let v = self.get(name);
            if v < lo || v > hi {
                return Err(Error::field(
                    file,
                    name,
                    format!("{v} is out of range"),
                    format!("use {lo}..={hi} ({why})"),
                ));
            }
        }
        if self.cube_map_face != 0 && !(self.cube_map_face >= 4 && self.cube_map_face.is_power_of_two()) {
            return Err(Error::field(
                file,
                "cube_map_face",
                format!("{} is not a power of two of at least 4", self.cube_map_face),
                "use 4, 8, 16, 32 (the Cg Tutorial's size), 64 or 128, or 0 for the normalise unit's arithmetic",
            ));
        }
        self.validate_embm(file)?;
        if !self.power_entries.is_power_of_two() {
            return Err(Error::field(
                file,
                "power_entries",
                format!("{} is not a power of two", self.power_entries),
                "use 2, 4, …, 256, … (the table is addressed by whole index bits)",
            ));
        }
        if self.power_entries > (1 << self.dot_frac_bits) + 1 {
            return Err(Error::field(
                file,
                "power_entries",
                format!(
                    "{} entries exceed the {} distinct dot-product codes",
                    self.power_entries,
                    (1u32 << self.dot_frac_bits) + 1
                ),
                "raise dot_frac_bits or lower power_entries",
            ));
        }
        if self.power_unit == PowerUnitKind::Segmented && self.power_segments >= self.dot_frac_bits {
            return Err(Error::field(
                file,
                "power_segments",
                format!(
                    "{} segments need more than {} dot-product bits",
                    self.power_segments, self.dot_frac_bits
                ),
                "use fewer segments or a wider dot_frac_bits",
            ));
        }
        if let Some((field, why)) = self.inert_field() {
            let d = PipelineConfig::default().get(field);
            return Err(Error::field(
                file,
                field,
                format!(
                    "{} does nothing here ({why}), yet it would change the configuration's hash and every module name",
                    self.get(field)
                ),
                format!("leave `{field}` out or at its default {d}"),
            ));
        }
        if !self.diffuse && !self.specular {
            return Err(Error::field(
                file,
                "diffuse",
                "both blend units are off",
                "enable `diffuse` or `specular`",
            ));
        }
        if !self.interpolate.is_none() && self.bump_state != BumpStateAt::Fragment {
            return Err(Error::field(
                file,
                "interpolate",
                format!(
                    "interpolate = \"{}\" sends L or H per fragment, which a per-triangle top cannot take",
                    if self.interpolate == Interpolate::Hl { "hl" } else { "h" }
                ),
                "set bump_state = \"fragment\" (the fragment port carries L and H), or interpolate = \"none\"",
            ));
        }
        if self.interpolate_k && self.bump_state != BumpStateAt::Fragment {
            return Err(Error::field(
                file,
                "interpolate_k",
                "interpolate_k = true sends each light's k per fragment, which a per-triangle top cannot take",
                "set bump_state = \"fragment\" (the fragment port carries k with L and H), or drop interpolate_k",
            ));
        }
        if self.interpolate_k && self.k_frac_bits == 0 {
            return Err(Error::field(
                file,
                "interpolate_k",
                "interpolate_k = true with k_frac_bits = 0: an interpolated k rounds to 0 or 1, so it only switches lights on and off",
                "give k fraction bits (k_frac_bits = 8 is the default), or drop interpolate_k",
            ));
        }
        if self.renormalise_bump && self.palette {
            return Err(Error::field(
                file,
                "renormalise_bump",
                "renormalise_bump = true with palette = true: a palette index is not filtered, so the fetched normal is the entry as loaded",
                "load unit-length palette entries and drop renormalise_bump, or set palette = false",
            ));
        }
        if self.renormalise && self.interpolate.is_none() {
            return Err(Error::field(
                file,
                "renormalise",
                "renormalise = true but nothing is interpolated: the per-triangle L and H are already unit vectors",
                "set interpolate = \"h\" or \"hl\" (with bump_state = \"fragment\"), or drop renormalise",
            ));
        }
        if self.renormalise && self.light_mode != LightMode::Parallel {
            return Err(Error::field(
                file,
                "renormalise",
                "renormalise = true needs light_mode = \"parallel\": the normalise units sit one per interpolated vector before the dot products",
                "set light_mode = \"parallel\", or drop renormalise",
            ));
        }
        if self.renormalise && !self.specular && !(self.diffuse && self.interpolate == Interpolate::Hl) {
            return Err(Error::field(
                file,
                "renormalise",
                "renormalise = true but no interpolated vector reaches a dot product (no specular path, and L is not interpolated)",
                "set specular = true, or interpolate = \"hl\" with diffuse = true, or drop renormalise",
            ));
        }
        if self.self_shadow && !self.diffuse {
            return Err(Error::field(
                file,
                "self_shadow",
                "self_shadow = true with diffuse = false: the highlight's cut reads each light's B·L, which only the diffuse path computes",
                "set diffuse = true, or drop self_shadow",
            ));
        }
        if self.frame_transform && self.per_triangle() {
            return Err(Error::field(
                file,
                "frame_transform",
                "frame_transform = true places the bump normal in a frame that enters with every fragment, which a per-triangle top cannot take",
                "set bump_state = \"fragment\" (the fragment port carries the frame with L and H), or drop frame_transform",
            ));
        }
        // A frame source needs the unit that places the normal in the frame, and one source
        // at a time: each rule names the one this configuration breaks.
        for (on, field, what) in [
            (self.frame_build, "frame_build", "builds a frame per fragment"),
            (
                self.triangle_frame,
                "triangle_frame",
                "has the rasteriser send the triangle's T and B as the frame",
            ),
            (self.frame_quaternion, "frame_quaternion", "forms the frame from a quaternion"),
        ] {
            if on && !self.frame_transform {
                return Err(Error::field(
                    file,
                    field,
                    format!("{field} = true {what} for the frame_transform unit, which this configuration does not have"),
                    format!("set frame_transform = true (and bump_state = \"fragment\"), or drop {field}"),
                ));
            }
        }
        let sources: Vec<&str> = [
            (self.frame_build, "frame_build"),
            (self.triangle_frame, "triangle_frame"),
            (self.frame_quaternion, "frame_quaternion"),
        ]
        .into_iter()
        .filter_map(|(on, f)| on.then_some(f))
        .collect();
        if sources.len() > 1 {
            let last = sources[sources.len() - 1];
            return Err(Error::field(
                file,
                last,
                format!(
                    "{} each give the frame_transform unit its frame: a configuration takes one source",
                    sources.join(" and ")
                ),
                format!("keep one of {} = true and set the other(s) false", sources.join(", ")),
            ));
        }
        if self.pixel_lh && !self.frame_transform {
            return Err(Error::field(
                file,
                "pixel_lh",
                "pixel_lh = true sends the viewer direction V on the H lanes, which is one constant vector only in eye space, where a frame_transform unit places the bump normal",
                "set frame_transform = true (and bump_state = \"fragment\"), or drop pixel_lh",
            ));
        }
        if self.pixel_lh && !(self.renormalise && self.interpolate == Interpolate::Hl) {
            return Err(Error::field(
                file,
                "pixel_lh",
                "pixel_lh = true forms L and H at the pixel with normalise units from the interpolated vector to the light, which needs interpolate = \"hl\" and renormalise = true",
                "set interpolate = \"hl\" and renormalise = true (with light_mode = \"parallel\"), or drop pixel_lh",
            ));
        }
        if self.power_rom && self.power_unit == PowerUnitKind::Squaring {
            return Err(Error::field(
                file,
                "power_rom",
                "power_rom = true with power_unit = \"squaring\": a squaring unit reads no table to make a ROM of (its exponent is built in already)",
                "drop power_rom",
            ));
        }
        if self.power_rom && !self.specular {
            return Err(Error::field(
                file,
                "power_rom",
                "power_rom = true but the configuration has no specular path, so no power table",
                "drop power_rom, or set specular = true",
            ));
        }
        if self.colour_guard_bits >= self.factor_frac() + self.k_frac_bits {
            return Err(Error::field(
                file,
                "colour_guard_bits",
                format!(
                    "{} guard bits leave nothing to round of the {} fraction bits of the blend sum they are taken from",
                    self.colour_guard_bits,
                    self.factor_frac() + self.k_frac_bits
                ),
                "lower colour_guard_bits, or raise dot_frac_bits, power_frac_bits or k_frac_bits",
            ));
        }
        if self.term_fmt().sum(self.lights).width + 1 > crate::fixed::MAX_WIDTH {
            return Err(Error::field(
                file,
                "colour_bits",
                "blend accumulator too wide",
                "lower colour_bits, dot_frac_bits or k_frac_bits",
            ));
        }
        Ok(())
    }

    /// EMBM's rules (`env_map_bits` > 0): the four light slots are the bilinear filter's
    /// four texels, on a parallel per-fragment top, and nothing else per fragment.
    fn validate_embm(&self, file: &str) -> Result<()> {
        if self.env_map_bits == 0 {
            return Ok(());
        }
        let e = "env_map_bits";
        let rules: [(bool, &str, String, &str); 15] = [
            (
                self.env_map_bits < 2,
                e,
                format!("{} gives maps of fewer than 4x4 texels", self.env_map_bits),
                "use 2..=8, or 0 for no EMBM",
            ),
            (
                self.lights != 4,
                "lights",
                format!(
                    "lights = {}: EMBM's four light slots are the bilinear filter's four texels",
                    self.lights
                ),
                "set lights = 4",
            ),
            (
                self.light_mode != LightMode::Parallel,
                "light_mode",
                "EMBM filters its four texels in one parallel blend per map".into(),
                "set light_mode = \"parallel\"",
            ),
            (
                self.bump_state != BumpStateAt::Fragment,
                "bump_state",
                "EMBM's map coordinates are interpolated, so they enter with every fragment".into(),
                "set bump_state = \"fragment\"",
            ),
            (
                self.palette,
                "palette",
                "EMBM reads the stored normal's x and y as (du, dv)".into(),
                "set palette = false",
            ),
            (
                !self.interpolate.is_none(),
                "interpolate",
                "EMBM has no L or H to interpolate: its lighting is in the maps".into(),
                "leave interpolate out",
            ),
            (
                self.renormalise,
                "renormalise",
                "EMBM has no L or H to renormalise".into(),
                "drop renormalise",
            ),
            (
                self.interpolate_k,
                "interpolate_k",
                "EMBM has no k per light: each texel's weight is the filter's".into(),
                "drop interpolate_k",
            ),
            (
                self.renormalise_bump,
                "renormalise_bump",
                "EMBM reads the fetched (du, dv) as stored".into(),
                "drop renormalise_bump",
            ),
            (
                self.frame_transform,
                "frame_transform",
                "EMBM perturbs map coordinates, not a normal in a frame".into(),
                "drop frame_transform",
            ),
            (
                self.self_shadow,
                "self_shadow",
                "EMBM has no light direction to shadow by".into(),
                "drop self_shadow",
            ),
            (
                self.white_lights,
                "white_lights",
                "EMBM's light slots carry the texels' colours".into(),
                "drop white_lights",
            ),
            (
                self.power_rom,
                "power_rom",
                "EMBM's specular light comes from its map, not a power table".into(),
                "drop power_rom",
            ),
            (
                self.diffuse && self.dot_frac_bits < 8,
                "dot_frac_bits",
                format!(
                    "{}: the bilinear weights have 8 fraction bits, which the diffuse factor must hold",
                    self.dot_frac_bits
                ),
                "use dot_frac_bits >= 8",
            ),
            (
                self.specular && self.power_frac_bits < 8,
                "power_frac_bits",
                format!(
                    "{}: the bilinear weights have 8 fraction bits, which the specular factor must hold",
                    self.power_frac_bits
                ),
                "use power_frac_bits >= 8",
            ),
        ];
        match rules.into_iter().find(|r| r.0) {
            Some((_, field, msg, fix)) if field == e => Err(Error::field(file, field, msg, fix)),
            Some((_, field, msg, fix)) => Err(Error::field(
                file,
                field,
                msg,
                format!(
                    "{fix} (env_map_bits = {} asks for EMBM), or set env_map_bits = 0",
                    self.env_map_bits
                ),
            )),
            None => Ok(()),
        }
    }

    /// Whether the top is EMBM's (`env_map_bits` > 0).
    pub fn embm(&self) -> bool {
        self.env_map_bits > 0
    }

    /// Texels along a side of each EMBM environment map.
    pub fn env_map_side(&self) -> u32 {
        1 << self.env_map_bits
    }

    /// Field `field`'s value as its TOML writes it, `toml` being this configuration's
    /// [`to_toml`](Self::to_toml); a field at its default is left out of the TOML
    /// (colour_guard_bits = 0, white_lights = false, interpolate = "none"): that default.
    pub fn field_text(&self, toml: &str, field: &str) -> String {
        toml.lines()
            .find_map(|l| {
                l.split_once('=')
                    .filter(|(k, _)| k.trim() == field)
                    .map(|(_, v)| v.trim().to_string())
            })
            .unwrap_or_else(|| match LIMITS.iter().any(|l| l.0 == field) {
                true => self.get(field).to_string(),
                false if field == "interpolate" => "\"none\"".into(),
                false => "false".into(),
            })
    }

    /// The numeric field `name` of [`LIMITS`].
    pub fn get(&self, name: &str) -> u32 {
        match name {
            "normal_bits" => self.normal_bits,
            "lh_bits" => self.lh_bits,
            "dot_frac_bits" => self.dot_frac_bits,
            "power_entries" => self.power_entries,
            "power_frac_bits" => self.power_frac_bits,
            "power_segments" => self.power_segments,
            "shininess" => self.shininess,
            "colour_bits" => self.colour_bits,
            "colour_guard_bits" => self.colour_guard_bits,
            "k_frac_bits" => self.k_frac_bits,
            "lights" => self.lights,
            "triangle_banks" => self.triangle_banks,
            "pipeline_depth" => self.pipeline_depth,
            "cube_map_face" => self.cube_map_face,
            "env_map_bits" => self.env_map_bits,
            _ => unreachable!("LIMITS names a field `get` does not know: {name}"),
        }
    }

    /// Expanded bump-normal component: `s0.(nb-1)` in `nb` bits.
    #[inline]
    pub fn normal_fmt(&self) -> Format {
        Format::s(self.normal_bits, self.normal_bits - 1)
    }
    /// L/H component: `s1.(w-2)`.
    #[inline]
    pub fn lh_fmt(&self) -> Format {
        Format::s(self.lh_bits, self.lh_bits - 2)
    }
    /// Exact B·V before clamping.
    #[inline]
    pub fn dot_exact_fmt(&self) -> Format {
        self.normal_fmt().product(self.lh_fmt()).sum(3)
    }
    /// Clamped dot product fd / power index: `u1.F`.
    #[inline]
    pub fn dot_fmt(&self) -> Format {
        Format::u(self.dot_frac_bits + 1, self.dot_frac_bits)
    }
    /// Power-table entry fs: `u1.P`.
    pub fn power_fmt(&self) -> Format {
        Format::u(self.power_frac_bits + 1, self.power_frac_bits)
    }
    /// Per-light modulation k: `u1.K`.
    pub fn k_fmt(&self) -> Format {
        Format::u(self.k_frac_bits + 1, self.k_frac_bits)
    }
    /// Colour channel code.
    pub fn colour_fmt(&self) -> Format {
        Format::u(self.colour_bits, 0)
    }
    /// Largest colour code (1.0).
    #[inline]
    pub fn colour_max(&self) -> u32 {
        (1u32 << self.colour_bits) - 1
    }
    /// A colour between the colour stages: `colour_bits` integer bits and
    /// `colour_guard_bits` fraction bits (the colour format itself when there are none).
    pub fn stage_colour_fmt(&self) -> Format {
        Format::u(self.colour_bits + self.colour_guard_bits, self.colour_guard_bits)
    }
    /// The light colour the blends multiply by: a slot's own, or white (every code at 1.0)
    /// when `white_lights` strips the multiply.
    #[inline]
    pub fn light_colour(&self, lc: [u32; 3]) -> [u32; 3] {
        if self.white_lights {
            [self.colour_max(); 3]
        } else {
            lc
        }
    }
    /// Largest stage colour code (1.0 in [`Self::stage_colour_fmt`]).
    #[inline]
    pub fn stage_colour_max(&self) -> i64 {
        (self.colour_max() as i64) << self.colour_guard_bits
    }
    /// Fraction bits of the blend factor (fd or fs) feeding the blend units.
    #[inline]
    pub fn factor_frac(&self) -> u32 {
        self.dot_frac_bits.max(self.power_frac_bits)
    }
    /// Blend factor (fd or fs aligned to a common format) so that one blend unit serves both.
    pub fn factor_fmt(&self) -> Format {
        Format::u(self.factor_frac() + 1, self.factor_frac())
    }
    /// One light's exact term f·k·Lc in colour units.
    pub fn term_fmt(&self) -> Format {
        self.factor_fmt().product(self.k_fmt()).product(self.colour_fmt())
    }
    /// Exact sum over all light slots.
    pub fn acc_fmt(&self) -> Format {
        self.term_fmt().sum(self.lights)
    }
    /// Index bits of a plain power table.
    pub fn power_index_bits(&self) -> u32 {
        self.power_entries.trailing_zeros()
    }
    /// The power unit as a design of `model::power_unit`.
    pub fn power_unit_design(&self) -> crate::model::power_unit::PowerUnitDesign {
        use crate::model::power_unit::PowerUnitDesign;
        match self.power_unit {
            PowerUnitKind::Table => PowerUnitDesign::Table {
                entries: self.power_entries,
                nearest: self.power_index == PowerIndex::Nearest,
            },
            PowerUnitKind::Lerp => PowerUnitDesign::Lerp { knots: self.power_entries },
            PowerUnitKind::Segmented => PowerUnitDesign::Segmented {
                segments: self.power_segments,
                per_segment: self.power_entries,
                lerp: true,
            },
            PowerUnitKind::Squaring => PowerUnitDesign::Squaring {
                guard: SQUARING_GUARD_BITS,
            },
        }
    }

    /// Why the top's power-table load port is unused, when it is: the table is a ROM
    /// (`power_rom = true`), or there is no table (`power_unit = "squaring"`): exactly the
    /// hardware of one shininess.
    pub fn power_table_unused(&self) -> Option<&'static str> {
        if self.embm() {
            // EMBM's specular light is its map's: there is no power unit.
            return Some("env_map_bits > 0 (EMBM)");
        }
        self.fixed_shininess().map(|f| f.setting)
    }

    /// The exponent the power unit raises to for shininess `n`: n, or for a squaring unit the
    /// power of two its successive squarings reach.
    pub fn power_exponent(&self, n: u32) -> u32 {
        match self.power_unit {
            PowerUnitKind::Squaring => crate::model::power_unit::squarings_exponent(n),
            _ => n,
        }
    }

    /// Whether the hardware serves one shininess only, and which: `power_rom` (the table is a
    /// ROM) or `power_unit = "squaring"` (the exponent is built in).
    pub fn fixed_shininess(&self) -> Option<FixedShininess> {
        if self.power_unit == PowerUnitKind::Squaring {
            Some(FixedShininess {
                field: "power_unit",
                setting: "power_unit = \"squaring\"",
                what: format!("power unit squares for shininess {} (power_unit = \"squaring\")", self.shininess),
                release: "power_unit = \"table\"",
            })
        } else if self.power_rom {
            Some(FixedShininess {
                field: "power_rom",
                setting: "power_rom = true",
                what: format!("power table is a ROM holding shininess {}", self.shininess),
                release: "power_rom = false",
            })
        } else {
            None
        }
    }
    /// [`fixed_shininess`](Self::fixed_shininess), where a set of `target` reads it: the
    /// top's, and `power_unit`'s under squaring (its exponent is built into the unit, where a
    /// ROM unit's table is loaded by its harness as a loadable one's is).
    pub fn fixed_shininess_of(&self, target: &str) -> Option<FixedShininess> {
        let reads = target == "top" || (target == "power_unit" && self.power_unit == PowerUnitKind::Squaring);
        self.fixed_shininess().filter(|_| reads)
    }

    /// Input and output fraction bits of the power unit.
    pub fn power_formats(&self) -> crate::model::power_unit::PowerFormats {
        crate::model::power_unit::PowerFormats {
            f: self.dot_frac_bits,
            p: self.power_frac_bits,
        }
    }
    /// Words of the power unit's loadable memory.
    pub fn power_depth(&self) -> u32 {
        (self.power_table_design().rom_bits(self.power_formats()) / (self.power_frac_bits as u64 + 1)) as u32
    }
    /// The design whose table the power table memory holds: the power unit's own, or for a
    /// squaring unit (which reads none) the plain table of `power_entries`, so the load port,
    /// its init file and every bench's table load keep their shape.
    pub fn power_table_design(&self) -> crate::model::power_unit::PowerUnitDesign {
        match self.power_unit {
            PowerUnitKind::Squaring => crate::model::power_unit::PowerUnitDesign::Table {
                entries: self.power_entries,
                nearest: self.power_index == PowerIndex::Nearest,
            },
            _ => self.power_unit_design(),
        }
    }
    /// Address bits of the power unit's memory (its load port).
    pub fn power_addr_bits(&self) -> u32 {
        (32 - (self.power_depth().max(2) - 1).leading_zeros()).max(1)
    }
    /// The flat, unperturbed bump-normal code (0, 0, largest) after expansion.
    /// The factor between a normal component and its code over 2^(w-1): 1 for `binary`,
    /// 2^(w-1) / (2^(w-1)-1) for `symmetric`. Normals are encoded divided by it and the
    /// per-triangle L and H are sent multiplied by it.
    pub fn normal_scale(&self) -> f64 {
        match self.normal_range {
            NormalRange::Binary => 1.0,
            NormalRange::Symmetric => {
                let half = (1u64 << (self.normal_bits - 1)) as f64;
                half / (half - 1.0)
            }
        }
    }
    #[inline]
    pub fn flat_normal(&self) -> [i64; 3] {
        [0, 0, self.normal_fmt().max_raw()]
    }
    /// Overflow behaviour of every narrowing in the blends: saturate, as the paper's `sat`.
    pub fn overflow(&self) -> Overflow {
        Overflow::Saturate
    }
    /// Whether the top has a triangle-setup port (the bump state per triangle).
    pub fn per_triangle(&self) -> bool {
        self.bump_state == BumpStateAt::Triangle
    }
    /// Bits of a fragment's bank tag in a per-triangle top.
    pub fn bank_bits(&self) -> u32 {
        (32 - (self.triangle_banks - 1).leading_zeros()).max(1)
    }
    /// Clock cycles between accepted fragments.
    pub fn initiation_interval(&self) -> u32 {
        match self.light_mode {
            LightMode::Serial => self.lights,
            LightMode::Parallel => 1,
        }
    }
    /// `name = value` lines of every resolved parameter, for file headers and manifests.
    pub fn resolved_lines(&self) -> Vec<String> {
        let mut v: Vec<String> = self
            .to_toml()
            .lines()
            .filter(|l| !l.trim().is_empty())
            .map(str::to_string)
            .collect();
        let formats: Vec<String> = self.formats().iter().map(|(n, f)| format!("{n} {}", f.name())).collect();
        v.push(format!("# formats: {}", formats.join(" ")));
        v
    }

    /// The derived formats every header states, by name (also the Python module's `formats`).
    pub fn formats(&self) -> [(&'static str, Format); 8] {
        [
            ("normal", self.normal_fmt()),
            ("lh", self.lh_fmt()),
            ("dot", self.dot_fmt()),
            ("power", self.power_fmt()),
            ("k", self.k_fmt()),
            ("colour", self.colour_fmt()),
            ("term", self.term_fmt()),
            ("acc", self.acc_fmt()),
        ]
    }
}

/// A field's error placed at its line of `text`: a value out of range, or at odds with
/// another, is refused where it is written (under its old name, where it was read under one).
fn at_line(text: &str, e: Error) -> Error {
    let Error::Field { file, field, msg, fix } = e else {
        return e;
    };
    let old = RENAMED_FIELDS.iter().find(|(_, new)| *new == field).map(|(old, _)| *old);
    let written_old = old.and_then(|o| Some((crate::toml_line::place(text, o)?, o)));
    let (place, field) = match (crate::toml_line::place(text, &field), written_old) {
        (None, Some((at, old))) => (Some(at), old.to_string()),
        (place, _) => (place, field),
    };
    Error::Field {
        file: place.map_or(file.clone(), |(l, c)| format!("{file}:{l}:{c}")),
        field,
        msg,
        fix,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every one of EMBM's rules refuses its configuration with the field it names and a fix,
    /// and the README states the ones a designer picks by.
    #[test]
    fn every_embm_rule_refuses_naming_its_field() {
        let base = "lights = 4\nlight_mode = \"parallel\"\nbump_state = \"fragment\"\nenv_map_bits = 4\n";
        assert!(PipelineConfig::from_toml("e.toml", base).is_ok());
        let breaks = [
            ("env_map_bits = 1", "env_map_bits"),
            ("lights = 2", "lights"),
            ("light_mode = \"serial\"", "light_mode"),
            ("bump_state = \"triangle\"", "bump_state"),
            ("palette = true", "palette"),
            ("interpolate = \"h\"", "interpolate"),
            ("renormalise = true", "renormalise"),
            ("interpolate_k = true", "interpolate_k"),
            ("renormalise_bump = true", "renormalise_bump"),
            ("frame_transform = true", "frame_transform"),
            ("self_shadow = true", "self_shadow"),
            ("white_lights = true", "white_lights"),
            ("power_rom = true", "power_rom"),
            ("dot_frac_bits = 7", "dot_frac_bits"),
            ("power_frac_bits = 7", "power_frac_bits"),
        ];
        for (line, field) in breaks {
            // A later line of the same key replaces the base's.
            let text = base
                .lines()
                .filter(|l| l.split(" =").next() != line.split(" =").next())
                .chain([line])
                .collect::<Vec<_>>()
                .join("\n");
            let e = PipelineConfig::from_toml("e.toml", &text).expect_err(line).to_string();
            assert!(e.contains(field) && e.contains("fix:"), "{line}: {e}");
        }
        let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
        let flat = readme.split_whitespace().collect::<Vec<_>>().join(" ");
        let (lo, hi) = (2, LIMITS.iter().find(|l| l.0 == "env_map_bits").map(|l| l.2).expect("a limit"));
        let want = format!("`env_map_bits = E` ({lo} to {hi}, with `lights = 4`, `light_mode = \"parallel\"`, `bump_state = \"fragment\"` and `dot_frac_bits` and `power_frac_bits` of at least 8;");
        assert!(flat.contains(&want), "README should say: {want}");
    }

    #[test]
    fn default_round_trips_and_hash_is_stable() {
        let c = PipelineConfig::default();
        let back = PipelineConfig::from_toml("x.toml", &c.to_toml()).unwrap();
        assert_eq!(back, c);
        assert_eq!(back.hash(), c.hash());
        let mut d = c.clone();
        d.lights = 2;
        assert_ne!(d.hash(), c.hash());
    }

    #[test]
    fn retired_names_are_the_renamed_fields() {
        let old: Vec<&str> = RENAMED_FIELDS.iter().map(|r| r.0).collect();
        assert_eq!(old, crate::error::RETIRED_NAMES);
        // A typo is answered with the current name, never an old one.
        match PipelineConfig::from_toml("t.toml", "bump_stat = \"fragment\"\n") {
            Err(Error::Input { msg, fix, .. }) => {
                assert_eq!(msg, "unknown field `bump_stat`");
                assert!(fix.starts_with("did you mean `bump_state`?"), "{fix}");
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn old_field_names_read_as_the_new_ones() {
        let old = PipelineConfig::from_toml("o.toml", "lights = 2\ndot_bits = 10\n  power_bits=9\nk_bits = 7\n").unwrap();
        let new = PipelineConfig::from_toml("n.toml", "lights = 2\ndot_frac_bits = 10\npower_frac_bits = 9\nk_frac_bits = 7\n").unwrap();
        assert_eq!(old, new);
        assert_eq!((new.dot_frac_bits, new.power_frac_bits, new.k_frac_bits), (10, 9, 7));
        // However the key is written: quoted, or the list's every entry as a quoted key.
        let quoted: String = RENAMED_FIELDS
            .iter()
            .zip([10, 9, 7])
            .map(|((o, _), v)| format!("\"{o}\" = {v}\n"))
            .collect();
        assert_eq!(PipelineConfig::from_toml("q.toml", &format!("lights = 2\n{quoted}")).unwrap(), new);
        // Both names at once is one field twice.
        let e = PipelineConfig::from_toml("b.toml", "dot_bits = 10\ndot_frac_bits = 9\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("given twice") && e.starts_with("b.toml:1:1:"), "{e}");
        // Lines are kept, so an error after a renamed key still names its own line.
        let e = PipelineConfig::from_toml("o.toml", "dot_bits = 10\nlights = \"x\"\n")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("o.toml:2:"), "{e}");
    }

    #[test]
    fn errors_name_line_and_field() {
        let e = PipelineConfig::from_toml("cfg.toml", "lights = 4\nnormal_bits = \"eight\"\n")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("cfg.toml:2:"), "{e}");
        let e = PipelineConfig::from_toml("cfg.toml", "lights = 9\n").unwrap_err().to_string();
        assert!(e.contains("`lights`") && e.contains("1..=8"), "{e}");
        let e = PipelineConfig::from_toml("cfg.toml", "power_entries = 100\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("power of two"), "{e}");
        let e = PipelineConfig::from_toml("cfg.toml", "bogus = 1\n").unwrap_err().to_string();
        assert!(e.contains("unknown field"), "{e}");
        // The parser's own message is empty at a missing value and never names the key.
        for text in ["lh_bits = 16\nshininess = ", "shininess =\nlights = 2\n"] {
            let e = PipelineConfig::from_toml("cfg.toml", text).unwrap_err().to_string();
            assert!(e.contains("`shininess` has no value after `=`"), "{text:?}: {e}");
        }
        let e = PipelineConfig::from_toml("cfg.toml", "lights = 2\nlh_bits = \"x\"\n")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("cfg.toml:2:") && e.contains("`lh_bits`: invalid type"), "{e}");
    }

    /// A value no unit reads under the other settings is refused, since it would only change
    /// the hash; the same value where a unit reads it is accepted, and `canonical` (what the
    /// fuzzer draws through) puts it back.
    #[test]
    fn inert_fields_are_refused_and_canonical_clears_them() {
        for (text, field) in [
            ("bump_state = \"fragment\"\ntriangle_banks = 4\n", "triangle_banks"),
            ("power_unit = \"lerp\"\npower_segments = 4\n", "power_segments"),
            ("power_segments = 4\n", "power_segments"),
            ("cube_map_face = 32\n", "cube_map_face"),
        ] {
            let e = PipelineConfig::from_toml("cfg.toml", text).unwrap_err().to_string();
            assert!(
                e.contains(&format!("`{field}`")) && e.contains("does nothing here") && e.contains("leave"),
                "{e}"
            );
            let c: PipelineConfig = toml::from_str(text).unwrap();
            let c = c.canonical();
            assert_eq!(c.inert_field(), None);
            c.validate("canonical").unwrap();
        }
        PipelineConfig::from_toml("cfg.toml", "triangle_banks = 4\n").unwrap();
        PipelineConfig::from_toml("cfg.toml", "power_unit = \"segmented\"\npower_segments = 4\n").unwrap();
        let d = PipelineConfig::default();
        assert_eq!(d.clone().canonical().hash(), d.hash());
    }

    /// A cube map needs normalise units to read it and a face of a power of two from 4 texels;
    /// at 0 it is left out of the TOML, so every older hash is unchanged.
    #[test]
    fn cube_map_face_is_checked_and_keeps_old_hashes() {
        let base = "bump_state = \"fragment\"\ninterpolate = \"hl\"\nrenormalise = true\nlight_mode = \"parallel\"\n";
        let plain = PipelineConfig::from_toml("c.toml", base).unwrap();
        assert!(!plain.to_toml().contains("cube_map_face"));
        let cube = PipelineConfig::from_toml("c.toml", &format!("{base}cube_map_face = 32\n")).unwrap();
        assert_ne!(cube.hash(), plain.hash());
        for bad in [2, 3, 48, 256] {
            let e = PipelineConfig::from_toml("c.toml", &format!("{base}cube_map_face = {bad}\n"))
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("c.toml") && e.contains("cube_map_face") && e.contains("fix"),
                "{bad}: {e}"
            );
        }
    }

    /// A squaring unit has no table to make a ROM of, self-shadowing reads the diffuse path's
    /// B·L, and both leave older hashes alone when off.
    #[test]
    fn squaring_and_self_shadow_are_checked_and_keep_old_hashes() {
        let d = PipelineConfig::default();
        assert!(!d.to_toml().contains("self_shadow"));
        let e = PipelineConfig::from_toml("c.toml", "power_unit = \"squaring\"\npower_rom = true\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("c.toml") && e.contains("power_rom") && e.contains("squaring"), "{e}");
        let e = PipelineConfig::from_toml("c.toml", "self_shadow = true\ndiffuse = false\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("self_shadow") && e.contains("diffuse = true"), "{e}");
        let sq = PipelineConfig::from_toml("c.toml", "power_unit = \"squaring\"\nshininess = 20\nself_shadow = true\n").unwrap();
        assert_ne!(sq.hash(), d.hash());
        // Successive squarings reach the power of two nearest the shininess.
        assert_eq!(sq.power_exponent(20), 16);
        assert_eq!(d.power_exponent(20), 20);
        assert!(sq.fixed_shininess().unwrap().what.contains("squares for shininess 20"));
        // The unused load port keeps a plain table's shape.
        assert_eq!(sq.power_depth(), d.power_depth());
    }
}
