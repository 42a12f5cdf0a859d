#!/usr/bin/env python3
"""A notebook session with the lucent Python module, cell by cell: load a scene, read and edit a material by
name, render in real time, tone-map for display, render a short CPU reference with a progress bar, compare, then
sweep a camera orbit and a material parameter through one live lucent.Renderer, timed against lucent.render calls.

    PYTHONPATH=build/python /usr/bin/python3 examples/python_notebook.py [--width 64 --height 40 --spp 4]

In a notebook, `plt.imshow(display)` shows the tone-mapped uint8 array; Ctrl-C (the notebook's interrupt) stops
a long lucent.reference or lucent.render with KeyboardInterrupt, and lucent's warnings arrive as
lucent.LucentWarning through Python's warnings module.
"""
import argparse
import sys
import time
import warnings

import numpy as np

import lucent


def progress_bar(label):
    def show(fraction):
        filled = int(30 * fraction)
        sys.stdout.write(f"\r{label} [{'#' * filled}{'.' * (30 - filled)}] {100 * fraction:5.1f}%")
        if fraction >= 1.0:
            sys.stdout.write("\n")
        sys.stdout.flush()
    return show


def orbit_camera(camera, degrees):
    """The scene camera turned about the vertical through its target."""
    a = np.radians(degrees)
    eye, target = np.array(camera["eye"]), np.array(camera["target"])
    d = eye - target
    eye = target + np.array([np.cos(a) * d[0] + np.sin(a) * d[2], d[1], -np.sin(a) * d[0] + np.cos(a) * d[2]])
    return dict(camera, eye=eye.tolist(), target=list(target), up=list(camera["up"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--width", type=int, default=64)
    parser.add_argument("--height", type=int, default=40)
    parser.add_argument("--spp", type=int, default=4, help="reference samples per pixel")
    parser.add_argument("--scene", default=None, help="scene file (default: the built-in scene)")
    parser.add_argument("--views", type=int, default=16, help="camera positions of the orbit (cell 7)")
    parser.add_argument("--frames", type=int, default=8, help="frames per lucent.render call (cell 7)")
    args = parser.parse_args()
    warnings.simplefilter("always", lucent.LucentWarning)

    # Cell 1: the scene, its objects by name and their materials as typed values.
    scene = lucent.load_scene(args.scene)
    print(scene)
    for obj in scene.objects:
        what = obj.material["name"] if obj.material else f"opaque, albedo {obj.albedo}"
        print(f"  objects[{obj.index}] '{obj.name}': {what}")
    name = next(obj.name for obj in scene.objects if obj.material)
    print(f"  {name}.material = {scene.objects[name].material}")

    # Cell 2: edit that material by name: another preset, then its refractive index.
    scene.set(f"objects.{name}.material", "Ketchup").set(f"objects.{name}.material.eta", 1.4)
    material = scene.objects[name].material
    assert material["name"] == "Ketchup" and abs(material["eta"] - 1.4) < 1e-6
    print(f"  now {material['name']}, eta {material['eta']}, sigma_s' {material['sigma_s_prime']} mm^-1")

    # Cell 3: a real-time render (the BSSRDF model on the GPU) and the array imshow wants.
    size = dict(width=args.width, height=args.height)
    image = lucent.render(scene, method="per-pixel", params={"N": 16, "light_map_size": 128}, frames=2, **size)
    display = lucent.tonemap(image, exposure=scene.exposure, operator=scene.tonemap)  # as `lucent render` shows it
    print(f"render: {image.shape} {image.dtype}, display: {display.shape} {display.dtype}, "
          f"mean display value {display.mean():.1f}")

    # Cell 4: the CPU reference of the same model, with a progress bar (Ctrl-C stops it).
    mean, standard_error = lucent.reference(scene, integrator="bssrdf", spp=args.spp,
                                            progress=progress_bar("reference"), **size)

    # Cell 5: how far the real-time image is from it, and what the reference's own noise accounts for.
    error = lucent.compare(image, mean, standard_error=standard_error)
    linear = error["linear"]
    print(f"RMSE {linear['rmse_rgb']:.4f} (reference noise {linear['reference_noise_rms'] * np.sqrt(3):.4f}), "
          f"display PSNR {error['display']['psnr_db']:.1f} dB")

    # Cell 7: a camera orbit and a material sweep, first as separate lucent.render calls (each loads the scene,
    # builds the renderer, compiles shaders and accumulates `frames` frames), then through one live renderer: it is
    # built once, and radiosity-maps' light-space maps go on accumulating while only the camera moves, so after the
    # first view one frame per view gives the converged image. A material edit restarts the accumulation (the maps
    # hold the old material) but keeps the shaders.
    live_scene = lucent.load_scene(args.scene)
    method, params = "radiosity-maps", {"K": 6, "N": 8, "map_size": 64, "light_map_size": 128}
    orbit = [orbit_camera(live_scene.camera, 360.0 * k / args.views) for k in range(args.views)]
    started = time.perf_counter()
    separate = []
    for camera in orbit:
        view = lucent.load_scene(args.scene).set("camera", camera)
        separate.append(lucent.render(view, method=method, params=params, frames=args.frames, **size))
    separate_s = time.perf_counter() - started
    started = time.perf_counter()
    with lucent.Renderer(live_scene, method=method, params=params, **size) as renderer:
        live = [renderer.render(camera=camera, frames=args.frames if k == 0 else 1) for k, camera in enumerate(orbit)]
        live_s = time.perf_counter() - started
        difference = max(float(np.sqrt(((a - b) ** 2).mean())) for a, b in zip(live, separate))
        print(f"orbit of {args.views} views: lucent.render {1000 * separate_s / args.views:.0f} ms per view, "
              f"lucent.Renderer {1000 * live_s / args.views:.0f} ms per view ({live_s / separate_s:.2f} of the "
              f"time); largest RMSE between the two images of a view {difference:.4f}")

        # The material sweep: one refractive index per call, `frames` frames each.
        sweep = [1.3, 1.4, 1.5]
        started = time.perf_counter()
        for eta in sweep:
            renderer.set(f"objects.{name}.material.eta", eta)
            renderer.render(frames=args.frames)
        live_sweep_s = time.perf_counter() - started
    started = time.perf_counter()
    for eta in sweep:
        edited = lucent.load_scene(args.scene).set(f"objects.{name}.material.eta", eta)
        lucent.render(edited, method=method, params=params, frames=args.frames, **size)
    separate_sweep_s = time.perf_counter() - started
    print(f"sweep of {len(sweep)} refractive indices: lucent.render {1000 * separate_sweep_s / len(sweep):.0f} ms "
          f"per value, lucent.Renderer {1000 * live_sweep_s / len(sweep):.0f} ms per value")

    # Cell 8: let go of the OpenGL context (GPU memory) when done; a later render makes a fresh one.
    lucent.release()
    return 0 if np.isfinite(linear["rmse_rgb"]) and display.max() > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
