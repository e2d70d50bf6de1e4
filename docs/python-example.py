#!/usr/bin/env python3
"""The paper's §3.2 and §3.3 from Python, then a relight series — the spectralrenderer package (README, "Python").

    python3 docs/python-example.py [--out DIR] [--scale S] [--quick]

§3.2 (Fig. 4): the Stanford bunny wearing ColorChecker patches 5, 7, 14 and 19 under D65, and the bunny's mean rendered
spectrum (its pixels picked by object id).
§3.3 (Fig. 5): the statue under A, D65 and the blue and green LEDs. Then the §3.1 chart relit under blackbodies of
2000–10000 K (no ray traced: sr.relight from the render's per-light transfer), with the CIE 1931 chromaticity (x, y) of
one patch under each — computed with colour-science when it is installed (else from X, Y, Z by x = X/(X+Y+Z)), and
plotted (Matplotlib; colour-science's CIE 1931 diagram when both are there). Needs the meshes (SPECTRAL_MODELS, README
"Meshes") for §3.2–3.3: a part whose inputs are missing prints "skipped: <why>" and the script goes on.
Writes DIR/*.png (previews, plots) and DIR/chromaticities.csv.
"""
import argparse
import os
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
try:
    import spectralrenderer as sr
except ImportError:   # run from a checkout without the wheel installed: the package's source (SPECTRAL_LIBRARY set)
    sys.path.insert(0, str(REPO / "python"))
    import spectralrenderer as sr


def optional(name):
    """The module, or None when it is not installed (or is only a stand-in: colour-science puts a mock Matplotlib
    without a version into sys.modules when the real one is missing)."""
    try:
        module = __import__(name)
    except ImportError:
        return None
    return module if getattr(module, "__version__", None) else None


matplotlib = optional("matplotlib")  # before colour-science, which may stand a mock in for it
if matplotlib:
    matplotlib.use("Agg")
    import matplotlib.pyplot  # noqa: E402,F401
colour = optional("colour")          # colour-science


def mesh_missing(scene):
    """The scene's mesh file when it is on no model search path (README, "Meshes"), else None."""
    import re
    name = re.search(r'"file":\s*"([^"]+)"', (REPO / scene).read_text())
    if not name:
        return None
    folders = [REPO / "scenes", REPO / "models"] + [Path(p) for p in os.environ.get("SPECTRAL_MODELS", "").split(os.pathsep) if p]
    return None if any((f / name.group(1)).exists() for f in folders) else name.group(1)


def save_png(render, path):
    path.write_bytes(render._repr_png_())
    print(f"wrote {path}")


def xy(xyz):
    """CIE 1931 chromaticity of an X, Y, Z triple: colour-science's XYZ_to_xy when installed."""
    if colour:
        return tuple(colour.XYZ_to_xy(np.asarray(xyz, dtype=float)))
    x, y, z = xyz
    return x / (x + y + z), y / (x + y + z)


def object_pixels(render, name):
    """The pixels whose centre ray sees the object named `name` (render.json's objects, ids from 1)."""
    names = [o["name"] for o in render.manifest["objects"]]
    return render.ids == names.index(name) + 1


def section_3_2(out, scale, quick):
    for patch in ("05",) if quick else ("05", "07", "14", "19"):
        scene = f"scenes/paper-3.2-bunny-{patch}.json"
        if (missing := mesh_missing(scene)):
            print(f"skipped: §3.2 bunny {patch}: the mesh {missing} is not on the model search path (set SPECTRAL_MODELS)")
            return
        r = sr.render(REPO / scene, width=int(640 * scale), height=int(480 * scale), spp=1)
        save_png(r, out / f"bunny-{patch}.png")
        mean = r.cube[object_pixels(r, "bunny")].mean(axis=0)
        print(f"§3.2 bunny {patch}: mean band values " + " ".join(f"{v:.3f}" for v in mean[::4]) + " … (every 4th band)")
        if matplotlib:
            ax = sr.plot_spectrum(r.wavelengths, mean, label=f"bunny, patch {patch}", ylabel="band value (relative)")
            ax.figure.savefig(out / f"bunny-{patch}-spectrum.png")
            matplotlib.pyplot.close(ax.figure)


def section_3_3(out, scale, quick):
    for light in ("A",) if quick else ("A", "D65", "led-blue", "led-green"):
        scene = f"scenes/paper-3.3-statue-{light}.json"
        if (missing := mesh_missing(scene)):
            print(f"skipped: §3.3 statue: the mesh {missing} is not on the model search path (set SPECTRAL_MODELS)")
            return
        r = sr.render(REPO / scene, width=int(480 * scale), height=int(600 * scale), spp=1)
        save_png(r, out / f"statue-{light}.png")


def relight_series(out, scale, patch="patch-13"):
    chart = sr.render(REPO / "scenes/paper-3.1-colorchecker-d65.json", width=int(720 * scale), height=int(480 * scale),
                      formats="npy,lights")
    mask = object_pixels(chart, patch)
    rows = []
    for kelvin in (2000, 2856, 4000, 5000, 6504, 8000, 10000):
        r = sr.relight(chart, lights={"D65": f"blackbody:{kelvin}"})
        x, y = xy(r.xyz[mask].mean(axis=0))
        rows.append((kelvin, x, y))
        print(f"{patch} under blackbody:{kelvin}: CIE 1931 x = {x:.4f}, y = {y:.4f}")
    (out / "chromaticities.csv").write_text("kelvin,x,y\n" + "".join(f"{k},{x:.6f},{y:.6f}\n" for k, x, y in rows))
    print(f"wrote {out / 'chromaticities.csv'}" + ("" if colour else " (colour-science not installed: x = X/(X+Y+Z))"))
    if not matplotlib:
        print("skipped: the chromaticity plot: Matplotlib is not installed (pip install matplotlib)")
        return
    if colour:
        from colour.plotting import plot_chromaticity_diagram_CIE1931
        fig, ax = plot_chromaticity_diagram_CIE1931(show=False)
    else:
        fig, ax = matplotlib.pyplot.subplots()
    ax.plot([x for _, x, _ in rows], [y for _, _, y in rows], "o-", label=f"{patch} under blackbodies")
    for k, x, y in rows:
        ax.annotate(f"{k} K", (x, y), fontsize=7)
    ax.set_xlabel("CIE 1931 x")
    ax.set_ylabel("CIE 1931 y")
    ax.legend()
    fig.savefig(out / "chromaticities.png")
    print(f"wrote {out / 'chromaticities.png'}")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="python-example", help="output folder")
    p.add_argument("--scale", type=float, default=0.5, help="image size as a fraction of the scenes' own")
    p.add_argument("--quick", action="store_true", help="tiny images, one scene per section (a smoke test)")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    scale = 0.05 if a.quick else a.scale
    section_3_2(out, scale, a.quick)
    section_3_3(out, scale, a.quick)
    relight_series(out, scale)


if __name__ == "__main__":
    main()
