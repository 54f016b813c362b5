"""Compares two folders of renders made by tests/images/same.sh: the EXRs' pixels, the PNGs'
pixels (not their bytes: a PNG's text chunks name the version and commit that made it,
which differ between the two builds by design). Prints each pair that differs (with the
largest difference of an EXR's pixels) and a count; exits 1 if any differs."""

import pathlib
import sys

import numpy as np
import OpenEXR
from PIL import Image

old, new = (pathlib.Path(a) for a in sys.argv[1:3])
same, differ = 0, 0
for a in sorted(old.iterdir()):
    b = new / a.name
    if a.suffix == ".exr":
        ca, cb = OpenEXR.File(str(a)).channels(), OpenEXR.File(str(b)).channels()
        if ca.keys() == cb.keys() and all(np.array_equal(ca[k].pixels, cb[k].pixels) for k in ca):
            same += 1
            continue
        worst = max(
            float(np.nanmax(np.abs(ca[k].pixels.astype(np.float64) - cb[k].pixels))) for k in ca
        )
        print(f"differs: {a.name} (largest difference {worst:.3g})")
    elif a.suffix == ".png":
        pa, pb = Image.open(a), Image.open(b)
        if (pa.mode, pa.size, pa.tobytes()) == (pb.mode, pb.size, pb.tobytes()):
            same += 1
            continue
        print(f"differs: {a.name}")
    else:
        continue
    differ += 1
print(f"{same} identical, {differ} different")
sys.exit(1 if differ else 0)
