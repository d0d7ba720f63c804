"""Render one gonio conformance scene with Mitsuba 3 (embedded in gonio-conformance, run by
`gonio conformance`).

Usage: python3 mitsuba.py SCENE.json OUTPUT.f32

SCENE.json is the scene as gonio-conformance's Mitsuba writer made it: {"variant", "size",
"spp", "seed", "sensor": {"origin", "target", "up", "fov"}, "objects": {name: plugin dict}}, where
a dict's "to_world" is {"translate": [x, y, z], "rotate_x_deg": a, "scale": [sx, sy, sz]}
(applied as scale, then the rotation, then the translation) and a spectrum is
{"type": "spectrum", "value": [[nm, value], ...]}. The picture (size x size x 3 float32, linear,
rows from the top) is written raw to OUTPUT.f32. Exit status 77 when Mitsuba is not installed.
"""
import json
import sys

try:
    import mitsuba as mi
    import numpy as np
except ImportError:
    sys.exit(77)


def convert(node):
    """The scene dict with transforms and spectra turned into Mitsuba's objects."""
    if isinstance(node, dict):
        if "translate" in node and "rotate_x_deg" in node:
            t = mi.ScalarTransform4f().translate(node["translate"])
            t = t @ mi.ScalarTransform4f().rotate([1.0, 0.0, 0.0], node["rotate_x_deg"])
            return t @ mi.ScalarTransform4f().scale(node["scale"])
        if node.get("type") == "spectrum" and isinstance(node.get("value"), list):
            return {"type": "spectrum", "value": [tuple(p) for p in node["value"]]}
        return {k: convert(v) for k, v in node.items()}
    return node


def main():
    with open(sys.argv[1]) as f:
        spec = json.load(f)
    mi.set_variant(spec["variant"])
    size, s = spec["size"], spec["sensor"]
    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 9},
        "sensor": {
            "type": "perspective",
            "fov": s["fov"],
            "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(origin=s["origin"], target=s["target"], up=s["up"]),
            "film": {"type": "hdrfilm", "width": size, "height": size, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": spec["spp"]},
        },
    }
    scene.update(convert(spec["objects"]))
    image = mi.render(mi.load_dict(scene), spp=spec["spp"], seed=spec["seed"])
    np.asarray(np.array(image)[..., :3], dtype="<f4").tofile(sys.argv[2])


if __name__ == "__main__":
    main()
