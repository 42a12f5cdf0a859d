#!/usr/bin/env python3
"""model_totals.py: the diffusion models' flat half-space total diffuse reflectance against exact transport.

For every reduced albedo a' and relative index eta and incidence angle, prints the total reflectance per refracted
power of each model as lucent applies it (`lucent bssrdf --total`) and of exact transport (`lucent slab`, Monte
Carlo photon transport in a half-space with isotropic scattering, validated against Chandrasekhar's H-function
tables), with the ratio model / exact. One markdown table per eta.
  python3 bench/model_totals.py [LUCENT] [PHOTONS]
"""
import json
import subprocess
import sys

lucent = sys.argv[1] if len(sys.argv) > 1 else "build/lucent"
photons = int(sys.argv[2]) if len(sys.argv) > 2 else 100000
albedos = [0.3, 0.5, 0.8, 0.9, 0.95, 0.99, 0.999]
etas = [1.0, 1.3, 1.5]
angles = [0, 45, 75]
models = ["standard", "directional", "photon-beam", "better-dipole"]


def run(args):
    return json.loads(subprocess.run([lucent] + args + ["--json"], check=True, capture_output=True, text=True).stdout)


def model_total(model, albedo, eta, angle):
    j = run(["bssrdf", "--total", "--model", model, "--sigma-a", str(1.0 - albedo), "--sigma-s-prime", str(albedo),
             "--eta", str(eta), "--incidence-deg", str(angle)])
    return j["total"][0], j["radiosity"][0], j["exit_transmittance"]


def exact(albedo, eta, angle):
    j = run(["slab", "--albedo", str(albedo), "--eta", str(eta), "--incidence-deg", str(angle), "--photons",
             str(photons)])
    r = j["diffuse_reflectance_per_refracted"]
    return r["mean"], r["standard_error"]


for eta in etas:
    print(f"\n### eta = {eta}\n")
    print("| a' | angle | exact (+- SE) | " + " | ".join(f"{m} (ratio)" for m in models) +
          " | Jensen's S_d = R_d / pi (ratio) |")
    print("|---|---|---|" + "---|" * len(models) + "---|")
    for albedo in albedos:
        for angle in angles:
            e, se = exact(albedo, eta, angle)
            cells = []
            jensen = None
            for m in models:
                t, radiosity, exit_t = model_total(m, albedo, eta, angle)
                cells.append(f"{t:.4f} ({t / e:.3f})")
                if m == "standard":  # without the exit normalisation the exit transmittance applies once more
                    jensen = t * exit_t
            print(f"| {albedo} | {angle} | {e:.4f} +- {se:.4f} | " + " | ".join(cells) +
                  f" | {jensen:.4f} ({jensen / e:.3f}) |", flush=True)
