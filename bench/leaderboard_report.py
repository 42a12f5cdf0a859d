#!/usr/bin/env python3
"""Writes docs/leaderboard.md (and its plots) from the results of `lucent bench bench/leaderboard.json`.

Usage: leaderboard_report.py RESULTS_JSON OUT_MD PLOT_DIR [--runtime SECONDS] [--command TEXT] [--notes FILE]

--notes: a hand-written markdown file (the reading of the numbers) placed after the summary.

Per scene: an error-against-time plot (every setting of every method, the Pareto front marked), the equal-time
ranking, and a table of every setting; then a summary of which method wins where. Only the Python standard library
and gnuplot (a lucent dependency) are used.

Definitions (also written into the page):
- time: the time to the image, frames x the median frame time (the sum of the method's GPU pass times), in ms;
  precomputation cached on disk (atlases, kernels, form factors, tables) is not counted.
- error: the RMSE of linear radiance against the volpath reference (the physics), corrected for the reference's own
  noise: sqrt(RMSE^2 - noise^2); the same against the bssrdf reference (the model) is in the tables.
- equal time: each method is ranked by its most accurate setting within a budget, at two budgets per scene: tight
  (the median over methods of each method's fastest setting) and generous (the largest of them).
"""
import json
import math
import os
import struct
import subprocess
import sys
import zlib


def fmt_ms(ms):
    return f"{ms:.1f} ms" if ms < 1000 else f"{ms / 1000:.2f} s"


def load(path):
    with open(path) as f:
        return json.load(f)


def error(result, integrator):
    e = result.get("error", {}).get(integrator)
    if e is None:
        return None
    if "rmse_rgb_corrected" in e:
        return e["rmse_rgb_corrected"]
    noise = e["reference_noise_rms"] * math.sqrt(3.0)
    return math.sqrt(max(0.0, e["rmse_rgb"] ** 2 - noise ** 2))


def time_ms(result):
    return result["frames"] * result["total_ms"]["median"]


def read_png(path):
    """8-bit RGB or RGBA PNG (as lucent writes them) -> (width, height, rows of RGB bytes)."""
    with open(path, "rb") as f:
        data = f.read()
    pos, idat, width, height, channels = 8, b"", 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            if depth != 8 or colour not in (2, 6):
                raise ValueError(f"{path}: only 8-bit RGB/RGBA PNGs")
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        rows.append(bytes(line[k] for k in range(stride) if k % channels < 3))
    return width, height, rows


def write_strip(paths, out_png, gap=2):
    """The images side by side (same height), separated by a dark gap: a contact strip for the page."""
    images = [read_png(p) for p in paths]
    height = max(h for _, h, _ in images)
    width = sum(w for w, _, _ in images) + gap * (len(images) - 1)
    raw = b""
    for y in range(height):
        line = b""
        for k, (w, h, rows) in enumerate(images):
            line += rows[y] if y < h else bytes(3 * w)
            if k + 1 < len(images):
                line += bytes([40, 40, 40]) * gap
        raw += b"\x00" + line
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff)
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    tmp = out_png + ".tmp"
    with open(tmp, "wb") as f:
        f.write(png)
    os.replace(tmp, out_png)


def pareto(points):
    """Indices of the points (time, error) not dominated by another (faster and at least as accurate)."""
    front = []
    for i, (t, e) in enumerate(points):
        dominated = any((t2 <= t and e2 <= e) and (t2 < t or e2 < e) for j, (t2, e2) in enumerate(points) if j != i)
        if not dominated:
            front.append(i)
    return front


def plot(run, rows, out_png):
    """Error (volpath) against time, log-log, one series per method, the Pareto front as a line."""
    methods = sorted({method_label(r) for r in rows})
    data = out_png[:-4] + ".dat"
    with open(data, "w") as f:
        for m in methods:
            f.write(f'"{m}"\n')
            for r in sorted((r for r in rows if method_label(r) == m), key=time_ms):
                f.write(f"{time_ms(r)} {max(error(r, 'volpath'), 1e-5)}\n")
            f.write("\n\n")
        pts = [(time_ms(r), error(r, "volpath")) for r in rows]
        f.write('"Pareto front"\n')
        for i in sorted(pareto(pts), key=lambda i: pts[i][0]):
            f.write(f"{pts[i][0]} {max(pts[i][1], 1e-5)}\n")
    colours = ["#e41a1c", "#377eb8", "#4daf4a", "#984ea3", "#ff7f00", "#a65628", "#f781bf", "#999999", "#17becf",
               "#bcbd22", "#000080", "#808000"]
    series = [f"'{data}' index {k} with linespoints lw 2 lc rgb '{colours[k % len(colours)]}' pt {k % 13 + 1} ps 1.3 "
              f"title columnheader(1)" for k in range(len(methods))]
    series.append(f"'{data}' index {len(methods)} with lines dt 2 lw 1 lc rgb 'black' title columnheader(1)")
    script = f"""set terminal pngcairo size 900,600 font ',11'
set output '{out_png}'
set logscale xy
set xlabel 'time to the image [ms] (frames x median frame time)'
set ylabel 'RMSE against volpath (noise-corrected)'
set title '{run}' noenhanced\nset key noenhanced
set key outside right top
set grid
plot {', '.join(series)}
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    os.remove(data)


def method_label(result):
    """The method as the page names it: with the denoising stage after it, "<method> + denoise"."""
    return result["method"] + (" + denoise" if result.get("denoise") else "")


def main():
    args = sys.argv[1:]
    runtime = None
    command = "bash bench/leaderboard.sh"
    if "--runtime" in args:
        k = args.index("--runtime")
        runtime = float(args[k + 1])
        del args[k:k + 2]
    notes = None
    if "--notes" in args:
        k = args.index("--notes")
        notes = args[k + 1]
        del args[k:k + 2]
    if "--command" in args:
        k = args.index("--command")
        command = args[k + 1]
        del args[k:k + 2]
    if len(args) != 3:
        sys.exit("usage: leaderboard_report.py RESULTS_JSON OUT_MD PLOT_DIR [--runtime S] [--command TEXT]")
    results_path, out_md, plot_dir = args
    doc = load(results_path)
    os.makedirs(plot_dir, exist_ok=True)
    results = doc["results"]
    runs = []
    for r in results:
        if r["run"] not in runs:
            runs.append(r["run"])

    md = ["# Leaderboard: every method on one scene suite against one ground truth", ""]
    md.append("Generated by `bench/leaderboard_report.py` from `lucent bench bench/leaderboard.json`; do not edit by "
              "hand, rerun the command below.")
    md.append("")
    md.append(f"- Device: {doc.get('device', '?')}.")
    md.append(f"- Command: `{command}`" + (f"; total runtime {runtime / 60:.1f} min." if runtime else "."))
    if doc.get("set"):
        md.append(f"- Overrides for every variant: `{' '.join(doc['set'])}`.")
    if not doc.get("complete", True):
        md.append("- **Incomplete**: the bench was stopped before its last run; the tables hold the runs it finished.")
    md.append("- **Time** is the time to the image: frames x the median frame time (the sum of the method's GPU pass "
              "times), in ms, measured after a warm-up frame and a restart of the method (`warmup_frames`), so a "
              "1-frame setting costs what an image after a scene change costs, without shader compilation or "
              "first-use driver work. Precomputation cached on disk (atlases, kernels, form factors, tables) is not counted. "
              "On a software rasterizer (llvmpipe) the times rank the methods' work, not what a GPU would show; "
              "`docs/performance.md` has GPU timings.")
    md.append("- **Error** is the RMSE of linear radiance against the volpath reference (the physics), corrected for "
              "the reference's own noise; `bssrdf` is the same against the BSSRDF reference (the material's own "
              "diffusion model), so error against volpath = model error + method error, and against bssrdf the "
              "method's error alone. relMSE is the mean of (a - b)^2 / (b^2 + 0.01); bias the mean of (a - b) +- "
              "its standard error.")
    md.append("- **Equal time**: each method is ranked by its most accurate setting within a time budget, at two "
              "budgets per scene: tight, the median (the lower middle value for an even count) over methods of each "
              "method's fastest setting (about half the methods fit), and generous, the largest of them (every method fits). The Pareto front holds the settings no other setting beats in both time and error.")
    md.append("")

    summary = []
    sections = []
    for run in runs:
        rows = [r for r in results if r["run"] == run and "refused" not in r and error(r, "volpath") is not None]
        refused = [r for r in results if r["run"] == run and "refused" in r]
        sec = [f"## {run}", ""]
        scene = next((r.get("scene") for r in results if r["run"] == run and r.get("scene")), None)
        if scene and os.path.exists(scene):
            with open(scene) as f:
                comment = json.load(f).get("comment", "")
            sec.append(f"`{scene}`: {comment.removeprefix('Leaderboard: ')}")
            sec.append("")
        if not rows:
            sec.append("No comparable results.")
            sections.append("\n".join(sec))
            continue
        png = os.path.join(plot_dir, f"{run}.png")
        plot(run, rows, png)
        rel = os.path.relpath(png, os.path.dirname(out_md) or ".")
        sec.append(f"![{run}: error against time]({rel})")
        sec.append("")
        # The references and, per method, its most accurate setting: what the numbers describe.
        images_dir = os.path.join(os.path.dirname(results_path), "images")
        by_method_best = {}
        for r in rows:
            if method_label(r) not in by_method_best or error(r, "volpath") < error(by_method_best[method_label(r)], "volpath"):
                by_method_best[method_label(r)] = r
        strip = [os.path.join(os.path.dirname(results_path), rows[0]["error"]["volpath"]["reference_image"])]
        names = ["volpath"]
        if "bssrdf" in rows[0]["error"]:
            strip.append(os.path.join(os.path.dirname(results_path), rows[0]["error"]["bssrdf"]["reference_image"]))
            names.append("bssrdf")
        for m in sorted(by_method_best):
            strip.append(os.path.join(os.path.dirname(results_path), by_method_best[m]["image"]))
            names.append(f"{m} ({by_method_best[m]['variant']})")
        if all(os.path.exists(p) for p in strip):
            strip_png = os.path.join(plot_dir, f"{run}_images.png")
            write_strip(strip, strip_png)
            sec.append(f"![{run}: references and each method's most accurate setting]"
                       f"({os.path.relpath(strip_png, os.path.dirname(out_md) or '.')})")
            sec.append("")
            sec.append("Left to right: " + "; ".join(names) + ".")
            sec.append("")
        # Equal-time rankings: at the tight budget (the median of the methods' fastest settings: half the methods
        # fit) and at the generous one (the largest: every method fits).
        by_method = {}
        for r in rows:
            by_method.setdefault(method_label(r), []).append(r)
        fastest_per_method = sorted(min(time_ms(r) for r in rs) for rs in by_method.values())
        budgets = {"tight": fastest_per_method[(len(fastest_per_method) - 1) // 2], "generous": fastest_per_method[-1]}
        rankings = {}
        for label, budget in budgets.items():
            ranking = []
            for m, rs in by_method.items():
                within = [r for r in rs if time_ms(r) <= budget * (1 + 1e-9)]
                if within:
                    best = min(within, key=lambda r: error(r, "volpath"))
                    ranking.append((error(best, "volpath"), m, best))
            ranking.sort(key=lambda x: x[0])
            rankings[label] = ranking
            over = sorted(m for m in by_method if m not in {x[1] for x in ranking})
            sec.append(f"Equal-time ranking, {label} budget ({fmt_ms(budget)})" +
                       (f"; over budget: {', '.join(over)}" if over else "") + ":")
            sec.append("")
            sec.append("| rank | method | setting | time | RMSE vs volpath | RMSE vs bssrdf |")
            sec.append("|---|---|---|---|---|---|")
            for k, (e, m, r) in enumerate(ranking):
                eb = error(r, "bssrdf")
                sec.append(f"| {k + 1} | {m} | {r['variant']} | {fmt_ms(time_ms(r))} | {e:.4f} | "
                           f"{'-' if eb is None else f'{eb:.4f}'} |")
            sec.append("")
        pts = [(time_ms(r), error(r, "volpath")) for r in rows]
        front = set(pareto(pts))
        sec.append("Every setting (Pareto front in bold):")
        sec.append("")
        sec.append("| method | setting | time | RMSE vs volpath | relMSE vs volpath | bias vs volpath | "
                   "RMSE vs bssrdf | error image (vs volpath) |")
        sec.append("|---|---|---|---|---|---|---|---|")
        order = sorted(range(len(rows)), key=lambda i: (method_label(rows[i]), pts[i][0]))
        for i in order:
            r = rows[i]
            ev = r["error"]["volpath"]
            eb = error(r, "bssrdf")
            name = f"**{r['variant']}**" if i in front else r["variant"]
            stem = os.path.splitext(os.path.basename(r["image"]))[0]
            sec.append(f"| {method_label(r)} | {name} | {fmt_ms(pts[i][0])} | {pts[i][1]:.4f} | {ev['relative_mse']:.4f} | "
                       f"{ev['mean_error']:+.4f} +- {ev['mean_error_se']:.4f} | {'-' if eb is None else f'{eb:.4f}'} | "
                       f"`images/{stem}+vs_volpath.png` |")
        for r in refused:
            sec.append(f"| {r['method']} | {r['variant']} | refused: {r['refused'].replace('|', '/')} | | | | | |")
        ref = rows[0]["error"]["volpath"]
        refb = rows[0]["error"].get("bssrdf")
        sec.append("")
        sec.append(f"References: volpath {ref['reference_spp']} spp ({ref['reference_seconds'] / 60:.1f} min, noise "
                   f"{ref['reference_noise_rms'] * math.sqrt(3):.4f})" +
                   (f"; bssrdf {refb['reference_spp']} spp ({refb['reference_seconds'] / 60:.1f} min, noise "
                    f"{refb['reference_noise_rms'] * math.sqrt(3):.4f})" if refb else "") + ".")
        sections.append("\n".join(sec))
        best_any = min(rows, key=lambda r: error(r, "volpath"))
        fastest = min(rows, key=time_ms)
        summary.append((run, rankings["tight"][0], rankings["generous"][0], best_any, len(refused)))

    md.append("## Summary: who wins where")
    md.append("")
    md.append("| scene | wins at the tight budget (RMSE vs volpath) | wins at the generous budget | "
              "most accurate at any time | refusals |")
    md.append("|---|---|---|---|---|")
    for run, (e, m, r), (e2, m2, r2), best, nref in summary:
        md.append(f"| {run} | {m}, {r['variant']} ({e:.4f}, {fmt_ms(time_ms(r))}) | {m2}, {r2['variant']} "
                  f"({e2:.4f}, {fmt_ms(time_ms(r2))}) | {method_label(best)}, {best['variant']} "
                  f"({error(best, 'volpath'):.4f}, {fmt_ms(time_ms(best))}) | {nref} |")
    md.append("")
    for k, label in ((1, "tight"), (2, "generous")):
        wins = {}
        for row in summary:
            wins.setdefault(row[k][1], []).append(row[0])
        md.append(f"Wins at the {label} budget: " + "; ".join(
            f"{m} {len(v)} ({', '.join(v)})" for m, v in sorted(wins.items(), key=lambda x: -len(x[1]))) + ".")
        md.append("")
    if notes and os.path.exists(notes):
        with open(notes) as f:
            md.append(f.read().rstrip("\n"))
        md.append("")
    md.extend(sections)
    md.append("")
    tmp = out_md + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(md))
    os.replace(tmp, out_md)
    print(f"{out_md}: {len(runs)} scenes, {len(results)} results")


if __name__ == "__main__":
    main()
