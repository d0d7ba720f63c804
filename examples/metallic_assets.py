#!/usr/bin/env python3
"""Generate the two procedural assets of examples/metallic.toml (standard library only):

- studio.hdr: a 256 x 128 equirectangular Radiance RGBE environment (+y up, the renderer's
  mapping: row v = theta/pi from the zenith, column u = phi/2pi). Above the horizon a sky
  gradient (radiance 0.25 at the horizon to 0.6 at the zenith, slightly blue); below it a dark
  floor (0.04); a large softbox (radiance 6, theta 25-55 deg, phi 60-120 deg, in front of and
  above the objects) and a wide low softbox behind the objects (radiance 3, theta 58-78 deg, phi 245-295 deg) that
  the panel mirrors toward the camera. The softboxes give the near-specular colour, the sky the
  far-from-specular "flop" colour.
- panel.obj: a curved panel like a car bonnet, 2.4 m x 1.6 m, bent about both axes
  (y = -0.35 (x/1.2)^2 - 0.15 (z/0.8)^2), 32 x 20 quads split into triangles, with the analytic
  normals, so that the viewing and lighting angles sweep across it.

Run from the repository root: python3 examples/metallic_assets.py
"""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def radiance(theta, phi):
    """RGB radiance (W m^-2 sr^-1) of the studio in the direction (theta from +y, phi)."""
    deg_t, deg_p = math.degrees(theta), math.degrees(phi) % 360.0
    if 25.0 <= deg_t <= 55.0 and 60.0 <= deg_p <= 120.0:
        return (6.0, 6.0, 6.0)
    if 58.0 <= deg_t <= 78.0 and 245.0 <= deg_p <= 295.0:
        return (3.0, 3.0, 3.0)
    if deg_t > 90.0:
        return (0.04, 0.04, 0.04)
    s = 0.25 + 0.35 * math.cos(theta)
    return (0.9 * s, 0.95 * s, 1.1 * s)


def rgbe(rgb):
    """One Radiance RGBE pixel (Ward, Graphics Gems II, 'Real pixels')."""
    m = max(rgb)
    if m < 1e-32:
        return bytes(4)
    mant, exp = math.frexp(m)
    scale = mant * 256.0 / m
    return bytes([int(c * scale) for c in rgb] + [exp + 128])


def write_hdr(path, width=256, height=128):
    rows = []
    for j in range(height):
        theta = (j + 0.5) / height * math.pi
        row = b"".join(
            rgbe(radiance(theta, (i + 0.5) / width * 2.0 * math.pi)) for i in range(width)
        )
        rows.append(row)
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\n# examples/metallic_assets.py: procedural studio\n")
        f.write(b"FORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {height} +X {width}\n".encode())
        for row in rows:
            f.write(row)


def write_panel(path, nx=32, nz=20, half_x=1.2, half_z=0.8):
    def height(x, z):
        return -0.35 * (x / half_x) ** 2 - 0.15 * (z / half_z) ** 2

    def normal(x, z):
        dx = -0.7 * x / half_x**2
        dz = -0.3 * z / half_z**2
        n = (-dx, 1.0, -dz)
        length = math.sqrt(sum(c * c for c in n))
        return tuple(c / length for c in n)

    lines = ["# examples/metallic_assets.py: curved panel (car-bonnet-like), metres"]
    for j in range(nz + 1):
        z = -half_z + 2.0 * half_z * j / nz
        for i in range(nx + 1):
            x = -half_x + 2.0 * half_x * i / nx
            lines.append(f"v {x:.5f} {height(x, z):.5f} {z:.5f}")
            lines.append("vn {:.5f} {:.5f} {:.5f}".format(*normal(x, z)))
    for j in range(nz):
        for i in range(nx):
            a = j * (nx + 1) + i + 1
            b, c, d = a + 1, a + nx + 1, a + nx + 2
            # Counter-clockwise seen from +y.
            lines.append(f"f {a}//{a} {c}//{c} {b}//{b}")
            lines.append(f"f {b}//{b} {c}//{c} {d}//{d}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    write_hdr(os.path.join(HERE, "studio.hdr"))
    write_panel(os.path.join(HERE, "panel.obj"))
