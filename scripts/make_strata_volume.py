#!/usr/bin/env python3
"""Writes scenes/volumes/strata.{json,raw}: a 2 x 400 x 2 float32 density grid for a heterogeneous medium
(lucent/medium_volume.h) holding four flat layers of equal thickness, from the top of the object's bounds down,
with density multipliers 1, 2, 0.5 and 1.5: the layer stack of scenes/layered_strata.json, whose layered-stm
coefficients are these multipliers applied to the material (sigma_t = m sigma_t, sigma_s = min(m, 1) sigma_s).
With 400 voxels across the slab's height the trilinear lookup blurs each boundary over 1/400 of it.
Only the standard library; the committed files were made with this script."""
import json, os, struct

multipliers = [1.0, 2.0, 0.5, 1.5]  # layers 0 (top) to 3
ny = 400
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "volumes")
values = bytearray()
for z in range(2):
    for y in range(ny):
        for x in range(2):
            depth = 1.0 - (y + 0.5) / ny  # y = 0 is the bottom of the bounds
            values += struct.pack("<f", multipliers[min(3, int(depth * 4))])
with open(os.path.join(root, "strata.raw"), "wb") as f:
    f.write(values)
with open(os.path.join(root, "strata.json"), "w") as f:
    json.dump({"size": [2, ny, 2], "format": "float32", "data": "strata.raw"}, f, indent=2)
    f.write("\n")
