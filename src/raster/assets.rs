//! Everything per object that the renderers share: mesh, normal map (f64), stored bump
//! map (codes), texture, per-triangle bump states, EMBM's maps, and power tables per shininess.

use super::tri_state::{tri_states, TriState};
use crate::bumpmap::{NormalMap, StoredMap};
use crate::config::PipelineConfig;
use crate::error::Result;
use crate::model::env_map::EnvMaps;
use crate::model::PowerTable;
use crate::scene::mesh::{tessellate, Mesh};
use crate::scene::{Camera, Object, Scene, Texture};
use glam::{DVec2, DVec3};
use std::collections::BTreeMap;

pub struct ObjectAssets {
    pub mesh: Mesh,
    pub normals: NormalMap,
    pub stored: StoredMap,
    pub tris: Vec<TriState>,
    /// EMBM's diffuse and specular maps of this object (empty without EMBM).
    pub env: EnvMaps,
    /// The mean of the mesh's vertices: where EMBM's stationary lights are evaluated.
    pub centre: DVec3,
}

/// A scene made ready to render under one configuration at one size.
pub struct Prepared<'a> {
    pub scene: &'a Scene,
    pub cfg: &'a PipelineConfig,
    pub camera: Camera,
    pub objects: Vec<ObjectAssets>,
    pub tables: BTreeMap<u32, PowerTable>,
}

impl<'a> Prepared<'a> {
    pub fn new(scene: &'a Scene, cfg: &'a PipelineConfig, w: u32, h: u32) -> Result<Prepared<'a>> {
        // The least any command keeps a pixel (each checks its own plan first).
        crate::limits::check_render(crate::limits::PixelUse::Render, &scene.file, w, h, scene.triangles())?;
        let camera = Camera::new(&scene.camera, w, h);
        let mut objects = Vec::new();
        let mut tables = BTreeMap::new();
        for (i, o) in scene.objects.iter().enumerate() {
            let normals = scene.normal_map(i)?;
            let stored = StoredMap::store(cfg, &normals);
            let mesh = tessellate(o);
            mirrored_refused(scene, cfg, objects.len(), &mesh)?;
            let tris = tri_states(scene, cfg, &camera, &mesh)?;
            tables.entry(o.shininess).or_insert_with(|| PowerTable::build(cfg, o.shininess));
            let centre = crate::scene::sphere_map::centre(&mesh);
            let env = match cfg.embm() {
                true => super::env_setup::object_maps(cfg, scene, &camera, objects.len(), centre),
                false => EnvMaps::default(),
            };
            objects.push(ObjectAssets {
                mesh,
                normals,
                stored,
                tris,
                env,
                centre,
            });
        }
        Ok(Prepared {
            scene,
            cfg,
            camera,
            objects,
            tables,
        })
    }
}

/// `frame_build` forms B as N × m and `frame_quaternion` sends the rotation of (T, N × T, N):
/// both right-handed, so a vertex whose uv mapping is mirrored (its binormal along −N × T)
/// would have its bumps' v slope turned over. Such a mesh is refused rather than rendered
/// wrong; the interpolated frame (Harmony) and the per-triangle frame carry B as it is.
fn mirrored_refused(scene: &Scene, cfg: &PipelineConfig, obj: usize, mesh: &Mesh) -> Result<()> {
    let field = match (cfg.frame_build, cfg.frame_quaternion) {
        (true, _) => "frame_build = true builds right-handed frames (B = N x m)",
        (_, true) => "frame_quaternion = true sends each vertex frame as a rotation (B = N x T)",
        _ => return Ok(()),
    };
    match mesh.verts.iter().position(|v| v.b.dot(v.n.cross(v.t)) < 0.0) {
        None => Ok(()),
        Some(i) => Err(crate::error::Error::field(
            &scene.file,
            &format!("objects[{obj}]"),
            format!("vertex {i} has a mirrored uv mapping (its binormal is -N x T), and {field}"),
            "map the object's texture without mirroring, or use a frame that keeps B as it is (frame_transform with the interpolated frame: the harmony engine; or triangle_frame = true)",
        )),
    }
}

/// Texture colour at `uv` in [0,1]³.
pub fn texture_at(o: &Object, uv: DVec2) -> DVec3 {
    match &o.texture {
        Texture::Constant { colour } => DVec3::from_array(*colour),
        Texture::Checker { cells, a, b } => {
            let c = *cells as f64;
            let k = ((uv.x * c).floor() as i64 + (uv.y * c).floor() as i64).rem_euclid(2);
            DVec3::from_array(if k == 0 { *a } else { *b })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::mesh::Vertex;

    /// Scene files cannot mirror a mapping (uv scales are positive and the binormal follows
    /// ∂P/∂v), so a mesh is built here: one vertex with B = −N × T is refused, by index.
    #[test]
    fn a_mirrored_vertex_is_refused_by_the_right_handed_frame_sources_with_its_object_and_the_fix() {
        let scene = Scene::load("cg_wall_front").unwrap();
        let v = |b: DVec3| Vertex {
            p: DVec3::ZERO,
            n: DVec3::Z,
            t: DVec3::X,
            b,
            uv: DVec2::ZERO,
        };
        let mut mesh = Mesh {
            verts: vec![v(DVec3::Y), v(DVec3::Y), v(DVec3::Y)],
            tris: vec![[0, 1, 2]],
        };
        let build = PipelineConfig {
            frame_build: true,
            ..Default::default()
        };
        let quaternion = PipelineConfig {
            frame_quaternion: true,
            ..Default::default()
        };
        let harmony = PipelineConfig {
            frame_transform: true,
            ..Default::default()
        };
        for cfg in [&build, &quaternion, &harmony] {
            mirrored_refused(&scene, cfg, 0, &mesh).unwrap();
        }
        mesh.verts[2].b = -DVec3::Y;
        for (cfg, field) in [(&build, "frame_build = true"), (&quaternion, "frame_quaternion = true")] {
            let e = mirrored_refused(&scene, cfg, 3, &mesh).unwrap_err().to_string();
            assert!(
                e.contains("objects[3]") && e.contains("vertex 2") && e.contains(field) && e.contains("harmony"),
                "{e}"
            );
        }
        // The interpolated frame carries B as it is: nothing to refuse.
        mirrored_refused(&scene, &harmony, 3, &mesh).unwrap();
    }
}
