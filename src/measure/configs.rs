//! The configurations the report measures besides the default, inline so a report runs from
//! any folder (a test keeps each equal to its file under `tests/configs`).

/// `tests/configs/one_light_parallel.toml`, the second configuration of the FPGA section
/// (inline, so the report runs from any folder; a test keeps the two equal).
pub const ONE_LIGHT_PARALLEL: &str = "lights = 1\nlight_mode = \"parallel\"\n";

/// `tests/configs/paper_sample_one_light.toml`: one light in parallel with k_i an on/off
/// enable (`k_frac_bits = 0`), the paper's sample implementation (inline, as above).
pub const PAPER_SAMPLE_ONE_LIGHT: &str = "lights = 1\nlight_mode = \"parallel\"\nk_frac_bits = 0\n";

#[cfg(test)]
mod tests {
    #[test]
    fn the_inline_one_light_config_is_the_test_config() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/configs/one_light_parallel.toml");
        let file = crate::config::PipelineConfig::from_toml(path, &std::fs::read_to_string(path).unwrap()).unwrap();
        let inline = crate::config::PipelineConfig::from_toml("inline", super::ONE_LIGHT_PARALLEL).unwrap();
        assert_eq!(file.hash(), inline.hash());
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/configs/paper_sample_one_light.toml");
        let file = crate::config::PipelineConfig::from_toml(path, &std::fs::read_to_string(path).unwrap()).unwrap();
        let inline = crate::config::PipelineConfig::from_toml("inline", super::PAPER_SAMPLE_ONE_LIGHT).unwrap();
        assert_eq!(file.hash(), inline.hash());
    }
}
