#!/usr/bin/env python3
"""The random-walk method's frames against CPU volpath on the same image (bench/random_walk.sh writes the inputs).

  python3 bench/random_walk_report.py TIMINGS.json JUMPS WALL_SECONDS CORES VOLPATH_1_CORE.meta.json VOLPATH_ALL.meta.json \
      [TIMED.json]

TIMED.json: the same frames rendered with the method's time_dispatches on (each dispatch waited for and timed by
wall clock): the share of the trace time spent in sparse dispatches.

Per frame: the trace pass's time, dispatches (and those with under a tenth of the pool busy), read-backs, paths
finished in the frame's dispatches and their walk steps, traversals per step and per next-event estimate, node visits
per step. Then the totals over frames 2..F (frame 1 compiles the shaders). Steps per path are counted as volpath
counts them: over the paths of pixels that hit something (a background pixel's path takes no step), the frame's own
paths for the walk. volpath's camera paths per second count every pixel, like the walk's paths per second.
"""
import json
import sys

frames = json.load(open(sys.argv[1]))["frames"]
jumps, wall, cores = sys.argv[2], float(sys.argv[3]), int(sys.argv[4])
one, every = (json.load(open(p)) for p in sys.argv[5:7])
print(f"\nsphere jumps {jumps}: the command took {wall:.1f} s; the frames' pass times sum to "
      f"{sum(f['total_ms'] for f in frames) / 1e3:.1f} s (frame 1 compiles)")
print("| frame | trace ms | dispatches | sparse | read-backs | paths | steps | traversals/step | traversals/estimate | nodes/step |")
print("|---|---|---|---|---|---|---|---|---|---|")
t = dict(ms=0.0, paths=0.0, steps=0.0, dispatches=0.0, sparse=0.0, reads=0.0, trav=0.0, nodes=0.0, own_steps=0.0,
         own_paths=0.0, covered=0.0, frames=0)
for f in frames:
    s, ms = f["stats"], f["passes"].get("trace", 0.0)
    paths = s.get("paths_per_second", 0.0) * ms * 1e-3
    steps = s.get("steps_per_second", 0.0) * ms * 1e-3
    print(f"| {f['frame']} | {ms:.0f} | {s['dispatches']:.0f} | {s['sparse_dispatches']:.0f} | {s['read_backs']:.0f} | "
          f"{paths:.0f} | {steps:.0f} | {s['traversals_per_step']:.2f} | {s['traversals_per_next_event']:.2f} | "
          f"{s['node_visits_per_step']:.0f} |")
    if f["frame"] < 2:
        continue
    t["frames"] += 1
    t["ms"] += ms; t["paths"] += paths; t["steps"] += steps
    t["dispatches"] += s["dispatches"]; t["sparse"] += s["sparse_dispatches"]; t["reads"] += s["read_backs"]
    t["trav"] += s["traversals_per_step"] * steps; t["nodes"] += s["node_visits_per_step"] * steps
    t["own_steps"] += s["walk_steps"]; t["own_paths"] += s["walk_paths"]
walk_rate = t["paths"] / (t["ms"] * 1e-3)
# The share of pixels that hit something: the walk's covered paths per frame over its paths per frame.
frame_paths = t["paths"] / t["frames"]
coverage = min(1.0, t["own_paths"] / t["frames"] / frame_paths) if frame_paths > 0 else 1.0
print(f"frames 2..{len(frames)}: {t['ms'] / t['frames']:.0f} ms per frame, {walk_rate:.4g} paths/s, "
      f"{t['steps'] / (t['ms'] * 1e-3):.4g} steps/s, {t['own_steps'] / t['own_paths']:.2f} steps/path, "
      f"{t['trav'] / t['steps']:.2f} traversals/step, {t['nodes'] / t['steps']:.0f} nodes/step, "
      f"{t['sparse'] / t['dispatches']:.0%} of {t['dispatches']:.0f} dispatches sparse, "
      f"{t['reads'] / t['frames']:.2f} read-backs per frame")
for name, m in (("1 core", one), (f"{cores} cores", every)):
    rate = m["camera_paths_per_second"]
    print(f"volpath, {name}: {rate:.4g} paths/s, {rate * coverage * m['steps_per_path']:.4g} steps/s, "
          f"{m['steps_per_path']:.2f} +- {m.get('steps_per_path_standard_error', 0.0):.2f} steps/path")
print(f"volpath paths/s over the walk's (both on the same {cores} cores on llvmpipe; per core alike): "
      f"{every['camera_paths_per_second'] / walk_rate:.2f}x")
if len(sys.argv) > 7:
    timed = [f for f in json.load(open(sys.argv[7]))["frames"] if f["frame"] >= 2]
    shares = [(f["stats"].get("sparse_time_share", 0.0), f["passes"].get("trace", 0.0)) for f in timed]
    total = sum(ms for _, ms in shares)
    print("share of the trace time in sparse dispatches (timed run, frames 2..; per frame: "
          + ", ".join(f"{share:.0%}" for share, _ in shares) + "): "
          + (f"{sum(share * ms for share, ms in shares) / total:.0%}" if total > 0 else "n/a"))
