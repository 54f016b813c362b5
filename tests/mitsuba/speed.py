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
import statistics
import sys
import tempfile

import drjit as dr
import mitsuba as mi

import peer

raylab = sys.argv[1] if len(sys.argv) > 1 else "target/release/raylab"
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
sampler = sys.argv[3] if len(sys.argv) > 3 else "independent"
names = sys.argv[4].split(",") if len(sys.argv) > 4 else peer.NAMES
spp = 64

mi.set_variant("llvm_ad_rgb")
dr.set_thread_count(2)

samples = peer.WIDTH * peer.HEIGHT * spp
with tempfile.TemporaryDirectory() as tmp:
    for name in names:
        scene = peer.scene(name, spp, sampler)
        peer.mitsuba_render(scene, spp, 0)  # the JIT compiles here
        ours, theirs = [], []
        out = os.path.join(tmp, f"{name}.exr")
        for run in range(runs):
            ours.append(peer.raylab_render(raylab, name, out))
            seconds, image = peer.mitsuba_render(scene, spp, run + 1)
            theirs.append(seconds)
        # The same work: the two images agree within noise.
        a, b = peer.rgb(out), peer.rgb(image)
        print(f"{name}: image mean raylab {a.mean():.4f}, Mitsuba {b.mean():.4f}")
        r = samples / statistics.median(ours) / 1e6
        m = samples / statistics.median(theirs) / 1e6
        print(f"{name}: raylab {r:.1f} M samples/s, Mitsuba ({sampler}) {m:.1f} M "
              f"samples/s: {r / m:.2f}x  (raylab {min(ours):.3f}-{max(ours):.3f} s, "
              f"Mitsuba {min(theirs):.3f}-{max(theirs):.3f} s over {runs} runs each)")
print(f"load average: {os.getloadavg()[0]:.2f}")
