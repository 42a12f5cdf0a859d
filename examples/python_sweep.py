#!/usr/bin/env python3
"""Error against time as a method's sample count grows, through the lucent Python module.

Renders the built-in default scene with the per-pixel method for N = 1, 2, 4, ... light-space samples per pixel,
measures each image against the CPU reference of the same BSSRDF model (lucent.reference, integrator "bssrdf",
pixel centres as the rasterizer samples them) and the GPU time per frame, then writes <out>.csv and plots it with
gnuplot to <out>.png.

    PYTHONPATH=build/python /usr/bin/python3 examples/python_sweep.py [--out out/python_sweep]
"""
import argparse
import csv
import math
import subprocess
import time
from pathlib import Path

import lucent

WIDTH, HEIGHT, FRAMES = 160, 100, 8  # the image, and the frames accumulated (the fastest one is timed)


def sweep(scene, reference, standard_error, samples):
    rows = []
    for N in samples:
        image, info = lucent.render(scene, width=WIDTH, height=HEIGHT, frames=FRAMES, method="per-pixel",
                                    params={"N": N}, timings=True)
        error = lucent.compare(image, reference, standard_error=standard_error)["linear"]
        frame_ms = min(f["total_ms"] for f in info["frames"])  # the least disturbed frame on a shared machine
        # The reference's own noise in the units of rmse_rgb (an error this small cannot be told from it).
        noise_rgb = error["reference_noise_rms"] * math.sqrt(3.0)
        rows.append({"N": N, "frame_ms": frame_ms, "rmse_rgb": error["rmse_rgb"], "relative_mse": error["relative_mse"],
                     "reference_noise_rgb": noise_rgb, "device": info["device"]})
        print(f"N {N:4d}: {frame_ms:8.2f} ms/frame  RMSE {error['rmse_rgb']:.5f}  relMSE {error['relative_mse']:.5f}")
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def plot(csv_path, png_path, title):
    script = f"""
set terminal pngcairo size 800,500
set output '{png_path}'
set datafile separator ','
set key autotitle columnhead
set logscale xy
set xlabel 'GPU time per frame [ms]'
set ylabel 'RMSE sqrt(dr^2+dg^2+db^2) vs the bssrdf reference'
set title '{title}'
set grid
plot '{csv_path}' using 2:3 with linespoints pt 7 title 'per-pixel, N = 1, 2, 4, ...', \\
     '' using 2:3:(sprintf('N=%d', $1)) with labels offset 2,0.8 notitle, \\
     '' using 2:5 with lines dt 2 lc rgb 'gray40' title 'reference noise (its standard error, RGB)'
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/python_sweep", help="output stem: <out>.csv and <out>.png")
    parser.add_argument("--spp", type=int, default=1024, help="samples per pixel of the reference")
    parser.add_argument("--samples", default="1,2,4,8,16,32,64", help="per-pixel N values")
    args = parser.parse_args()
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)

    scene = lucent.load_scene()
    start = time.perf_counter()
    reference, standard_error = lucent.reference(scene, integrator="bssrdf", spp=args.spp, width=WIDTH, height=HEIGHT)
    print(f"reference: bssrdf, {args.spp} spp, {WIDTH}x{HEIGHT}, {time.perf_counter() - start:.1f} s")
    lucent.write_png(f"{out}_reference.png", reference)

    rows = sweep(scene, reference, standard_error, [int(n) for n in args.samples.split(",")])
    write_csv(f"{out}.csv", rows)
    device = rows[0]["device"].split(" (")[0].split(",")[0]  # "llvmpipe", "NVIDIA H100 80GB HBM3/PCIe/SSE2"
    plot(f"{out}.csv", f"{out}.png", f"default scene {WIDTH}x{HEIGHT}, {FRAMES} frames, {device}")
    print(f"-> {out}.csv, {out}.png")


if __name__ == "__main__":
    main()
