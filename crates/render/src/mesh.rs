//! Triangle meshes from Wavefront OBJ text, read from a file or from bytes the program holds
//! (the panel of [`crate::panel`] is embedded): every object, triangulated, smooth-shaded
//! where the file gives normals.

use crate::error::{RenderError, Result};
use crate::geometry::Shape;
use glam::DVec3;
use std::path::Path;

/// The triangles of every object of the Wavefront OBJ file `path`.
pub fn read_obj(path: &Path) -> Result<Vec<Shape>> {
    let bytes = std::fs::read(path).map_err(|error| RenderError::Io {
        path: path.to_path_buf(),
        error,
    })?;
    parse_obj(&bytes, path)
}

/// The triangles of every object of the Wavefront OBJ text `bytes` (its materials ignored);
/// `path` names it in errors.
pub fn parse_obj(bytes: &[u8], path: &Path) -> Result<Vec<Shape>> {
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut &bytes[..], &opts, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| RenderError::scene(path, format!("cannot read the OBJ mesh: {e}")))?;
    let mut tris = Vec::new();
    for m in &models {
        let mesh = &m.mesh;
        let n_vert = mesh.positions.len() / 3;
        let vertex = |i: u32| -> Result<DVec3> {
            let i = i as usize;
            if i >= n_vert {
                return Err(RenderError::scene(
                    path,
                    format!(
                        "object `{}`: vertex index {i} out of range ({n_vert} vertices)",
                        m.name
                    ),
                ));
            }
            Ok(DVec3::new(
                f64::from(mesh.positions[3 * i]),
                f64::from(mesh.positions[3 * i + 1]),
                f64::from(mesh.positions[3 * i + 2]),
            ))
        };
        let has_normals = mesh.normals.len() == mesh.positions.len();
        for f in mesh.indices.chunks_exact(3) {
            let p = [vertex(f[0])?, vertex(f[1])?, vertex(f[2])?];
            let n = has_normals.then(|| {
                [f[0], f[1], f[2]].map(|i| {
                    let i = i as usize;
                    DVec3::new(
                        f64::from(mesh.normals[3 * i]),
                        f64::from(mesh.normals[3 * i + 1]),
                        f64::from(mesh.normals[3 * i + 2]),
                    )
                })
            });
            if (p[1] - p[0]).cross(p[2] - p[0]).length_squared() > 0.0 {
                tris.push(Shape::Triangle { p, n });
            }
        }
    }
    if tris.is_empty() {
        return Err(RenderError::scene(path, "the OBJ mesh has no triangles"));
    }
    Ok(tris)
}
