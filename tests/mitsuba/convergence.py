"""Time to an RMSE of 0.01: raylab (Sobol, Owen-scrambled) against Mitsuba 3 (`llvm_ad_rgb`,
its `multijitter` sampler by default) on the speed scenes (see speed.py and peer.py), 320 x
240, 2 threads, box filter.

Each renderer's error is measured against its own reference (REF spp, another seed), so a
difference of convention between them (a checker cell's edge, an emitter's side) cannot
count as noise; the two references' means are printed to show they are the same image.
Both render at 1, 2, 4, ... spp; the spp where RMSE (over pixels and channels, linear
values) crosses 0.01 and its time are interpolated in log-log between the two renders
around it (Mitsuba's `multijitter` rounds some counts up, 32 to 35: the spp printed for it
are those asked, its times those of what it rendered). Each render is timed as speed.py
times it (Mitsuba after one warm-up render per spp, so its JIT compile is not counted),
the median of RUNS.

    python tests/mitsuba/convergence.py [target/release/raylab] [RUNS] [SAMPLER] [NAME,...] [REF]
"""

import math
import os
import statistics
import sys
import tempfile

import drjit as dr
import mitsuba as mi
import numpy as np

import peer

raylab = sys.argv[1] if len(sys.argv) > 1 else "target/release/raylab"
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 3
sampler = sys.argv[3] if len(sys.argv) > 3 else "multijitter"
names = sys.argv[4].split(",") if len(sys.argv) > 4 else peer.NAMES
reference_spp = int(sys.argv[5]) if len(sys.argv) > 5 else 4096
TARGET = 0.01

mi.set_variant("llvm_ad_rgb")
dr.set_thread_count(2)


def mitsuba(scene, spp, seed, compiled):
    """(seconds, image) of one render, its kernel compiled first where the spp is not in
    `compiled`."""
    if spp not in compiled:
        peer.mitsuba_render(scene, spp, seed + 1000)
        compiled.add(spp)
    seconds, image = peer.mitsuba_render(scene, spp, seed)
    return seconds, peer.rgb(image)


def ours(name, spp, seed, out):
    """(seconds, image) of one raylab render."""
    seconds = peer.raylab_render(raylab, name, out, "--spp", str(spp), "--set", f"seed={seed}")
    return seconds, peer.rgb(out)


def rmse(image, reference):
    return float(np.sqrt(np.mean((image - reference) ** 2)))


def time_to_target(render, reference):
    """(spp, seconds) where the error crosses TARGET, interpolated between the powers of
    two around it, and the (spp, rmse, seconds) measured."""
    rows, spp = [], 1
    while True:
        times, errors = [], []
        for run in range(runs):
            seconds, image = render(spp, run + 1)
            times.append(seconds)
            errors.append(rmse(image, reference))
        rows.append((spp, statistics.median(errors), statistics.median(times)))
        if rows[-1][1] <= TARGET or spp >= reference_spp // 4:
            break
        spp *= 2
    if len(rows) < 2 or rows[-1][1] > TARGET:
        return None, rows
    (n0, e0, t0), (n1, e1, t1) = rows[-2], rows[-1]
    # log e, log n and log t linear in one another between the two renders: the time from
    # the renders' own times, so that a sampler rounding its count up (Mitsuba's
    # multijitter takes 35 for 32) is timed for what it did.
    a = (math.log(TARGET) - math.log(e0)) / (math.log(e1) - math.log(e0))
    n = math.exp(math.log(n0) + a * (math.log(n1) - math.log(n0)))
    return (n, math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))), rows


with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "image.exr")
    for name in names:
        scene, compiled = peer.scene(name, 64, sampler), set()
        _, ours_ref = ours(name, reference_spp, 777, out)
        _, theirs_ref = mitsuba(scene, reference_spp, 777, {reference_spp})
        print(f"{name}: reference means raylab {ours_ref.mean():.4f}, "
              f"Mitsuba {theirs_ref.mean():.4f} ({reference_spp} spp); "
              f"between them RMSE {rmse(ours_ref, theirs_ref):.4f}")
        our_time, our_rows = time_to_target(
            lambda spp, seed: ours(name, spp, seed, out), ours_ref)
        their_time, their_rows = time_to_target(
            lambda spp, seed: mitsuba(scene, spp, seed, compiled), theirs_ref)
        for who, rows in (("raylab", our_rows), (f"Mitsuba {sampler}", their_rows)):
            print(f"  {who}: " + ", ".join(f"{n} spp {e:.4f} in {t:.3f} s" for n, e, t in rows))
        if our_time and their_time:
            (n, t), (m, u) = our_time, their_time
            print(f"{name}: RMSE {TARGET} at {n:.1f} spp in {t:.3f} s (raylab), "
                  f"{m:.1f} spp in {u:.3f} s (Mitsuba): raylab takes {t / u:.2f} of the peer's time")
        else:
            print(f"{name}: RMSE {TARGET} not reached below {reference_spp // 4} spp")
print(f"load average: {os.getloadavg()[0]:.2f}")
