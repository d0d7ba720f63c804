//! The scenes for Radiance: a `.rad` scene and the pixels' rays (2 × 2 per pixel, at the
//! centres of its quarters), traced by `rtrace` (PyPI pyradiance's binaries) through the
//! embedded driver `radiance.py`, with one ambient bounce sampled without caching (`-ab 1 -aa 0
//! -ad 256`): the uniform sky is a `glow` source of 360° reached only by ambient rays.
//!
//! Materials, two ways ([`crate::suite::Route`]). Through gonio's exports: every material is
//! gonio's table of it ([`crate::export::table`]) written as an XML BSDF
//! (`gonio_brdf::formats::radiance_xml`, a tensor tree) for the `BSDF` material; a tensor tree
//! has no delta component, so the coat's mirror reflection `F(θv) L` and the whole mirror are
//! lost. Natively, for comparison: a Lambertian is `plastic` with no specular part (its diffuse
//! reflectance the colour, per RGB channel); the mirror is Radiance's `mirror`, whose
//! reflectance is one constant, set to the Fresnel reflectance at 45° (the middle of the
//! region's angles): Radiance has no smooth dielectric reflector without transmission, so the
//! change of F across the region is lost; the coat has no native version (Radiance has no
//! smooth coat over a diffuse base). Radiance is an RGB renderer: a spectral patch becomes its
//! linear sRGB under D65 (natively) or its XYZ (the XML), and the sky's colour that of the
//! illuminant's white, so two patches equal under D65 stay equal under any light: the
//! metameric pair collapses.

use crate::error::{Error, Result};
use crate::export;
use crate::metamer;
use crate::optics::fresnel;
use crate::python;
use crate::scene::{Geometry, Light, Material, SIZE, Scene, rect_frame};
use crate::suite::Route;
use glam::DVec3;
use gonio_color::{Illuminant, LinearSrgb, Observer, SpectralToXyz};
use std::fmt::Write as _;
use std::path::Path;

/// The driver.
const DRIVER: &str = include_str!("radiance.py");

/// The rtrace options: one ambient bounce, 256 stratified ambient samples per ray without the
/// ambient cache, direct light without jitter or subdivision limits, two processes.
const OPTIONS: [&str; 14] = [
    "-ab", "1", "-aa", "0", "-ad", "256", "-as", "0", "-lw", "1e-6", "-dj", "0", "-n", "2",
];

/// The angle at which the mirror's constant reflectance is the Fresnel reflectance, degrees.
pub const MIRROR_ANGLE_DEG: f64 = 45.0;

fn rgb_line(v: [f64; 3]) -> String {
    format!("{} {} {}", v[0], v[1], v[2])
}

fn srgb(v: LinearSrgb) -> [f64; 3] {
    [v.r, v.g, v.b]
}

/// The polygon of a rectangle, counter-clockwise seen from its front.
fn polygon(center: [f64; 3], half: [f64; 2], rotate_x_deg: f64) -> String {
    let (ex, ey, _) = rect_frame(rotate_x_deg);
    let c = DVec3::from(center);
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mut s = String::from("0\n0\n12");
    for (u, v) in corners {
        let p = c + u * half[0] * ex + v * half[1] * ey;
        let _ = write!(s, " {} {} {}", p.x, p.y, p.z);
    }
    s
}

/// Whether Radiance has a native version of `scene`'s materials (not of the coat).
pub fn has_native(scene: &Scene) -> bool {
    !scene
        .objects
        .iter()
        .any(|o| matches!(o.material, Material::Coat(_)))
}

/// The `.rad` text of `scene` by `route`, writing the XML BSDFs it names into `dir`.
pub fn scene_rad(scene: &Scene, dir: &Path, route: Route) -> Result<String> {
    let mut t = format!("# {}\n", scene.title);
    let d65 = SpectralToXyz::new(
        &metamer::wavelengths_nm(),
        Illuminant::D65,
        Observer::Cie1931TwoDegree,
    )?;
    for light in &scene.lights {
        match *light {
            Light::Sky { radiance } => {
                let white = metamer::xyz(
                    &vec![1.0; metamer::wavelengths_nm().len()],
                    scene.cie_illuminant(),
                )?;
                let c = srgb(LinearSrgb::from_xyz(white)).map(|c| c * radiance);
                let _ = writeln!(
                    t,
                    "void glow skyglow 0 0 4 {} 0\nskyglow source sky 0 0 4 0 0 1 360",
                    rgb_line(c)
                );
            }
            Light::Rectangle {
                center,
                half,
                rotate_x_deg,
                radiance,
            } => {
                let _ = writeln!(
                    t,
                    "void light emitter 0 0 3 {r} {r} {r}\nemitter polygon lamp\n{}",
                    polygon(center, half, rotate_x_deg),
                    r = radiance
                );
            }
        }
    }
    for o in &scene.objects {
        let name = &o.name;
        if route == Route::Export {
            let xml = export::radiance_file(dir, scene.id.name(), name);
            export::write_radiance(&o.material, &xml)?;
            let _ = writeln!(t, "void BSDF {name}_m 6 0 {} 0 1 0 . 0 0", xml.display());
        }
        let _ = match &o.material {
            _ if route == Route::Export => Ok(()),
            Material::Lambert { albedo } => {
                writeln!(t, "void plastic {name}_m 0 0 5 {} 0 0", rgb_line(*albedo))
            }
            Material::Spectral { reflectance } => {
                // The patch's colour under D65, white the perfect diffuser (1, 1, 1).
                let rgb = srgb(d65.linear_srgb(reflectance)?);
                let white = srgb(d65.linear_srgb(&vec![1.0; reflectance.len()])?);
                let c = [0, 1, 2].map(|k| rgb[k] / white[k]);
                writeln!(t, "void plastic {name}_m 0 0 5 {} 0 0", rgb_line(c))
            }
            Material::Mirror { index } => {
                let f = fresnel(MIRROR_ANGLE_DEG.to_radians().cos(), *index);
                writeln!(t, "void mirror {name}_m 0 0 3 {f} {f} {f}")
            }
            Material::Coat(_) => {
                return Err(Error::Invalid(
                    "Radiance has no native smooth coat over a diffuse base".into(),
                ));
            }
        };
        let _ = match o.geometry {
            Geometry::Sphere { center, radius } => writeln!(
                t,
                "{name}_m sphere {name} 0 0 4 {} {} {} {radius}",
                center[0], center[1], center[2]
            ),
            Geometry::Rectangle {
                center,
                half,
                rotate_x_deg,
            } => writeln!(
                t,
                "{name}_m polygon {name}\n{}",
                polygon(center, half, rotate_x_deg)
            ),
        };
    }
    Ok(t)
}

/// The rays, 2 × 2 per pixel, "ox oy oz dx dy dz" per line, pixels row by row from the top.
pub fn rays(scene: &Scene) -> String {
    let o = scene.camera.position;
    let mut s = String::new();
    for k in 0..SIZE * SIZE {
        let (x, y) = ((k % SIZE) as f64, (k / SIZE) as f64);
        for (i, j) in [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)] {
            let d = scene.camera.ray(x + i, y + j);
            let _ = writeln!(s, "{} {} {} {} {} {}", o[0], o[1], o[2], d.x, d.y, d.z);
        }
    }
    s
}

/// Radiance's picture of `scene` by `route` (files in `dir`), `None` when pyradiance is
/// missing.
pub fn render(scene: &Scene, dir: &Path, route: Route) -> Result<Option<Vec<[f64; 3]>>> {
    let name = format!("{}_{}", scene.id.name(), route.name());
    let rad = dir.join(format!("{name}.rad"));
    let rays_path = dir.join(format!("{name}.rays"));
    let options = dir.join("rtrace_options.json");
    let out = dir.join(format!("{name}.radiance.f32"));
    let io = |p: &Path, e| Error::io(&p.display().to_string(), e);
    std::fs::write(&rad, scene_rad(scene, dir, route)?).map_err(|e| io(&rad, e))?;
    std::fs::write(&rays_path, rays(scene)).map_err(|e| io(&rays_path, e))?;
    std::fs::write(&options, serde_json::to_string(&OPTIONS)?).map_err(|e| io(&options, e))?;
    if python::run(
        "radiance_driver.py",
        DRIVER,
        dir,
        &[&rad, &rays_path, &options, &out],
    )?
    .is_none()
    {
        return Ok(None);
    }
    let v = python::read_f32(&out, SIZE * SIZE * 4 * 3)?;
    Ok(Some(
        v.chunks_exact(12)
            .map(|p| [0, 1, 2].map(|c| (0..4).map(|r| f64::from(p[3 * r + c])).sum::<f64>() / 4.0))
            .collect(),
    ))
}
