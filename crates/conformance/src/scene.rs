//! The conformance scenes: what each holds (camera, objects, materials, lights), in a form every
//! renderer's writer reads; their geometry is in [`crate::geometry`], their analytic reference
//! picture and regions, computed by casting the pixels' rays through it, in [`crate::reference`].
//!
//! Every scene is square, [`SIZE`] pixels per side, seen through a pinhole camera whose pixel
//! (x, y) spans film points x..x+1, y..y+1 (gonio's `Camera::ray`, Mitsuba's `perspective` with a
//! box filter, the rays the Radiance driver traces). The reference value of a pixel is the mean
//! of the analytic radiance at 4 × 4 points spread evenly over it (a box filter like the
//! renderers'); a region holds the pixels all of whose 16 points satisfy the region's rule, so
//! no region pixel straddles an edge.

pub use crate::geometry::{Camera, Geometry, rect_frame};
use crate::metamer;
use crate::optics::kubelka_munk;
pub use crate::reference::Reference;
use gonio_color::Illuminant;
use serde::Serialize;

/// Pixels per side of every picture (small, so that the suite runs in seconds).
pub const SIZE: usize = 64;

/// Points per side of a pixel at which the reference is evaluated.
pub(crate) const SUPERSAMPLE: usize = 4;

/// A smooth clear coat over a Kubelka-Munk pigmented layer over a substrate, all grey.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Coat {
    /// The coat's refractive index.
    pub index: f64,
    /// The layer's absorption and scattering coefficients, 1/µm.
    pub k_per_um: f64,
    pub s_per_um: f64,
    /// The layer's thickness, µm.
    pub thickness_um: f64,
    /// The substrate's reflectance.
    pub substrate: f64,
}

impl Coat {
    /// The base's reflectance seen from inside the coat (Kubelka-Munk, [`kubelka_munk`]).
    pub fn base_reflectance(&self) -> f64 {
        kubelka_munk(
            self.k_per_um,
            self.s_per_um,
            self.thickness_um,
            self.substrate,
        )
    }

    /// The coating description (`gonio coating`'s TOML, `docs/coatings.md`) of this coat: a
    /// clear coat of constant index without absorption over a one-pigment Kubelka-Munk layer.
    pub fn description(&self) -> String {
        format!(
            "[coat]\nindex = {}\nthickness_um = 40\nabsorption_per_um = 0\n\n[base]\n\
             kind = \"kubelka-munk\"\nthickness_um = {}\nsubstrate = {}\n\n\
             [[base.pigment]]\nname = \"grey\"\nconcentration = 1.0\nk_per_um = {}\n\
             s_per_um = {}\n",
            self.index, self.thickness_um, self.substrate, self.k_per_um, self.s_per_um
        )
    }
}

/// What a shape is made of.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Material {
    /// Lambertian, albedo per linear sRGB channel.
    Lambert { albedo: [f64; 3] },
    /// Lambertian with a spectral reflectance at [`metamer::wavelengths_nm`].
    Spectral { reflectance: Vec<f64> },
    /// A smooth coat over a Kubelka-Munk base.
    Coat(Coat),
    /// A smooth dielectric of index `index` over a black base: its Fresnel mirror only.
    Mirror { index: f64 },
}

/// A shape with its material.
#[derive(Debug, Clone, Serialize)]
pub struct Object {
    /// Its name (regions and materials are named after it).
    pub name: String,
    pub geometry: Geometry,
    pub material: Material,
}

/// A light.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Light {
    /// Uniform radiance from every direction (W m⁻² sr⁻¹, white: the scene's illuminant).
    Sky { radiance: f64 },
    /// A rectangle (as [`Geometry::Rectangle`]) emitting `radiance` from its front (+z side).
    Rectangle {
        center: [f64; 3],
        half: [f64; 2],
        rotate_x_deg: f64,
        radiance: f64,
    },
}

/// Which pixels of an object a region holds.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(tag = "rule", rename_all = "snake_case")]
pub enum Rule {
    /// A sphere's pixels whose normal is within `max_deg` of the direction to the camera.
    Facing { max_deg: f64 },
    /// A rectangle's pixels within `fraction` of its half sizes from its centre.
    Interior { fraction: f64 },
    /// A mirror's pixels within `fraction` of its half sizes whose mirrored ray meets the
    /// emitter within `emitter_fraction` of its half sizes.
    Mirrored {
        fraction: f64,
        emitter_fraction: f64,
    },
}

/// A region: a set of pixels, a patch or an object's interior.
#[derive(Debug, Clone, Serialize)]
pub struct RegionSpec {
    pub name: String,
    /// Index into the scene's objects.
    pub object: usize,
    pub rule: Rule,
}

/// The scenes of the suite.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SceneId {
    WhiteFurnace,
    GreyFurnace,
    Plate,
    Coat,
    Mirror,
    MetamerD65,
    MetamerA,
}

impl SceneId {
    /// Every scene, in the report's order.
    pub const ALL: [SceneId; 7] = [
        SceneId::WhiteFurnace,
        SceneId::GreyFurnace,
        SceneId::Plate,
        SceneId::Coat,
        SceneId::Mirror,
        SceneId::MetamerD65,
        SceneId::MetamerA,
    ];

    /// Its short name (files, JSON).
    pub fn name(self) -> &'static str {
        match self {
            SceneId::WhiteFurnace => "white_furnace",
            SceneId::GreyFurnace => "grey_furnace",
            SceneId::Plate => "plate",
            SceneId::Coat => "coat",
            SceneId::Mirror => "mirror",
            SceneId::MetamerD65 => "metamer_d65",
            SceneId::MetamerA => "metamer_a",
        }
    }
}

/// A scene.
#[derive(Debug, Clone, Serialize)]
pub struct Scene {
    pub id: SceneId,
    /// One line saying what it is and what its reference is.
    pub title: String,
    pub camera: Camera,
    pub objects: Vec<Object>,
    pub lights: Vec<Light>,
    /// The illuminant the lights' "white" stands for (D65 but in the second metameric scene).
    pub illuminant: &'static str,
    /// The radiance taken as CIELAB's white (a perfect diffuser under the scene's lights).
    pub white: f64,
    pub regions: Vec<RegionSpec>,
}

/// The coat of the coat scene: index 1.5 over 10 µm of a grey pigmented layer (K 0.1/µm, S
/// 1/µm) on a substrate of reflectance 0.5.
pub const COAT: Coat = Coat {
    index: 1.5,
    k_per_um: 0.1,
    s_per_um: 1.0,
    thickness_um: 10.0,
    substrate: 0.5,
};

/// The plate's albedo (linear sRGB).
pub const PLATE_ALBEDO: [f64; 3] = [0.6, 0.4, 0.2];
/// The mirror's index and the emitter's radiance.
pub const MIRROR_INDEX: f64 = 1.5;
pub const EMITTER_RADIANCE: f64 = 10.0;

fn camera(position: [f64; 3], fov_deg: f64) -> Camera {
    Camera {
        position,
        look_at: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        fov_deg,
    }
}

fn sphere(name: &str, material: Material) -> Object {
    Object {
        name: name.into(),
        geometry: Geometry::Sphere {
            center: [0.0; 3],
            radius: 1.0,
        },
        material,
    }
}

fn facing(name: &str) -> Vec<RegionSpec> {
    vec![RegionSpec {
        name: name.into(),
        object: 0,
        rule: Rule::Facing { max_deg: 60.0 },
    }]
}

impl Scene {
    /// The scene `id`.
    pub fn new(id: SceneId) -> crate::Result<Scene> {
        let sky = |radiance| vec![Light::Sky { radiance }];
        let scene = match id {
            SceneId::WhiteFurnace | SceneId::GreyFurnace => {
                let rho = if id == SceneId::WhiteFurnace {
                    1.0
                } else {
                    0.5
                };
                Scene {
                    id,
                    title: format!(
                        "{} furnace: a Lambertian sphere of albedo {rho} under a uniform sky of \
                         radiance 1; reference ρL = {rho}",
                        if rho == 1.0 { "White" } else { "Grey" }
                    ),
                    camera: camera([0.0, 0.0, 4.0], 36.0),
                    objects: vec![sphere("sphere", Material::Lambert { albedo: [rho; 3] })],
                    lights: sky(1.0),
                    illuminant: "D65",
                    white: 1.0,
                    regions: facing("sphere"),
                }
            }
            SceneId::Plate => Scene {
                id,
                title: format!(
                    "Lambertian plate of albedo {PLATE_ALBEDO:?} (linear sRGB) under a uniform \
                     sky of radiance 1, seen at 37°; reference ρL per channel"
                ),
                camera: camera([0.0, -2.4, 3.2], 36.0),
                objects: vec![Object {
                    name: "plate".into(),
                    geometry: Geometry::Rectangle {
                        center: [0.0; 3],
                        half: [1.0, 1.0],
                        rotate_x_deg: 0.0,
                    },
                    material: Material::Lambert {
                        albedo: PLATE_ALBEDO,
                    },
                }],
                lights: sky(1.0),
                illuminant: "D65",
                white: 1.0,
                regions: vec![RegionSpec {
                    name: "interior".into(),
                    object: 0,
                    rule: Rule::Interior { fraction: 0.85 },
                }],
            },
            SceneId::Coat => Scene {
                id,
                title: format!(
                    "Smooth coat (n = {}) over a Kubelka-Munk base (K {}/µm, S {}/µm, {} µm over \
                     a substrate of {}: R_b = {:.4}) on a sphere under a uniform sky of radiance \
                     1; reference L[F(θv) + (1 − F(θv)) R_b (1 − r_i)/(1 − R_b r_i)] per pixel",
                    COAT.index,
                    COAT.k_per_um,
                    COAT.s_per_um,
                    COAT.thickness_um,
                    COAT.substrate,
                    COAT.base_reflectance()
                ),
                camera: camera([0.0, 0.0, 4.0], 36.0),
                objects: vec![sphere("sphere", Material::Coat(COAT))],
                lights: sky(1.0),
                illuminant: "D65",
                white: 1.0,
                regions: facing("sphere"),
            },
            SceneId::Mirror => Scene {
                id,
                title: format!(
                    "A smooth dielectric (n = {MIRROR_INDEX}) over black reflecting a rectangular \
                     emitter of radiance {EMITTER_RADIANCE}, seen at about 45°; reference \
                     F(θ)·Le per pixel"
                ),
                camera: camera([0.0, -3.0, 3.0], 30.0),
                objects: vec![Object {
                    name: "mirror".into(),
                    geometry: Geometry::Rectangle {
                        center: [0.0; 3],
                        half: [1.0, 1.0],
                        rotate_x_deg: 0.0,
                    },
                    material: Material::Mirror {
                        index: MIRROR_INDEX,
                    },
                }],
                lights: vec![Light::Rectangle {
                    center: [0.0, 3.0, 3.0],
                    half: [1.6, 1.6],
                    rotate_x_deg: 135.0,
                    radiance: EMITTER_RADIANCE,
                }],
                illuminant: "D65",
                white: EMITTER_RADIANCE,
                regions: vec![RegionSpec {
                    name: "reflection".into(),
                    object: 0,
                    rule: Rule::Mirrored {
                        fraction: 0.95,
                        emitter_fraction: 0.9,
                    },
                }],
            },
            SceneId::MetamerD65 | SceneId::MetamerA => {
                let pair = metamer::pair()?;
                let a = id == SceneId::MetamerA;
                let patch = |name: &str, x: f64, reflectance: Vec<f64>| Object {
                    name: name.into(),
                    geometry: Geometry::Rectangle {
                        center: [x, 0.0, 0.0],
                        half: [0.4, 0.4],
                        rotate_x_deg: 0.0,
                    },
                    material: Material::Spectral { reflectance },
                };
                let n = pair.first.len();
                Scene {
                    id,
                    title: format!(
                        "Metameric pair under {}: two Lambertian patches whose CIE 1931 2° XYZ \
                         are equal under D65, beside a perfect white, under a uniform sky of \
                         that illuminant; reference CIELAB of each patch (the white patch as \
                         white) and their ΔE00 ({:.2} under D65, {:.2} under A)",
                        if a { "illuminant A" } else { "D65" },
                        metamer::pair_delta_e(&pair, Illuminant::D65)?,
                        metamer::pair_delta_e(&pair, Illuminant::A)?
                    ),
                    camera: camera([0.0, 0.0, 4.0], 36.0),
                    objects: vec![
                        patch("first", -0.85, pair.first),
                        patch("second", 0.0, pair.second),
                        patch("white", 0.85, vec![1.0; n]),
                    ],
                    lights: sky(1.0),
                    illuminant: if a { "A" } else { "D65" },
                    white: 1.0,
                    regions: ["first", "second", "white"]
                        .iter()
                        .enumerate()
                        .map(|(object, name)| RegionSpec {
                            name: (*name).into(),
                            object,
                            rule: Rule::Interior { fraction: 0.8 },
                        })
                        .collect(),
                }
            }
        };
        Ok(scene)
    }

    /// The illuminant the scene's white light stands for.
    pub fn cie_illuminant(&self) -> Illuminant {
        if self.illuminant == "A" {
            Illuminant::A
        } else {
            Illuminant::D65
        }
    }

    /// Whether colour depends on spectra here (the metameric scenes).
    pub fn is_spectral(&self) -> bool {
        self.objects
            .iter()
            .any(|o| matches!(o.material, Material::Spectral { .. }))
    }
}
