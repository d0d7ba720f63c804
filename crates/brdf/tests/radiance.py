"""Run Radiance's own tools on the PAB-Opto files gonio wrote and report what Radiance makes of
them. The tools come from PyPI's pyradiance (`pip install pyradiance`), which ships the
Radiance binaries and a binding of its BSDF library.

Usage: python3 radiance.py DIR QUERIES.json

DIR holds the .dat files, one per incidence. QUERIES.json is
  {"pairs": [[theta_light, phi_light, theta_view, phi_view], ...], "dhr_theta": [...]}
with angles in degrees, and optionally
  "pabopto2bsdf": [options], "bsdf2ttree": [options]: added to those commands (e.g. ["-g", "6"],
      ["-g", "5"]); without them Radiance's defaults;
  "render": [[theta_light, phi_light, theta_view, phi_view], ...]: pairs rendered by rtrace;
  "grid_lambert": {"albedo": a, "step_deg": s, "max_theta_deg": t, "incidences_deg": [...]}:
      instead of DIR's files, PAB-Opto files of a Lambertian that this script writes itself, the
      way a goniophotometer records (every s degrees in theta and in phi up to t), into
      DIR/grid_lambert (an independent table: gonio writes none of it);
  "floor_file": {"theta_deg": t, "value": v}: one more file, at incidence t, every direction
      holding v (written into DIR/floor, on a 2.5 degree grid): it lowers the BSDF minimum that
      pabopto2bsdf takes from the first percentile of all values (below);
  "function": "expr": no files; bsdf2ttree tabulates bsdf(ix,iy,iz,ox,oy,oz) = expr itself
      (its -t3 -e input, e.g. "0.5/PI"), which skips pabopto2bsdf's interpolant;
  "xml": path: no files and no conversion: the XML BSDF gonio wrote itself
      (formats::radiance_xml, a tensor tree), read as it is;
  "picture": {"scene": text, "view": [rpict view options], "resolution": n, "output": path}:
      the Radiance scene (text of a .rad file, which names the XML) rendered by rpict, n x n
      pixels, direct light only (-ab 0), into the Radiance picture `output`.
The script runs `pabopto2bsdf DIR/*.dat > DIR/radiance.sir` and `bsdf2ttree DIR/radiance.sir >
DIR/radiance.xml` (by default a 64 x 64 tensor tree per incidence, 90% culling) and prints one
JSON object:
  "pyradiance": its version;
  "colorimetry": the COLORIMETRY line of the interpolant's header (CIE-Y or CIE-XYZ);
  "bsdf_min": the BSDFMIN line of that header (the value Radiance never goes below);
  "lobes": per incidence of the interpolant (pabopto2bsdf's radial basis functions, the binary
           format of save_bsdf_rep in Radiance src/cv/bsdfrep.c): the incidence [theta, phi]
           in degrees, the number of lobes and their chromaticity [x, y]: the lobes' (u', v')
           codes (8 bits each at 1/410, c_decodeChroma in src/common/ccolor.c) turned into
           X, Y, Z weighted by each lobe's volume (peak times radius squared) and summed;
  "tree_xy": the chromaticity of the median u' and v' leaves of bsdf2ttree's CIE-u and CIE-v
             trees (null without colour);
  "y": per pair, the BSDF (Y, 1/sr) that Radiance's BSDF library returns (SDevalBSDF through
       pyradiance.bsdf.query) for light from (theta_light, phi_light) seen from
       (theta_view, phi_view), in the order Radiance's renderer passes them (below);
  "query_xy": per pair, the chromaticity that pyradiance.bsdf.query reports;
  "rendered": per "render" pair, the BSDF (Y, 1/sr) that rtrace renders (below);
  "rendered_xyz": per "render" pair, the same as CIE XYZ: rtrace's RGB turned into XYZ by
       Radiance's own primaries (src/common/color.h: CIE_x_r 0.640, CIE_y_r 0.330, green
       0.290, 0.600, blue 0.150, 0.060, white the equal-energy x = y = 1/3);
  "dhr": per dhr_theta, the directional-hemispherical reflectance (Y) of the tensor tree for
         the tree's incidence at (theta, 0) (SDdirectHemi, all reflection components): the
         integral over the tree's outgoing directions, which the renderer takes for the lights.
Exit status 77 when pyradiance is not installed, so the caller can skip.

Which direction is which. pyradiance.bsdf.query(sd, t1, p1, t2, p2) calls SDevalBSDF(sv, vec(t1,
p1), vec(t2, p2), sd) (pyradiance src/binding/bsdf_ext.cpp); the first direction indexes the
tensor tree's incidence, where bsdf2ttree puts pabopto2bsdf's incidences, the files'
#intheta/#inphi (a tree of bsdf = iz returns cos t1). Radiance's renderer passes the direction
toward the viewer first and the one toward the light second (src/rt/m_bsdf.c, dir_bsdf:
SDevalBSDF(&sv, vjit, vsmp, sd), the jittered ray and source directions): rtrace, lighting a
plane of the BSDF material with a distant source, returns query(view, light), so a table whose
value grows with the file's incidence brightens with the viewing angle. Radiance thus renders
the files' incidence as the view, which needs reciprocity (f(light, view) = f(view, light)), and
the "pairs" here are evaluated the way it renders: query(sd, theta_view, phi_view, theta_light,
phi_light).
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


def write_pabopto(path, theta_in, directions, value):
    """One PAB-Opto file (the header pabopto2bsdf reads, src/cv/pabopto2bsdf.c) holding `value`
    at every (theta, phi) of `directions`."""
    with open(path, "w") as f:
        f.write('#sample_name "independent"\n#format: theta phi BSDF\n#colorimetry: CIE-Y\n')
        f.write(f"#upphi 90\n#intheta {theta_in}\n#inphi 0\n")
        for theta, phi in directions:
            f.write(f"{theta:.4f} {phi:.4f} {value:.6e}\n")


def grid(step, max_theta):
    """A goniophotometer's grid: the pole, then every `step` degrees in theta up to
    `max_theta`, every `step` degrees in phi."""
    out = [(0.0, 0.0)]
    rings = int(round(max_theta / step))
    azimuths = int(round(360.0 / step))
    for i in range(1, rings + 1):
        out += [(i * step, j * 360.0 / azimuths) for j in range(azimuths)]
    return out


ttree = [os.path.join(binpath, "bsdf2ttree"), *queries.get("bsdf2ttree", [])]
sir = os.path.join(directory, "radiance.sir")
xml = os.path.join(directory, "radiance.xml")
if "xml" in queries:
    # gonio's own tensor tree: nothing to convert.
    xml = queries["xml"]
    sir = None
elif "function" in queries:
    # bsdf2ttree's own tabulation of a function (-t3: isotropic), no interpolant.
    expr = f"bsdf(ix,iy,iz,ox,oy,oz)={queries['function']};"
    run([*ttree, "-t3", "-e", expr, "bsdf"], xml)
    sir = None
else:
    if "grid_lambert" in queries:
        lam = queries["grid_lambert"]
        source = os.path.join(directory, "grid_lambert")
        os.makedirs(source, exist_ok=True)
        directions = grid(lam["step_deg"], lam["max_theta_deg"])
        for t in lam["incidences_deg"]:
            path = os.path.join(source, f"lambert_t{t}.dat")
            write_pabopto(path, t, directions, lam["albedo"] / math.pi)
    else:
        source = directory
    files = sorted(glob.glob(os.path.join(source, "*.dat")))
    if "floor_file" in queries:
        floor = queries["floor_file"]
        os.makedirs(os.path.join(directory, "floor"), exist_ok=True)
        path = os.path.join(directory, "floor", "floor.dat")
        write_pabopto(path, floor["theta_deg"], grid(2.5, 87.5), floor["value"])
        files.append(path)
    p2b = [os.path.join(binpath, "pabopto2bsdf"), *queries.get("pabopto2bsdf", [])]
    run([*p2b, *files], sir)
    run([*ttree, sir], xml)


def xy_of_uv(u, v):
    d = 6.0 * u - 16.0 * v + 12.0
    return [9.0 * u / d, 4.0 * v / d]


def read_sir(path):
    """Header colorimetry and BSDF minimum and, per incidence, the lobes of pabopto2bsdf's
    interpolant."""
    data = open(path, "rb").read()
    end = data.index(b"\n\n") + 2
    header = data[:end].decode(errors="replace")
    colorimetry = re.search(r"COLORIMETRY=(\S+)", header)
    bsdf_min = re.search(r"BSDFMIN=(\S+)", header)
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
    return (
        (colorimetry.group(1) if colorimetry else None),
        (float(bsdf_min.group(1)) if bsdf_min else None),
        nodes,
    )


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


def vec(theta, phi):
    t, p = math.radians(theta), math.radians(phi)
    return (math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t))


def render(pairs):
    """The BSDF that rtrace renders for each pair: a plane of the BSDF material (up vector +y,
    the frame of the files' #upphi 90) at z = 0 under a distant source of radiance R and
    half-angle 0.25 degrees toward the light, one ray from the viewer, direct light only (-ab 0,
    and -ss 0: no specular sample rays, which would take a share of the BSDF's weight) and one
    sample of the source (-dj 0, -ds 0). Its radiance is f R omega cos(theta_light),
    omega the source's solid angle, whence f. rtrace gives RGB; the tree is photometric (Y),
    so every pair is grey and Y is any channel (the mean is taken)."""
    if not pairs:
        return []
    radiance, half_angle = 1000.0, 0.25
    omega = 2.0 * math.pi * (1.0 - math.cos(math.radians(half_angle)))
    scene_dir = os.path.join(directory, "render")
    os.makedirs(scene_dir, exist_ok=True)
    out = []
    for theta_l, phi_l, theta_v, phi_v in pairs:
        s = vec(theta_l, phi_l)
        scene = os.path.join(scene_dir, "scene.rad")
        with open(scene, "w") as f:
            f.write(f"void light bright 0 0 3 {radiance} {radiance} {radiance}\n")
            f.write(f"bright source sun 0 0 4 {s[0]} {s[1]} {s[2]} {2 * half_angle}\n")
            f.write(f"void BSDF mat 6 0 {os.path.abspath(xml)} 0 1 0 . 0 0\n")
            f.write("mat polygon floor 0 0 12 -100 -100 0 100 -100 0 100 100 0 -100 100 0\n")
        octree = os.path.join(scene_dir, "scene.oct")
        run([os.path.join(binpath, "oconv"), scene], octree)
        v = vec(theta_v, phi_v)
        ray = f"{10 * v[0]} {10 * v[1]} {10 * v[2]} {-v[0]} {-v[1]} {-v[2]}\n"
        options = ["-h", "-ab", "0", "-ss", "0", "-dj", "0", "-ds", "0", "-ov"]
        done = subprocess.run(
            [os.path.join(binpath, "rtrace"), *options, octree],
            input=ray.encode(),
            capture_output=True,
            env=env,
        )
        if done.returncode != 0:
            sys.stderr.write(done.stderr.decode(errors="replace"))
            sys.exit(f"rtrace failed with status {done.returncode}")
        rgb = [float(x) for x in done.stdout.split()[:3]]
        scale = radiance * omega * math.cos(math.radians(theta_l))
        out.append([sum(m * c for m, c in zip(row, rgb)) / scale for row in RGB_TO_XYZ])
    return out


def rgb_to_xyz():
    """Radiance's RGB -> XYZ matrix: the primaries' XYZ (x/y, 1, z/y) scaled so that RGB
    (1, 1, 1) is the equal-energy white X = Y = Z = 1."""
    prims = [(0.640, 0.330), (0.290, 0.600), (0.150, 0.060)]
    cols = [[x / y, 1.0, (1.0 - x - y) / y] for x, y in prims]
    # Solve cols^T s = (1, 1, 1) for the scales s (Cramer's rule on the 3 x 3 system).
    m = [[cols[c][r] for c in range(3)] for r in range(3)]

    def det(a):
        return (
            a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
        )

    d = det(m)
    s = []
    for c in range(3):
        mc = [[1.0 if k == c else m[r][k] for k in range(3)] for r in range(3)]
        s.append(det(mc) / d)
    return [[m[r][c] * s[c] for c in range(3)] for r in range(3)]


RGB_TO_XYZ = rgb_to_xyz()


def picture(spec):
    """Render spec["scene"] with rpict (direct light only, no jitter) into spec["output"]."""
    scene_dir = os.path.join(directory, "picture")
    os.makedirs(scene_dir, exist_ok=True)
    scene = os.path.join(scene_dir, "scene.rad")
    with open(scene, "w") as f:
        f.write(spec["scene"])
    octree = os.path.join(scene_dir, "scene.oct")
    run([os.path.join(binpath, "oconv"), scene], octree)
    n = str(spec["resolution"])
    options = ["-ab", "0", "-ss", "0", "-dj", "0", "-ds", "0", "-ps", "1", "-pj", "0"]
    run(
        [os.path.join(binpath, "rpict"), *spec["view"], "-x", n, "-y", n, *options, octree],
        spec["output"],
    )


colorimetry, bsdf_min, lobes = read_sir(sir) if sir else (None, None, [])
if "picture" in queries:
    picture(queries["picture"])
sd = rbsdf.load_file(os.path.abspath(xml))
values, query_xy, query_xyz = [], [], []
for theta_l, phi_l, theta_v, phi_v in queries["pairs"]:
    # The viewer first, the light second: the order of Radiance's renderer (see the top).
    xyz = rbsdf.query(sd, theta_v, phi_v, theta_l, phi_l)
    values.append(float(xyz[1]))
    query_xyz.append([float(v) for v in xyz])
    s = float(sum(xyz))
    query_xy.append([float(xyz[0]) / s, float(xyz[1]) / s] if s > 0 else None)
rendered = render(queries.get("render", []))
flags = rbsdf.SAMPLE_R | rbsdf.SAMPLE_DF | rbsdf.SAMPLE_SP
dhr = [rbsdf.direct_hemi(sd, t, 0.0, flags) for t in queries["dhr_theta"]]
print(
    json.dumps(
        {
            "pyradiance": importlib.metadata.version("pyradiance"),
            "colorimetry": colorimetry,
            "bsdf_min": bsdf_min,
            "lobes": lobes,
            "tree_xy": None if "xml" in queries else tree_xy(xml),
            "y": values,
            "query_xy": query_xy,
            "query_xyz": query_xyz,
            "rendered": [xyz[1] for xyz in rendered],
            "rendered_xyz": rendered,
            "dhr": dhr,
        }
    )
)
