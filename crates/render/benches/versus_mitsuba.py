#!/usr/bin/env python3
"""gonio's path tracer against Mitsuba 3 on the same exported BRDF table (results in
docs/performance.md, "Against Mitsuba 3 on the same exported table").

A GGX table (alpha 0.2, index 1.5, over a coloured Lambert base) is tabulated by gonio and
exported as a Mitsuba 3 tensor `.bsdf`; a sphere wearing it is rendered under
examples/studio.hdr by `gonio render` (the .gbrdf) and by Mitsuba 3 (`scalar_rgb`, the `measured`
plugin on the .bsdf, `ldsampler`, the `path` integrator), at the same size and samples per
pixel. Each renderer's image is compared with its own converged reference (the same renderer
at REF_SPP), so the figure is each renderer's noise at equal samples, whatever small
differences of convention remain between the two scenes; and each render is timed (wall clock,
both on all cores, the time to write the image included for gonio, the scene load excluded for
neither).

    python3 crates/render/benches/versus_mitsuba.py [path/to/gonio]   (default target/release/gonio)

Prints one JSON object. Relative RMSE: sqrt(mean((I - R)²)) / mean(R) over every pixel and
channel of the linear image; the reference's own noise adds sqrt(SPP/REF_SPP) of its RMSE in
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
MODEL = '{"model":"ggx","alpha":0.2,"index":1.5,"diffuse":[0.5,0.3,0.1]}'
CAMERA = dict(origin=[0.0, 0.0, 4.0], target=[0.0, 0.0, 0.0], up=[0.0, 1.0, 0.0], fov=30.0)

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

[[lights]]
type = "environment"
file = "{envmap}"
"""


def gonio_render(gonio, scene, out, spp):
    start = time.perf_counter()
    subprocess.run(
        [gonio, "render", scene, "--spp", str(spp), "--seed", "1", "-o", out],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    seconds = time.perf_counter() - start
    return np.array(mi.Bitmap(out)).astype(np.float64)[..., :3], seconds


def mitsuba_scene(bsdf_file, envmap):
    # gonio reads the map at u = phi/360° with phi from +x toward +z; Mitsuba at
    # u = atan2(x, -z)/360°, a quarter turn ahead: turning its map by -90° about +y aligns them.
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
            "light": {
                "type": "envmap",
                "filename": envmap,
                "to_world": mi.ScalarTransform4f().rotate([0.0, 1.0, 0.0], -90.0),
            },
        }
    )


def mitsuba_render(scene, spp, seed):
    start = time.perf_counter()
    image = mi.render(scene, spp=spp, seed=seed)
    image = np.array(image).astype(np.float64)[..., :3]
    return image, time.perf_counter() - start


def rel_rmse(image, ref):
    return float(math.sqrt(np.mean((image - ref) ** 2)) / np.mean(ref))


def main():
    gonio = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "target", "release", "gonio")
    mi.set_variant("scalar_rgb")
    envmap = os.path.join(ROOT, "examples", "studio.hdr")
    with tempfile.TemporaryDirectory() as d:
        table, bsdf = os.path.join(d, "ggx.gbrdf"), os.path.join(d, "ggx.bsdf")
        subprocess.run([gonio, "brdf", "tabulate", "--model", MODEL, "-o", table], check=True,
                       stdout=subprocess.DEVNULL)
        subprocess.run([gonio, "brdf", "export", table, "--format", "mitsuba", "-o", bsdf],
                       check=True, stdout=subprocess.DEVNULL)
        scene = os.path.join(d, "scene.toml")
        with open(scene, "w") as f:
            f.write(SCENE.format(size=SIZE, table=table, envmap=envmap, **CAMERA))
        g_img, g_time = gonio_render(gonio, scene, os.path.join(d, "g.exr"), SPP)
        g_ref, g_ref_time = gonio_render(gonio, scene, os.path.join(d, "g_ref.exr"), REF_SPP)
        m_scene = mitsuba_scene(bsdf, envmap)
        mitsuba_render(m_scene, 4, 0)  # warm the caches (the texture, the tensor file)
        m_img, m_time = mitsuba_render(m_scene, SPP, 1)
        m_ref, m_ref_time = mitsuba_render(m_scene, REF_SPP, 2)
    print(json.dumps({
        "size": SIZE, "spp": SPP, "reference_spp": REF_SPP,
        "mitsuba": mi.__version__, "variant": "scalar_rgb", "threads": os.cpu_count(),
        "gonio_seconds": round(g_time, 2), "mitsuba_seconds": round(m_time, 2),
        "time_ratio_gonio_over_mitsuba": round(g_time / m_time, 3),
        "gonio_relative_rmse": round(rel_rmse(g_img, g_ref), 4),
        "mitsuba_relative_rmse": round(rel_rmse(m_img, m_ref), 4),
        "reference_seconds": {"gonio": round(g_ref_time, 1), "mitsuba": round(m_ref_time, 1)},
        "mean_radiance": {"gonio": round(float(np.mean(g_ref)), 4),
                          "mitsuba": round(float(np.mean(m_ref)), 4)},
    }, indent=1))


if __name__ == "__main__":
    main()
