//! Everything per object that the renderers share: mesh, normal map (f64), stored bump
//! map (codes), texture, per-triangle bump states, and power tables per shininess.

use super::tri_state::{tri_states, TriState};
use crate::bumpmap::{NormalMap, StoredMap};
use crate::config::PipelineConfig;
use crate::error::Result;
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
}

/// An object's f64 normal map: its height field, differentiated, curved for a facet-baked
/// cylinder.
pub fn normal_map(scene: &Scene, o: &Object) -> Result<NormalMap> {
    let hf = o.bump.source.generate(o.bump.size as usize, &scene.base)?;
    let mut normals = NormalMap::from_height(&hf, o.bump.method, o.bump.strength);
    if o.bump.cylinder_sides > 0 {
        normals.curve_for_cylinder(o.bump.cylinder_sides);
    }
    Ok(normals)
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
        crate::limits::check_render(&scene.file, w, h, scene.triangles())?;
        let camera = Camera::new(&scene.camera, w, h);
        let mut objects = Vec::new();
        let mut tables = BTreeMap::new();
        for o in &scene.objects {
            let normals = normal_map(scene, o)?;
            let stored = StoredMap::store(cfg, &normals);
            let mesh = tessellate(o);
            if cfg.frame_build {
                mirrored_refused(scene, objects.len(), &mesh)?;
            }
            let tris = tri_states(scene, cfg, &camera, &mesh)?;
            tables.entry(o.shininess).or_insert_with(|| PowerTable::build(cfg, o.shininess));
            objects.push(ObjectAssets {
                mesh,
                normals,
                stored,
                tris,
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

/// `frame_build` forms B as N × T, a right-handed frame: a vertex whose uv mapping is
/// mirrored (its binormal along −N × T) would have its bumps' v slope turned over, so such a
/// mesh is refused rather than rendered wrong.
fn mirrored_refused(scene: &Scene, obj: usize, mesh: &Mesh) -> Result<()> {
    match mesh.verts.iter().position(|v| v.b.dot(v.n.cross(v.t)) < 0.0) {
        None => Ok(()),
        Some(i) => Err(crate::error::Error::field(
            &scene.file,
            &format!("objects[{obj}]"),
            format!("vertex {i} has a mirrored uv mapping (its binormal is -N x T), and frame_build = true builds right-handed frames (B = N x m)"),
            "map the object's texture without mirroring, or use the interpolated frame (frame_build = false; the harmony engine)",
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
    fn a_mirrored_vertex_is_refused_with_its_object_and_the_fix() {
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
        mirrored_refused(&scene, 0, &mesh).unwrap();
        mesh.verts[2].b = -DVec3::Y;
        let e = mirrored_refused(&scene, 3, &mesh).unwrap_err().to_string();
        assert!(
            e.contains("objects[3]") && e.contains("vertex 2") && e.contains("frame_build = false"),
            "{e}"
        );
    }
}
