"""Cross-checks raylab's path tracer (transport = "path") against Mitsuba 3's.

path.toml here: glass, mirror and diffuse spheres on a diffuse floor under a rectangle
light, black elsewhere. Mitsuba 3 (scalar_rgb, its `path` integrator) renders the same
scene; each renderer renders it twice with different seeds, and the halves' difference
gives each pixel's noise. Printed: the mean difference of the images with its standard
error, and per 8 x 8 block how many differ by more than 3 standard errors (noise alone
puts about 0.3 % of blocks there).

raylab's max_depth counts bounces and gathers light at the last one: its paths have up
to max_depth + 2 segments, Mitsuba's max_depth + 2 = 10 segments here.

With a ROUGHNESS above 0 the glass sphere is rough glass: raylab's `roughness`, Mitsuba's
`roughdielectric` (GGX, the same α, visible normals sampled). MAX_DEPTH is raylab's
(Mitsuba's is 2 more): rough glass traps light inside for many bounces, and where the two
count the last of a long path differently a deep limit keeps that apart from the surface.

    pip install mitsuba==3.9.1 numpy
    cargo build --release
    python tests/mitsuba/path.py [target/release/raylab] [SPP] [ROUGHNESS] [MAX_DEPTH]
"""

import pathlib
import subprocess
import sys
import tempfile

import mitsuba as mi
import numpy as np

here = pathlib.Path(__file__).parent
raylab = sys.argv[1] if len(sys.argv) > 1 else "target/release/raylab"
spp = int(sys.argv[2]) if len(sys.argv) > 2 else 2048
roughness = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
max_depth = int(sys.argv[4]) if len(sys.argv) > 4 else 8

mi.set_variant("scalar_rgb")
T = mi.ScalarTransform4f


def diffuse(r, g, b):
    return {"type": "diffuse", "reflectance": {"type": "rgb", "value": [r, g, b]}}


scene = mi.load_dict({
    "type": "scene",
    "integrator": {"type": "path", "max_depth": max_depth + 2},
    "sensor": {
        "type": "perspective", "fov": 40, "fov_axis": "y",
        "to_world": T().look_at(origin=[0, 1.6, 6], target=[0, 0.7, 0], up=[0, 1, 0]),
        "film": {"type": "hdrfilm", "width": 96, "height": 72, "rfilter": {"type": "box"}},
        "sampler": {"type": "independent", "sample_count": spp},
    },
    # Mitsuba's rectangle spans [-1, 1]^2 in z = 0 facing +z; turned to face down.
    "light": {"type": "rectangle",
              "to_world": T().translate([0, 3.5, 0]) @ T().rotate([1, 0, 0], 90)
              @ T().scale([0.75, 0.75, 1]),
              "emitter": {"type": "area", "radiance": {"type": "rgb", "value": 20 / 1.5**2}},
              "bsdf": diffuse(0, 0, 0)},  # raylab's lights reflect nothing
    "floor": {"type": "rectangle",
              "to_world": T().rotate([1, 0, 0], -90) @ T().scale([10, 10, 1]),
              "bsdf": diffuse(0.6, 0.6, 0.6)},
    "clay": {"type": "sphere", "center": [-1.6, 0.7, 0], "radius": 0.7,
             "bsdf": diffuse(0.7, 0.3, 0.2)},
    "mirror": {"type": "sphere", "center": [0, 0.7, -0.8], "radius": 0.7,
               "bsdf": {"type": "conductor", "material": "none",
                        "specular_reflectance": {"type": "rgb", "value": 0.9}}},
    "glass": {"type": "sphere", "center": [1.6, 0.7, 0], "radius": 0.7,
              "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0} if roughness == 0
              else {"type": "roughdielectric", "distribution": "ggx", "alpha": roughness,
                    "sample_visible": True, "int_ior": 1.5, "ext_ior": 1.0}},
})

mitsuba = [np.array(mi.render(scene, seed=s))[:, :, :3] for s in (1, 2)]
ours = []
with tempfile.TemporaryDirectory() as tmp:
    for s in (1, 2):
        out = pathlib.Path(tmp) / f"r{s}.exr"
        subprocess.run([raylab, "render", str(here / "path.toml"), "-o", str(out), "-q",
                        "--set", f"seed={s}", "--set", f"spp={spp}",
                        "--set", f"roughness={roughness}", "--set", f"max_depth={max_depth}"],
                       check=True)
        ours.append(np.array(mi.Bitmap(str(out)))[:, :, :3])


def full_and_variance(halves):
    a, b = halves
    return (a + b) / 2, (a - b) ** 2 / 4


r, vr = full_and_variance(ours)
m, vm = full_and_variance(mitsuba)
d = r - m
se = np.sqrt((vr + vm).sum()) / d.size
print(f"image mean: raylab {r.mean():.5f}, Mitsuba {m.mean():.5f}")
print(f"mean difference {d.mean():+.6f}, standard error {se:.6f} "
      f"({d.mean() / se:+.2f} standard errors)")
blocks = 0
outliers = 0
for y in range(0, d.shape[0], 8):
    for x in range(0, d.shape[1], 8):
        db = d[y:y + 8, x:x + 8]
        seb = np.sqrt((vr + vm)[y:y + 8, x:x + 8].sum()) / db.size
        blocks += 1
        if seb > 0 and abs(db.mean()) > 3 * seb:
            outliers += 1
            print(f"  block at ({x}, {y}): {db.mean():+.5f} ({db.mean() / seb:+.1f} se), "
                  f"Mitsuba mean {m[y:y + 8, x:x + 8].mean():.5f}")
print(f"{outliers} of {blocks} blocks beyond 3 standard errors")
