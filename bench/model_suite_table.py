#!/usr/bin/env python3
"""The diffusion models against the physics on the leaderboard's scene suite, with no method in between.

For every scene of bench/leaderboard.json and every diffusion model, the CPU bssrdf reference (the Monte Carlo
integral of that model) is compared with the volpath reference (the physics) of the same scene: the difference is
the model's error alone. Prints a markdown table (noise-corrected RMSE of linear radiance, mean signed error), the
mean over scenes and how often each model is closest, and writes the numbers as JSON.

  python3 bench/model_suite_table.py [--lucent build/lucent] [--cache out/leaderboard/references]
                                     [--out out/model_suite] [--bssrdf-spp 1024] [--volpath-spp 256] [--run NAME ...]
                                     [--models NAME ...]

Volpath references are taken from the leaderboard's cache when one of the same scene and settings is there
(bash bench/leaderboard.sh fills it), else rendered into --out; so are bssrdf references of a model for a scene with
one translucent object (the leaderboard's multipole variants make them). A bssrdf reference already in --out is
reused. docs/accuracy.md reads the table.
"""
import argparse
import copy
import json
import os
import subprocess
import sys

MODELS = ["standard", "directional", "better-dipole", "photon-beam", "tabulated", "multipole"]
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def set_path(obj, path, value):
    keys = path.split(".")
    for k in keys[:-1]:
        obj = obj[int(k)] if isinstance(obj, list) else obj.setdefault(k, {})
    last = keys[-1]
    if isinstance(obj, list):
        obj[int(last)] = value
    else:
        obj[last] = value


def scene_with_model(scene, sets, model):
    """The scene with the run's overrides applied and every translucent object's material set to `model`."""
    s = copy.deepcopy(scene)
    for assignment in sets:
        path, text = assignment.split("=", 1)
        set_path(s, path, json.loads(text))
    for obj in s.get("objects", []):
        material = obj.get("material")
        if material is None:
            continue
        if isinstance(material, str):
            material = {"preset": material}
        material["model"] = model
        obj["material"] = material
    return s


def find_cached(cache, integrator, scene_path, overrides, spp):
    """A reference in the leaderboard's cache of this integrator, scene and overrides (method overrides aside), with at
    least spp samples per pixel; None if there is none."""
    if not os.path.isdir(cache):
        return None
    want = sorted(o for o in overrides if not o.startswith("method"))
    for name in sorted(os.listdir(cache)):
        if not (name.startswith(integrator + "_") and name.endswith(".meta.json")):
            continue
        meta = json.load(open(os.path.join(cache, name)))
        got = sorted(o for o in meta.get("overrides", []) if not o.startswith("method"))
        if meta.get("scene") == scene_path and got == want and meta.get("samples_per_pixel", 0) >= spp:
            return os.path.join(cache, name[: -len(".meta.json")] + ".exr")
    return None


def run(cmd):
    result = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"model_suite_table: {' '.join(cmd)} failed: {result.stderr.strip().splitlines()[-1:]}")
    return result.stdout


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lucent", default="build/lucent")
    ap.add_argument("--cache", default="out/leaderboard/references")
    ap.add_argument("--out", default="out/model_suite")
    ap.add_argument("--bssrdf-spp", type=int, default=1024)
    ap.add_argument("--volpath-spp", type=int, default=256)
    ap.add_argument("--run", nargs="*", default=None)
    ap.add_argument("--models", nargs="*", default=MODELS, choices=MODELS)
    args = ap.parse_args()
    models = args.models
    bench = json.load(open(os.path.join(ROOT, "bench/leaderboard.json")))
    os.makedirs(os.path.join(ROOT, args.out), exist_ok=True)
    size_sets = bench.get("set", [])
    method = 'method={"name": "radiosity-maps", "specular": false}'
    results = []
    for r in bench["runs"]:
        if args.run and r["name"] not in args.run:
            continue
        sets = r.get("set", [])
        volpath = find_cached(os.path.join(ROOT, args.cache), "volpath", r["scene"], size_sets + sets, args.volpath_spp)
        if volpath is None:
            volpath = os.path.join(args.out, f"{r['name']}_volpath.exr")
            cmd = [args.lucent, "reference", r["scene"], "--integrator", "volpath", "--spp", str(args.volpath_spp), "-q",
                   "-o", volpath]
            for s in size_sets + sets + [method]:
                cmd += ["--set", s]
            run(cmd)
        scene = json.load(open(os.path.join(ROOT, r["scene"])))
        row = {"run": r["name"], "volpath": os.path.relpath(volpath, ROOT) if os.path.isabs(volpath) else volpath}
        single = sum(1 for o in scene.get("objects", []) if "material" in o) == 1
        for model in models:
            exr = os.path.join(args.out, f"{r['name']}_bssrdf_{model}.exr")
            # The leaderboard's variants set the first object's model so.
            cached = find_cached(os.path.join(ROOT, args.cache), "bssrdf", r["scene"],
                                 size_sets + sets + [f'objects.0.material.model="{model}"'], args.bssrdf_spp)
            if single and cached:
                exr = cached
            if single and cached or os.path.exists(os.path.join(ROOT, exr)):
                j = json.loads(run([args.lucent, "compare", exr, volpath, "--json"]))["linear"]
                noise = j["reference_noise_rms"] * 3 ** 0.5
                row[model] = {"rmse": j["rmse_rgb"], "corrected": max(0.0, j["rmse_rgb"] ** 2 - noise ** 2) ** 0.5,
                              "noise": noise, "mean_error": j["mean_error"], "mean_error_se": j["mean_error_se"]}
                continue
            # Beside the scene file, so that its relative paths resolve as they do for the scene itself.
            tmp = os.path.join(os.path.dirname(r["scene"]), f".model_suite_{model}.json")
            with open(os.path.join(ROOT, tmp), "w") as f:
                json.dump(scene_with_model(scene, sets, model), f)
            try:
                cmd = [args.lucent, "reference", tmp, "--integrator", "bssrdf", "--spp", str(args.bssrdf_spp), "-q",
                       "-o", exr]
                for s in size_sets + [method]:
                    cmd += ["--set", s]
                run(cmd)
            finally:
                os.remove(os.path.join(ROOT, tmp))
            j = json.loads(run([args.lucent, "compare", exr, volpath, "--json"]))["linear"]
            noise = j["reference_noise_rms"] * 3 ** 0.5
            row[model] = {"rmse": j["rmse_rgb"], "corrected": max(0.0, j["rmse_rgb"] ** 2 - noise ** 2) ** 0.5,
                          "noise": noise, "mean_error": j["mean_error"], "mean_error_se": j["mean_error_se"]}
        results.append(row)
        print(f"{r['name']}: " + ", ".join(f"{m} {row[m]['corrected']:.4f}" for m in models), file=sys.stderr)
    json.dump(results, open(os.path.join(ROOT, args.out, "model_suite.json"), "w"), indent=1)

    print("| scene | " + " | ".join(models) + " | closest |")
    print("|---|" + "---|" * (len(models) + 1))
    wins = {m: 0 for m in models}
    for row in results:
        best = min(models, key=lambda m: row[m]["corrected"])
        wins[best] += 1
        cells = [f"{row[m]['corrected']:.4f}, {row[m]['mean_error']:+.4f}" for m in models]
        cells = [f"**{c}**" if m == best else c for c, m in zip(cells, models)]
        print(f"| {row['run']} | " + " | ".join(cells) + f" | {best} |")
    means = {m: sum(row[m]["corrected"] for row in results) / len(results) for m in models}
    bias = {m: sum(abs(row[m]["mean_error"]) for row in results) / len(results) for m in models}
    print("| mean corrected RMSE, mean abs(bias) | " + " | ".join(f"{means[m]:.4f}, {bias[m]:.4f}" for m in models) +
          f" | {min(models, key=means.get)} |")
    print("| closest on | " + " | ".join(str(wins[m]) for m in models) + " | |")


if __name__ == "__main__":
    main()
