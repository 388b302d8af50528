//! VISA+ (paper §3.2, Ernst et al. 1996): N' = N + A·V per pixel, V the map's offset vector
//! (Δu, Δv) and A the alignment matrix into the tangent plane, lit per pixel. A is held per
//! triangle: its columns are the triangle's T and B in the triangle's plane, so V turns
//! the same way over the whole triangle and adjacent triangles disagree along their shared
//! edge, the discontinuity that grows with the angle between them. The quaternion variant
//! (the paper's [5]) holds a rotation per vertex and interpolates it (normalised linear
//! interpolation of the vertex quaternions, signs aligned to the first), which removes it.
//!
//! The per-triangle variant's bit-accurate path is Harmony's top fed another frame
//! (`triangle_frame`): the rasteriser sends the triangle's plane T and B (A's columns) with
//! the interpolated normal N_i, and `frame_transform` forms T b_x + B b_y + N_i b_z, which is
//! b_z (N_i + A·V) with V = (b_x/b_z, b_y/b_z) the map's offsets; `normalise_b` removes the
//! b_z. It differs from this model where the text leaves the hardware open: N_i is added as
//! interpolated (|N_i| < 1 inside a triangle of a curved mesh, so the offsets weigh a little
//! more) where this model normalises N first; each light's L, H and k are interpolated from
//! the vertices rather than formed at the pixel; C_src is interpolated.
//!
//! The quaternion variant's path (`frame_quaternion`): the rasteriser interpolates the vertex
//! quaternions (signs aligned, not normalised) and sends them on `in_frame`'s first four
//! lanes, and the `quat_frame` unit forms the rotation's T, B, N in the homogeneous form
//! (|q|² times the rotation of q/|q|, ten products, no division) for `frame_transform`;
//! `normalise_b` removes the |q|² with the b_z. Beyond the per-triangle path's differences it
//! adds one: the frame's N is the rotation's (the vertex normals interpolated as rotations)
//! where this model adds the interpolated normal.

use super::common::{bump_normal, corners, finish, offsets, per_pixel_lights, plane_frame, Base};
use super::{Cost, Ctx, Engine, PerFragment};
use crate::raster::{Hit, PixelGeom, Prepared};
use glam::{DMat3, DVec3};

pub const VISA: Engine = Engine {
    name: "visa",
    source: "paper §3.2 (VISA+): N' = N + A·V, A per triangle",
    per_triangle: "the 2×3 alignment matrix A (6 words)",
    per_fragment: "P, N; L and H per light formed at the pixel",
    cost: Cost {
        triangle: 24,
        triangle_per_light: 0,
        fragment: 6,
        fragment_per_light: 0,
    },
    shade: shade_matrix,
    scene_blend: false,
    fixed: Some(PerFragment {
        triangle_frame: true,
        ..super::harmony::FRAME_PATH
    }),
};

pub const VISA_QUATERNION: Engine = Engine {
    name: "visa_quaternion",
    source: "paper §3.2 and [5]: A from vertex quaternions interpolated per pixel",
    per_triangle: "a quaternion per vertex (12 words)",
    per_fragment: "P, N, the quaternion (4 words, renormalised); L and H per light",
    cost: Cost {
        triangle: 30,
        triangle_per_light: 0,
        fragment: 10,
        fragment_per_light: 0,
    },
    shade: shade_quaternion,
    scene_blend: false,
    fixed: Some(PerFragment {
        frame_quaternion: true,
        ..super::harmony::FRAME_PATH
    }),
};

fn perturbed(p: &Prepared, hit: &Hit, g: &PixelGeom, t: DVec3, b: DVec3) -> DVec3 {
    let n = g.n.try_normalize().unwrap_or(DVec3::Z);
    let (du, dv) = offsets(bump_normal(p, hit, g));
    let np = (n + t * du + b * dv).try_normalize().unwrap_or(n);
    let (d, s) = per_pixel_lights(p, hit, g, np, n);
    finish(p, hit, g, Base::PerPixel, d, s)
}

fn shade_matrix(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let p = c.p;
    let (_, t, b) = plane_frame(&corners(p, hit));
    perturbed(p, hit, g, t, b)
}

fn shade_quaternion(c: &Ctx, hit: &Hit, g: &PixelGeom) -> DVec3 {
    let p = c.p;
    let q = crate::raster::tri_state::quaternion_at(&corners(p, hit), hit.bary);
    let r = DMat3::from_quat(q.normalize());
    let (t, b) = (r.x_axis, r.y_axis);
    // A mirrored frame is a rotation of (t, −b, n); the sign comes back here.
    let b = if b.dot(g.b) < 0.0 { -b } else { b };
    perturbed(p, hit, g, t, b)
}
