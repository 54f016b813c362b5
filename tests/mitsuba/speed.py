"""raylab's speed against Mitsuba 3's at equal work: samples per second at 320 x 240,
64 spp, 2 threads, box filter, each renderer run in turn.

The scenes (speed-NAME.toml, and peer.py for Mitsuba's side) are pure emission and
specular transport, so both trace one branch per hit (raylab's tree = "stochastic", as a
path tracer does): `glass`, a glass sphere before an emitting checkerboard; `dof`, three
emitting checkerboards through a thin lens; `misses`, small emitting boards through a thin
lens with most rays missing everything; `over`, two glass spheres on an emitting floor seen
from above; `mesh`, a glass Stanford bunny before an emitting checkerboard. Mitsuba runs
its `path` integrator with max_depth 10 (raylab's max_depth 8 counts bounces; see
path.py), `llvm_ad_rgb` (JIT, the CPU's widest vectors) after one warm-up render so that
its compile is not timed.

    apt-get install libllvm19    # Dr.Jit's LLVM back end needs 19 on Debian 12
    pip install mitsuba==3.9.1 drjit==1.5.0 numpy
    cargo build --release
    python tests/mitsuba/speed.py [target/release/raylab] [RUNS] [SAMPLER] [NAME,...]

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

import peer

here = pathlib.Path(__file__).parent
raylab = sys.argv[1] if len(sys.argv) > 1 else "target/release/raylab"
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
sampler = sys.argv[3] if len(sys.argv) > 3 else "independent"
spp = 64

mi.set_variant("llvm_ad_rgb")
dr.set_thread_count(2)
names = sys.argv[4].split(",") if len(sys.argv) > 4 else peer.NAMES
models = here.parent.parent / "scenes" / "models"


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


samples = peer.WIDTH * peer.HEIGHT * spp
with tempfile.TemporaryDirectory() as tmp:
    for name in names:
        scene = mi.load_dict(peer.scene(name, spp, sampler, models))
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
