//! Scene files (TOML) and the scene they describe: a camera, shapes with materials and
//! transforms, and lights. The format, with examples, is documented in `docs/render.md`;
//! every error names the file and, for a syntax or type error, the line and column.
//!
//! Transforms apply scale, then rotations about x, y and z (degrees), then the translation.
//! Relative paths (meshes, tables, maps) are relative to the scene file's directory.

use crate::assets::Assets;
use crate::camera::Camera;
use crate::error::{RenderError, Result};
use crate::geometry::{Accel, Shape};
use crate::image::{Display, Image, ToneCurve};
use crate::light::{EnvMap, Light};
use crate::material::{self, Material};
use crate::mesh::read_obj;
use crate::mesoscale::{Axis, MesoscaleDesc, Projection, Projections};
use glam::{DAffine3, DQuat, DVec3};
use gonio_brdf::models::{ModelSpec, Reflectance};
use rayon::prelude::*;
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

impl SceneDesc {
    /// Parse the TOML text of a scene file without building it (a caller may change the
    /// description first, then call [`Scene::build`]); `path` names the file in errors, which
    /// quote the line and column of the problem.
    pub fn from_toml(text: &str, path: &Path) -> Result<SceneDesc> {
        toml::from_str(text).map_err(|e| RenderError::scene(path, e.to_string()))
    }
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

/// `[materials.NAME]`: exactly one of `brdf`, `table`, `surface`, `coating`, and optionally
/// `coat_index` (`flakes` and `flake_seed` with `coating`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesc {
    /// An analytic model, e.g. `{ model = "ggx", alpha = 0.2, index = 1.5, diffuse = 0.5 }`.
    pub brdf: Option<ModelSpec>,
    /// A table file: `.gbrdf`, `.astm` or `.binary`.
    pub table: Option<PathBuf>,
    /// A height map and a scattering method.
    pub surface: Option<crate::surface::SurfaceDesc>,
    /// A coating description (`gonio coating`'s TOML), whose table is computed on loading
    /// (seconds; a smooth top's mirror is added by its index).
    pub coating: Option<PathBuf>,
    /// With `coating`: its flakes `smooth` (their average BRDF, the default) or `discrete`
    /// (one by one: sparkle).
    pub flakes: Option<crate::coating_material::FlakeMode>,
    /// With `flakes = "discrete"`: the seed that places the flakes (default 1).
    pub flake_seed: Option<u64>,
    /// The refractive index of a smooth clear coat over the BRDF, whose mirror reflection
    /// (Fresnel) is added as a delta lobe: for the body table of a coating with a smooth top
    /// (`gonio coating compute`), which leaves the mirror out. Default: no coat.
    pub coat_index: Option<f64>,
    /// A mesoscale height map (orange peel) tilting the shading normal over the BRDF
    /// ([`crate::mesoscale`]). Default: none.
    pub mesoscale: Option<MesoscaleDesc>,
}

/// Where a shape or a planar light is placed: scale, then rotations about x, y and z, then the
/// translation. The fields sit beside a shape's own (`translate = [...]` in its table).
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

/// `[[shapes]]`: a shape's geometry, its material and its transform.
#[derive(Debug, Clone, Deserialize)]
#[serde(try_from = "ShapeFields")]
pub struct ShapeDesc {
    /// The material's name in `[materials]`.
    pub material: String,
    /// The shape before its transform.
    pub geometry: Geometry,
    /// Where it is placed.
    pub transform: TransformDesc,
}

/// A shape before its transform (`type = "sphere"`, …).
#[derive(Debug, Clone)]
pub enum Geometry {
    /// A sphere of `radius` (default 1) at `center` (default origin).
    Sphere {
        /// Centre, m.
        center: [f64; 3],
        /// Radius, m.
        radius: f64,
    },
    /// A rectangle `size = [w, h]` (default 1 × 1) centred at the origin in the x-y plane,
    /// normal +z.
    Rectangle {
        /// Width and height, m.
        size: [f64; 2],
    },
    /// A disk of `radius` (default 1) centred at the origin in the x-y plane, normal +z.
    Disk {
        /// Radius, m.
        radius: f64,
    },
    /// A Wavefront OBJ mesh (every object in the file), smooth-shaded where it has normals.
    Mesh {
        /// The OBJ file.
        file: PathBuf,
    },
}

impl Geometry {
    /// The `type` of the shape in the scene file.
    pub fn name(&self) -> &'static str {
        match self {
            Geometry::Sphere { .. } => "sphere",
            Geometry::Rectangle { .. } => "rectangle",
            Geometry::Disk { .. } => "disk",
            Geometry::Mesh { .. } => "mesh",
        }
    }
}

/// The kinds of shape.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum ShapeKind {
    Sphere,
    Rectangle,
    Disk,
    Mesh,
}

/// A `[[shapes]]` table as written: every field any shape takes, checked against its `type` by
/// [`ShapeDesc::try_from`]. The transform's fields are written here once for every kind.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ShapeFields {
    #[serde(rename = "type")]
    kind: ShapeKind,
    material: String,
    center: Option<[f64; 3]>,
    radius: Option<f64>,
    size: Option<[f64; 2]>,
    file: Option<PathBuf>,
    translate: Option<[f64; 3]>,
    rotate_deg: Option<[f64; 3]>,
    scale: Option<Reflectance>,
}

impl TryFrom<ShapeFields> for ShapeDesc {
    type Error = String;

    fn try_from(f: ShapeFields) -> std::result::Result<ShapeDesc, String> {
        // The fields given that the shape's kind does not take, by name.
        let given = [
            ("center", f.center.is_some()),
            ("radius", f.radius.is_some()),
            ("size", f.size.is_some()),
            ("file", f.file.is_some()),
        ];
        let (name, takes): (&str, &[&str]) = match f.kind {
            ShapeKind::Sphere => ("sphere", &["center", "radius"]),
            ShapeKind::Rectangle => ("rectangle", &["size"]),
            ShapeKind::Disk => ("disk", &["radius"]),
            ShapeKind::Mesh => ("mesh", &["file"]),
        };
        if let Some((field, _)) = given.iter().find(|(n, g)| *g && !takes.contains(n)) {
            return Err(format!(
                "a {name} takes `{}` and the transform (`translate`, `rotate_deg`, `scale`), \
                 not `{field}`",
                takes.join("`, `")
            ));
        }
        let geometry = match f.kind {
            ShapeKind::Sphere => Geometry::Sphere {
                center: f.center.unwrap_or([0.0; 3]),
                radius: f.radius.unwrap_or(1.0),
            },
            ShapeKind::Rectangle => Geometry::Rectangle {
                size: f.size.unwrap_or([1.0, 1.0]),
            },
            ShapeKind::Disk => Geometry::Disk {
                radius: f.radius.unwrap_or(1.0),
            },
            ShapeKind::Mesh => Geometry::Mesh {
                file: f.file.ok_or("a mesh needs `file`, the OBJ file")?,
            },
        };
        Ok(ShapeDesc {
            material: f.material,
            geometry,
            transform: TransformDesc {
                translate: f.translate,
                rotate_deg: f.rotate_deg,
                scale: f.scale,
            },
        })
    }
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
    /// Rectangular area light (like the rectangle shape), emitting from its +z side; its
    /// `translate`, `rotate_deg` and `scale` make a [`TransformDesc`].
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
    /// A distant, collimated light (the sun, a booth's directional source) from `direction`
    /// (toward the light, normalised on reading), giving `irradiance` W/m² on a plane facing it.
    Distant {
        direction: [f64; 3],
        irradiance: Reflectance,
    },
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
    /// Per primitive, where it lies on its material's mesoscale map.
    pub projections: Projections,
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
        Scene::build(&SceneDesc::from_toml(text, path)?, path)
    }

    /// Build the scene of a parsed description, section by section.
    pub fn build(desc: &SceneDesc, path: &Path) -> Result<Scene> {
        Scene::build_with(desc, path, &Assets::new())
    }

    /// [`Scene::build`], taking the files that `assets` holds from memory (by the name the
    /// description gives them) and the others from disk.
    pub fn build_with(desc: &SceneDesc, path: &Path, assets: &Assets) -> Result<Scene> {
        let file = SceneFile {
            path,
            dir: path.parent().unwrap_or(Path::new(".")),
            assets,
        };
        let camera = build_camera(&desc.camera, &file)?;
        let (materials, material_index) = build_materials(&desc.materials, &file)?;
        let mut prims = Prims::default();
        build_shapes(&desc.shapes, &materials, &material_index, &file, &mut prims)?;
        let lights = build_lights(&desc.lights, &file, &mut prims)?;
        Ok(Scene {
            camera,
            display: Display {
                exposure: desc.camera.exposure,
                tone: desc.camera.tone,
            },
            render: desc.render.clone(),
            accel: Accel::new(prims.shapes),
            prims: prims.kinds,
            materials,
            lights,
            projections: prims.projections,
        })
    }
}

/// The scene file being built: its errors name it, and relative paths start in its directory.
struct SceneFile<'a> {
    path: &'a Path,
    dir: &'a Path,
    assets: &'a Assets,
}

impl SceneFile<'_> {
    /// A path from the file, relative to its directory unless absolute.
    fn resolve(&self, p: &Path) -> PathBuf {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.dir.join(p)
        }
    }

    /// An error in the file.
    fn bad(&self, problem: String) -> RenderError {
        RenderError::scene(self.path, problem)
    }
}

/// The primitives gathered from the shapes and the area lights, with what each is.
#[derive(Default)]
struct Prims {
    shapes: Vec<Shape>,
    kinds: Vec<PrimKind>,
    projections: Projections,
}

impl Prims {
    /// Add a primitive, with its projection onto a mesoscale map (an index from
    /// [`Projections::add`]) if its material has one.
    fn push(&mut self, shape: Shape, kind: PrimKind, projection: Option<u32>) {
        self.shapes.push(shape);
        self.kinds.push(kind);
        self.projections.push_prim(projection);
    }
}

/// `[camera]`.
fn build_camera(c: &CameraDesc, file: &SceneFile) -> Result<Camera> {
    if c.width == 0 || c.height == 0 || c.width > 1 << 15 || c.height > 1 << 15 {
        return Err(file.bad(format!(
            "[camera]: width and height must be 1 to 32768 pixels, got {} × {}",
            c.width, c.height
        )));
    }
    Camera::new(
        DVec3::from_array(c.position),
        DVec3::from_array(c.look_at),
        DVec3::from_array(c.up),
        c.fov_deg,
        c.width,
        c.height,
    )
    .ok_or_else(|| {
        file.bad(
            "[camera]: position and look_at must differ, up must not be parallel to the \
             view direction, and fov_deg must be between 0 and 180"
                .into(),
        )
    })
}

/// `[materials]`: the materials and each one's index by name. They are built in parallel (an
/// imported `.astm` table's fit or a height map's table takes seconds each); the first failing
/// material in the file's order is the one reported.
fn build_materials(
    descs: &BTreeMap<String, MaterialDesc>,
    file: &SceneFile,
) -> Result<(Vec<Material>, BTreeMap<String, usize>)> {
    let descs: Vec<(&String, &MaterialDesc)> = descs.iter().collect();
    let built: Vec<Result<Material>> = descs
        .par_iter()
        .map(|&(name, m)| build_material(name, m, file))
        .collect();
    let materials = built.into_iter().collect::<Result<Vec<Material>>>()?;
    let index = descs
        .iter()
        .enumerate()
        .map(|(i, (name, _))| ((*name).clone(), i))
        .collect();
    Ok((materials, index))
}

/// One `[materials.NAME]` entry.
fn build_material(name: &str, m: &MaterialDesc, file: &SceneFile) -> Result<Material> {
    if m.coating.is_none() && (m.flakes.is_some() || m.flake_seed.is_some()) {
        return Err(file.bad(format!(
            "material `{name}`: `flakes` and `flake_seed` go with `coating` (a coating \
             description with [flakes])"
        )));
    }
    let material = match (&m.brdf, &m.table, &m.surface, &m.coating) {
        (Some(spec), None, None, None) => {
            Material::new(name, material::from_model(spec, file.path, name)?)
        }
        (None, Some(table), None, None) => match file.assets.table(table) {
            Some(held) => Material::new(name, held.clone()),
            None => Material::from_table(name, material::read_table(&file.resolve(table))?),
        },
        (None, None, Some(surface), None) => Material::from_table(
            name,
            crate::surface::table(surface, file.dir, file.path, name)?,
        ),
        (None, None, None, Some(coating)) => {
            if m.coat_index.is_some() {
                return Err(file.bad(format!(
                    "material `{name}`: a coating's smooth top gives its own coat index; \
                     remove `coat_index`"
                )));
            }
            crate::coating_material::material(
                name,
                &file.resolve(coating),
                file.path,
                m.flakes.unwrap_or_default(),
                m.flake_seed.unwrap_or(1),
            )?
        }
        _ => {
            return Err(file.bad(format!(
                "material `{name}`: give exactly one of `brdf`, `table`, `surface`, `coating`"
            )));
        }
    };
    let material = match m.coat_index {
        None => material,
        Some(n) if n.is_finite() && n >= 1.0 => material.with_coat(n),
        Some(n) => {
            return Err(file.bad(format!(
                "material `{name}`: coat_index {n} must be a refractive index of at least 1 \
                 (1.5 for a typical clear coat)"
            )));
        }
    };
    match &m.mesoscale {
        None => Ok(material),
        Some(desc) => {
            let meso = crate::mesoscale::load(desc, file.dir, file.path, name)?;
            Ok(Material {
                mesoscale: Some(std::sync::Arc::new(meso)),
                ..material
            })
        }
    }
}

/// `[[shapes]]`: each shape's primitives, transformed, with its material.
fn build_shapes(
    descs: &[ShapeDesc],
    materials: &[Material],
    material_index: &BTreeMap<String, usize>,
    file: &SceneFile,
    prims: &mut Prims,
) -> Result<()> {
    for (k, s) in descs.iter().enumerate() {
        let bad = |p: &str| file.bad(format!("shape {} ({}): {p}", k + 1, s.geometry.name()));
        let Some(&mi) = material_index.get(&s.material) else {
            let defined = material_index.keys().cloned().collect::<Vec<_>>();
            return Err(bad(&format!(
                "material `{}` is not defined; defined: {}",
                s.material,
                defined.join(", ")
            )));
        };
        let local = match &s.geometry {
            Geometry::Sphere { center, radius } => {
                if radius.is_nan() || *radius <= 0.0 {
                    return Err(bad("`radius` must be positive"));
                }
                vec![Shape::Sphere {
                    centre: DVec3::from_array(*center),
                    radius: *radius,
                }]
            }
            Geometry::Rectangle { size } => {
                if !(size[0] > 0.0 && size[1] > 0.0) {
                    return Err(bad("`size` must be positive"));
                }
                vec![rectangle(*size)]
            }
            Geometry::Disk { radius } => {
                if radius.is_nan() || *radius <= 0.0 {
                    return Err(bad("`radius` must be positive"));
                }
                vec![Shape::Planar {
                    origin: DVec3::ZERO,
                    u: DVec3::X * *radius,
                    v: DVec3::Y * *radius,
                    disk: true,
                }]
            }
            Geometry::Mesh { file: obj } => match file.assets.mesh(obj) {
                Some(held) => held.as_ref().clone(),
                None => read_obj(&file.resolve(obj))?,
            },
        };
        let transform = s.transform.matrix();
        let projection = materials[mi].mesoscale.as_ref().map(|meso| {
            let axis = meso.axis().unwrap_or_else(|| thinnest_axis(&local));
            prims.projections.add(Projection::new(&transform, axis))
        });
        for shape in local {
            let shape = shape
                .transformed(&transform)
                .ok_or_else(|| bad("a sphere needs a uniform scale (one number)"))?;
            prims.push(shape, PrimKind::Surface(mi), projection);
        }
    }
    Ok(())
}

/// The object axis along which the shapes `local` (before their transform) are thinnest.
fn thinnest_axis(local: &[Shape]) -> Axis {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for shape in local {
        let (a, b) = shape.bounds();
        (lo, hi) = (lo.min(a), hi.max(b));
    }
    Axis::thinnest(lo, hi)
}

/// `[[lights]]`; area lights add their primitives.
fn build_lights(descs: &[LightDesc], file: &SceneFile, prims: &mut Prims) -> Result<Vec<Light>> {
    let mut lights = Vec::new();
    for (k, l) in descs.iter().enumerate() {
        let bad = |p: &str| file.bad(format!("light {}: {p}", k + 1));
        let rgb = |r: &Reflectance, what: &str| -> Result<DVec3> {
            let c = r.rgb();
            if c.is_finite() && c.min_element() >= 0.0 {
                Ok(c)
            } else {
                Err(bad(&format!("`{what}` must be non-negative")))
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
                    return Err(bad("`radius` must be positive"));
                }
                let sphere = Shape::Sphere {
                    centre: DVec3::from_array(*center),
                    radius: *radius,
                };
                prims.push(sphere, PrimKind::Emitter(lights.len()), None);
                Light::Area {
                    prim: prims.shapes.len() - 1,
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
                let placed = TransformDesc {
                    translate: *translate,
                    rotate_deg: *rotate_deg,
                    scale: *scale,
                };
                let shape = rectangle(size.unwrap_or([1.0, 1.0]))
                    .transformed(&placed.matrix())
                    .expect("planar shapes take any transform");
                if shape.area().is_nan() || shape.area() <= 0.0 {
                    return Err(bad("the rectangle has no area"));
                }
                prims.push(shape, PrimKind::Emitter(lights.len()), None);
                Light::Area {
                    prim: prims.shapes.len() - 1,
                    radiance: rgb(radiance, "radiance")?,
                }
            }
            LightDesc::Environment {
                file: map,
                scale,
                rotate_deg,
            } => {
                let image = match file.assets.image(map) {
                    Some(held) => held.as_ref().clone(),
                    None => Image::read(&file.resolve(map))?,
                };
                Light::Environment(EnvMap::new(
                    image,
                    scale.unwrap_or(1.0),
                    rotate_deg.unwrap_or(0.0).to_radians(),
                ))
            }
            LightDesc::Sky { radiance } => Light::Sky {
                radiance: rgb(radiance, "radiance")?,
            },
            LightDesc::Distant {
                direction,
                irradiance,
            } => {
                let d = DVec3::from_array(*direction);
                if !(d.length() > 0.0 && d.is_finite()) {
                    return Err(bad(
                        "a distant light's `direction` must be a non-zero vector",
                    ));
                }
                Light::Distant {
                    direction: d.normalize(),
                    irradiance: rgb(irradiance, "irradiance")?,
                }
            }
        };
        lights.push(light);
    }
    Ok(lights)
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
