//! A scene's fingerprint: everything that changes what it renders (every parsed field and the
//! bytes of every file it reads), for cache keys. Two scenes with equal fingerprints render
//! the same image under the same configuration.

use super::Scene;
use crate::bumpmap::HeightSource;
use crate::error::Result;

impl Scene {
    pub fn fingerprint(&self) -> Result<String> {
        let mut k = crate::cache::Key::new("scene");
        k.add(serde_json::to_string(self).expect("a scene serialises").as_bytes());
        for o in &self.objects {
            if let HeightSource::Png { path } = &o.bump.source {
                let p = if path.is_absolute() { path.clone() } else { self.base.join(path) };
                k.add_file(&p)?;
            }
        }
        Ok(k.finish())
    }
}
