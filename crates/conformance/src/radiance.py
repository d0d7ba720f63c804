"""Render one gonio conformance scene with Radiance (PyPI pyradiance's binaries; embedded in
gonio-conformance, run by `gonio conformance`).

Usage: python3 radiance.py SCENE.rad RAYS.txt OPTIONS.json OUTPUT.f32

SCENE.rad is the scene as gonio-conformance's Radiance writer made it; RAYS.txt holds one ray
per line, "ox oy oz dx dy dz" (the writer's: several per pixel). OPTIONS.json is a list of
rtrace options. `oconv` compiles the scene and `rtrace` traces the rays; their RGB radiances
(float32, three per ray, in the rays' order) are written raw to OUTPUT.f32. Exit status 77 when
pyradiance is not installed.
"""
import json
import os
import struct
import subprocess
import sys

try:
    import pyradiance
except ImportError:
    sys.exit(77)


def run(cmd, **kw):
    done = subprocess.run(cmd, capture_output=True, **kw)
    if done.returncode != 0:
        sys.stderr.write(done.stderr.decode(errors="replace"))
        sys.exit(f"{os.path.basename(cmd[0])} failed with status {done.returncode}")
    return done.stdout


def main():
    scene, rays, options, output = sys.argv[1:5]
    binpath = str(pyradiance.BINPATH)
    with open(options) as f:
        opts = json.load(f)
    octree = scene + ".oct"
    with open(octree, "wb") as f:
        f.write(run([os.path.join(binpath, "oconv"), scene]))
    with open(rays, "rb") as f:
        out = run([os.path.join(binpath, "rtrace"), "-h", "-ov", "-faf", *opts, octree], stdin=f)
    count = len(out) // 4
    values = struct.unpack(f"<{count}f", out[: 4 * count])
    with open(output, "wb") as f:
        f.write(struct.pack(f"<{count}f", *values))


if __name__ == "__main__":
    main()
