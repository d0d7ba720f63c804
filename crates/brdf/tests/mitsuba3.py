"""Load a tensor .bsdf written by gonio in Mitsuba 3 itself and report what Mitsuba makes of it.

Usage: python3 mitsuba3.py VARIANT FILE.bsdf PAIRS.txt

PAIRS.txt holds one direction pair per line, `wo_x wo_y wo_z wi_x wi_y wi_z` (gonio's
convention: wo toward the viewer, wi toward the light). The script prints, one JSON object:
  "eval":   per pair, the BRDF Mitsuba evaluates (its eval() returns f cos(theta_light); we divide
            by cos(theta_light)), as a list of channel values (RGB, or the spectrum reduced by
            Mitsuba to RGB in spectral variants is not used: the values are Mitsuba's own);
  "albedo": directional albedo at theta_view = 0, 30, 60 degrees, the mean of the weights
            (f cos / pdf) that Mitsuba's own sample() returns over a fixed stratified set, and
            its standard error (that of independent samples, an upper bound for a stratified
            set): [mean, standard error];
  "render": a sphere with the material under a uniform white environment, rendered by the path
            integrator: value count, NaN and infinity counts over all values, and the luminance
            Y = 0.2126 R + 0.7152 G + 0.0722 B (the linear sRGB channels of a spectral render
            may be negative for saturated colours; Y may not) of the pixels well inside the
            sphere's disc (min, mean, max) and of those well outside it (mean, max).
Exit status 77 when Mitsuba is not installed, so the caller can skip.
"""

import json
import math
import sys

try:
    import mitsuba as mi
except ImportError:
    sys.exit(77)

variant, bsdf_path, pairs_path = sys.argv[1:4]
mi.set_variant(variant)
bsdf = mi.load_dict({"type": "measured", "filename": bsdf_path})
ctx = mi.BSDFContext()


def frame_interaction(wo):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wo)
    si.wavelengths = mi.Spectrum(550.0) if "spectral" in variant else si.wavelengths
    return si


def channels(value):
    return [float(value[k]) for k in range(len(value))]


evals = []
with open(pairs_path) as f:
    for line in f:
        v = [float(t) for t in line.split()]
        if len(v) != 6:
            continue
        wo, wi = v[:3], v[3:]
        value = bsdf.eval(ctx, frame_interaction(wo), mi.Vector3f(*wi))
        evals.append([c / wi[2] for c in channels(value)])

albedo = {}
n = 128
for theta_deg in (0, 30, 60):
    t = math.radians(theta_deg)
    si = frame_interaction([math.sin(t), 0.0, math.cos(t)])
    total, total_sq = 0.0, 0.0
    for a in range(n):
        for b in range(n):
            _, weight = bsdf.sample(
                ctx, si, 0.5, mi.Point2f((a + 0.5) / n, (b + 0.5) / n)
            )
            c = channels(weight)
            w = sum(c) / len(c)
            total += w
            total_sq += w * w
    mean = total / (n * n)
    variance = max(total_sq / (n * n) - mean * mean, 0.0)
    albedo[str(theta_deg)] = [mean, math.sqrt(variance / (n * n))]

scene = mi.load_dict(
    {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 3},
        "sensor": {
            "type": "perspective",
            "fov": 35,
            "to_world": mi.ScalarTransform4f().look_at(
                origin=[0, 0, 4], target=[0, 0, 0], up=[0, 1, 0]
            ),
            "film": {"type": "hdrfilm", "width": 48, "height": 48},
            "sampler": {"type": "independent", "sample_count": 16},
        },
        "sphere": {"type": "sphere", "bsdf": bsdf},
        "light": {"type": "constant", "radiance": {"type": "rgb", "value": 1.0}},
    }
)
image = mi.render(scene)
values = [float(x) for x in image.array]
height, width, channels_per_pixel = image.shape
sphere, background = [], []
for row in range(height):
    for col in range(width):
        k = (row * width + col) * channels_per_pixel
        y = 0.2126 * values[k] + 0.7152 * values[k + 1] + 0.0722 * values[k + 2]
        # The sphere of radius 1 seen from 4 away fills asin(1/4) = 14.5 deg of the 17.5 deg
        # half field: 0.82 of the half width.
        r = math.hypot((col + 0.5) / width * 2 - 1, (row + 0.5) / height * 2 - 1)
        if r < 0.7:
            sphere.append(y)
        elif r > 0.95:
            background.append(y)
render = {
    "values": len(values),
    "nan": sum(1 for x in values if math.isnan(x)),
    "inf": sum(1 for x in values if math.isinf(x)),
    "sphere_min": min(sphere),
    "sphere_mean": sum(sphere) / len(sphere),
    "sphere_max": max(sphere),
    "background_mean": sum(background) / len(background),
    "background_max": max(background),
}
print(json.dumps({"mitsuba": mi.__version__, "eval": evals, "albedo": albedo, "render": render}))
