//! Geometry at the edges: degenerate frames and triangles, lights on the horizon, parallel to
//! the view and behind it. No NaN may reach any image; each fallback is documented in
//! ARCHITECTURE.md ("Degenerate geometry").

use gbump::raster::fragment::{fragments, pixel_geom};
use gbump::raster::rasterise::rasterise;
use gbump::raster::tri_state::tri_states;
use gbump::raster::Prepared;
use gbump::reference::{gouraud_f64, perpixel};
use gbump::render::{golden_image, render};
use gbump::scene::mesh::{frame, Mesh, Vertex};
use gbump::scene::Scene;
use glam::{DVec2, DVec3};

fn orthonormal(n: DVec3, t: DVec3, b: DVec3) {
    for v in [n, t, b] {
        assert!(v.is_finite() && (v.length() - 1.0).abs() < 1e-9, "{n} {t} {b}");
    }
    assert!(n.dot(t).abs() < 1e-9 && n.dot(b).abs() < 1e-9 && t.dot(b).abs() < 1e-9);
}

#[test]
fn frames_survive_every_degenerate_input() {
    let z = DVec3::ZERO;
    for (n, pu, pv) in [
        (z, z, z),                       // nothing at all: falls back to +Z and any tangent
        (DVec3::Z, z, DVec3::Y),         // zero ∂P/∂u (a pole): tangent from ∂P/∂v × N
        (DVec3::Z, DVec3::Z, z),         // tangent parallel to the normal
        (z, DVec3::X, DVec3::Y),         // zero normal: from ∂P/∂u × ∂P/∂v
        (DVec3::Z, DVec3::X, -DVec3::Y), // mirrored uv: the binormal follows ∂P/∂v
        (DVec3::new(1e-300, 0.0, 0.0), DVec3::new(0.0, 1e-300, 0.0), z),
    ] {
        let (a, b, c) = frame(n, pu, pv);
        orthonormal(a, b, c);
    }
    let (_, _, b) = frame(DVec3::Z, DVec3::X, -DVec3::Y);
    assert!(b.dot(-DVec3::Y) > 0.99, "mirrored texture space keeps its handedness");
}

fn scene_with(light: &str) -> Scene {
    let base = gbump::scene::builtin::get("cg_wall_front").unwrap();
    let start = base.find("[[lights]]").unwrap();
    let end = base.find("[[objects]]").unwrap();
    let text = format!("{}{light}\n{}", &base[..start], &base[end..]);
    Scene::from_toml("edge.toml", &text, std::path::Path::new("scenes")).unwrap()
}

fn assert_images_finite(s: &Scene) {
    let cfg = s.derive_config().unwrap();
    let img = render(s, &cfg, 64, 32, false).unwrap();
    assert!(
        img.gouraud
            .iter()
            .chain(&img.reference)
            .flatten()
            .all(|x| x.is_finite() && (0.0..=1.0).contains(x)),
        "{}",
        s.name
    );
    assert!(img.golden.iter().flatten().all(|c| *c <= img.colour_max));
    assert!(img.covered.iter().filter(|c| **c).count() > 1000);
}

#[test]
fn lights_parallel_to_the_view_on_the_horizon_and_behind_render_without_nan() {
    for light in [
        // Light along the view: L = V, so H = L.
        "[[lights]]\nkind = \"directional\"\ndirection = [0.0, 0.0, 1.0]\ncolour = [1.0, 1.0, 1.0]\n",
        // Light exactly on the horizon of the wall: B·L = 0 for the flat normal.
        "[[lights]]\nkind = \"directional\"\ndirection = [1.0, 0.0, 0.0]\ncolour = [1.0, 1.0, 1.0]\n",
        // Light exactly opposite the viewer: L + V = 0, the half vector falls back to L.
        "[[lights]]\nkind = \"directional\"\ndirection = [0.0, 0.0, -1.0]\ncolour = [1.0, 1.0, 1.0]\n",
        // A point light lying in the wall itself, at a vertex: its direction falls back to N there.
        "[[lights]]\nkind = \"point\"\nposition = [0.0, 0.0, 0.0]\ncolour = [1.0, 1.0, 1.0]\n",
        // A spotlight aimed away from everything, carried by the Gouraud colour.
        "[[lights]]\nkind = \"spot\"\nposition = [0.0, 0.0, 1.0]\ndirection = [0.0, 0.0, 1.0]\ncolour = [1.0, 0.0, 0.0]\nbump = false\n[[lights]]\nkind = \"directional\"\ndirection = [0.0, 0.3, 1.0]\ncolour = [0.5, 0.5, 0.5]\n",
    ] {
        assert_images_finite(&scene_with(light));
    }
    let horizon = scene_with("[[lights]]\nkind = \"directional\"\ndirection = [1.0, 0.0, 0.0]\ncolour = [1.0, 1.0, 1.0]\n");
    let cfg = horizon.derive_config().unwrap();
    let p = Prepared::new(&horizon, &cfg, 8, 8).unwrap();
    assert!(
        p.objects[0].tris.iter().all(|t| t.fixed.lights[0].l[2] == 0),
        "a horizon light has no normal component"
    );
}

#[test]
fn zero_area_coincident_and_mirrored_triangles_leave_no_nan() {
    let s = Scene::load("cg_wall_front").unwrap();
    let cfg = s.derive_config().unwrap();
    let mut p = Prepared::new(&s, &cfg, 48, 24).unwrap();
    let v = |x: f64, y: f64, u: f64, n: DVec3| Vertex {
        p: DVec3::new(x, y, 0.0),
        n,
        t: DVec3::X,
        b: DVec3::Y,
        uv: DVec2::new(u, y),
    };
    let mesh_verts = vec![
        v(-1.0, -0.8, 0.0, DVec3::Z),
        v(1.0, -0.8, 1.0, DVec3::Z),
        v(0.0, 0.8, 0.5, DVec3::Z), // ordinary
        v(0.0, 0.0, 0.0, DVec3::Z),
        v(0.0, 0.0, 0.0, DVec3::Z),
        v(0.0, 0.0, 0.0, DVec3::Z), // coincident
        v(-1.0, 0.0, 0.0, DVec3::ZERO),
        v(0.0, 0.0, 0.5, DVec3::ZERO),
        v(1.0, 0.0, 1.0, DVec3::ZERO), // collinear, zero normals
        v(-1.9, -0.9, 1.0, DVec3::Z),
        v(-1.2, -0.9, 0.0, DVec3::Z),
        v(-1.5, 0.9, 0.5, DVec3::Z), // mirrored in u
    ];
    let mesh = Mesh {
        verts: mesh_verts,
        tris: vec![[0, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11]],
    };
    let tris = tri_states(&s, &cfg, &p.camera, &mesh).unwrap();
    for t in &tris {
        assert!(t.l[0].is_finite() && t.h[0].is_finite());
    }
    p.objects[0].mesh = mesh;
    p.objects[0].tris = tris;
    let gb = rasterise(&p).unwrap();
    let frags = fragments(&p, &gb);
    assert!(!frags.is_empty());
    assert!(frags.iter().all(|f| f.tri == 0 || f.tri == 3), "degenerate triangles cover nothing");
    let img = golden_image(&p, &frags, &indicatif::ProgressBar::hidden());
    assert!(img.iter().flatten().all(|c| *c <= cfg.colour_max()));
    for hit in gb.hits.iter().flatten() {
        let g = pixel_geom(&p, hit);
        assert!(gouraud_f64::shade(&p, hit, &g).is_finite() && perpixel::shade(&p, hit, &g).is_finite());
    }
}

/// A short `up` is a direction like any other: the camera's fallback for an up along the
/// view (which validation refuses) tests the same thing, relative to up's length. A wall
/// seen with up = 1e-7·Y is the wall seen with up = Y, not one turned by a fallback axis.
#[test]
fn a_short_up_turns_the_camera_as_a_unit_one_does() {
    let base = gbump::scene::builtin::get("cg_wall_front").unwrap();
    assert!(base.contains("up = [0.0, 1.0, 0.0]"));
    let image = |up: &str| {
        let text = base.replace("up = [0.0, 1.0, 0.0]", up);
        let s = Scene::from_toml("up.toml", &text, std::path::Path::new("scenes")).unwrap();
        let cfg = s.derive_config().unwrap();
        render(&s, &cfg, 64, 32, false).unwrap().golden
    };
    let unit = image("up = [0.0, 1.0, 0.0]");
    for up in ["up = [0.0, 1e-7, 0.0]", "up = [0.0, 3.0, 0.0]", "up = [0.0, 1e-7, 1e-6]"] {
        let other = image(up);
        let differ = unit.iter().zip(&other).filter(|(a, b)| a != b).count();
        assert!(
            differ <= unit.len() / 100,
            "{up}: {differ} of {} pixels differ from up = Y",
            unit.len()
        );
    }
}
