#!/usr/bin/python3
"""Writes scenes/volumes/plume.vdb: an OpenVDB float grid "density" of 40^3 voxels (voxel size 1/40, so the active
voxels fill the unit cube [0, 1]^3 in the VDB's world coordinates) for the vdb medium field (lucent/medium_vdb.h,
scenes/vdb_plume.json). m = 0.25 in the bulk plus a rising, twisting plume of denser, absorbing matter (m up to
about 2.2) and two small dense knots; every voxel of the box is active (zeros included), so the active bounding box
is the whole grid and "object-bounds" spans exactly these 40^3 voxels.

With --raw DIR it also writes DIR/plume.json and DIR/plume.raw, the same values as a raw volume
(lucent/medium_volume.h), to compare a "volume" field with the "vdb" one.

Needs Debian's python3-openvdb (import pyopenvdb) and numpy, i.e. /usr/bin/python3, not another interpreter."""
import argparse, json, math, os, struct

import numpy as np
import pyopenvdb as vdb

n = 40
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "volumes")


def density(u):
    x, y, z = u
    # the plume: a column rising from the bottom, its centre circling as it rises, widening towards the top
    cx = 0.5 + 0.18 * math.cos(5.0 * y)
    cz = 0.5 + 0.18 * math.sin(5.0 * y)
    radius = 0.08 + 0.12 * y
    d = math.hypot(x - cx, z - cz) / radius
    plume = math.exp(-d * d) * min(1.0, 3.0 * y)
    knots = 0.0
    for (kx, ky, kz, r) in ((0.25, 0.3, 0.7, 0.08), (0.75, 0.65, 0.3, 0.06)):
        q = ((x - kx) ** 2 + (y - ky) ** 2 + (z - kz) ** 2) / (r * r)
        knots += math.exp(-q)
    return 0.25 + 1.9 * plume + 1.5 * knots


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--raw", metavar="DIR", help="also write DIR/plume.json and DIR/plume.raw (the same values)")
    args = parser.parse_args()
    values = np.zeros((n, n, n), dtype=np.float32)  # indexed [x, y, z] as pyopenvdb's copyFromArray expects
    for z in range(n):
        for y in range(n):
            for x in range(n):
                values[x, y, z] = density([(c + 0.5) / n for c in (x, y, z)])
    grid = vdb.FloatGrid(0.0)
    grid.name = "density"
    grid.copyFromArray(values, ijk=(0, 0, 0), tolerance=-1.0)  # tolerance < 0: every voxel active, zeros too
    grid.transform = vdb.createLinearTransform(voxelSize=1.0 / n)
    # the index-space voxel centres sit at integers: shift by half a voxel so the active voxels fill [0, 1]^3
    grid.transform.translate((0.5 / n, 0.5 / n, 0.5 / n))
    grid.gridClass = vdb.GridClass.FOG_VOLUME
    vdb.write(os.path.join(root, "plume.vdb"), grids=[grid])
    if args.raw:
        raw = bytearray()
        for z in range(n):
            for y in range(n):
                for x in range(n):
                    raw += struct.pack("<f", float(values[x, y, z]))
        with open(os.path.join(args.raw, "plume.raw"), "wb") as f:
            f.write(raw)
        with open(os.path.join(args.raw, "plume.json"), "w") as f:
            json.dump({"size": [n, n, n], "format": "float32", "data": "plume.raw"}, f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main()
