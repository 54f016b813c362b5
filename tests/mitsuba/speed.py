"""raylab's speed against Mitsuba 3's on the same two scenes, at equal work: samples per
second at 320 x 240, 64 spp, 2 threads, box filter, each renderer run in turn.

speed-glass.toml: a glass sphere (IOR 1.5) before an emitting checkerboard of square
cells (one quad). speed-dof.toml: three emitting checkerboards at 3, 6 and 10 units seen
through a thin lens of radius 0.2 focused at 6. raylab traces one branch per hit
(tree = "stochastic"), as a path tracer does; Mitsuba runs its `path` integrator with
max_depth 10 (raylab's max_depth 8 counts bounces; see path.py), `llvm_ad_rgb` (JIT,
the CPU's widest vectors) after one warm-up render so that its compile is not timed.

    apt-get install libllvm19    # Dr.Jit's LLVM back end needs 19 on Debian 12
    pip install mitsuba==3.9.1 drjit==1.5.0 numpy
    cargo build --release
    python tests/mitsuba/speed.py [target/release/raylab] [RUNS] [SAMPLER]

SAMPLER is Mitsuba's sampler, `independent` (the default) or `multijitter`.
Printed: each scene's image mean in both (the same work: they agree within noise), each
renderer's median samples per second, their ratio, and the machine's load average.
"""

import os
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile
import time

import drjit as dr
import mitsuba as mi
import numpy as np

here = pathlib.Path(__file__).parent
raylab = sys.argv[1] if len(sys.argv) > 1 else "target/release/raylab"
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
sampler = sys.argv[3] if len(sys.argv) > 3 else "independent"
width, height, spp = 320, 240, 64

mi.set_variant("llvm_ad_rgb")
dr.set_thread_count(2)
T = mi.ScalarTransform4f


def board(center, size, cells, color0, color1):
    """An emitting rectangle of `size`, `cells` checks along each side (raylab's `scale`
    on a quad): Mitsuba's checkerboard has 2 x 2 checks per unit of uv."""
    return {
        "type": "rectangle",
        "to_world": T().translate(center) @ T().scale([size[0] / 2, size[1] / 2, 1]),
        "emitter": {"type": "area", "radiance": {
            "type": "checkerboard",
            "color0": {"type": "rgb", "value": color0},
            "color1": {"type": "rgb", "value": color1},
            "to_uv": mi.ScalarTransform3f().scale([cells[0] / 2, cells[1] / 2]),
        }},
    }


def sensor(lens):
    s = {
        "to_world": T().look_at(origin=[0, 0, 6], target=[0, 0, 0], up=[0, 1, 0]),
        "fov": 40, "fov_axis": "y",
        "film": {"type": "hdrfilm", "width": width, "height": height,
                 "rfilter": {"type": "box"}},
        "sampler": {"type": sampler, "sample_count": spp},
    }
    if lens:
        s.update({"type": "thinlens", "aperture_radius": 0.2, "focus_distance": 6.0})
    else:
        s["type"] = "perspective"
    return s


scenes = {
    "glass": {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 10},
        "sensor": sensor(lens=False),
        "board": board([0, 0, -4], [16, 12], [16, 12], [1, 0.95, 0.9], [0.05, 0.1, 0.3]),
        "glass": {"type": "sphere", "center": [0, 0, 0], "radius": 1.3,
                  "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0}},
    },
    "dof": {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 10},
        "sensor": sensor(lens=True),
        "near": board([-1.4, -0.1, 3], [1.6, 1.6], [4, 4], [1, 0.3, 0.2], [0.1, 0.05, 0.02]),
        "middle": board([0.4, 0, 0], [3.2, 3.2], [8, 8], [0.9, 0.9, 0.85], [0.05, 0.05, 0.1]),
        "far": board([0, 0, -4], [16, 12], [16, 12], [0.2, 0.4, 1], [0.02, 0.04, 0.1]),
    },
}


def mitsuba_seconds(scene, seed):
    """Seconds for one render, and its image (evaluated: Dr.Jit launches lazily)."""
    start = time.perf_counter()
    image = mi.render(scene, spp=spp, seed=seed)
    dr.eval(image)
    dr.sync_thread()
    return time.perf_counter() - start, image


def raylab_seconds(name, out):
    o = subprocess.run([raylab, "render", str(here / f"speed-{name}.toml"), "-o", out,
                        "--threads", "2"], check=True, capture_output=True, text=True)
    # The summary line: "NAME WxH at N spp: S s, ..."
    return float(re.search(r"spp: ([0-9.]+) s", o.stderr).group(1))


samples = width * height * spp
with tempfile.TemporaryDirectory() as tmp:
    for name, d in scenes.items():
        scene = mi.load_dict(d)
        mitsuba_seconds(scene, 0)  # the JIT compiles here
        ours, theirs = [], []
        out = os.path.join(tmp, f"{name}.exr")
        for run in range(runs):
            ours.append(raylab_seconds(name, out))
            seconds, image = mitsuba_seconds(scene, run + 1)
            theirs.append(seconds)
        # The same work: the two images agree within noise.
        a = np.array(mi.Bitmap(out))[:, :, :3]
        b = np.array(image)[:, :, :3]
        print(f"{name}: image mean raylab {a.mean():.4f}, Mitsuba {b.mean():.4f}")
        r = samples / statistics.median(ours) / 1e6
        m = samples / statistics.median(theirs) / 1e6
        print(f"{name}: raylab {r:.1f} M samples/s, Mitsuba ({sampler}) {m:.1f} M "
              f"samples/s: {r / m:.2f}x  (raylab {min(ours):.3f}-{max(ours):.3f} s, "
              f"Mitsuba {min(theirs):.3f}-{max(theirs):.3f} s over {runs} runs each)")
print(f"load average: {os.getloadavg()[0]:.2f}")
