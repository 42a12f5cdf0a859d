#!/usr/bin/env python3
"""The multipole model's slab totals against exact transport: `lucent slab --model multipole` over thicknesses,
albedos and eta. Prints a markdown table (per refracted power, unscattered light removed) for docs/accuracy.md.

  python3 bench/multipole_slab.py [--lucent build/lucent] [--photons 200000]
"""
import argparse
import json
import subprocess

THICKNESSES = [1, 2, 4, 8, 16, 32, 64]
ALBEDOS = [0.8, 0.95, 0.99, 0.999]
ETAS = [1.0, 1.4]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lucent", default="build/lucent")
    ap.add_argument("--photons", type=int, default=200000)
    args = ap.parse_args()
    print("| eta | albedo | thickness | R exact | R model | ratio | T exact | T model | ratio |")
    print("|---|---|---|---|---|---|---|---|---|")
    worst = {}
    for eta in ETAS:
        for albedo in ALBEDOS:
            for d in THICKNESSES:
                out = subprocess.run([args.lucent, "slab", "--albedo", str(albedo), "--eta", str(eta), "--thickness",
                                      str(d), "--photons", str(args.photons), "--model", "multipole", "--json"],
                                     capture_output=True, text=True, check=True).stdout
                j = json.loads(out)
                r = j["diffuse_reflectance_per_refracted"]["mean"]
                t = j["model"]["transport_diffuse_transmittance_per_refracted"]["mean"]
                mr = j["model"]["diffuse_reflectance_per_refracted"]
                mt = j["model"]["diffuse_transmittance_per_refracted"]
                rt = f"{mt / t:.3f}" if t > 1e-3 else "-"
                print(f"| {eta} | {albedo} | {d} | {r:.4f} | {mr:.4f} | {mr / r:.3f} | {t:.4f} | {mt:.4f} | {rt} |")
                key = (eta, albedo)
                w = max(abs(mr / r - 1), abs(mt / t - 1) if t > 0.01 else 0)
                worst[key] = max(worst.get(key, 0), w)
    print()
    print("worst |ratio - 1| (R, and T where over 1% crosses) per eta and albedo: " +
          ", ".join(f"eta {e} albedo {a}: {100 * w:.1f}%" for (e, a), w in sorted(worst.items())))


if __name__ == "__main__":
    main()
