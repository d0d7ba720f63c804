"""Run Radiance's own tools on the PAB-Opto files gonio wrote and report what Radiance makes of
them. The tools come from PyPI's pyradiance (`pip install pyradiance`), which ships the
Radiance binaries and a binding of its BSDF library.

Usage: python3 radiance.py DIR QUERIES.json

DIR holds the .dat files, one per incidence. QUERIES.json is
  {"pairs": [[theta_light, phi_light, theta_view, phi_view], ...], "dhr_theta": [...]}
with angles in degrees. The script runs `pabopto2bsdf DIR/*.dat > DIR/radiance.sir` and
`bsdf2ttree DIR/radiance.sir > DIR/radiance.xml` (default settings: a 64 x 64 tensor tree per
incidence, 90% culling) and prints one JSON object:
  "pyradiance": its version;
  "colorimetry": the COLORIMETRY line of the interpolant's header (CIE-Y or CIE-XYZ);
  "lobes": per incidence of the interpolant (pabopto2bsdf's radial basis functions, the binary
           format of save_bsdf_rep in Radiance src/cv/bsdfrep.c): the incidence [theta, phi]
           in degrees, the number of lobes and their chromaticity [x, y]: the lobes' (u', v')
           codes (8 bits each at 1/410, c_decodeChroma in src/common/ccolor.c) turned into
           X, Y, Z weighted by each lobe's volume (peak times radius squared) and summed;
  "tree_xy": the chromaticity of the median u' and v' leaves of bsdf2ttree's CIE-u and CIE-v
             trees (null without colour);
  "y": per pair, the BSDF (Y, 1/sr) that Radiance's BSDF library returns (SDevalBSDF through
       pyradiance.bsdf.query) for light from (theta_light, phi_light) seen from
       (theta_view, phi_view);
  "query_xy": per pair, the chromaticity that pyradiance.bsdf.query reports;
  "dhr": per dhr_theta, the directional-hemispherical reflectance (Y) of the tensor tree for
         light from (theta, 0) (SDdirectHemi, all reflection components).
Exit status 77 when pyradiance is not installed, so the caller can skip.
"""

import glob
import importlib.metadata
import json
import math
import os
import re
import statistics
import subprocess
import sys

try:
    import pyradiance
    from pyradiance import bsdf as rbsdf
except ImportError:
    sys.exit(77)

directory, queries_path = sys.argv[1:3]
with open(queries_path) as f:
    queries = json.load(f)

binpath = str(pyradiance.BINPATH)
env = dict(os.environ)
env["PATH"] = binpath + os.pathsep + env.get("PATH", "")
# wrapBSDF, which bsdf2ttree calls, finds its XML template on RAYPATH.
env["RAYPATH"] = os.pathsep.join([".", os.path.join(binpath, "..", "lib")])


def run(cmd, out_path):
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    if done.returncode != 0:
        sys.stderr.write(done.stderr.decode(errors="replace"))
        sys.exit(f"{cmd[0]} failed with status {done.returncode}")
    with open(out_path, "wb") as f:
        f.write(done.stdout)


files = sorted(glob.glob(os.path.join(directory, "*.dat")))
sir = os.path.join(directory, "radiance.sir")
xml = os.path.join(directory, "radiance.xml")
run([os.path.join(binpath, "pabopto2bsdf"), *files], sir)
run([os.path.join(binpath, "bsdf2ttree"), sir], xml)


def xy_of_uv(u, v):
    d = 6.0 * u - 16.0 * v + 12.0
    return [9.0 * u / d, 4.0 * v / d]


def read_sir(path):
    """Header colorimetry and, per incidence, the lobes of pabopto2bsdf's interpolant."""
    data = open(path, "rb").read()
    end = data.index(b"\n\n") + 2
    header = data[:end].decode(errors="replace")
    colorimetry = re.search(r"COLORIMETRY=(\S+)", header)
    pos = end

    def getint(n):
        nonlocal pos
        v = int.from_bytes(data[pos : pos + n], "big", signed=True)
        pos += n
        return v

    def getflt():  # putflt: mantissa * 0x7fffffff in 4 bytes, then the exponent in 1
        m = getint(4)
        e = getint(1)
        return m / 0x7FFFFFFF * 2.0**e

    getint(2)  # magic
    nodes = []
    while True:
        if getint(4) < 0:
            break
        invec = [getflt(), getflt(), getflt()]
        getflt()  # vtotal
        count = getint(4)
        total = [0.0, 0.0, 0.0]
        for _ in range(count):
            peak = getflt()
            chroma = getint(2) & 0xFFFF
            crad = getint(2) & 0xFFFF
            getint(2)
            getint(2)
            rad = (crad + 0.5) * (math.pi / 65536.0)  # R2ANG in src/cv/bsdfrep.h
            volume = peak * rad * rad
            x, y = xy_of_uv((chroma & 0xFF) / 410.0, (chroma >> 8 & 0xFF) / 410.0)
            total[0] += volume * x / y
            total[1] += volume
            total[2] += volume * (1.0 - x - y) / y
        s = sum(total)
        nodes.append(
            {
                "incidence": [
                    math.degrees(math.acos(max(-1.0, min(1.0, invec[2])))),
                    math.degrees(math.atan2(invec[1], invec[0])) % 360.0,
                ],
                "count": count,
                "xy": [total[0] / s, total[1] / s] if s > 0 else None,
            }
        )
    return (colorimetry.group(1) if colorimetry else None), nodes


def tree_xy(path):
    text = open(path).read()
    leaves = {}
    for block in re.findall(r"<WavelengthData>(.*?)</WavelengthData>", text, re.S):
        name = re.search(r"<Wavelength[^>]*>([^<]*)</Wavelength>", block).group(1).strip()
        if name in ("CIE-u", "CIE-v"):
            data = re.search(r"<ScatteringData>(.*?)</ScatteringData>", block, re.S).group(1)
            # The dead half of an isotropic tree (incidences it does not use) holds zeros.
            leaves[name] = [float(t) for t in re.findall(r"[-+0-9.eE]+", data) if float(t) > 0]
    if len(leaves) < 2:
        return None
    return xy_of_uv(statistics.median(leaves["CIE-u"]), statistics.median(leaves["CIE-v"]))


colorimetry, lobes = read_sir(sir)
sd = rbsdf.load_file(os.path.abspath(xml))
values, query_xy = [], []
for theta_l, phi_l, theta_v, phi_v in queries["pairs"]:
    xyz = rbsdf.query(sd, theta_l, phi_l, theta_v, phi_v)
    values.append(float(xyz[1]))
    s = float(sum(xyz))
    query_xy.append([float(xyz[0]) / s, float(xyz[1]) / s] if s > 0 else None)
flags = rbsdf.SAMPLE_R | rbsdf.SAMPLE_DF | rbsdf.SAMPLE_SP
dhr = [rbsdf.direct_hemi(sd, t, 0.0, flags) for t in queries["dhr_theta"]]
print(
    json.dumps(
        {
            "pyradiance": importlib.metadata.version("pyradiance"),
            "colorimetry": colorimetry,
            "lobes": lobes,
            "tree_xy": tree_xy(xml),
            "y": values,
            "query_xy": query_xy,
            "dhr": dhr,
        }
    )
)
