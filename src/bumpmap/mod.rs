//! Bump maps: height fields (procedural or PNG), their normals (paper Eq. 2 or the Cg
//! tutorial's difference vectors), range-compressed and palettised storage, and filtering.

pub mod height;
pub mod normals;
pub mod palette;
pub mod sample;
pub mod storage;

pub use height::{HeightField, HeightSource};
pub use normals::{NormalMap, NormalMethod};
pub use sample::Filter;
pub use storage::StoredMap;
