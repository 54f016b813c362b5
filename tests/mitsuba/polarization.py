"""Cross-checks raylab's polarisation against Mitsuba 3's polarised path tracer.

A glass sphere (n = 1.5) between two emitting panels, black elsewhere (polarization.toml
here): raylab renders it through polarisers at 0, 45, 90 and 135 degrees, giving the
Stokes components S0 = I0 + I90, S1 = I0 - I90, S2 = I45 - I135 in the image's frame;
Mitsuba 3's `stokes` integrator renders S0..S3 directly. The degrees of linear
polarisation S1/S0 and S2/S0 are compared pixel by pixel (green channel).

    pip install mitsuba==3.9.1 numpy
    cargo build --release
    python tests/mitsuba/polarization.py [target/release/raylab]
"""

import pathlib
import subprocess
import sys
import tempfile

import mitsuba as mi
import numpy as np

here = pathlib.Path(__file__).parent
raylab = sys.argv[1] if len(sys.argv) > 1 else "target/release/raylab"

mi.set_variant("scalar_spectral_polarized")
T = mi.ScalarTransform4f
panel = {"type": "area", "radiance": {"type": "uniform", "value": 1.0}}
scene = mi.load_dict({
    "type": "scene",
    "integrator": {"type": "stokes", "integrator": {"type": "path", "max_depth": 17}},
    "sensor": {
        "type": "perspective", "fov": 30, "fov_axis": "y",
        "to_world": T().look_at(origin=[0, 0, 4], target=[0, 0, 0], up=[0, 1, 0]),
        "film": {"type": "hdrfilm", "width": 64, "height": 64, "rfilter": {"type": "box"}},
        "sampler": {"type": "independent", "sample_count": 4096},
    },
    "back": {"type": "rectangle", "emitter": panel,
             "to_world": T().translate([0, 1.5, -3]) @ T().scale([3, 1.5, 1])},
    "top": {"type": "rectangle", "emitter": panel,
            "to_world": T().translate([0, 3, 0]) @ T().rotate([1, 0, 0], 90) @ T().scale([2, 2, 1])},
    "sphere": {"type": "sphere", "center": [0, 0, 0], "radius": 1.0,
               "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0}},
})
m = np.array(mi.render(scene))
# Channels: R, G, B, then S0..S3 each as R, G, B.
s0m, s1m, s2m = m[:, :, 4], m[:, :, 7], m[:, :, 10]

images = {}
with tempfile.TemporaryDirectory() as tmp:
    for angle in (0, 45, 90, 135):
        out = pathlib.Path(tmp) / f"r{angle}.exr"
        subprocess.run([raylab, "render", str(here / "polarization.toml"), "-o", str(out), "-q",
                        "--set", f"polarizer={angle}"], check=True)
        images[angle] = np.array(mi.Bitmap(str(out)))[:, :, 1]
s0r = images[0] + images[90]
s1r = images[0] - images[90]
s2r = images[45] - images[135]

lit = (s0m > 0.05) & (s0r > 0.05)
np.seterr(divide="ignore", invalid="ignore")  # unlit pixels are left out by `lit`
for name, ours, theirs in (("S1/S0", s1r / s0r, s1m / s0m), ("S2/S0", s2r / s0r, s2m / s0m)):
    d = (ours - theirs)[lit]
    print(f"{name}: mean |raylab - Mitsuba| {np.abs(d).mean():.4f}, "
          f"mean |value| {np.abs(theirs[lit]).mean():.4f}, mean difference {d.mean():+.4f}")
print(f"S0 ratio (Mitsuba's white is {s0m[0, 0]:.4f}): {s0m[lit].mean() / s0r[lit].mean():.4f}")
