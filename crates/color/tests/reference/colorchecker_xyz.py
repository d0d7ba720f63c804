"""Independent reference XYZ of the 24 ColorChecker patches for crates/color/tests/it/colorchecker.rs.

Run from the repository root with colour-science 0.4.7 (pip install colour-science; numpy only,
no scipy needed):

    python crates/color/tests/reference/colorchecker_xyz.py

Inputs are the same tables gonio embeds (crates/color/data/): the CIE 1931 2-degree and 1964
10-degree colour-matching functions and illuminants D65 and A at 1 nm (360-830 nm), and N. Ohta's
ColorChecker reflectances at 5 nm (380-780 nm).

Method (CIE 15:2004 section 7.1), all done by colour-science:
  * each reflectance is interpolated to 1 nm with colour's LinearInterpolator, then extended to
    360-830 nm with colour's Extrapolator in "Constant" mode (the end values are held: CIE 15:2004
    7.2.2.1);
  * colour.sd_to_XYZ(..., method="Integration") sums S * R * cmf at 1 nm with
    k = 100 / sum(S * ybar), so the perfect reflecting diffuser has Y = 100.
For comparison it also prints colour-science's default method (ASTM E308-15 tristimulus
weighting factors for 5 nm data, i.e. Lagrange interpolation of the weights), which the Rust
tests do not use.
"""

import pathlib
import warnings

import numpy as np

warnings.filterwarnings("ignore")
import colour  # noqa: E402
from colour.algebra import Extrapolator, LinearInterpolator  # noqa: E402

DATA = pathlib.Path(__file__).resolve().parents[2] / "data"


def cmfs(name, file):
    table = np.loadtxt(DATA / file, delimiter=",")
    return colour.colorimetry.XYZ_ColourMatchingFunctions(
        table[:, 1:], table[:, 0], name=name, labels=("x_bar", "y_bar", "z_bar")
    )


def illuminant(name, file):
    table = np.loadtxt(DATA / file, delimiter=",")
    return colour.SpectralDistribution(table[:, 1], table[:, 0], name=name)


OBSERVERS = {2: cmfs("CIE 1931 2", "ciexyz_1931_2.dat"), 10: cmfs("CIE 1964 10", "ciexyz_1964_10.dat")}
ILLUMINANTS = {"D65": illuminant("D65", "CIE_D65.csv"), "A": illuminant("A", "CIE_A.csv")}
FULL = colour.SpectralShape(360, 830, 1)

checker = np.loadtxt(DATA / "MacbethColorChecker.dat", delimiter=",")
wavelengths = checker[:, 0]


def patch_sd(p):
    sd = colour.SpectralDistribution(checker[:, p], wavelengths, name=f"patch {p}")
    sd.interpolate(colour.SpectralShape(380, 780, 1), interpolator=LinearInterpolator)
    sd.extrapolate(FULL, extrapolator=Extrapolator, extrapolator_kwargs={"method": "Constant"})
    assert sd.shape == FULL
    return sd


for ill_name, obs_deg in [("D65", 2), ("D65", 10), ("A", 2)]:
    cmf, ill = OBSERVERS[obs_deg], ILLUMINANTS[ill_name]
    white = colour.sd_to_XYZ(colour.sd_ones(FULL), cmf, ill, method="Integration")
    print(f"// {ill_name}, {obs_deg} deg observer: white {white.round(6).tolist()}")
    print(f"const XYZ_{ill_name}_{obs_deg}DEG: [[f64; 3]; 24] = [")
    for p in range(1, 25):
        xyz = colour.sd_to_XYZ(patch_sd(p), cmf, ill, method="Integration")
        print(f"    [{xyz[0]:.6f}, {xyz[1]:.6f}, {xyz[2]:.6f}],")
    print("];")
    if (ill_name, obs_deg) == ("D65", 2):
        xy_white = colour.XYZ_to_xy(white)
        for p in (1,):
            xyz = colour.sd_to_XYZ(patch_sd(p), cmf, ill, method="Integration")
            lab = colour.XYZ_to_Lab(xyz / 100, xy_white)
            print(f"// patch {p} Lab: {lab.round(4).tolist()}")
        worst = 0.0
        for p in range(1, 25):
            sd5 = colour.SpectralDistribution(checker[:, p], wavelengths)
            e308 = colour.sd_to_XYZ(sd5, cmf, ill)  # default: ASTM E308 weighting factors
            lin = colour.sd_to_XYZ(patch_sd(p), cmf, ill, method="Integration")
            worst = max(worst, np.abs(e308 - lin).max())
        print(f"// largest |ASTM E308 (5 nm) - linear 1 nm| over the 24 patches: {worst:.4f}")
