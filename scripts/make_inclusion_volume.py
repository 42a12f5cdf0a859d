#!/usr/bin/env python3
"""Writes scenes/volumes/inclusion.{json,raw}: a 32^3 float32 density grid for a heterogeneous medium
(lucent/medium_volume.h). m = 1 in the bulk and an absorbing inclusion (m up to 1.6) off the axis at 60%
height with a smooth rim. m > 1 adds absorbing matter sigma_t (m - 1): for a high-albedo medium (sigma_s ~ 2.3,
sigma_a ~ 0.003 per mm) m = 1.6 multiplies the absorption by about 400, so small excesses are already dark
(and uint8 quantisation near m = 1 would not do: one step of a [0, 2] range changes sigma_a by 2.5x).
Only the standard library; the committed files were made with this script."""
import json, math, os, struct

n = 32
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "volumes")
values = bytearray()
for z in range(n):
    for y in range(n):
        for x in range(n):
            u = [(c + 0.5) / n for c in (x, y, z)]
            # inclusion: an ellipsoid centred at (0.6, 0.6, 0.5), radii 0.22, 0.15, 0.22 (unit cube)
            d = math.sqrt(((u[0] - 0.6) / 0.22) ** 2 + ((u[1] - 0.6) / 0.15) ** 2 + ((u[2] - 0.5) / 0.22) ** 2)
            w = min(1.0, max(0.0, (1.0 - d) * 4.0))  # smooth rim
            values += struct.pack("<f", 1.0 + 0.6 * w)
with open(os.path.join(root, "inclusion.raw"), "wb") as f:
    f.write(values)
with open(os.path.join(root, "inclusion.json"), "w") as f:
    json.dump({"size": [n, n, n], "format": "float32", "data": "inclusion.raw"}, f, indent=2)
    f.write("\n")
