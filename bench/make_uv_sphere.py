#!/usr/bin/env python3
# make_uv_sphere.py: writes the same UV sphere twice as OBJ, with latitude-longitude texture coordinates (area
# distorted toward the poles) and without any (so lucent builds its atlas), for the atlas-quality experiment of
# docs/methods/texture-space-is.md.   python3 bench/make_uv_sphere.py OUT_DIR
import math, os, sys
out = sys.argv[1]
os.makedirs(out, exist_ok=True)
rings, segments = 48, 96
verts, uvs, faces = [], [], []
for i in range(rings + 1):
    theta = math.pi * i / rings
    for j in range(segments + 1):
        phi = 2 * math.pi * j / segments
        verts.append((math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)))
        uvs.append((j / segments, 1 - i / rings))
for i in range(rings):
    for j in range(segments):
        a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
        if i > 0: faces.append((a, a + 1, b))
        if i < rings - 1: faces.append((a + 1, b + 1, b))
for name, with_uv in (("sphere_latlong.obj", True), ("sphere_plain.obj", False)):
    with open(os.path.join(out, name), "w") as f:
        for v in verts: f.write("v %.6f %.6f %.6f\n" % v)
        if with_uv:
            for t in uvs: f.write("vt %.6f %.6f\n" % t)
        for a, b, c in faces:
            if with_uv: f.write("f %d/%d %d/%d %d/%d\n" % (a + 1, a + 1, c + 1, c + 1, b + 1, b + 1))
            else: f.write("f %d %d %d\n" % (a + 1, c + 1, b + 1))
