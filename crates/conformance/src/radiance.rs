//! The scenes for Radiance: a `.rad` scene and the pixels' rays (2 × 2 per pixel, at the
//! centres of its quarters), traced by `rtrace` (PyPI pyradiance's binaries) through the
//! embedded driver `radiance.py`, with one ambient bounce sampled without caching (`-ab 1 -aa 0
//! -ad 256`): the uniform sky is a `glow` source of 360° reached only by ambient rays.
//!
//! Materials, and which export each is. A Lambertian is `plastic` with no specular part (its
//! diffuse reflectance is the colour, per RGB channel). The coat is gonio's export of the coat's
//! body table as an XML BSDF (`gonio_brdf::formats::radiance_xml`, a tensor tree) for the
//! `BSDF` material: a tensor tree has no delta component, so the coat's mirror reflection
//! `F(θv) L` is lost. The mirror is Radiance's `mirror`, whose reflectance is one constant, set
//! to the Fresnel reflectance at 45° (the middle of the region's angles): Radiance has no
//! smooth dielectric reflector without transmission, so the change of F across the region is
//! lost. Radiance is an RGB renderer: a spectral patch becomes its linear sRGB under D65 and
//! the sky's colour that of the illuminant's white, so two patches equal under D65 stay equal
//! under any light: the metameric pair collapses.

use crate::error::{Error, Result};
use crate::metamer;
use crate::optics::fresnel;
use crate::python;
use crate::scene::{Geometry, Light, Material, SIZE, Scene, rect_frame};
use glam::DVec3;
use gonio_brdf::table::{BrdfTable, Channels, Resolution};
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

/// The `.rad` text of `scene`, writing the XML BSDF it names into `dir`.
pub fn scene_rad(scene: &Scene, dir: &Path) -> Result<String> {
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
        let _ = match &o.material {
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
            Material::Coat(coat) => {
                let xml = dir.join(format!("{name}.xml"));
                write_coat_xml(&coat.description(), &xml)?;
                writeln!(t, "void BSDF {name}_m 6 0 {} 0 1 0 . 0 0", xml.display())
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

/// The coat's body table (gonio's closed form for a smooth coat over a diffuse base, at 500 and
/// 600 nm, the first band kept: the coat is grey) exported as an XML BSDF to `path`.
fn write_coat_xml(description: &str, path: &Path) -> Result<()> {
    let bands = gonio_coating::system::default_bands();
    let coating = gonio_coating::description::parse(description, &bands)
        .map_err(|e| Error::Invalid(format!("coat: {e}")))?;
    let stack = coating
        .clear_coat()
        .ok_or_else(|| Error::Invalid("coat: not a smooth coat over a diffuse base".into()))?;
    let res = Resolution::isotropic(45, 45, 24);
    let spectral = stack
        .body_table(
            res,
            &[500.0, 600.0],
            gonio_coating::clear_coat::body_provenance("gonio conformance coat"),
        )
        .map_err(|e| Error::Invalid(format!("coat: {e}")))?;
    let mono = BrdfTable::from_values(
        res,
        Channels::Mono,
        spectral.provenance().clone(),
        spectral.values().iter().step_by(2).copied().collect(),
    )
    .map_err(|e| Error::Invalid(format!("coat table: {e}")))?;
    gonio_brdf::formats::radiance_xml::write(&mono, path, "coat", None)
        .map_err(|e| Error::Invalid(format!("coat XML: {e}")))?;
    Ok(())
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

/// Radiance's picture of `scene` (files in `dir`), `None` when pyradiance is missing.
pub fn render(scene: &Scene, dir: &Path) -> Result<Option<Vec<[f64; 3]>>> {
    let name = scene.id.name();
    let rad = dir.join(format!("{name}.rad"));
    let rays_path = dir.join(format!("{name}.rays"));
    let options = dir.join("rtrace_options.json");
    let out = dir.join(format!("{name}.radiance.f32"));
    let io = |p: &Path, e| Error::io(&p.display().to_string(), e);
    std::fs::write(&rad, scene_rad(scene, dir)?).map_err(|e| io(&rad, e))?;
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
