"""The speed scenes (speed-NAME.toml beside this file) as Mitsuba 3 scene dictionaries,
built from the same numbers, and each renderer's timed render of them, for speed.py and
convergence.py. Every one is pure emission
and specular transport, so the two renderers do the same work per sample: one branch per
hit (raylab's tree = "stochastic", Mitsuba's `path` integrator), no light sampling.

Conventions matched (see ../shared/PLATFORM.md): `perspective` fov along y, `thinlens`
takes an aperture radius, box pixel filter, emitters seen on their front side (raylab's
quads' front is edge_u x edge_v), Mitsuba's max_depth 10 against raylab's 8 bounces.
"""

import pathlib
import re
import subprocess
import time

import drjit as dr
import mitsuba as mi
import numpy as np

WIDTH, HEIGHT = 320, 240
HERE = pathlib.Path(__file__).parent
MODELS = HERE.parent.parent / "scenes" / "models"


def T(*a):
    """A transform (looked up when called: Mitsuba's types exist once a variant is set)."""
    return mi.ScalarTransform4f(*a)


def quad(corner, edge_u, edge_v, cells, color0, color1):
    """An emitting parallelogram `corner + a edge_u + b edge_v` with `cells` checks along
    u and v (raylab's `scale`): Mitsuba's rectangle is [-1, 1]^2 in z = 0 facing +z, and
    its checkerboard has 2 x 2 checks per unit of uv."""
    u = [e / 2 for e in edge_u]
    v = [e / 2 for e in edge_v]
    n = [edge_u[1] * edge_v[2] - edge_u[2] * edge_v[1],
         edge_u[2] * edge_v[0] - edge_u[0] * edge_v[2],
         edge_u[0] * edge_v[1] - edge_u[1] * edge_v[0]]
    length = sum(c * c for c in n) ** 0.5
    n = [c / length for c in n]
    c = [corner[i] + u[i] + v[i] for i in range(3)]
    matrix = [[u[i], v[i], n[i], c[i]] for i in range(3)] + [[0, 0, 0, 1]]
    return {
        "type": "rectangle",
        "to_world": T(matrix),
        "emitter": {"type": "area", "radiance": {
            "type": "checkerboard",
            "color0": {"type": "rgb", "value": color0},
            "color1": {"type": "rgb", "value": color1},
            "to_uv": mi.ScalarTransform3f().scale([cells[0] / 2, cells[1] / 2]),
        }},
    }


def sensor(spp, sampler, origin=(0, 0, 6), target=(0, 0, 0), lens=None):
    s = {
        "type": "perspective",
        "to_world": T().look_at(origin=list(origin), target=list(target), up=[0, 1, 0]),
        "fov": 40, "fov_axis": "y",
        "film": {"type": "hdrfilm", "width": WIDTH, "height": HEIGHT,
                 "rfilter": {"type": "box"}},
        "sampler": {"type": sampler, "sample_count": spp},
    }
    if lens:
        s.update({"type": "thinlens", "aperture_radius": lens[0], "focus_distance": lens[1]})
    return s


def glass(ior, **shape):
    return dict(shape, bsdf={"type": "dielectric", "int_ior": ior, "ext_ior": 1.0})


WHITE, BLUE = [1, 0.95, 0.9], [0.05, 0.1, 0.3]
WARM, WARM_DARK = [1, 0.5, 0.2], [0.1, 0.05, 0.02]


# Per scene, its camera (`sensor`'s arguments) and its objects.
SCENES = {
    "glass": ({}, lambda: {
        "board": quad([-8, -6, -4], [16, 0, 0], [0, 12, 0], [16, 12], WHITE, BLUE),
        "glass": glass(1.5, type="sphere", center=[0, 0, 0], radius=1.3),
    }),
    "dof": ({"lens": (0.2, 6.0)}, lambda: {
        "near": quad([-2.2, -0.9, 3], [1.6, 0, 0], [0, 1.6, 0], [4, 4],
                     [1, 0.3, 0.2], [0.1, 0.05, 0.02]),
        "middle": quad([-1.2, -1.6, 0], [3.2, 0, 0], [0, 3.2, 0], [8, 8],
                       [0.9, 0.9, 0.85], [0.05, 0.05, 0.1]),
        "far": quad([-8, -6, -4], [16, 0, 0], [0, 12, 0], [16, 12],
                    [0.2, 0.4, 1], [0.02, 0.04, 0.1]),
    }),
    "misses": ({"lens": (0.2, 6.0)}, lambda: {
        "near": quad([-1.5, -0.9, 3.5], [0.6, 0, 0], [0, 0.6, 0], [3, 3], WARM, WARM_DARK),
        "focused": quad([0.2, 0.3, 0], [1.2, 0, 0], [0, 0.4, 0], [6, 2],
                        [0.9, 0.9, 0.85], [0.05, 0.05, 0.1]),
        "far": quad([-2.6, 0.4, -3], [1.5, 0, 0], [0, 1.5, 0], [5, 5],
                    [0.2, 0.5, 1], [0.02, 0.05, 0.1]),
        "farthest": quad([1, -2.8, -6], [2, 0, 0], [0, 2, 0], [3, 3], WARM, WARM_DARK),
    }),
    "over": ({"origin": (0, 3.5, 4.5), "target": (0, 0.3, 0)}, lambda: {
        "floor": quad([-2.5, 0, 2.5], [5, 0, 0], [0, 0, -5], [10, 10], WHITE, BLUE),
        "glass": glass(1.5, type="sphere", center=[-0.6, 0.8, 0], radius=0.8),
        "dense": glass(1.8, type="sphere", center=[0.9, 0.45, 0.6], radius=0.45),
    }),
    "mesh": ({"origin": (0, 0.6, 3.2), "target": (0, 0.5, 0)}, lambda: {
        "board": quad([-4, -2.5, -2], [8, 0, 0], [0, 6, 0], [16, 12], WHITE, BLUE),
        "bunny": glass(1.5, type="obj", filename=str(MODELS / "bunny.obj"),
                       to_world=T().rotate([0, 1, 0], 20) @ T().scale(0.12)),
    }),
}
NAMES = list(SCENES)


def scene(name, spp, sampler):
    """Mitsuba's scene of speed-NAME.toml at `spp` samples with `sampler`, loaded."""
    camera, objects = SCENES[name]
    return mi.load_dict(dict({"type": "scene", "integrator": {"type": "path", "max_depth": 10},
                              "sensor": sensor(spp, sampler, **camera)}, **objects()))


def mitsuba_render(scene, spp, seed):
    """(seconds, image) of one Mitsuba render, evaluated (Dr.Jit launches lazily: without
    `dr.eval` and `dr.sync_thread`, `mi.render` returns before the work is done). The
    first render at an spp compiles its kernel: warm up before timing."""
    start = time.perf_counter()
    image = mi.render(scene, spp=spp, seed=seed)
    dr.eval(image)
    dr.sync_thread()
    return time.perf_counter() - start, image


def raylab_render(raylab, name, out, *options):
    """Seconds of one raylab render of speed-NAME.toml to `out` on 2 threads, as its
    summary line ("NAME WxH at N spp: S s, ...") gives them."""
    o = subprocess.run([raylab, "render", str(HERE / f"speed-{name}.toml"), "-o", out,
                        "--threads", "2", *options], check=True, capture_output=True, text=True)
    return float(re.search(r"spp: ([0-9.]+) s", o.stderr).group(1))


def rgb(image):
    """An image's colour channels as an array (a Mitsuba image, or a file's path)."""
    if isinstance(image, str):
        image = mi.Bitmap(image)
    return np.array(image)[:, :, :3]
