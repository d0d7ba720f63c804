#!/usr/bin/env python3
"""gonio's path tracer against Mitsuba 3 on the same exported BRDF table (results in
docs/performance.md, "Against Mitsuba 3 on the same exported table").

Each case tabulates a GGX model over a coloured Lambert base with gonio and exports it as a
Mitsuba 3 tensor `.bsdf`; a unit sphere wearing it is rendered by `gonio render` (the .gbrdf) and
by Mitsuba 3 (`scalar_rgb`, the `measured` plugin on the .bsdf, `ldsampler`, the `path`
integrator), at the same size and samples per pixel, under one of two lights:

- studio: examples/studio.hdr, the demo's studio (two soft boxes over a grey floor);
- booth: the viewing booth's light (docs/standard.md), half diffuse and half directional: a
  uniform sky and a collimated source at 45° giving the same irradiance on a horizontal plane.

Each renderer's image is compared with its own converged reference (the same renderer at
REF_SPP), so the figure is each renderer's noise at equal samples, whatever small differences of
convention remain between the two scenes. Each render is timed without its scene's loading:
Mitsuba's `mi.render` after a warm-up render, gonio's own render time (`gonio render --json`,
the tiles alone: not the process's start, the table's loading or the image's writing; the wall
time of the whole command is printed beside it). Efficiency is 1 / (time × relative RMSE²).

    python3 crates/render/benches/versus_mitsuba.py [path/to/gonio] [case ...]
    (default target/release/gonio and every case)

Prints one JSON object per case. Relative RMSE: sqrt(mean((I - R)²)) / mean(R) over every pixel
and channel of the linear image; the reference's own noise adds sqrt(SPP/REF_SPP) of its RMSE in
quadrature (1/4 with the defaults: the figures are about 3% high). Needs `pip install mitsuba
numpy`.
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import mitsuba as mi
import numpy as np

SIZE, SPP, REF_SPP = 256, 64, 1024
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
CAMERA = dict(origin=[0.0, 0.0, 4.0], target=[0.0, 0.0, 0.0], up=[0.0, 1.0, 0.0], fov=30.0)
# The booth's light: a uniform sky of radiance L gives pi L on a horizontal plane; the collimated
# source at 45° (toward +y and +z, in front of the sphere, above) gives the same there.
SKY = 0.5
TOWARD_LIGHT = [0.0, 1.0, 1.0]
DISTANT = math.pi * SKY / math.cos(math.radians(45.0))

CASES = {
    "studio-ggx0.2": dict(model='{"model":"ggx","alpha":0.2,"index":1.5,"diffuse":[0.5,0.3,0.1]}',
                          light="studio"),
    "studio-ggx0.05": dict(model='{"model":"ggx","alpha":0.05,"index":1.5,"diffuse":[0.5,0.3,0.1]}',
                           light="studio"),
    "booth-ggx0.05": dict(model='{"model":"ggx","alpha":0.05,"index":1.5,"diffuse":[0.5,0.3,0.1]}',
                          light="booth"),
}

SCENE = """
[camera]
position = {origin}
look_at = {target}
up = {up}
fov_deg = {fov}
width = {size}
height = {size}

[render]
max_bounces = 8

[materials.paint]
table = "{table}"

[[shapes]]
type = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
material = "paint"
"""

STUDIO = """
[[lights]]
type = "environment"
file = "{envmap}"
"""

BOOTH = """
[[lights]]
type = "sky"
radiance = {sky}

[[lights]]
type = "distant"
direction = {toward}
irradiance = {distant}
"""


def gonio_render(gonio, scene, out, spp):
    start = time.perf_counter()
    run = subprocess.run(
        [gonio, "render", scene, "--spp", str(spp), "--seed", "1", "-o", out, "--json"],
        check=True,
        capture_output=True,
        text=True,
    )
    wall = time.perf_counter() - start
    seconds = json.loads(run.stdout)["seconds"]
    return np.array(mi.Bitmap(out)).astype(np.float64)[..., :3], seconds, wall


def mitsuba_scene(bsdf_file, light, envmap):
    if light == "studio":
        # gonio reads the map at u = phi/360° with phi from +x toward +z; Mitsuba at
        # u = atan2(x, -z)/360°, a quarter turn ahead: turning its map by -90° about +y aligns
        # them.
        lights = {
            "light": {
                "type": "envmap",
                "filename": envmap,
                "to_world": mi.ScalarTransform4f().rotate([0.0, 1.0, 0.0], -90.0),
            }
        }
    else:
        lights = {
            "sky": {"type": "constant", "radiance": {"type": "rgb", "value": [SKY] * 3}},
            # Mitsuba's direction is the light's travel, away from the light.
            "sun": {
                "type": "directional",
                "direction": [-c for c in TOWARD_LIGHT],
                "irradiance": {"type": "rgb", "value": [DISTANT] * 3},
            },
        }
    return mi.load_dict(
        {
            "type": "scene",
            "integrator": {"type": "path", "max_depth": 9},
            "sensor": {
                "type": "perspective",
                "fov": CAMERA["fov"],
                "to_world": mi.ScalarTransform4f().look_at(
                    origin=CAMERA["origin"], target=CAMERA["target"], up=CAMERA["up"]
                ),
                "film": {"type": "hdrfilm", "width": SIZE, "height": SIZE, "rfilter": {"type": "box"}},
                "sampler": {"type": "ldsampler", "sample_count": SPP},
            },
            "sphere": {
                "type": "sphere",
                "center": [0.0, 0.0, 0.0],
                "radius": 1.0,
                "bsdf": {"type": "measured", "filename": bsdf_file},
            },
            **lights,
        }
    )


def mitsuba_render(scene, spp, seed):
    start = time.perf_counter()
    image = mi.render(scene, spp=spp, seed=seed)
    image = np.array(image).astype(np.float64)[..., :3]
    return image, time.perf_counter() - start


def rel_rmse(image, ref):
    return float(math.sqrt(np.mean((image - ref) ** 2)) / np.mean(ref))


def run_case(gonio, name, case, d):
    envmap = os.path.join(ROOT, "examples", "studio.hdr")
    table, bsdf = os.path.join(d, name + ".gbrdf"), os.path.join(d, name + ".bsdf")
    subprocess.run([gonio, "brdf", "tabulate", "--model", case["model"], "-o", table], check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run([gonio, "brdf", "export", table, "--format", "mitsuba", "-o", bsdf],
                   check=True, stdout=subprocess.DEVNULL)
    scene = os.path.join(d, name + ".toml")
    lights = (STUDIO.format(envmap=envmap) if case["light"] == "studio"
              else BOOTH.format(sky=SKY, toward=TOWARD_LIGHT, distant=DISTANT))
    with open(scene, "w") as f:
        f.write(SCENE.format(size=SIZE, table=table, **CAMERA) + lights)
    g_img, g_time, g_wall = gonio_render(gonio, scene, os.path.join(d, name + "_g.exr"), SPP)
    g_ref, g_ref_time, _ = gonio_render(gonio, scene, os.path.join(d, name + "_gref.exr"), REF_SPP)
    m_scene = mitsuba_scene(bsdf, case["light"], envmap)
    mitsuba_render(m_scene, 4, 0)  # warm the caches (the texture, the tensor file)
    m_img, m_time = mitsuba_render(m_scene, SPP, 1)
    m_ref, m_ref_time = mitsuba_render(m_scene, REF_SPP, 2)
    g_err, m_err = rel_rmse(g_img, g_ref), rel_rmse(m_img, m_ref)
    return {
        "case": name, "model": json.loads(case["model"]), "light": case["light"],
        "size": SIZE, "spp": SPP, "reference_spp": REF_SPP,
        "mitsuba": mi.__version__, "variant": "scalar_rgb", "threads": os.cpu_count(),
        "gonio_seconds": round(g_time, 2), "gonio_wall_seconds": round(g_wall, 2),
        "mitsuba_seconds": round(m_time, 2),
        "gonio_relative_rmse": round(g_err, 4),
        "mitsuba_relative_rmse": round(m_err, 4),
        "efficiency_gonio_over_mitsuba": round((m_time * m_err**2) / (g_time * g_err**2), 2),
        "reference_seconds": {"gonio": round(g_ref_time, 1), "mitsuba": round(m_ref_time, 1)},
        "mean_radiance": {"gonio": round(float(np.mean(g_ref)), 4),
                          "mitsuba": round(float(np.mean(m_ref)), 4)},
    }


def main():
    args = sys.argv[1:]
    gonio = os.path.join(ROOT, "target", "release", "gonio")
    if args and args[0] not in CASES:
        gonio, args = args[0], args[1:]
    mi.set_variant("scalar_rgb")
    with tempfile.TemporaryDirectory() as d:
        for name in args or list(CASES):
            print(json.dumps(run_case(gonio, name, CASES[name], d), indent=1), flush=True)


if __name__ == "__main__":
    main()
