#!/usr/bin/env python3
"""Writes cases/geometry/boulder_sdf_2d.h5, the signed-distance grid of the boulder in
cases/dambreak_sdf_obstacle_2d.textproto: the smooth union (Quilez's polynomial smooth minimum,
k = 0.1) of two disks, r = 0.3 at (2.9, 0.15) and r = 0.2 at (3.25, 0.05), sampled every 0.01 m
(half the case's dx) over [2.4, 3.7] x [-0.3, 0.6], as dataset "sdf" ([ny][nx], x fastest,
float32). The smooth union is not an exact distance near the seam but has the right sign,
which is all the fill uses. Needs h5import (Debian: hdf5-tools)."""
import math
import os
import struct
import subprocess
import tempfile

ORIGIN = (2.4, -0.3)
SPACING = 0.01
NX, NY = 131, 91


def sdf(x, y):
    d1 = math.hypot(x - 2.9, y - 0.15) - 0.3
    d2 = math.hypot(x - 3.25, y - 0.05) - 0.2
    k = 0.1
    h = max(k - abs(d1 - d2), 0.0) / k
    return min(d1, d2) - h * h * k / 4


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = os.path.join(root, "geometry", "boulder_sdf_2d.h5")
    with tempfile.TemporaryDirectory() as tmp:
        raw = os.path.join(tmp, "sdf.bin")
        with open(raw, "wb") as f:
            for j in range(NY):
                for i in range(NX):
                    f.write(struct.pack("<f", sdf(ORIGIN[0] + i * SPACING, ORIGIN[1] + j * SPACING)))
        config = os.path.join(tmp, "sdf.cfg")
        with open(config, "w") as f:
            f.write("PATH sdf\nINPUT-CLASS FP\nINPUT-SIZE 32\nINPUT-BYTE-ORDER LE\nRANK 2\n"
                    f"DIMENSION-SIZES {NY} {NX}\nOUTPUT-CLASS FP\nOUTPUT-SIZE 32\n"
                    "OUTPUT-BYTE-ORDER LE\n")
        if os.path.exists(out):
            os.remove(out)
        subprocess.run(["h5import", raw, "-c", config, "-o", out], check=True)
    print("wrote", out)


if __name__ == "__main__":
    main()
