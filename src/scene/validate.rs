//! Scene validation: every number finite and in range, with the field's path and line.

use super::{LightKind, Scene, Shape, Texture};
use crate::error::{Error, Result};
use crate::limits::{MAX_BUMP_SIDE, MAX_CYLINDER_SIDES, MAX_IMAGE_SIDE, MAX_SEGMENTS, MAX_SHININESS, MAX_TRIANGLES};

/// A number as a person reads it: 1e300 as `1e300`, not as 301 digits.
pub(crate) fn short(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e7).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

struct Checker<'a> {
    s: &'a Scene,
    text: &'a str,
}

impl Checker<'_> {
    fn fail(&self, path: &str, msg: String, fix: &str) -> Error {
        let at = crate::toml_line::suffix(self.text, path);
        Error::field(&format!("{}{at}", self.s.file), path, msg, fix)
    }

    fn num(&self, path: &str, v: f64, lo: f64, hi: f64) -> Result<()> {
        if !v.is_finite() {
            return Err(self.fail(path, format!("{v} is not a finite number"), "give a finite number"));
        }
        if v < lo || v > hi {
            return Err(self.fail(
                path,
                format!("{} is out of range", short(v)),
                &format!("use a value in [{lo}, {hi}]"),
            ));
        }
        Ok(())
    }

    fn vec3(&self, path: &str, v: [f64; 3], lo: f64, hi: f64) -> Result<()> {
        for (i, c) in v.iter().enumerate() {
            self.num(&format!("{path}[{i}]"), *c, lo, hi)?;
        }
        Ok(())
    }

    fn dir(&self, path: &str, v: [f64; 3]) -> Result<()> {
        self.vec3(path, v, -1e6, 1e6)?;
        if v.iter().map(|c| c * c).sum::<f64>() < 1e-24 {
            return Err(self.fail(
                path,
                format!("{v:?} is shorter than 1e-12, too short to give a direction"),
                "give a vector of length 1e-12 or more (its length does not matter, only its direction)",
            ));
        }
        Ok(())
    }
}

/// An array in the file longer than the field it fills (serde reads a fixed-size array's
/// first values and drops the rest, so `size = [32, 24, 3]` would render 32×24 silently):
/// the scene as read, serialised again, is walked beside the file's own values.
fn no_extra_values(s: &Scene, text: &str) -> Result<()> {
    fn walk(given: &toml::Value, read: &toml::Value, path: &str) -> Option<(String, usize, usize)> {
        match (given, read) {
            (toml::Value::Table(g), toml::Value::Table(r)) => g.iter().find_map(|(k, gv)| {
                let p = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                r.get(k).and_then(|rv| walk(gv, rv, &p))
            }),
            (toml::Value::Array(g), toml::Value::Array(r)) => {
                if g.len() > r.len() {
                    return Some((path.to_string(), g.len(), r.len()));
                }
                g.iter()
                    .zip(r)
                    .enumerate()
                    .find_map(|(i, (gv, rv))| walk(gv, rv, &format!("{path}[{i}]")))
            }
            _ => None,
        }
    }
    let (Ok(given), Ok(read)) = (toml::from_str::<toml::Value>(text), toml::Value::try_from(s)) else {
        return Ok(());
    };
    match walk(&given, &read, "") {
        None => Ok(()),
        Some((path, got, takes)) => {
            let c = Checker { s, text };
            Err(c.fail(
                &path,
                format!("{got} values where the field takes {takes}"),
                &format!("give exactly {takes} values"),
            ))
        }
    }
}

/// Each light's fields as its kind reads them: a point or spot light without `position`
/// (it would sit at the origin, default values, unannounced), a directional or spot light
/// without `direction`, and a field the kind never reads (`direction` on a point light,
/// `cutoff_deg` on a directional one) are named rather than passed over.
fn light_fields(s: &Scene, text: &str) -> Result<()> {
    let Ok(given) = toml::from_str::<toml::Table>(text) else {
        return Ok(());
    };
    let Some(lights) = given.get("lights").and_then(|l| l.as_array()) else {
        return Ok(());
    };
    // Each kind: its name, the fields it needs, and the optional ones it reads; a field of
    // another kind's is unused on it.
    const READS: [(LightKind, &str, &[&str], &[&str]); 3] = [
        (LightKind::Directional, "directional", &["direction"], &[]),
        (LightKind::Point, "point", &["position"], &[]),
        (LightKind::Spot, "spot", &["position", "direction"], &["cutoff_deg", "exponent"]),
    ];
    let reads = |r: &(LightKind, &str, &[&str], &[&str]), k: &str| r.2.contains(&k) || r.3.contains(&k);
    let c = Checker { s, text };
    for (i, (l, read)) in lights.iter().zip(&s.lights).enumerate() {
        let Some(l) = l.as_table() else { continue };
        let this = READS.iter().find(|r| r.0 == read.kind).expect("every kind is listed");
        let (kind, needs) = (this.1, this.2);
        let unused = ["position", "direction", "cutoff_deg", "exponent"]
            .into_iter()
            .find(|k| l.contains_key(*k) && !reads(this, k));
        if let Some(k) = needs.iter().find(|k| !l.contains_key(**k)) {
            return Err(c.fail(
                &format!("lights[{i}]"),
                format!("a {kind} light needs `{k}`"),
                &format!("give {k} = [x, y, z]"),
            ));
        }
        if let Some(k) = unused {
            let readers: Vec<&str> = READS.iter().filter(|r| reads(r, k)).map(|r| r.1).collect();
            return Err(c.fail(
                &format!("lights[{i}].{k}"),
                format!("`{k}` does nothing on a {kind} light"),
                &format!(
                    "remove it, or set the kind that reads it (`{k}` is read by {} lights)",
                    readers.join(" and ")
                ),
            ));
        }
    }
    Ok(())
}

pub fn validate(s: &Scene, text: &str) -> Result<()> {
    no_extra_values(s, text)?;
    light_fields(s, text)?;
    let c = Checker { s, text };
    let bump = s.bump_lights().count();
    let max_lights = crate::config::limit("lights").1;
    if bump as u32 > max_lights {
        return Err(c.fail(
            "lights",
            format!("{bump} lights act on the bump map; the pipeline has at most {max_lights} light slots"),
            &format!("set bump = false on all but {max_lights} of them (they then light the Gouraud colour only)"),
        ));
    }
    // The name becomes part of every output file's name.
    if !crate::names::is_safe(&s.name) {
        let at = crate::toml_line::suffix(text, "name");
        return crate::names::check(&format!("{}{at}", s.file), "name", &s.name);
    }
    for (i, v) in s.size.iter().enumerate() {
        if *v == 0 || *v > MAX_IMAGE_SIDE {
            return Err(c.fail(
                &format!("size[{i}]"),
                format!("{v} is out of range"),
                &format!("use 1..={MAX_IMAGE_SIDE} pixels (MAX_IMAGE_SIDE)"),
            ));
        }
    }
    let cam = &s.camera;
    c.vec3("camera.eye", cam.eye, -1e6, 1e6)?;
    c.vec3("camera.target", cam.target, -1e6, 1e6)?;
    c.dir("camera.up", cam.up)?;
    let view: Vec<f64> = (0..3).map(|i| cam.target[i] - cam.eye[i]).collect();
    if view.iter().map(|x| x * x).sum::<f64>() < 1e-18 {
        return Err(c.fail("camera.eye", "eye and target coincide".into(), "move the eye away from the target"));
    }
    // Along the view, `up` names no direction on the screen: the image would come out turned
    // by whichever axis a fallback picked.
    let (f, u) = (
        glam::DVec3::from_slice(&view).normalize(),
        glam::DVec3::from_array(cam.up).normalize(),
    );
    if f.cross(u).length_squared() < 1e-12 {
        return Err(c.fail(
            "camera.up",
            format!("{:?} is parallel to the view (target - eye = {:?})", cam.up, view),
            "give an up that is not along the view, the screen's upward direction (for example [0, 1, 0] for a camera looking along z)",
        ));
    }
    c.num("camera.height", cam.height, 1e-6, 1e6)?;
    c.vec3("camera.background", cam.background, 0.0, 1.0)?;
    c.vec3("ambient", s.ambient, 0.0, 1.0)?;
    for (i, l) in s.lights.iter().enumerate() {
        let p = format!("lights[{i}]");
        c.vec3(&format!("{p}.colour"), l.colour, 0.0, 1.0)?;
        c.num(&format!("{p}.k"), l.k, 0.0, 1.0)?;
        match l.kind {
            LightKind::Directional => c.dir(&format!("{p}.direction"), l.direction)?,
            LightKind::Point => c.vec3(&format!("{p}.position"), l.position, -1e6, 1e6)?,
            LightKind::Spot => {
                c.vec3(&format!("{p}.position"), l.position, -1e6, 1e6)?;
                c.dir(&format!("{p}.direction"), l.direction)?;
                c.num(&format!("{p}.cutoff_deg"), l.cutoff_deg, 0.0, 90.0)?;
                c.num(&format!("{p}.exponent"), l.exponent, 0.0, 1024.0)?;
            }
        }
    }
    if s.objects.is_empty() {
        return Err(c.fail("objects", "the scene has no objects".into(), "add an [[objects]] table"));
    }
    if !s.objects.iter().any(|o| o.diffuse || o.specular) {
        // The derived configuration would have no blend unit to light with.
        return Err(c.fail(
            "objects[0].diffuse",
            "every object has diffuse = false and specular = false: nothing would be lit, and a pipeline needs one blend".into(),
            "set diffuse = true or specular = true on an object",
        ));
    }
    for (i, o) in s.objects.iter().enumerate() {
        let p = format!("objects[{i}]");
        let pos = |k: &str, v: f64| c.num(&format!("{p}.shape.{k}"), v, 1e-6, 1e6);
        match &o.shape {
            Shape::Plane { size } => {
                pos("size[0]", size[0])?;
                pos("size[1]", size[1])?;
            }
            Shape::Sphere { radius } => pos("radius", *radius)?,
            Shape::Cylinder { radius, height, sides } => {
                pos("radius", *radius)?;
                pos("height", *height)?;
                if *sides == 1 || *sides == 2 || *sides > MAX_CYLINDER_SIDES {
                    return Err(c.fail(
                        &format!("{p}.shape.sides"),
                        format!("{sides} sides"),
                        &format!("use 0 (smooth) or 3..={MAX_CYLINDER_SIDES} (MAX_CYLINDER_SIDES)"),
                    ));
                }
            }
            Shape::Torus { major, minor } => {
                pos("major", *major)?;
                pos("minor", *minor)?;
            }
            Shape::Teapot {} => {}
        }
        let least = super::mesh::min_segments(&o.shape);
        for (k, v) in o.segments.iter().enumerate() {
            if *v < least[k] || *v > MAX_SEGMENTS {
                let why = if *v > MAX_SEGMENTS {
                    ": more than MAX_SEGMENTS per direction"
                } else if least[k] > 1 {
                    ": fewer tessellate the shape into slivers of no area"
                } else {
                    ""
                };
                return Err(c.fail(
                    &format!("{p}.segments[{k}]"),
                    format!("{v} is out of range for a {}{why}", o.shape.kind()),
                    &format!("use {}..={MAX_SEGMENTS} (MAX_SEGMENTS)", least[k]),
                ));
            }
        }
        c.vec3(&format!("{p}.translate"), o.translate, -1e6, 1e6)?;
        c.vec3(&format!("{p}.rotate_deg"), o.rotate_deg, -3600.0, 3600.0)?;
        c.num(&format!("{p}.scale"), o.scale, 1e-6, 1e6)?;
        c.num(&format!("{p}.uv_scale[0]"), o.uv_scale[0], 1e-6, 1e6)?;
        c.num(&format!("{p}.uv_scale[1]"), o.uv_scale[1], 1e-6, 1e6)?;
        // A prism's facets each take the map's u from 0 to 1 (its baked normals span one
        // facet), so a u scale would be dropped without a word.
        if matches!(o.shape, Shape::Cylinder { sides: 1.., .. }) && o.uv_scale[0] != 1.0 {
            return Err(c.fail(
                &format!("{p}.uv_scale[0]"),
                format!(
                    "{} on a prism (a cylinder with sides > 0), whose every facet spans u from 0 to 1 of the map",
                    o.uv_scale[0]
                ),
                "drop uv_scale[0] (1) for a prism, or set sides = 0 for a smooth cylinder that repeats the map around it",
            ));
        }
        // Baked cylinder normals curve each facet through 360°/cylinder_sides: on a prism of
        // another count the facets' shading no longer meets at their edges.
        if let Shape::Cylinder { sides: sides @ 1.., .. } = o.shape {
            if o.bump.cylinder_sides > 0 && o.bump.cylinder_sides != sides {
                return Err(c.fail(
                    &format!("{p}.bump.cylinder_sides"),
                    format!(
                        "{} on a prism of {sides} sides: the map's normals would curve each facet through 360°/{}, not 360°/{sides}",
                        o.bump.cylinder_sides, o.bump.cylinder_sides
                    ),
                    &format!("set cylinder_sides = {sides} (the shape's sides), or 0 for flat facets"),
                ));
            }
        }
        if o.shininess > MAX_SHININESS {
            return Err(c.fail(
                &format!("{p}.shininess"),
                format!("{} is out of range", o.shininess),
                &format!("use 0..={MAX_SHININESS} (MAX_SHININESS)"),
            ));
        }
        match &o.texture {
            Texture::Constant { colour } => c.vec3(&format!("{p}.texture.colour"), *colour, 0.0, 1.0)?,
            Texture::Checker { cells, a: ca, b: cb } => {
                if *cells == 0 {
                    return Err(c.fail(&format!("{p}.texture.cells"), "0 cells".into(), "use 1 or more"));
                }
                c.vec3(&format!("{p}.texture.a"), *ca, 0.0, 1.0)?;
                c.vec3(&format!("{p}.texture.b"), *cb, 0.0, 1.0)?;
            }
        }
        let b = &o.bump;
        if b.size < 2 || b.size > MAX_BUMP_SIDE {
            return Err(c.fail(
                &format!("{p}.bump.size"),
                format!("{} is out of range", b.size),
                &format!("use 2..={MAX_BUMP_SIDE} texels (MAX_BUMP_SIDE)"),
            ));
        }
        c.num(&format!("{p}.bump.strength"), b.strength, 0.0, 1e4)?;
        if b.cylinder_sides == 1 || b.cylinder_sides == 2 || b.cylinder_sides > MAX_CYLINDER_SIDES {
            return Err(c.fail(
                &format!("{p}.bump.cylinder_sides"),
                format!("{} sides is out of range", b.cylinder_sides),
                &format!("use 0 (none) or 3..={MAX_CYLINDER_SIDES} (MAX_CYLINDER_SIDES)"),
            ));
        }
        use crate::bumpmap::HeightSource as H;
        match &b.source {
            H::Bricks { rows, cols, mortar } => {
                if *rows == 0 || *cols == 0 {
                    return Err(c.fail(&format!("{p}.bump.source"), "zero rows or columns".into(), "use 1 or more"));
                }
                c.num(&format!("{p}.bump.source.mortar"), *mortar, 1e-3, 0.45)?;
            }
            H::SphereCaps { cells, radius } => {
                if *cells == 0 {
                    return Err(c.fail(&format!("{p}.bump.source.cells"), "0 cells".into(), "use 1 or more"));
                }
                c.num(&format!("{p}.bump.source.radius"), *radius, 1e-3, 0.5)?;
            }
            H::MexicanHat { cells, sigma } => {
                if *cells == 0 {
                    return Err(c.fail(&format!("{p}.bump.source.cells"), "0 cells".into(), "use 1 or more"));
                }
                c.num(&format!("{p}.bump.source.sigma"), *sigma, 1e-3, 1.0)?;
            }
            H::Png { path } => {
                // The image is decoded later (its size checked from its header); that it is a
                // file there is checked here, so every command refuses the scene alike, at its line.
                // `join` keeps an absolute path as it is.
                let full = s.base.join(path);
                let at = format!("{p}.bump.source.path");
                if !full.is_file() {
                    // Why, as the system says it: a loop of links or a folder is not "missing".
                    let what = match std::fs::metadata(&full) {
                        Ok(_) => "is not a file".to_string(),
                        Err(e) if e.kind() == std::io::ErrorKind::NotFound => "is not there".to_string(),
                        Err(e) => format!("cannot be read ({e})"),
                    };
                    return Err(c.fail(
                        &at,
                        format!("{} {what}", full.display()),
                        "give the path of a greyscale or RGB PNG, relative to the scene file's folder",
                    ));
                }
            }
            H::Flat {} => {}
        }
    }
    let tris: u64 = s.objects.iter().map(super::mesh::triangle_count).sum();
    if tris > MAX_TRIANGLES {
        // The object that makes the most of them, with its own shape's rule.
        let (i, o, made) = s
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| (i, o, super::mesh::triangle_count(o)))
            .max_by_key(|t| t.2)
            .expect("a scene with triangles has an object");
        let rule = match &o.shape {
            Shape::Teapot {} => "64 triangles per segment pair: two per quad of each of its 32 patches".to_string(),
            Shape::Cylinder { sides, .. } if *sides > 0 => format!("2 x sides ({sides}) x segments[1] triangles"),
            _ => "2 triangles per segment pair".to_string(),
        };
        return Err(c.fail(
            &format!("objects[{i}].segments"),
            format!(
                "the scene tessellates into {tris} triangles, more than MAX_TRIANGLES = {MAX_TRIANGLES}; objects[{i}] (a {}) makes {made} of them ({rule})",
                o.shape.kind()
            ),
            &format!("lower objects[{i}].segments, now {:?}", o.segments),
        ));
    }
    Ok(())
}
