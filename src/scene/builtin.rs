//! The built-in scenes: the files in `scenes/`, compiled in so the binary needs no data folder.

/// (name, TOML text) of every built-in scene; the first is the default.
pub const ALL: &[(&str, &str)] = &[
    ("torus_caps", include_str!("../../scenes/torus_caps.toml")),
    ("sphere_bricks_spots", include_str!("../../scenes/sphere_bricks_spots.toml")),
    ("flat_artifact", include_str!("../../scenes/flat_artifact.toml")),
    ("flat_artifact_fixed", include_str!("../../scenes/flat_artifact_fixed.toml")),
    ("cylinder_smooth", include_str!("../../scenes/cylinder_smooth.toml")),
    ("teapot_hat", include_str!("../../scenes/teapot_hat.toml")),
    ("blend_split", include_str!("../../scenes/blend_split.toml")),
    ("blend_texture_last", include_str!("../../scenes/blend_texture_last.toml")),
    ("cg_wall_lower_left", include_str!("../../scenes/cg_wall_lower_left.toml")),
    ("cg_wall_front", include_str!("../../scenes/cg_wall_front.toml")),
    ("cg_wall_upper_right", include_str!("../../scenes/cg_wall_upper_right.toml")),
    ("cg_wall_floor", include_str!("../../scenes/cg_wall_floor.toml")),
];

/// The scene the README's main command renders.
pub const DEFAULT: &str = "torus_caps";

/// TOML text of a built-in scene.
pub fn get(name: &str) -> Option<&'static str> {
    ALL.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The names among `names` that are scene files rather than built-in scenes.
pub fn files_among<'a>(names: impl IntoIterator<Item = &'a String>) -> Vec<String> {
    names.into_iter().filter(|n| get(n).is_none()).cloned().collect()
}
