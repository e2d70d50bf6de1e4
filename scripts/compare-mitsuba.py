#!/usr/bin/env python3
"""Our `path` integrator against Mitsuba 3's path tracer on the same scene, side by side in one run (issue 23).

What it measures (a table on stdout, and --json FILE for machines):
  1. Region means, converged: our render and Mitsuba's of the same scene (same geometry, the same tabulated spectra
     given to Mitsuba as `irregular` spectra — no RGB upsampling —, the same pinhole camera and box pixel filter,
     physical radiometry) at high spp, each as K independent parts (seeds) so that the standard error of every
     figure is known. Our film holds band means of spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹); Mitsuba's `specfilm`
     channel j holds ∫ L(λ)·S_j(λ) dλ for its response S_j, so S_j is the band's box (1 inside the band) and the
     channel is divided by the band width. Regions: every object seen (by our object-id map, eroded by a pixel) and
     the four quadrants of the image (the room's pixels in them). Printed: per band the worst relative difference Mitsuba/ours − 1 over the
     regions, and the worst of all, with its standard error.
  2. Equal time: each renderer gets the same render-time budget T (spp chosen from the rates of part 1), R rounds,
     alternating ours / Mitsuba so that the machine's load hits both alike. Error of each image against its own
     converged reference (part 1, other seeds): RMS ΔE00 over the pixels of the room (CIE 1931 2°, XYZ from the 20
     bands, Lab white = D65 chromaticity at the luminance of the mean of the object named "back") and the RMS
     relative error of 8×8-pixel block means per band (blocks whose reference is above 1e-3 of the brightest). Errors are also scaled to exactly T (error·sqrt(t/T)), as noise falls as 1/√t.
  3. Samples per second of each (pixels × spp / render time). Ours: the render time render.json records (in the
     process, after scene load: includes the JIT's first calls). Mitsuba: mi.render() + read back of a kernel
     already compiled (a warm-up render with the same spp before every timed one; the compile is not counted).
Only ratios of one run are fair figures on a loaded machine.

Run with the anchors' Python (../shared/anchors/setup.sh VENV; test-only tooling, never an engine dependency):
    VENV/bin/python scripts/compare-mitsuba.py [--quick] [--scene scenes/path-cornell-room.json] [--json out.json]
Mitsuba's llvm_* variants need a libLLVM that can compile drjit's kernels (here LLVM 16 aborted on `fminimum`;
Debian 12's libllvm19 works): DRJIT_LIBLLVM_PATH, else the newest /usr/lib/*/libLLVM*.so* found at version >= 17,
else the scalar_spectral variant (said in the output). --regions-only stops after part 1 (the Interop test).
Exit 0 when it ran (the bars are printed, not enforced), 2 on bad input (an unsupported scene feature).

--xml FILE (issue 39): a Mitsuba 3 XML scene rendered by both from the same file — Mitsuba loads the XML itself, ours
imports it (`spectral render FILE.xml`, scenes/…/docs/import.md) — with only the film (its size; Mitsuba's becomes a
`specfilm` of box bands) and the sampler (sample count, seed) rewritten in a copy, so what is compared is the importer's
conversion of everything else. Our bands: --xml-bands (380:780:20). Also prints BAND lines (every region × band).

Part 1 also prints a TOTAL line per region: the radiance over the band range of ours and of Mitsuba's, their relative
difference and its standard error (the points of `spectral validate --mitsuba PYTHON`, which runs this script). --spectral
is our CLI: a spectral.dll (run by dotnet) or an executable.
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def fail(msg, code=2):
    print(f"compare-mitsuba: {msg}", file=sys.stderr)
    sys.exit(code)


def find_llvm():
    given = os.environ.get("DRJIT_LIBLLVM_PATH")
    if given:
        return given
    best = None
    for p in glob.glob("/usr/lib/*/libLLVM*.so*") + glob.glob("/usr/lib/llvm-*/lib/libLLVM*.so*"):
        m = re.search(r"libLLVM[-.]?(?:so\.)?(\d+)", os.path.basename(p))
        if m and int(m.group(1)) >= 17 and (best is None or int(m.group(1)) > best[0]):
            best = (int(m.group(1)), p)
    return best[1] if best else None


def spectral_command(args):
    """Our CLI: `dotnet spectral.dll` for a framework-dependent build's dll, else the executable itself (the apphost, a
    published or Native AOT binary), as `spectral validate --mitsuba` passes its own."""
    return ["dotnet", args.spectral] if args.spectral.endswith(".dll") else [args.spectral]


# ---------------------------------------------------------------- scene JSON (comments and trailing commas allowed)

def read_scene(path):
    text = open(path, encoding="utf-8").read()
    out, i, n, in_str = [], 0, len(text), False
    while i < n:
        c = text[i]
        if in_str:
            out.append(c)
            if c == "\\":
                out.append(text[i + 1]); i += 1
            elif c == '"':
                in_str = False
        elif c == '"':
            in_str = True; out.append(c)
        elif text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
            continue
        elif text.startswith("/*", i):
            i = text.index("*/", i) + 2
            continue
        else:
            out.append(c)
        i += 1
    return json.loads(re.sub(r",(\s*[}\]])", r"\1", "".join(out)))


def csv_table(name):
    import numpy as np
    with open(os.path.join(REPO, "data", name), encoding="utf-8") as f:
        head = f.readline().strip().split(",")
        rows = np.array([[float(v) for v in line.split(",")] for line in f if line.strip()])
    return head, rows


class Spectra:
    """The scene's spectra as (wavelengths, values) tables: the same data files and names our loader resolves."""
    # Built-ins whose table is used as published (100 at 560 nm); the flux-normalised ones (FL2, FL11, LEDs) are not here.
    ILLUMINANTS = ("A", "D65", "D50", "E")

    def __init__(self, scene):
        self.named = scene.get("spectra", {})

    def resolve(self, e, where):
        import numpy as np
        if isinstance(e, (int, float)):
            return np.array([300.0, 900.0]), np.array([float(e)] * 2)
        if isinstance(e, list):
            a = np.array(e, dtype=float)
            return a[:, 0], a[:, 1]
        if isinstance(e, dict):
            if "name" in e:
                wl, v = self.resolve(e["name"], where)
            elif "values" in e:
                wl, v = self.resolve(e["values"], where)
            elif "constant" in e:
                wl, v = self.resolve(float(e["constant"]), where)
            else:
                fail(f"{where}: spectrum objects with csv are not supported by this script")
            return wl, v * float(e.get("scale", 1))
        if isinstance(e, str):
            if e in self.named:
                return self.resolve(self.named[e], where)
            if e in self.ILLUMINANTS:
                head, rows = csv_table("illuminants.csv")
                return rows[:, 0], rows[:, head.index(e)]
            if e.startswith("colorchecker:"):
                key = e.split(":", 1)[1].lower()
                head, rows = csv_table("colorchecker-ohta.csv")
                for j, col in enumerate(head[1:], start=1):
                    number, name = col.split(" ", 1)
                    words = name.split("(")[0].strip().split(" ")
                    short = (f"neutral-{words[1]}" if words[0] == "neutral" else words[0]) if len(words) == 2 \
                        and re.match(r"^[0-9.]+$", words[1]) else "-".join(words)
                    if key in (str(int(number)), short.lower(), name.lower(), "-".join(name.lower().split())):
                        return rows[:, 0], rows[:, j]
            fail(f"{where}: spectrum '{e}' is not supported by this script (D65, A, D50, E, colorchecker:*, numbers, pairs)")
        fail(f"{where}: unexpected spectrum {e!r}")


# ---------------------------------------------------------------- our renderer

def ours_render(args, scene, width, height, spp, seed, out):
    """One `spectral render` of the scene with the path integrator's seed set; returns (bands H×W×N, ids, render_s)."""
    import numpy as np
    s = dict(scene)
    integ = s.get("integrator", "path")
    integ = {"type": integ} if isinstance(integ, str) else dict(integ)
    integ["seed"] = seed
    if args.spectral_grid:
        integ["spectral_grid"] = args.spectral_grid
    s["integrator"] = integ
    cmd = [*spectral_command(args), "render", "-", "-o", out, "--width", str(width), "--height", str(height),
           "--spp", str(spp), "--formats", "npy,aov", "--quiet"]
    r = subprocess.run(cmd, input=json.dumps(s), text=True, capture_output=True, cwd=os.path.dirname(args.scene))
    if r.returncode != 0:
        fail(f"our render failed ({' '.join(cmd)}):\n{r.stderr}", 1)
    meta = json.load(open(os.path.join(out, "render.json")))
    ids = read_png16(os.path.join(out, "object-id.png"))
    return np.load(os.path.join(out, "spectral.npy")).astype(np.float64), ids, meta["timings_s"]["render"], meta


def read_png16(path):
    import mitsuba as mi
    import numpy as np
    a = np.array(mi.Bitmap(path))
    return a.reshape(a.shape[:2]).astype(np.int64)


# ---------------------------------------------------------------- Mitsuba's scene

def mitsuba_scene(scene, spectra, edges, width, height, sampler):
    import mitsuba as mi
    import numpy as np

    def irregular(wl, v, scale=1.0):
        if np.all(v == v[0]):   # a constant (Mitsuba's irregular spectrum cannot be 0 everywhere)
            return {"type": "uniform", "value": float(v[0] * scale)}
        return {"type": "irregular", "wavelengths": ", ".join(f"{x:g}" for x in wl),
                "values": ", ".join(f"{x * scale:.9g}" for x in v)}

    def spectrum(e, where, scale=1.0):
        wl, v = spectra.resolve(e, where)
        return irregular(wl, v, scale)

    if scene.get("radiometry") != "physical":
        fail("$.radiometry: the comparison needs a physical scene (Mitsuba renders radiance)")
    for key in ("background", "sky", "ambient"):
        if key in scene:
            fail(f"$.{key}: not translated to Mitsuba by this script")
    cam = scene["camera"]
    up = cam.get("up", [0, 1, 0])
    d = {"type": "scene"}
    integ = scene.get("integrator", "path")
    integ = {"type": integ} if isinstance(integ, str) else integ
    max_depth = integ.get("max_depth", -1)
    d["integrator"] = {"type": "path", "max_depth": -1 if max_depth < 0 else max_depth + 1,
                       "rr_depth": int(integ.get("rr_depth", 5))}
    film = {"type": "specfilm", "width": width, "height": height, "component_format": "float32",
            "rfilter": {"type": "box"}}
    for b in range(len(edges) - 1):
        lo, hi = edges[b], edges[b + 1]
        # a box response over the band: a `regular` spectrum (its resolution, 5 nm here, sets the film's sampling table)
        film[f"band{b:03d}"] = {"type": "regular", "wavelength_min": float(lo), "wavelength_max": float(hi),
                                "values": ", ".join(["1"] * 5)}
    d["sensor"] = {"type": "perspective", "fov": float(cam.get("fov", 40)), "fov_axis": "y",
                   "to_world": mi.ScalarTransform4f().look_at(origin=cam["position"], target=cam["look_at"], up=up),
                   "sampler": {"type": sampler, "sample_count": 4}, "film": film}
    mats = scene["materials"]
    for i, o in enumerate(scene["objects"]):
        where = f"$.objects[{i}]"
        m = mats[o["material"]]
        if m.get("type") not in ("lambertian",):
            fail(f"$.materials.{o['material']}: only lambertian materials are translated")
        bsdf = {"type": "twosided", "bsdf": {"type": "diffuse",
                                             "reflectance": spectrum(m["reflectance"], f"$.materials.{o['material']}")}}
        if o["type"] == "quad":
            size = o.get("size", [1, 1])
            size = [size, size] if isinstance(size, (int, float)) else size
            n = np.array(o["normal"], float); n /= np.linalg.norm(n)
            u = np.array(o.get("up", [0, 1, 0]), float)
            x = np.cross(u, n); x /= np.linalg.norm(x)
            y = np.cross(n, x)
            c = o.get("center", [0, 0, 0])
            # our canonical quad is [-1/2, 1/2]² (normal +z), Mitsuba's rectangle [-1, 1]²
            mat = np.identity(4)
            mat[:3, 0] = x * size[0] / 2; mat[:3, 1] = y * size[1] / 2; mat[:3, 2] = n; mat[:3, 3] = c
            shape = {"type": "rectangle", "to_world": mi.ScalarTransform4f(mat.tolist())}
        elif o["type"] == "box":
            lo = np.array(o["min"], float) if "min" in o else np.array(o["center"]) - np.array(o["size"]) / 2
            hi = np.array(o["max"], float) if "max" in o else np.array(o["center"]) + np.array(o["size"]) / 2
            shape = {"type": "cube", "to_world": mi.ScalarTransform4f().translate(((lo + hi) / 2).tolist())
                     @ mi.ScalarTransform4f().scale(((hi - lo) / 2).tolist())}
        else:
            fail(f"{where}: object type '{o['type']}' is not translated by this script (quad, box)")
        if "transform" in o:
            fail(f"{where}.transform: not translated by this script")
        shape["bsdf"] = bsdf
        if "emission" in m:
            e = m["emission"]
            if e.get("two_sided"):
                fail(f"$.materials.{o['material']}.emission.two_sided: Mitsuba's area light is one-sided")
            # spectral radiance W·m⁻²·sr⁻¹·nm⁻¹ = spectrum × radiance, on the side the normal points to (both renderers)
            shape["emitter"] = {"type": "area", "radiance": spectrum(e["spectrum"], f"$.materials.{o['material']}.emission",
                                                                    float(e.get("radiance", 1)))}
        d[f"obj{i:03d}_{o.get('name', '')}"] = shape
    for i, light in enumerate(scene.get("lights", [])):
        if light.get("type") != "point":
            fail(f"$.lights[{i}]: only point lights are translated")
        # radiant intensity W·sr⁻¹·nm⁻¹ = spectrum × intensity (physical radiometry)
        d[f"light{i:03d}"] = {"type": "point", "position": light["position"],
                              "intensity": spectrum(light.get("spectrum", "D65"), f"$.lights[{i}]",
                                                    float(light.get("intensity", 1)))}
    return mi.load_dict(d)


def mitsuba_render(mi_scene, spp, seed, band_width, warm):
    """One mi.render at spp (a warm-up render of the same size first when warm is set, not timed): band means, seconds
    and the spp the sampler really took (stratified and ldsampler round it)."""
    import mitsuba as mi
    import numpy as np
    if warm:
        np.array(mi.render(mi_scene, spp=spp, seed=seed + 7919))
    t = time.perf_counter()
    img = np.array(mi.render(mi_scene, spp=spp, seed=seed))
    took = mi_scene.sensors()[0].sampler().sample_count()
    return img.astype(np.float64) / band_width[None, None, :], time.perf_counter() - t, took


# ---------------------------------------------------------------- comparison

def regions(ids, names):
    import numpy as np
    h, w = ids.shape
    bw, bh = w // 2, h // 2
    pad = np.pad(ids, 1, constant_values=-1)
    interior = np.ones_like(ids, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            interior &= pad[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] == ids
    out = {}
    for k in sorted(set(ids.reshape(-1).tolist()) - {0}):
        mask = interior & (ids == k)
        if mask.sum() >= 4:
            out[names.get(k, f"object {k}")] = mask
    for y in range(0, h - bh + 1, bh):
        for x in range(0, w - bw + 1, bw):
            mask = np.zeros_like(interior); mask[y:y + bh, x:x + bw] = True
            mask &= ids != 0
            if mask.sum() >= bw * bh // 4:
                out[f"quadrant {x},{y}"] = mask
    return out


def colour_error(img, ref, room, cmf, yn):
    import colour
    import numpy as np
    xyz = img @ cmf / yn
    xyz_ref = ref @ cmf / yn
    white = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]
    de = colour.delta_E(colour.XYZ_to_Lab(xyz, white), colour.XYZ_to_Lab(xyz_ref, white), method="CIE 2000")
    return float(np.sqrt(np.mean(de[room] ** 2)))


def block_error(img, ref, block=8):
    import numpy as np
    h, w, n = img.shape
    hb, wb = h // block, w // block
    a = img[:hb * block, :wb * block].reshape(hb, block, wb, block, n).mean(axis=(1, 3))
    r = ref[:hb * block, :wb * block].reshape(hb, block, wb, block, n).mean(axis=(1, 3))
    ok = r > 1e-3 * r.max()
    return float(np.sqrt(np.mean(((a[ok] - r[ok]) / r[ok]) ** 2)))


def band_cmf(edges):
    """∫ x̄, ȳ, z̄ dλ over each band (CIE 1931 2°, data/cie1931-2deg-cmf.csv, linear between its rows, 0.1 nm steps)."""
    import numpy as np
    _, rows = csv_table("cie1931-2deg-cmf.csv")
    out = np.zeros((len(edges) - 1, 3))
    for b in range(len(edges) - 1):
        lam = np.arange(edges[b], edges[b + 1], 0.1) + 0.05
        for c in range(3):
            out[b, c] = np.interp(lam, rows[:, 0], rows[:, 1 + c]).sum() * 0.1
    return out


# ---------------------------------------------------------------- a Mitsuba XML scene rendered by both (--xml)

def xml_copy(path, width, height, spp, seed, edges, work, tag, sampler="independent"):
    """The XML with its film and sampler rewritten: ours (edges None) an hdrfilm of width × height, Mitsuba's a specfilm
    with one box response per band; the sampler's sample_count and seed set. Written beside the original when the scene
    refers to files (relative paths keep working), else in the work folder; returns its path."""
    import xml.etree.ElementTree as ET
    tree = ET.parse(path)
    sensor = tree.getroot().find("sensor")
    if sensor is None:
        fail(f"{path}: no <sensor>")
    for old in sensor.findall("film") + sensor.findall("sampler"):
        sensor.remove(old)
    sampling = ET.SubElement(sensor, "sampler", {"type": sampler})
    ET.SubElement(sampling, "integer", {"name": "sample_count", "value": str(spp)})
    ET.SubElement(sampling, "integer", {"name": "seed", "value": str(seed)})
    film = ET.SubElement(sensor, "film", {"type": "hdrfilm" if edges is None else "specfilm"})
    ET.SubElement(film, "integer", {"name": "width", "value": str(width)})
    ET.SubElement(film, "integer", {"name": "height", "value": str(height)})
    ET.SubElement(film, "rfilter", {"type": "box"})
    if edges is not None:
        ET.SubElement(film, "string", {"name": "component_format", "value": "float32"})
        for b in range(len(edges) - 1):
            band = ET.SubElement(film, "spectrum", {"name": f"band{b:03d}", "type": "regular"})
            ET.SubElement(band, "float", {"name": "wavelength_min", "value": f"{edges[b]:g}"})
            ET.SubElement(band, "float", {"name": "wavelength_max", "value": f"{edges[b + 1]:g}"})
            ET.SubElement(band, "string", {"name": "values", "value": ", ".join(["1"] * 5)})
    refers = any("filename" in e.attrib or e.get("name") == "filename" for e in tree.iter())
    folder = os.path.dirname(os.path.abspath(path)) if refers else work
    out = os.path.join(folder, f".compare-mitsuba-{os.getpid()}-{tag}.xml")
    tree.write(out, encoding="utf-8", xml_declaration=True)
    return out


def ours_render_xml(args, width, height, spp, seed, out, work):
    """`spectral render COPY.xml` (the importer's conversion in memory); returns (bands H×W×N, ids, render_s, meta)."""
    import numpy as np
    copy = xml_copy(args.xml, width, height, spp, seed, None, work, f"ours{seed}")
    try:
        cmd = [*spectral_command(args), "render", copy, "-o", out, "--bands", args.xml_bands, "--formats", "npy,aov", "--quiet"]
        r = subprocess.run(cmd, text=True, capture_output=True)
    finally:
        os.remove(copy)
    if r.returncode != 0:
        fail(f"our render failed ({' '.join(cmd)}):\n{r.stderr}", 1)
    meta = json.load(open(os.path.join(out, "render.json")))
    ids = read_png16(os.path.join(out, "object-id.png"))
    return np.load(os.path.join(out, "spectral.npy")).astype(np.float64), ids, meta["timings_s"]["render"], meta


def mitsuba_load_xml(args, width, height, edges, work):
    import mitsuba as mi
    copy = xml_copy(args.xml, width, height, 1, 0, edges, work, "mitsuba", args.mitsuba_sampler)
    try:
        return mi.load_file(copy)
    finally:
        os.remove(copy)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default=os.path.join(REPO, "scenes", "path-cornell-room.json"))
    ap.add_argument("--quick", action="store_true", help="32×24, fewer samples and rounds (a smoke run, minutes)")
    ap.add_argument("--regions-only", action="store_true", help="only the converged region means (part 1)")
    ap.add_argument("--width", type=int); ap.add_argument("--height", type=int)
    ap.add_argument("--ref-spp", type=int, help="spp of each converged reference (ours and Mitsuba's)")
    ap.add_argument("--parts", type=int, help="independent parts (seeds) of each reference")
    ap.add_argument("--time", type=float, help="the equal-time budget T in seconds of render time")
    ap.add_argument("--rounds", type=int, help="equal-time rounds")
    ap.add_argument("--variant", help="Mitsuba variant (default llvm_ad_spectral when a libLLVM >= 17 is found)")
    ap.add_argument("--spectral-grid", type=float, help="our internal grid's width in nm (default: the scene's, 5)")
    ap.add_argument("--mitsuba-sampler", default="independent",
                    help="Mitsuba's sampler: independent (its default), stratified, multijitter, orthogonal, ldsampler")
    ap.add_argument("--spectral", default=os.path.join(REPO, "src", "SpectralRenderer.Cli", "bin", "Release", "net10.0",
                                                       "spectral.dll"), help="our CLI's spectral.dll (built if absent)")
    ap.add_argument("--json", help="write every figure to this file")
    ap.add_argument("--xml", help="a Mitsuba 3 XML scene: Mitsuba renders the file, ours imports it (issue 39)")
    ap.add_argument("--xml-bands", default="380:780:20", help="our bands for --xml (edges start:end:count)")
    args = ap.parse_args()
    args.scene = os.path.abspath(args.xml or args.scene)
    if args.xml:
        args.xml = os.path.abspath(args.xml)
        args.regions_only = True   # the equal-time parts compare a JSON scene
    q = args.quick
    width = args.width or (32 if q else 64)
    height = args.height or (24 if q else 48)
    ref_spp = args.ref_spp or (1024 if q else 16384)
    parts = args.parts or (2 if q else 4)
    budget = args.time or (0.5 if q else 2.0)
    rounds = args.rounds or (2 if q else 5)
    if parts < 2:
        fail("--parts must be at least 2 (the standard errors come from the spread of the parts)")

    llvm = None
    if args.variant is None or args.variant.startswith("llvm"):
        llvm = find_llvm()
        if llvm:
            os.environ["DRJIT_LIBLLVM_PATH"] = llvm
    variant = args.variant or ("llvm_ad_spectral" if llvm else "scalar_spectral")
    import warnings
    warnings.filterwarnings("ignore", module="colour")   # its notes on optional SciPy/Matplotlib
    import numpy as np
    import mitsuba as mi
    mi.set_variant(variant)

    if not os.path.exists(args.spectral):
        print("building our CLI (Release) ...", file=sys.stderr)
        subprocess.run(["dotnet", "build", "-c", "Release", "-v", "q", "-nologo",
                        os.path.join(REPO, "src", "SpectralRenderer.Cli")], check=True, stdout=subprocess.DEVNULL)
    scene = None if args.xml else read_scene(args.scene)
    spectra = None if args.xml else Spectra(scene)
    work = tempfile.mkdtemp(prefix="compare-mitsuba-")

    # Part 1: converged references, K parts each, ours and Mitsuba's alternating.
    part_spp = max(1, ref_spp // parts)
    pass_spp = min(part_spp, 256)
    ours_parts, mi_parts, ours_rate, mi_rate = [], [], [], []
    mi_scene = edges = None
    for k in range(parts):
        if args.xml:
            img, ids, secs, meta = ours_render_xml(args, width, height, part_spp, 1000 + k, os.path.join(work, f"ref{k}"), work)
        else:
            img, ids, secs, meta = ours_render(args, scene, width, height, part_spp, 1000 + k, os.path.join(work, f"ref{k}"))
        ours_parts.append(img); ours_rate.append(width * height * part_spp / secs)
        if mi_scene is None:
            edges = np.array(meta["bands"]["edges_nm"], float)
            mi_scene = mitsuba_load_xml(args, width, height, edges, work) if args.xml else \
                mitsuba_scene(scene, spectra, edges, width, height, args.mitsuba_sampler)
            band_width = np.diff(edges)
            mitsuba_render(mi_scene, pass_spp, 0, band_width, warm=False)   # compile
        acc, secs, done = 0, 0.0, 0
        while done < part_spp:
            img, t, took = mitsuba_render(mi_scene, pass_spp, 100000 * (k + 1) + done, band_width, warm=False)
            acc = acc + img * took; secs += t; done += took
        mi_parts.append(acc / done); mi_rate.append(width * height * done / secs)
        print(f"reference part {k + 1}/{parts}: ours {part_spp} spp {ours_rate[-1]:.0f} samples/s, "
              f"Mitsuba {done} spp {mi_rate[-1]:.0f} samples/s", file=sys.stderr)
    ours_ref, mi_ref = np.mean(ours_parts, axis=0), np.mean(mi_parts, axis=0)
    regs = regions(ids, {o["id"]: o["name"] for o in meta["objects"]})
    nb = len(edges) - 1
    rows, worst_band, band_lines = [], np.zeros(nb), []
    worst = (0.0, None, None, 0.0)
    for name, mask in regs.items():
        o = np.array([p[mask].mean(axis=0) for p in ours_parts])   # K × bands
        m = np.array([p[mask].mean(axis=0) for p in mi_parts])
        om, mm = o.mean(axis=0), m.mean(axis=0)
        rel = mm / om - 1
        se = np.sqrt((o.std(axis=0, ddof=1) / om) ** 2 + (m.std(axis=0, ddof=1) / om) ** 2) / np.sqrt(parts)
        b = int(np.argmax(np.abs(rel)))
        for j in range(nb):   # machine-readable, every band (the importer's Interop test)
            band_lines.append(f"BAND region={name.replace(' ', '_')} band={j + 1} rel={rel[j]:.6f} se={se[j]:.6f}")
        # The region's radiance over the band range, ∫L dλ = Σ band mean × width (W·m⁻²·sr⁻¹), each part's; Mitsuba/ours − 1
        # and its standard error from the parts as above (`spectral validate --mitsuba`'s points).
        ot, mt = o @ np.diff(edges), m @ np.diff(edges)
        tr = mt.mean() / ot.mean() - 1
        tse = np.sqrt((ot.std(ddof=1) / ot.mean()) ** 2 + (mt.std(ddof=1) / ot.mean()) ** 2) / np.sqrt(parts)
        band_lines.append(f"TOTAL region={name.replace(' ', '_')} pixels={int(mask.sum())} ours={ot.mean():.9g} "
                          f"mitsuba={mt.mean():.9g} rel={tr:.6f} se={tse:.6f}")
        rows.append((name, int(mask.sum()), float(rel[b]), int(b), float(se[b]), float(np.mean(rel))))
        worst_band = np.maximum(worst_band, np.abs(rel))
        if abs(rel[b]) > abs(worst[0]):
            worst = (float(rel[b]), name, b, float(se[b]))

    print(f"\n# Mitsuba {mi.__version__} {variant}" + (f" (libLLVM {llvm})" if llvm and variant.startswith("llvm") else "")
          + f" against ours, {os.path.relpath(args.scene, REPO)}, {width}×{height}")
    print(f"## 1. converged region means: {parts} parts × {part_spp} spp each (ours: seeds 1000…; Mitsuba: {args.mitsuba_sampler} sampler, other seeds)")
    print(f"{'region':<14}{'pixels':>7}{'worst band':>12}{'Mi/ours-1':>11}{'± se':>9}{'mean over bands':>17}")
    for name, n, rel, b, se, mean in rows:
        print(f"{name:<14}{n:>7}{b + 1:>12}{rel * 100:>10.2f}%{se * 100:>8.2f}%{mean * 100:>16.2f}%")
    print("per band, worst |Mi/ours-1| over the regions (%): "
          + " ".join(f"{edges[b]:.0f}-{edges[b + 1]:.0f}:{worst_band[b] * 100:.2f}" for b in range(nb)))
    print(f"WORST region {worst[1]} band {worst[2] + 1}: {worst[0] * 100:+.2f}% ± {worst[3] * 100:.2f}% (bar: within 1%)")
    result = {"variant": variant, "scene": os.path.relpath(args.scene, REPO), "width": width, "height": height,
              "parts": parts, "part_spp": part_spp, "regions": [dict(zip(("name", "pixels", "rel", "band", "se", "mean"), r))
                                                             for r in rows],
              "worst_region_rel": worst[0], "worst_region_se": worst[3], "worst_per_band": worst_band.tolist(),
              "ref_rate_ours": float(np.median(ours_rate)), "ref_rate_mitsuba": float(np.median(mi_rate))}
    for name, n, rel, b, se, mean in rows:   # machine-readable (the Interop test)
        print(f"REGION name={name.replace(' ', '_')} pixels={n} band={b + 1} rel={rel:.6f} se={se:.6f} mean={mean:.6f}")
    print(f"REGIONS worst_rel={worst[0]:.6f} se={worst[3]:.6f} regions={len(rows)}")
    print("\n".join(band_lines))

    if not args.regions_only:
        # Part 2 and 3: equal time, R rounds alternating.
        cmf = band_cmf(edges)
        room = ids != 0
        back = regs.get("back")
        yn = float((ours_ref @ cmf)[back if back is not None else room][:, 1].mean())
        px = width * height
        spp_o = max(1, round(budget * float(np.median(ours_rate)) / px))
        spp_m = max(1, round(budget * float(np.median(mi_rate)) / px))
        eo, em = [], []
        for r in range(rounds):
            for who in (("ours", "mitsuba") if r % 2 == 0 else ("mitsuba", "ours")):
                if who == "ours":
                    img, _, t, _ = ours_render(args, scene, width, height, spp_o, 7 + r, os.path.join(work, f"eq{r}"))
                    ref, spp, acc = ours_ref, spp_o, eo
                else:
                    img, t, took = mitsuba_render(mi_scene, spp_m, 7 + r, band_width, warm=True)
                    ref, spp, acc = mi_ref, took, em
                de, be = colour_error(img, ref, room, cmf, yn), block_error(img, ref)
                s = np.sqrt(t / budget)
                acc.append((t, px * spp / t, de, be, de * s, be * s))
        med = lambda a, i: float(np.median([x[i] for x in a]))
        print(f"\n## 2. equal time: budget T = {budget} s of render time, {rounds} rounds alternating; "
              f"ours {spp_o} spp, Mitsuba {spp_m} spp (medians over rounds)")
        print(f"{'':<10}{'time s':>8}{'samples/s':>12}{'RMS dE00':>10}{'8x8 rel':>9}{'dE00@T':>9}{'8x8@T':>9}")
        for name, a in (("ours", eo), ("mitsuba", em)):
            print(f"{name:<10}{med(a, 0):>8.3f}{med(a, 1):>12.0f}{med(a, 2):>10.3f}{med(a, 3) * 100:>8.2f}%"
                  f"{med(a, 4):>9.3f}{med(a, 5) * 100:>8.2f}%")
        ratio_de, ratio_be = med(em, 4) / med(eo, 4), med(em, 5) / med(eo, 5)
        ratio_rate = med(eo, 1) / med(em, 1)
        print(f"Mitsuba/ours error at T: RMS dE00 {ratio_de:.2f}×, 8×8 block means {ratio_be:.2f}× (bar: >= 2×)")
        print(f"## 3. samples per second, ours/Mitsuba: {ratio_rate:.2f} (equal-time rounds), "
              f"{result['ref_rate_ours'] / result['ref_rate_mitsuba']:.2f} (reference parts) (bar: >= 1)")
        print(f"EQUALTIME de_ratio={ratio_de:.4f} block_ratio={ratio_be:.4f} rate_ratio={ratio_rate:.4f}")
        result.update({"budget_s": budget, "rounds": rounds, "spp_ours": spp_o, "spp_mitsuba": spp_m,
                       "ours": eo, "mitsuba": em, "de_ratio": ratio_de, "block_ratio": ratio_be, "rate_ratio": ratio_rate})
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
