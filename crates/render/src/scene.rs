//! Scene files (TOML) and the scene they describe: a camera, shapes with materials and
//! transforms, and lights. The format, with examples, is documented in `docs/render.md`;
//! every error names the file and, for a syntax or type error, the line and column.
//!
//! Transforms apply scale, then rotations about x, y and z (degrees), then the translation.
//! Relative paths (meshes, tables, maps) are relative to the scene file's directory.

use crate::camera::Camera;
use crate::error::{RenderError, Result};
use crate::geometry::{Accel, Shape};
use crate::image::{Display, Image, ToneCurve};
use crate::light::{EnvMap, Light};
use crate::material::{self, Material};
use glam::{DAffine3, DQuat, DVec3};
use gonio_brdf::models::{ModelSpec, Reflectance};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The whole file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// The camera.
    pub camera: CameraDesc,
    /// Default render settings (overridden by the command line).
    #[serde(default)]
    pub render: RenderDesc,
    /// Named materials.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialDesc>,
    /// The shapes.
    #[serde(default)]
    pub shapes: Vec<ShapeDesc>,
    /// The lights.
    #[serde(default)]
    pub lights: Vec<LightDesc>,
}

/// `[camera]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Position, m.
    pub position: [f64; 3],
    /// The point at the centre of the image, m.
    pub look_at: [f64; 3],
    /// Toward the top of the image (default +y).
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    /// Vertical field of view, degrees.
    pub fov_deg: f64,
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    /// Exposure of PNG output, stops (default 0).
    #[serde(default)]
    pub exposure: f64,
    /// Tone curve of PNG output: `filmic` (default), `reinhard` or `clamp`.
    #[serde(default)]
    pub tone: ToneCurve,
}

fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

/// `[render]`: defaults for the render options.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderDesc {
    /// Samples per pixel.
    pub spp: Option<u32>,
    /// Seed of the sample sequences.
    pub seed: Option<u32>,
    /// Longest path, in surface interactions.
    pub max_bounces: Option<u32>,
    /// Denoise the picture (`gonio_render::denoise`); default no.
    pub denoise: Option<bool>,
}

/// `[materials.NAME]`: exactly one of `brdf`, `table`, `surface`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesc {
    /// An analytic model, e.g. `{ model = "ggx", alpha = 0.2, index = 1.5, diffuse = 0.5 }`.
    pub brdf: Option<ModelSpec>,
    /// A table file: `.gbrdf`, `.astm` or `.binary`.
    pub table: Option<PathBuf>,
    /// A height map and a scattering method.
    pub surface: Option<crate::surface::SurfaceDesc>,
}

/// The transform fields every shape and planar light accepts.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransformDesc {
    /// Translation, m.
    #[serde(default)]
    pub translate: Option<[f64; 3]>,
    /// Rotations about x, then y, then z, degrees.
    #[serde(default)]
    pub rotate_deg: Option<[f64; 3]>,
    /// Scale: one factor or one per axis.
    #[serde(default)]
    pub scale: Option<Reflectance>,
}

impl TransformDesc {
    /// The affine map `T · Rz · Ry · Rx · S`.
    pub fn matrix(&self) -> DAffine3 {
        let s = self.scale.map_or(DVec3::ONE, |s| s.rgb());
        let r = self.rotate_deg.unwrap_or([0.0; 3]).map(f64::to_radians);
        let q = DQuat::from_rotation_z(r[2])
            * DQuat::from_rotation_y(r[1])
            * DQuat::from_rotation_x(r[0]);
        let t = DVec3::from_array(self.translate.unwrap_or([0.0; 3]));
        DAffine3::from_scale_rotation_translation(s, q, t)
    }
}

/// `[[shapes]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum ShapeDesc {
    /// A sphere of `radius` (default 1) at `center` (default origin).
    Sphere {
        material: String,
        #[serde(default)]
        center: Option<[f64; 3]>,
        #[serde(default)]
        radius: Option<f64>,
        #[serde(default)]
        translate: Option<[f64; 3]>,
        #[serde(default)]
        rotate_deg: Option<[f64; 3]>,
        #[serde(default)]
        scale: Option<Reflectance>,
    },
    /// A rectangle `size = [w, h]` (default 1 × 1) centred at the origin in the x-y plane,
    /// normal +z, then transformed.
    Rectangle {
        material: String,
        #[serde(default)]
        size: Option<[f64; 2]>,
        #[serde(default)]
        translate: Option<[f64; 3]>,
        #[serde(default)]
        rotate_deg: Option<[f64; 3]>,
        #[serde(default)]
        scale: Option<Reflectance>,
    },
    /// A disk of `radius` (default 1) centred at the origin in the x-y plane, normal +z.
    Disk {
        material: String,
        #[serde(default)]
        radius: Option<f64>,
        #[serde(default)]
        translate: Option<[f64; 3]>,
        #[serde(default)]
        rotate_deg: Option<[f64; 3]>,
        #[serde(default)]
        scale: Option<Reflectance>,
    },
    /// A Wavefront OBJ mesh (every object in the file), smooth-shaded where it has normals.
    Mesh {
        material: String,
        file: PathBuf,
        #[serde(default)]
        translate: Option<[f64; 3]>,
        #[serde(default)]
        rotate_deg: Option<[f64; 3]>,
        #[serde(default)]
        scale: Option<Reflectance>,
    },
}

/// `[[lights]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum LightDesc {
    /// Point light of `intensity` W/sr (one value or RGB).
    Point {
        position: [f64; 3],
        intensity: Reflectance,
    },
    /// Spherical area light of uniform `radiance` W m⁻² sr⁻¹.
    Sphere {
        center: [f64; 3],
        radius: f64,
        radiance: Reflectance,
    },
    /// Rectangular area light (like the rectangle shape), emitting from its +z side.
    Rectangle {
        radiance: Reflectance,
        #[serde(default)]
        size: Option<[f64; 2]>,
        #[serde(default)]
        translate: Option<[f64; 3]>,
        #[serde(default)]
        rotate_deg: Option<[f64; 3]>,
        #[serde(default)]
        scale: Option<Reflectance>,
    },
    /// Equirectangular environment map (`.hdr`, `.exr`), +y up, times `scale`, turned by
    /// `rotate_deg` about +y.
    Environment {
        file: PathBuf,
        #[serde(default)]
        scale: Option<f64>,
        #[serde(default)]
        rotate_deg: Option<f64>,
    },
    /// Uniform radiance from every direction.
    Sky { radiance: Reflectance },
}

/// What a primitive is: a surface with a material, or an area light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PrimKind {
    /// Index into [`Scene::materials`].
    Surface(usize),
    /// Index into [`Scene::lights`].
    Emitter(usize),
}

/// A scene ready to render.
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// PNG display settings.
    pub display: Display,
    /// Defaults from `[render]`.
    pub render: RenderDesc,
    /// Primitives and their BVH.
    pub accel: Accel,
    /// Per primitive, its material or light.
    pub prims: Vec<PrimKind>,
    /// The materials.
    pub materials: Vec<Material>,
    /// The lights.
    pub lights: Vec<Light>,
}

impl Scene {
    /// Read and build the scene file `path`.
    pub fn from_file(path: &Path) -> Result<Scene> {
        let text = std::fs::read_to_string(path).map_err(|e| RenderError::Io {
            path: path.to_path_buf(),
            error: e,
        })?;
        Scene::from_toml(&text, path)
    }

    /// Build a scene from TOML text; `path` names the file in errors and relative paths are
    /// taken from its directory.
    pub fn from_toml(text: &str, path: &Path) -> Result<Scene> {
        let desc: SceneDesc =
            toml::from_str(text).map_err(|e| RenderError::scene(path, e.to_string()))?;
        Scene::build(&desc, path)
    }

    /// Build the scene of a parsed description.
    pub fn build(desc: &SceneDesc, path: &Path) -> Result<Scene> {
        let dir = path.parent().unwrap_or(Path::new("."));
        let resolve = |p: &Path| {
            if p.is_absolute() {
                p.to_path_buf()
            } else {
                dir.join(p)
            }
        };
        let bad = |problem: String| RenderError::scene(path, problem);

        let c = &desc.camera;
        if c.width == 0 || c.height == 0 || c.width > 1 << 15 || c.height > 1 << 15 {
            return Err(bad(format!(
                "[camera]: width and height must be 1 to 32768 pixels, got {} × {}",
                c.width, c.height
            )));
        }
        let camera = Camera::new(
            DVec3::from_array(c.position),
            DVec3::from_array(c.look_at),
            DVec3::from_array(c.up),
            c.fov_deg,
            c.width,
            c.height,
        )
        .ok_or_else(|| {
            bad(
                "[camera]: position and look_at must differ, up must not be parallel to the \
                 view direction, and fov_deg must be between 0 and 180"
                    .into(),
            )
        })?;

        let mut materials = Vec::new();
        let mut material_index = BTreeMap::new();
        for (name, m) in &desc.materials {
            let material = match (&m.brdf, &m.table, &m.surface) {
                (Some(spec), None, None) => {
                    Material::new(name.clone(), material::from_model(spec, path, name)?)
                }
                (None, Some(file), None) => {
                    Material::from_table(name.clone(), material::read_table(&resolve(file))?)
                }
                (None, None, Some(surface)) => Material::from_table(
                    name.clone(),
                    crate::surface::table(surface, dir, path, name)?,
                ),
                _ => {
                    return Err(bad(format!(
                        "material `{name}`: give exactly one of `brdf`, `table`, `surface`"
                    )));
                }
            };
            material_index.insert(name.clone(), materials.len());
            materials.push(material);
        }

        let mut shapes = Vec::new();
        let mut prims = Vec::new();
        for (k, s) in desc.shapes.iter().enumerate() {
            let (material, local, transform) = shape_of(s, &resolve, path, k)?;
            let Some(&mi) = material_index.get(material) else {
                return Err(bad(format!(
                    "shape {} ({}): material `{material}` is not defined; defined: {}",
                    k + 1,
                    shape_name(s),
                    desc.materials
                        .keys()
                        .cloned()
                        .collect::<Vec<_>>()
                        .join(", ")
                )));
            };
            for shape in local {
                let shape = shape.transformed(&transform).ok_or_else(|| {
                    bad(format!(
                        "shape {}: a sphere needs a uniform scale (one number)",
                        k + 1
                    ))
                })?;
                shapes.push(shape);
                prims.push(PrimKind::Surface(mi));
            }
        }

        let mut lights = Vec::new();
        for (k, l) in desc.lights.iter().enumerate() {
            let rgb = |r: &Reflectance, what: &str| -> Result<glam::DVec3> {
                let c = r.rgb();
                if c.is_finite() && c.min_element() >= 0.0 {
                    Ok(c)
                } else {
                    Err(bad(format!(
                        "light {}: `{what}` must be non-negative",
                        k + 1
                    )))
                }
            };
            let light = match l {
                LightDesc::Point {
                    position,
                    intensity,
                } => Light::Point {
                    position: DVec3::from_array(*position),
                    intensity: rgb(intensity, "intensity")?,
                },
                LightDesc::Sphere {
                    center,
                    radius,
                    radiance,
                } => {
                    if radius.is_nan() || *radius <= 0.0 {
                        return Err(bad(format!("light {}: `radius` must be positive", k + 1)));
                    }
                    shapes.push(Shape::Sphere {
                        centre: DVec3::from_array(*center),
                        radius: *radius,
                    });
                    prims.push(PrimKind::Emitter(lights.len()));
                    Light::Area {
                        prim: shapes.len() - 1,
                        radiance: rgb(radiance, "radiance")?,
                    }
                }
                LightDesc::Rectangle {
                    radiance,
                    size,
                    translate,
                    rotate_deg,
                    scale,
                } => {
                    let t = TransformDesc {
                        translate: *translate,
                        rotate_deg: *rotate_deg,
                        scale: *scale,
                    };
                    let shape = rectangle(size.unwrap_or([1.0, 1.0]))
                        .transformed(&t.matrix())
                        .expect("planar shapes take any transform");
                    if shape.area().is_nan() || shape.area() <= 0.0 {
                        return Err(bad(format!("light {}: the rectangle has no area", k + 1)));
                    }
                    shapes.push(shape);
                    prims.push(PrimKind::Emitter(lights.len()));
                    Light::Area {
                        prim: shapes.len() - 1,
                        radiance: rgb(radiance, "radiance")?,
                    }
                }
                LightDesc::Environment {
                    file,
                    scale,
                    rotate_deg,
                } => {
                    let image = Image::read(&resolve(file))?;
                    Light::Environment(EnvMap::new(
                        image,
                        scale.unwrap_or(1.0),
                        rotate_deg.unwrap_or(0.0).to_radians(),
                    ))
                }
                LightDesc::Sky { radiance } => Light::Sky {
                    radiance: rgb(radiance, "radiance")?,
                },
            };
            lights.push(light);
        }

        Ok(Scene {
            camera,
            display: Display {
                exposure: c.exposure,
                tone: c.tone,
            },
            render: desc.render.clone(),
            accel: Accel::new(shapes),
            prims,
            materials,
            lights,
        })
    }
}

fn shape_name(s: &ShapeDesc) -> &'static str {
    match s {
        ShapeDesc::Sphere { .. } => "sphere",
        ShapeDesc::Rectangle { .. } => "rectangle",
        ShapeDesc::Disk { .. } => "disk",
        ShapeDesc::Mesh { .. } => "mesh",
    }
}

/// The centred rectangle `size[0] × size[1]` in the x-y plane, normal +z.
fn rectangle(size: [f64; 2]) -> Shape {
    Shape::Planar {
        origin: DVec3::ZERO,
        u: DVec3::X * (0.5 * size[0]),
        v: DVec3::Y * (0.5 * size[1]),
        disk: false,
    }
}

/// The material name, the untransformed primitives and the transform of a shape.
fn shape_of<'a>(
    s: &'a ShapeDesc,
    resolve: &dyn Fn(&Path) -> PathBuf,
    scene: &Path,
    k: usize,
) -> Result<(&'a str, Vec<Shape>, DAffine3)> {
    let bad =
        |p: String| RenderError::scene(scene, format!("shape {} ({}): {p}", k + 1, shape_name(s)));
    let (material, translate, rotate_deg, scale, shapes) = match s {
        ShapeDesc::Sphere {
            material,
            center,
            radius,
            translate,
            rotate_deg,
            scale,
        } => {
            let r = radius.unwrap_or(1.0);
            if r.is_nan() || r <= 0.0 {
                return Err(bad("`radius` must be positive".into()));
            }
            let centre = DVec3::from_array(center.unwrap_or([0.0; 3]));
            (
                material,
                translate,
                rotate_deg,
                scale,
                vec![Shape::Sphere { centre, radius: r }],
            )
        }
        ShapeDesc::Rectangle {
            material,
            size,
            translate,
            rotate_deg,
            scale,
        } => {
            let size = size.unwrap_or([1.0, 1.0]);
            if !(size[0] > 0.0 && size[1] > 0.0) {
                return Err(bad("`size` must be positive".into()));
            }
            (
                material,
                translate,
                rotate_deg,
                scale,
                vec![rectangle(size)],
            )
        }
        ShapeDesc::Disk {
            material,
            radius,
            translate,
            rotate_deg,
            scale,
        } => {
            let r = radius.unwrap_or(1.0);
            if r.is_nan() || r <= 0.0 {
                return Err(bad("`radius` must be positive".into()));
            }
            let disk = Shape::Planar {
                origin: DVec3::ZERO,
                u: DVec3::X * r,
                v: DVec3::Y * r,
                disk: true,
            };
            (material, translate, rotate_deg, scale, vec![disk])
        }
        ShapeDesc::Mesh {
            material,
            file,
            translate,
            rotate_deg,
            scale,
        } => (
            material,
            translate,
            rotate_deg,
            scale,
            read_obj(&resolve(file))?,
        ),
    };
    let t = TransformDesc {
        translate: *translate,
        rotate_deg: *rotate_deg,
        scale: *scale,
    };
    Ok((material, shapes, t.matrix()))
}

/// The triangles of every object of a Wavefront OBJ file.
pub fn read_obj(path: &Path) -> Result<Vec<Shape>> {
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj(path, &opts)
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
