#!/usr/bin/env python3
"""Writes the corpus of broken inputs and faults (tests/corpus/inputs/*, tests/corpus/cases.json).

Each case: the command line (placeholders {in} = inputs/, {tmp} = a fresh folder for the case), set-up steps
run in {tmp} before it, the exit code and a regular expression the one line on stderr must match, and for bad
input (exit 2) the file (or option) the message must name and a pattern for the place in it. The test
(CorpusTests) runs every case through the real CLI in-process and checks all of that, plus: one printable line
of at most ~300 characters, a hint, and nothing written to the output folder. Run this script after changing
it; commit its output. found/ keeps the inputs fuzzing found (fuzz/run.sh), each also a case here.
"""
import json, os, shutil, struct, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
IN = os.path.join(HERE, "inputs")
shutil.rmtree(IN, ignore_errors=True)
os.makedirs(IN)
cases = []

def write(name, data):
    path = os.path.join(IN, name)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode("utf-8"))
    return name

def case(name, args, stderr, exit=2, file=None, place=None, setup=None):
    cases.append({"name": name, "args": args, "setup": setup or [], "exit": exit, "stderr": stderr,
                  "file": file, "place": place})

def render(scene, *extra):
    return ["render", scene, "-o", "{tmp}/out", "--quiet", *extra]

JSONPLACE = r"\.json:\d+:\d+|\.json: \$"
BASE = {
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 6},
    "materials": {"green": {"diffuse": "colorchecker:14"}},
    "lights": [{"type": "point", "position": [0, 3, 3], "spectrum": "D65"}],
    "objects": [{"type": "sphere", "radius": 1, "material": "green"}],
}

def scene_text(obj):
    return json.dumps(obj, indent=2, ensure_ascii=False)

def deep(obj):
    return json.loads(json.dumps(obj))

n = 0
def scene_case(label, obj_or_text, stderr, exit=2, place=JSONPLACE, extra=(), setup=None, file=None):
    global n
    n += 1
    fname = f"scene-{n:03d}-{label}.json"
    data = obj_or_text if isinstance(obj_or_text, (str, bytes)) else scene_text(obj_or_text)
    write(fname, data)
    case(f"scene/{label}", render("{in}/" + fname, *extra), stderr, exit, file or fname if exit == 2 else None,
         place if exit == 2 else None, setup)

def mutate(path, value):
    s = deep(BASE)
    cur = s
    for k in path[:-1]:
        cur = cur[k]
    if value is DELETE:
        del cur[path[-1]]
    else:
        cur[path[-1]] = value
    return s

DELETE = object()

# ---- A. scene JSON ---------------------------------------------------------------------------------
good = scene_text(BASE)
# syntax: the good text cut at many places
for i, cut in enumerate(range(1, len(good) - 1, max(1, len(good) // 24))):
    scene_case(f"truncated-at-{cut}", good[:cut], r"JSON syntax error|expected|missing")
scene_case("empty-object", "{}", r"missing required field 'camera'")
scene_case("array-root", "[]", r"expected an object, found an array")
scene_case("number-root", "5", r"expected an object, found a number")
scene_case("missing-comma", good.replace('"width": 8,', '"width": 8'), r"JSON syntax error")
scene_case("extra-bracket", good + "}", r"JSON syntax error")
scene_case("single-quotes", good.replace('"D65"', "'D65'"), r"JSON syntax error")
scene_case("nan-literal", good.replace('"radius": 1', '"radius": NaN'), r"JSON syntax error")
scene_case("infinity-literal", good.replace('"radius": 1', '"radius": Infinity'), r"JSON syntax error")
scene_case("number-overflow", good.replace('"radius": 1', '"radius": 1e999'), r"out of range|not a finite|cannot be represented")
scene_case("latin1-byte", good.replace('"green"', '"gr\u00fcn"', 1).encode("latin-1"), r"not valid UTF-8")
scene_case("nul-byte", good.replace('"D65"', '"D\u000065"'), r"JSON syntax error|unknown spectrum")
scene_case("raw-nul-outside", good.replace("{", "{\x00", 1), r"JSON syntax error")
scene_case("utf16-no-bom", good.encode("utf-16-le"), r"not valid UTF-8|JSON syntax error")
scene_case("duplicate-top-key", good.replace('"camera"', '"objects": [], "camera"', 1), r"key 'objects' appears a second time")
scene_case("duplicate-camera-key", good.replace('"width": 8', '"width": 8, "width": 9'), r"key 'width' appears a second time")
scene_case("duplicate-material", good.replace('"green": {', '"green": {"diffuse": 0.5}, "green": {'), r"key 'green' appears a second time")
scene_case("comment-unclosed", good.replace("{", "{ /* no end", 1), r"JSON syntax error")
# types
for label, path, value, pat in [
    ("camera-not-object", ["camera"], 5, r"expected an object, found a number"),
    ("camera-missing", ["camera"], DELETE, r"missing required field 'camera'"),
    ("objects-missing", ["objects"], DELETE, r"missing required field 'objects'"),
    ("objects-not-array", ["objects"], {}, r"expected an array of objects"),
    ("lights-not-array", ["lights"], "D65", r"expected an array of lights"),
    ("materials-array", ["materials"], [], r"expected an object, found an array"),
    ("position-string", ["camera", "position"], "0,0,5", r"expected \[x, y, z\]"),
    ("position-two", ["camera", "position"], [0, 5], r"expected \[x, y, z\]"),
    ("position-null-entry", ["camera", "position"], [0, None, 5], r"expected a number, found null"),
    ("position-1e39", ["camera", "position"], [0, 0, 1e39], r"out of range"),
    ("position-1e8", ["camera", "position"], [0, 0, 1e8], r"out of range"),
    ("lookat-equals-position", ["camera", "look_at"], [0, 0, 5], r"look_at equals position"),
    ("up-parallel", ["camera", "up"], [0, 0, 1], r"up is parallel"),
    ("up-zero", ["camera", "up"], [0, 0, 0], r"up is parallel"),
    ("fov-zero", ["camera", "fov"], 0, r"out of range"),
    ("fov-180", ["camera", "fov"], 180, r"out of range"),
    ("fov-string", ["camera", "fov"], "40", r"expected a number, found a string"),
    ("width-zero", ["camera", "width"], 0, r"not positive"),
    ("width-negative", ["camera", "width"], -8, r"not positive"),
    ("width-fraction", ["camera", "width"], 8.5, r"expected a whole number"),
    ("width-huge", ["camera", "width"], 40000, r"exceeds 32768"),
    ("width-beyond-int", ["camera", "width"], 1e12, r"expected a whole number"),
    ("framebuffer-too-big", ["camera"], {"position": [0, 0, 5], "look_at": [0, 0, 0], "width": 30000, "height": 30000}, r"framebuffer"),
    ("spp-zero", ["camera", "spp"], 0, r"out of range"),
    ("spp-huge", ["camera", "spp"], 10**9, r"out of range"),
    ("camera-unknown-key", ["camera", "zoom"], 2, r"unknown field 'zoom'"),
    ("top-unknown-key", ["colour"], 1, r"unknown field 'colour'"),
    ("max-depth-negative", ["max_depth"], -1, r"out of range"),
    ("max-depth-65", ["max_depth"], 65, r"out of range"),
    ("max-depth-string", ["max_depth"], "5", r"expected a whole number"),
    ("bands-number", ["bands"], 20, r"expected a string such as"),
    ("bands-bad", ["bands"], "380-780-20", r"is not a band grid"),
    ("bands-empty-range", ["bands"], "780:380:20", r"empty or not positive"),
    ("bands-zero-count", ["bands"], "380:780:0", r"outside 1"),
    ("bands-text", ["bands"], "a:b:c", r"non-numeric"),
    ("integration-bad", ["integration"], "bogus", r"unknown band integration"),
    ("observer-bad", ["observer"], 5, r"observer|unknown"),
    ("scaling-bad", ["scaling"], "photometric", r"unknown scaling"),
    ("white-unknown", ["white"], "D66", r"unknown spectrum 'D66'"),
    ("white-dark", ["white"], 0, r"no luminance"),
    ("name-object", ["name"], {"a": 1}, r"expected a string"),
    ("description-array", ["description"], [1, 2, 3], r"expected a string"),
    ("description-long", ["description"], "x" * 5000, r"more than 4096"),
    ("output-not-object", ["output"], "png", r"expected an object"),
    ("output-formats-empty", ["output"], {"formats": []}, r"names no output format"),
    ("output-formats-unknown", ["output"], {"formats": ["tiff"]}, r"unknown output format 'tiff'"),
    ("output-formats-string", ["output"], {"formats": "png"}, r"expected an array of format names"),
    ("output-rgb-bad", ["output"], {"rgb": "adobe"}, r"adobe|unknown"),
    ("output-exposure-negative", ["output"], {"exposure": -1}, r"out of range"),
    ("output-exr-bad", ["output"], {"exr_compression": "piz"}, r"unknown EXR compression"),
    ("output-unknown", ["output"], {"dpi": 300}, r"unknown field 'dpi'"),
    ("background-bad", ["background"], "nothing", r"unknown spectrum"),
    ("ambient-negative", ["ambient"], -1, r"out of range"),
]:
    scene_case(label, mutate(path, value), pat)

def with_material(m, label, pat, exit=2):
    s = deep(BASE); s["materials"]["green"] = m; scene_case(label, s, pat, exit)

for label, m, pat in [
    ("mat-unknown-key", {"diffuse": 0.5, "glossy": 1}, r"unknown field 'glossy'"),
    ("mat-diffuse-unknown", {"diffuse": "colorchecker:99"}, r"ColorChecker patch 99 does not exist"),
    ("mat-diffuse-negative", {"diffuse": -0.5}, r"out of range"),
    ("mat-diffuse-1e39", {"diffuse": 1e39}, r"out of range"),
    ("mat-shininess-negative", {"diffuse": 0.5, "shininess": -1}, r"out of range"),
    ("mat-model-bad", {"diffuse": 0.5, "model": "cook"}, r"unknown specular model"),
    ("mat-ior-zero", {"diffuse": 0.5, "ior": 0}, r"out of range"),
    ("mat-ior-string", {"diffuse": 0.5, "ior": "glass"}, r"expected a number, .*\{\"spectrum\": …\}, found a string"),
    ("mat-cauchy-short", {"diffuse": 0.5, "ior": {"cauchy": [1.5]}}, r"expected \[A, B\]"),
    ("mat-ior-key", {"diffuse": 0.5, "ior": {"cauchy": [1.5, 4200], "abbe": 60}}, r"unknown field 'abbe'"),
    ("mat-fresnel-string", {"diffuse": 0.5, "fresnel": "yes"}, r"expected true or false"),
    ("mat-values-number", {"diffuse": {"values": 5}}, r"expected inline pairs"),
    ("mat-values-object", {"diffuse": {"values": {"a": 1}}}, r"expected inline pairs"),
    ("mat-spectrum-two-kinds", {"diffuse": {"name": "D65", "constant": 1}}, r"exactly one of"),
    ("mat-spectrum-none", {"diffuse": {"scale": 2}}, r"exactly one of"),
    ("mat-scale-1e39", {"diffuse": {"constant": 1, "scale": 1e39}}, r"out of range"),
    ("mat-scale-overflow", {"diffuse": {"constant": 1e30, "scale": 1e30}}, r"beyond 1E\+30|beyond 1e\+30|reaches"),
    ("mat-extrapolate-bad", {"diffuse": {"values": [[400, 0.1], [700, 0.9]], "extrapolate": "mirror"}}, r"unknown extrapolation"),
    ("mat-inline-one-pair", {"diffuse": [[400, 0.5]]}, r"at least two"),
    ("mat-inline-unsorted", {"diffuse": [[700, 0.5], [400, 0.5]]}, r"does not follow"),
    ("mat-inline-equal", {"diffuse": [[400, 0.5], [400, 0.5]]}, r"does not follow"),
    ("mat-inline-negative-wl", {"diffuse": [[-400, 0.5], [700, 0.5]]}, r"out of range"),
    ("mat-inline-triple", {"diffuse": [[400, 0.5, 1], [700, 0.5]]}, r"expected a pair"),
    ("mat-inline-short-range", {"diffuse": [[400, 0.5], [700, 0.5]]}, r"covers 400–700 nm"),
    ("mat-inline-string-value", {"diffuse": [[380, "a"], [780, 0.5]]}, r"expected a number, found a string"),
    ("mat-csv-missing", {"diffuse": {"csv": "nothere.csv", "column": "r"}}, r"not found"),
    ("mat-csv-no-column", {"diffuse": {"csv": "nothere.csv"}}, r"missing required field 'column'"),
    ("mat-bool", {"diffuse": True}, r"expected a spectrum"),
    ("mat-ansi-name", {"diffuse": "\x1b[31mred\x1b[0m"}, r"unknown spectrum '\\e\[31mred\\e\[0m'"),
    ("mat-newline-name", {"diffuse": "line1\nline2"}, r"unknown spectrum 'line1\\nline2'"),
    ("mat-long-name", {"diffuse": "z" * 10000}, r"unknown spectrum 'z+…z+'"),
]:
    with_material(m, label, pat)

def with_light(l, label, pat, exit=2):
    s = deep(BASE); s["lights"] = [l]; scene_case(label, s, pat, exit)

for label, l, pat in [
    ("light-no-type", {"position": [0, 3, 3], "spectrum": "D65"}, r"missing required field 'type'"),
    ("light-type-bad", {"type": "area", "position": [0, 3, 3], "spectrum": "D65"}, r"unknown light type 'area'"),
    ("light-no-spectrum", {"type": "point", "position": [0, 3, 3]}, r"missing required field 'spectrum'"),
    ("light-no-position", {"type": "point", "spectrum": "D65"}, r"missing required field 'position'"),
    ("light-intensity-negative", {"type": "point", "position": [0, 3, 3], "spectrum": "D65", "intensity": -1}, r"out of range"),
    ("light-intensity-1e39", {"type": "point", "position": [0, 3, 3], "spectrum": "D65", "intensity": 1e39}, r"out of range"),
    ("light-intensity-overflow", {"type": "point", "position": [0, 3, 3], "spectrum": {"constant": 1e30}, "intensity": 1e20}, r"beyond"),
    ("light-attenuation-zero", {"type": "point", "position": [0, 3, 3], "spectrum": "D65", "attenuation": [0, 0, 0]}, r"all attenuation coefficients are zero"),
    ("light-attenuation-two", {"type": "point", "position": [0, 3, 3], "spectrum": "D65", "attenuation": [1, 0]}, r"expected \[c0, c1, c2\]"),
    ("light-attenuation-negative", {"type": "point", "position": [0, 3, 3], "spectrum": "D65", "attenuation": [1, -1, 0]}, r"out of range"),
    ("spot-no-direction", {"type": "spot", "position": [0, 3, 3], "spectrum": "D65"}, r"needs a direction or look_at"),
    ("spot-cutoff-200", {"type": "spot", "position": [0, 3, 3], "spectrum": "D65", "direction": [0, -1, 0], "cutoff": 200}, r"out of range"),
    ("spot-lookat-self", {"type": "spot", "position": [0, 3, 3], "spectrum": "D65", "look_at": [0, 3, 3]}, r"look_at equals position"),
    ("directional-zero", {"type": "directional", "direction": [0, 0, 0], "spectrum": "D65"}, r"zero vector"),
    ("directional-position", {"type": "directional", "direction": [0, -1, 0], "position": [0, 1, 0], "spectrum": "D65"}, r"unknown field 'position'"),
    ("light-name-number", {"type": "point", "position": [0, 3, 3], "spectrum": "D65", "name": 5}, r"expected a string"),
    ("light-not-object", "D65", r"expected an object, found a string"),
]:
    with_light(l, label, pat)

def with_object(o, label, pat, exit=2, setup=None):
    s = deep(BASE); s["objects"] = [o]; scene_case(label, s, pat, exit, setup=setup)

for label, o, pat in [
    ("obj-no-type", {"radius": 1, "material": "green"}, r"missing required field 'type'"),
    ("obj-type-bad", {"type": "cone", "material": "green"}, r"unknown object type 'cone'"),
    ("obj-no-material", {"type": "sphere"}, r"missing required field 'material'"),
    ("obj-material-unknown", {"type": "sphere", "material": "gren"}, r"did you mean 'green'"),
    ("sphere-radius-zero", {"type": "sphere", "radius": 0, "material": "green"}, r"out of range"),
    ("sphere-radius-negative", {"type": "sphere", "radius": -1, "material": "green"}, r"out of range"),
    ("sphere-radius-1e300", {"type": "sphere", "radius": 1e300, "material": "green"}, r"out of range"),
    ("sphere-radius-1e-20", {"type": "sphere", "radius": 1e-20, "material": "green"}, r"out of range"),
    ("sphere-center-1e39", {"type": "sphere", "center": [1e39, 0, 0], "material": "green"}, r"out of range"),
    ("box-size-1e-20", {"type": "box", "size": [1e-20, 1, 1], "material": "green"}, r"at least 1E-06|at least 1e-06"),
    ("box-size-negative", {"type": "box", "size": [-1, 1, 1], "material": "green"}, r"at least"),
    ("box-min-above-max", {"type": "box", "min": [1, 1, 1], "max": [0, 0, 0], "material": "green"}, r"at least"),
    ("box-min-only", {"type": "box", "min": [0, 0, 0], "material": "green"}, r"missing required field 'max'"),
    ("quad-size-three", {"type": "quad", "size": [1, 1, 1], "material": "green"}, r"expected \[width, height\]"),
    ("quad-up-parallel", {"type": "quad", "normal": [0, 1, 0], "up": [0, 1, 0], "material": "green"}, r"up is parallel to the normal"),
    ("plane-normal-zero", {"type": "plane", "normal": [0, 0, 0], "material": "green"}, r"zero vector"),
    ("transform-scale-zero", {"type": "sphere", "material": "green", "transform": {"scale": [0, 1, 1]}}, r"zero or extreme scale"),
    ("transform-scale-1e-20", {"type": "sphere", "material": "green", "transform": {"scale": 1e-20}}, r"out of range"),
    ("transform-unknown", {"type": "sphere", "material": "green", "transform": {"shear": 1}}, r"unknown field 'shear'"),
    ("colorchecker-material", {"type": "colorchecker", "material": "green"}, r"chooses its own materials"),
    ("colorchecker-patch-zero", {"type": "colorchecker", "patch_size": 0}, r"out of range"),
    ("mesh-no-file", {"type": "mesh", "material": "green"}, r"missing required field 'file'"),
    ("mesh-not-found", {"type": "mesh", "file": "missing.obj", "material": "green"}, r"not found"),
    ("mesh-wrong-extension", {"type": "mesh", "file": "scene-001-truncated-at-1.json", "material": "green"}, r"neither \.obj nor \.ply"),
    ("mesh-shading-bad", {"type": "mesh", "file": "tri.obj", "material": "green", "shading": "phong"}, r"unknown shading"),
    ("mesh-normals-bad", {"type": "mesh", "file": "tri.obj", "material": "green", "normals": "auto"}, r"unknown normals"),
    ("mesh-fit-inverted", {"type": "mesh", "file": "tri.obj", "material": "green", "fit": {"min": [1, 1, 1], "max": [0, 0, 0]}}, r"max is below min"),
    ("mesh-fit-1e39", {"type": "mesh", "file": "tri.obj", "material": "green", "fit": {"min": [-1e39, 0, 0], "max": [1, 1, 1]}}, r"out of range"),
    ("mesh-transform-far", {"type": "mesh", "file": "tri.obj", "material": "green", "transform": {"scale": 1e6, "translate": [9.5e6, 0, 0]}}, r"outside ±10000000"),
]:
    with_object(o, label, pat)
write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
s = deep(BASE); s["objects"] = [{"type": "sphere", "material": "green", "name": "a"}, {"type": "sphere", "material": "green", "name": "a"}]
scene_case("objects-same-name", s, r"two objects are named 'a'")
s = deep(BASE); s["objects"] = [{"type": "sphere", "material": "green", "name": "x\x1b[2J\ny"}, {"type": "sphere", "material": "green", "name": "x\x1b[2J\ny"}]
scene_case("objects-same-name-ansi", s, r"two objects are named 'x\\e\[2J\\ny'")
# named spectra: cycles by graph search, long valid chains
for k in (1, 2, 3, 30):
    s = deep(BASE); s["spectra"] = {f"s{i}": f"s{(i + 1) % k}" for i in range(k)}
    s["materials"]["green"] = {"diffuse": "s0"}
    scene_case(f"spectra-cycle-{k}", s, r"cycle: 's0' → .*'s0'")
s = deep(BASE); s["spectra"] = {f"s{i}": f"s{i + 1}" for i in range(21)}; s["spectra"]["s21"] = "colorchecker:14"
s["materials"]["green"] = {"diffuse": "s0"}
scene_case("spectra-chain-21", s, r"^$", exit=0)
s = deep(BASE); s["spectra"] = {f"s{i}": {"name": f"s{i + 1}", "scale": 1} for i in range(200)}; s["spectra"]["s200"] = "colorchecker:14"
s["materials"]["green"] = {"diffuse": "s0"}
scene_case("spectra-chain-200-objects", s, r"^$", exit=0)
s = deep(BASE); s["spectra"] = {"a": "b", "b": "c", "c": "b"}; s["materials"]["green"] = {"diffuse": "a"}
scene_case("spectra-cycle-tail", s, r"cycle: 'b' → 'c' → 'b'")
s = deep(BASE); s["spectra"] = {"a": {"name": "a"}}; s["materials"]["green"] = {"diffuse": "a"}
scene_case("spectra-cycle-object", s, r"cycle: 'a' → 'a'")
s = deep(BASE); s["spectra"] = "D65"
scene_case("spectra-not-object", s, r"expected an object, found a string")
s = deep(BASE); s["spectra"] = {"x": [[380, 1], [780, 1]]}; s["materials"]["green"] = {"diffuse": "y"}
scene_case("spectra-unknown-ref", s, r"unknown spectrum 'y'")

# ---- B. CLI arguments and files --------------------------------------------------------------------
write("good.json", good)
def cli(label, args, pat, exit=2, file=None, place=None, setup=None):
    case(f"cli/{label}", args, pat, exit, file, place, setup)
OPT = r"--[a-z-]+|-o|command line"
cli("no-command", [], r"usage|^$", exit=2)
cli("unknown-command", ["rendr"], r"unknown command 'rendr'.*did you mean 'render'", file="rendr", place=r"command")
cli("render-no-scene", ["render"], r"no scene file given", file="command line", place=OPT)
cli("render-two-scenes", ["render", "{in}/good.json", "{in}/good.json"], r"unexpected argument", file="command line", place=OPT)
cli("unknown-option", render("{in}/good.json", "--widht", "8"), r"unknown option '--widht'.*did you mean '--width'", file="command line", place=OPT)
cli("option-no-value", ["render", "{in}/good.json", "--width"], r"option --width needs a value", file="command line", place=OPT)
for opt, val, pat in [("--width", "abc", r"not a whole number"), ("--width", "0", r"not positive"), ("--width", "-5", r"not positive"),
                      ("--width", "99999999999", r"not a whole number"), ("--width", "40000", r"exceeds 32768"), ("--height", "1e3", r"not a whole number"),
                      ("--spp", "0", r"not a whole number in 1–65536"), ("--spp", "1000000", r"not a whole number in 1–65536"),
                      ("--threads", "0", r"not a whole number in 1–1024"), ("--threads", "5000", r"not a whole number"),
                      ("--bands", "0", r"band count 0 is outside 1–1024"), ("--bands", "4000", r"band count 4000 is outside 1–1024"), ("--bands", "abc", r"neither a band count"), ("--bands", "780:380:3", r"empty or not positive"),
                      ("--bands", "380:780:100000", r"outside 1"), ("--band-range", "1:2", r"not a band grid"),
                      ("--rgb", "adobe", r"adobe"), ("--integration", "bogus", r"unknown band integration"),
                      ("--formats", "", r"names no output format"), ("--formats", ",", r"names no output format"), ("--formats", "tiff", r"unknown output format 'tiff'"),
                      ("--exr-compression", "piz", r"unknown EXR compression"), ("--models", "{in}/no-such-folder", r"does not exist")]:
    file = "good.json" if opt in ("--width", "--height", "--bands", "--band-range") and pat in (r"not positive", r"exceeds 32768") else opt
    cli(f"{opt[2:]}-{val or 'empty'}".replace("/", "_").replace(":", "_").replace(",", "comma"), render("{in}/good.json", opt, val), pat, file=file, place=OPT + "|" + JSONPLACE)
cli("out-empty", ["render", "{in}/good.json", "-o", "", "--quiet"], r"output folder name is empty", file="-o", place=OPT)
cli("out-is-file", ["render", "{in}/good.json", "-o", "{in}/good.json", "--quiet"], r"exists and is a file", file="good.json", place=r".")
cli("out-long", ["render", "{in}/good.json", "-o", "{tmp}/" + "d" * 5000 + "/x", "--quiet"], r"cannot be written", file="ddd", place=r".")
cli("out-under-file", ["render", "{in}/good.json", "-o", "{in}/good.json/sub", "--quiet"], r"cannot be written|exists and is a file|Not a directory", file="good.json", place=r".")
cli("out-unwritable", ["render", "{in}/good.json", "-o", "{tmp}/ro/out", "--quiet"], r"cannot be written", file="ro", place=r".", setup=["mkdir ro", "chmod-ro ro"])
cli("scene-missing", render("{in}/missing.json"), r"scene file not found", file="missing.json", place=r".")
cli("scene-folder", render("{in}"), r"is a folder", file="inputs", place=r".")
cli("scene-empty", render("{tmp}/empty.json"), r"empty or not a regular file", file="empty.json", place=r".", setup=["touch empty.json"])
cli("scene-fifo", render("{tmp}/fifo.json"), r"empty or not a regular file", file="fifo.json", place=r".", setup=["mkfifo fifo.json"])
cli("scene-dev-zero", render("{tmp}/zero.json"), r"empty or not a regular file", file="zero.json", place=r".", setup=["symlink zero.json /dev/zero"])
cli("scene-dangling-link", render("{tmp}/dangling.json"), r"symbolic link .* does not exist", file="dangling.json", place=r".", setup=["symlink dangling.json {tmp}/nowhere.json"])
cli("scene-dev-null", render("/dev/null"), r"empty or not a regular file", file="/dev/null", place=r".")
cli("probe-no-folder", ["probe"], r"give one render folder", file="command line", place=OPT)
cli("probe-missing-folder", ["probe", "{tmp}/nothing", "--pixel", "1,1"], r"no such render folder", file="nothing", place=r".")
cli("probe-no-pixel", ["probe", "{tmp}"], r"give at least one --pixel", file="command line", place=OPT)
cli("colorcheck-missing", ["colorcheck", "{tmp}/nothing"], r"no such render folder", file="nothing", place=r".")
cli("colorcheck-empty-folder", ["colorcheck", "{tmp}"], r"has no render.json", file="{tmp}", place=r".")
cli("reconstruct-none", ["reconstruct"], r"give one render folder", file="command line", place=OPT)
cli("bench-two", ["bench", "a", "b"], r"unexpected argument", file="command line", place=OPT)

# mesh faults in the scene's folder (the loader looks there first)
for label, step, pat in [("fifo", "mkfifo m.obj", r"empty or not a regular file"), ("dev-zero", "symlink m.obj /dev/zero", r"empty or not a regular file"),
                         ("folder", "mkdir m.obj", r"not found"), ("empty", "touch m.obj", r"empty or not a regular file"),
                         ("dangling", "symlink m.obj {tmp}/gone.obj", r"not found|does not exist")]:
    s = deep(BASE); s["objects"] = [{"type": "mesh", "file": "m.obj", "material": "green"}]
    write(f"mesh-scene-{label}.json", scene_text(s))
    case(f"mesh/{label}", render("{tmp}/scene.json"), pat, 2, "m.obj", r".", [f"copy {{in}}/mesh-scene-{label}.json scene.json", step])

# ---- C. CSV spectra ---------------------------------------------------------------------------------
def csv_case(label, text, pat, column="r"):
    fname = f"csv-{label}.csv"
    write(fname, text)
    s = deep(BASE); s["materials"]["green"] = {"diffuse": {"csv": fname, "column": column}}
    sname = f"csv-{label}.json"
    write(sname, scene_text(s))
    scene_level = "has no column" in pat or "covers" in pat
    case(f"csv/{label}", render("{in}/" + sname), pat, 2, sname if scene_level else fname, JSONPLACE if scene_level else r"\.csv:\d+:\d+: ")

rows = "".join(f"{w},{0.5}\n" for w in range(380, 781, 10))
for label, text, pat in [
    ("empty-lines-only", "\n\n\n", r"the file is empty"),
    ("header-only", "wavelength_nm,r\n", r"header but no data rows"),
    ("one-column", "wavelength_nm\n380\n", r"fewer than two columns"),
    ("duplicate-column", "wavelength_nm,r,r\n380,1,1\n", r"column name 'r' appears twice"),
    ("empty-column-name", "wavelength_nm,,r\n380,1,1\n", r"column 2 has no name"),
    ("not-a-number", "wavelength_nm,r\n380,abc\n", r"'abc' in column 'r' is not a number"),
    ("nan", "wavelength_nm,r\n380,NaN\n780,1\n", r"not finite"),
    ("infinity", "wavelength_nm,r\n380,Infinity\n780,1\n", r"not finite"),
    ("1e39", "wavelength_nm,r\n380,1e39\n780,1\n", r"not finite"),
    ("negative", "wavelength_nm,r\n380,-0.1\n780,1\n", r"negative value"),
    ("unsorted", "wavelength_nm,r\n780,1\n380,1\n", r"not ascending"),
    ("duplicate-wl", "wavelength_nm,r\n380,1\n380,1\n", r"appears twice"),
    ("zero-wl", "wavelength_nm,r\n0,1\n780,1\n", r"not positive"),
    ("missing-cell", "wavelength_nm,r,g\n380,1\n", r"missing column"),
    ("extra-cell", "wavelength_nm,r\n380,1,2\n", r"cells, the header names only"),
    ("blank-line-inside", "wavelength_nm,r\n380,1\n\n780,1\n", r"empty line inside the data"),
    ("latin1", "wavelength_nm,r\n380,0.5\xb5\n".encode("latin-1"), r"is not a number"),
    ("nul-byte", "wavelength_nm,r\n380,0.\x005\n", r"'0\.\\05' in column 'r' is not a number"),
    ("ansi-cell", "wavelength_nm,r\n380,\x1b[31m1\n", r"'\\e\[31m1' in column"),
    ("long-cell", "wavelength_nm,r\n380," + "9" * 2000 + "x\n", r"'9+…9+x' in column 'r' is not a number"),
    ("comma-decimal", "wavelength_nm;r\n380;0,5\n", r"fewer than two columns|not a number|cells"),
    ("short-range", "wavelength_nm,r\n400,1\n700,1\n", r"covers 400–700 nm"),
    ("binary", bytes(range(256)) * 4, r"not a number|columns|cells|empty line"),
    ("hex-number", "wavelength_nm,r\n380,0x10\n", r"not a number"),
    ("space-in-number", "wavelength_nm,r\n380,1 2\n", r"not a number"),
    ("missing-wavelength", "wavelength_nm,r\n,1\n", r"not a number"),
]:
    csv_case(label, text, pat)
csv_case("no-such-column", "wavelength_nm,r\n" + rows, r"has no column 'x'", column="x")
csv_case("column-ansi", "wavelength_nm,r\n" + rows, r"has no column '\\e\[1m'", column="\x1b[1m")

# Photometric files (IES LM-63, EULUMDAT) of a goniometric light: file:line and a hint.
def photometric_case(label, ext, text, pat):
    fname = f"lum-{label}.{ext}"
    write(fname, text)
    s = deep(BASE); s["radiometry"] = "physical"
    s["lights"] = [{"type": "goniometric", "position": [0, 3, 3], "file": fname, "spectrum": "D65"}]
    sname = f"lum-{label}.json"
    write(sname, scene_text(s))
    case(f"photometric/{label}", render("{in}/" + sname), pat, 2, fname, r"\." + ext + r":\d+")
IES_HEAD = "IESNA:LM-63-2002\n[TEST] corpus\nTILT=NONE\n"
for label, text, pat in [
    ("ies-no-tilt", "IESNA:LM-63-2002\n[TEST] x\n", r"no TILT= line"),
    ("ies-tilt-file", "IESNA:LM-63-2002\nTILT=lamp.tlt\n", r"not supported"),
    ("ies-cut-short", IES_HEAD + "1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n10 20\n", r"ends before a candela value"),
    ("ies-type-b", IES_HEAD + "1 1000 1 2 1 2 2 0 0 0\n1 1 0\n0 90\n0\n10 20\n", r"photometric type 2"),
    ("ies-angles-descending", IES_HEAD + "1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 90 45\n0\n1 2 3\n", r"not ascending"),
    ("ies-horizontal-odd", IES_HEAD + "1 1000 1 2 2 1 2 0 0 0\n1 1 0\n0 90\n0 45\n1 2\n3 4\n", r"horizontal angles 0 … 45"),
    ("ies-candela-text", IES_HEAD + "1 1000 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n10 ten\n", r"'ten', not a number"),
    ("ies-candela-negative", IES_HEAD + "1 1000 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n10 -1\n", r"negative"),
    ("ies-nan", IES_HEAD + "1 1000 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n10 NaN\n", r"not a number"),
    ("ies-huge-count", IES_HEAD + "1 1000 1 999999999 1 1 2 0 0 0\n", r"number of vertical angles"),
    ("ies-trailing", IES_HEAD + "1 1000 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n10 20 30\n", r"values after the candela table"),
    # Issue 42: horizontal angles 0–270 match no LM-63 symmetry (were read as a full circle); a TILT=INCLUDE block is read.
    ("ies-horizontal-0-270", IES_HEAD + "1 1000 1 2 4 1 2 0 0 0\n1 1 0\n0 90\n0 90 180 270\n1 2\n1 2\n1 2\n1 2\n",
     r"horizontal angles 0 … 270 match no LM-63 symmetry"),
    ("ies-tilt-geometry-4", "IESNA:LM-63-2002\nTILT=INCLUDE\n4\n", r"lamp-to-luminaire geometry"),
    ("ies-tilt-factor-negative", "IESNA:LM-63-2002\nTILT=INCLUDE\n1\n2\n0 90\n1 -0.5\n", r"tilt factor"),
    ("ies-tilt-angle-above-90", "IESNA:LM-63-2002\nTILT=INCLUDE\n1\n2\n0 120\n1 0.5\n", r"tilt"),
]:
    photometric_case(label, "ies", text, pat)
LDT_HEAD = "corpus\n1\n1\n1\n0\n2\n90\nr\nl\n0\nf\nd\n" + "0\n" * 11 + "1\n0\n1\n1\nLED\n1000\n4000K\n80\n10\n" + "0.5\n" * 10
for label, text, pat in [
    ("ldt-isym-bad", "corpus\n1\n7\n", r"symmetry indicator Isym is 7"),
    ("ldt-cut-short", "corpus\n1\n1\n1\n0\n2\n", r"ends before"),
    ("ldt-angle-text", LDT_HEAD + "0\nzero\n", r"'zero', not a number"),
    ("ldt-gamma-descending", LDT_HEAD + "0\n90\n0\n100\n50\n", r"γ angle 0 is not in 0–180° after 90"),
    ("ldt-no-flux", LDT_HEAD.replace("LED\n1000\n", "LED\n0\n") + "0\n0\n90\n100\n50\n", r"luminous flux is 0"),
    ("ldt-trailing", LDT_HEAD + "0\n0\n90\n100\n50\n7\n", r"lines after the intensity table"),
    # Issue 42: a conversion factor of 0 was read as 1.
    ("ldt-cfli-zero", LDT_HEAD.replace("0\n" * 11 + "1\n0\n1\n", "0\n" * 11 + "0\n0\n1\n") + "0\n0\n90\n100\n50\n",
     r"conversion factor CFLI is 0"),
    ("ldt-isym3-odd", "corpus\n1\n3\n6\n60\n2\n90\nr\nl\n0\nf\nd\n" + "0\n" * 11 + "1\n0\n1\n1\nLED\n1000\n4000K\n80\n10\n" + "0.5\n" * 10
        + "0\n60\n120\n180\n240\n300\n0\n90\n", r"does not split into the planes symmetry 3 needs"),
]:
    photometric_case(label, "ldt", text, pat)

# ---- D. OBJ -----------------------------------------------------------------------------------------
def mesh_case(label, ext, data, pat, place, fit=False, scene_level=False):
    fname = f"{ext}-{label}.{ext}"
    write(fname, data)
    o = {"type": "mesh", "file": fname, "material": "green"}
    if fit:
        o["fit"] = {"min": [-1, -1, -1], "max": [1, 1, 1]}
    s = deep(BASE); s["objects"] = [o]
    sname = f"{ext}-{label}.json"
    write(sname, scene_text(s))
    case(f"{ext}/{label}", render("{in}/" + sname), pat, 2, sname if scene_level else fname, place)

OBJPLACE = r"\.obj:\d+"
TRI = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
for label, data, pat, fit in [
    ("no-faces", TRI, r"no faces", False),
    ("only-comments", "# nothing\n# here\n", r"no faces", False),
    ("face-two", TRI + "f 1 2\n", r"face has 2 vertices", False),
    ("face-zero-index", TRI + "f 0 1 2\n", r"index 0 out of range.*indices start at 1", False),
    ("face-out-of-range", TRI + "f 1 2 4\n", r"vertex index 4 out of range", False),
    ("face-negative-range", TRI + "f -1 -2 -4\n", r"vertex index -4 out of range", False),
    ("face-not-int", TRI + "f 1 2 x\n", r"vertex index 'x' is not an integer", False),
    ("face-float", TRI + "f 1 2 3.0\n", r"is not an integer", False),
    ("face-huge-index", TRI + "f 1 2 99999999999\n", r"is not an integer|out of range", False),
    ("vt-out-of-range", TRI + "vt 0 0\nf 1/1 2/2 3/1\n", r"texture coordinate index 2 out of range", False),
    ("vn-out-of-range", TRI + "vn 0 0 1\nf 1//1 2//2 3//1\n", r"normal index 2 out of range", False),
    ("v-two-coords", "v 0 0\n", r"needs 3 coordinates", False),
    ("v-not-number", "v 0 a 0\n", r"coordinate 'a' is not a finite number", False),
    ("v-nan", "v 0 nan 0\n" + "v 1 0 0\nv 0 1 0\nf 1 2 3\n", r"not a finite number", False),
    ("v-inf", "v 0 inf 0\n", r"not a finite number", False),
    ("v-1e39", "v 0 1e39 0\n", r"not a finite number", False),
    ("vn-bad", TRI + "vn x 0 1\n", r"coordinate 'x' is not a finite number", False),
    ("degenerate", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", r"degenerate", False),
    ("3e38-fit", "v -3e38 -3e38 -3e38\nv 3e38 3e38 3e38\nv 3e38 -3e38 0\nf 1 2 3\n", r"span more than single precision", True),
    ("3e38-nofit", "v -3e38 -3e38 -3e38\nv 3e38 3e38 3e38\nv 3e38 -3e38 0\nf 1 2 3\n", r"span more than single precision", False),
    ("1e20-nofit", "v -1e20 0 0\nv 1e20 0 0\nv 0 1e20 0\nf 1 2 3\n", r"outside ±10000000", False),
    ("nul-token", "v 0 0\x000 0\n", r"not a finite number", False),
    ("ansi-token", "v 0 \x1b[31m0 0\n", r"coordinate '\\e\[31m0' is not a finite number", False),
    ("long-token", "v 0 " + "1" * 3000 + "z 0\n", r"coordinate '1+…", False),
    ("binary", bytes(range(1, 256)) * 8, r"not a finite|not an integer|needs 3|no faces|face has", False),
    ("utf16", ("\ufeff" + TRI + "f 1 2 4\n").encode("utf-16-le"), r"vertex index 4 out of range", False),
    ("latin1-comment", ("# caf\xe9\n" + TRI + "f 1 2 5\n").encode("latin-1"), r"vertex index 5 out of range", False),
    ("crlf-bad-index", (TRI + "f 1 2 7\r\n"), r"vertex index 7 out of range", False),
]:
    scene_level = "span" in pat or "outside" in pat
    mesh_case(label, "obj", data, pat, JSONPLACE if scene_level else OBJPLACE, fit, scene_level)

# ---- E. PLY -----------------------------------------------------------------------------------------
PLYPLACE = r"\.ply:\d+|\.ply: element|\.ply: end of data|\.ply: header"
def ply_header(fmt="ascii", nv=3, nf=1, extra=""):
    return f"ply\nformat {fmt} 1.0\nelement vertex {nv}\nproperty float x\nproperty float y\nproperty float z\n{extra}element face {nf}\nproperty list uchar int vertex_indices\nend_header\n"
ATRI = "0 0 0\n1 0 0\n0 1 0\n"
for label, data, pat in [
    ("no-magic", "plx\n", r"not a PLY file"),
    ("no-format", "ply\nelement vertex 0\nend_header\n", r"no 'format' line"),
    ("bad-format", "ply\nformat xml 1.0\nend_header\n", r"unknown format 'xml'"),
    ("no-end-header", "ply\nformat ascii 1.0\nelement vertex 3\n", r"no 'end_header'"),
    ("element-malformed", "ply\nformat ascii 1.0\nelement vertex\nend_header\n", r"malformed element line"),
    ("element-negative", "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", r"malformed element line"),
    ("property-first", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", r"property before any element"),
    ("property-type", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", r"unknown property type 'quad'"),
    ("property-malformed", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float\nend_header\n", r"malformed property line"),
    ("list-float-count", "ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int idx\nend_header\n", r"not an integer type"),
    ("keyword", "ply\nformat ascii 1.0\nfoo bar\nend_header\n", r"unknown header keyword 'foo'"),
    ("ansi-keyword", "ply\nformat ascii 1.0\n\x1b[31mfoo\nend_header\n", r"unknown header keyword '\\e\[31mfoo'"),
    ("no-vertex", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n", r"declares no 'vertex' element"),
    ("no-x", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n0 0\n", r"no scalar property 'x'"),
    ("no-face", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n", r"no 'face' or 'tristrips'"),
    ("face-no-indices", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int idx\nend_header\n0 0 0\n3 0 0 0\n", r"no list property 'vertex_indices'"),
    ("ascii-not-number", ply_header() + "0 0 0\n1 a 0\n0 1 0\n3 0 1 2\n", r"'a' is not a number"),
    ("ascii-nan", ply_header() + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", r"not a finite number|not a number"),
    ("ascii-truncated", ply_header() + "0 0 0\n1 0\n", r"unexpected end of file"),
    ("ascii-index-range", ply_header() + ATRI + "3 0 1 3\n", r"vertex index 3 out of range"),
    ("ascii-index-negative", ply_header() + ATRI + "3 0 1 -1\n", r"vertex index -1 out of range"),
    ("ascii-face-two", ply_header() + ATRI + "2 0 1\n", r"face has 2 vertices"),
    ("ascii-list-negative", ply_header().replace("uchar", "int") + ATRI + "-3 0 1 2\n", r"negative length"),
    ("ascii-list-fraction", ply_header() + ATRI + "3.5 0 1 2\n", r"not an integer"),
    ("ascii-degenerate", ply_header() + "0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n", r"degenerate"),
    ("ascii-huge-count", ply_header(nv=2000000000) + ATRI + "3 0 1 2\n", r"cannot fit|declares|unexpected end|more than"),
    ("ascii-huge-faces", ply_header(nf=2000000000) + ATRI + "3 0 1 2\n", r"cannot fit|declares|unexpected end|more than"),
    ("binary-truncated", ply_header("binary_little_endian").encode() + struct.pack("<3f", 0, 0, 0), r"unexpected end of file|truncated|more than"),
    ("binary-huge-count", ply_header("binary_little_endian", nv=1000000000).encode() + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0), r"declares|unexpected end|more than|truncated"),
    ("binary-index-range", ply_header("binary_little_endian").encode() + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<B3i", 3, 0, 1, 9), r"out of range"),
    ("binary-nan", ply_header("binary_little_endian").encode() + struct.pack("<9f", 0, float("nan"), 0, 1, 0, 0, 0, 1, 0) + struct.pack("<B3i", 3, 0, 1, 2), r"not a finite number"),
    ("binary-big-truncated", ply_header("binary_big_endian").encode() + struct.pack(">5f", 0, 0, 0, 1, 0), r"unexpected end of file|truncated|more than"),
    ("binary-list-huge", ply_header("binary_little_endian").replace("uchar", "int").encode() + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<i", 2000000000), r"unexpected end|truncated|more than|negative"),
    ("binary-list-negative", ply_header("binary_little_endian").replace("uchar", "int").encode() + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<i3i", -3, 0, 1, 2), r"negative length"),
    ("binary-3e38-fit", ply_header("binary_little_endian").encode() + struct.pack("<9f", -3e38, -3e38, -3e38, 3e38, 3e38, 3e38, 3e38, -3e38, 0) + struct.pack("<B3i", 3, 0, 1, 2), r"span more than single precision"),
    ("nul-in-header", "ply\nformat ascii 1.0\ncomment a\x00b\nelement\x00 vertex 1\nend_header\n", r"unknown header keyword|malformed"),
    ("crlf-header", "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 5\r\n", r"vertex index 5 out of range"),
]:
    fit = "3e38" in label
    scene_level = "span" in pat
    mesh_case(label, "ply", data, pat, JSONPLACE if scene_level else PLYPLACE, fit, scene_level)

# ---- F. render folders: the manifest and the cube, image and id readers -------------------------------
# Set-up "base-render DIR" renders good.json into {tmp}/DIR (the test caches one render and copies it).
def folder_case(label, steps, pat, file, place=r".", cmd=("probe", "{tmp}/r", "--pixel", "1,1"), exit=2):
    case(f"folder/{label}", list(cmd), pat, exit, file, place, ["base-render r", *steps])

def npy(shape, dtype="<f4", body=b"", fortran=False, version=1, header=None):
    h = header or "{'descr': '%s', 'fortran_order': %s, 'shape': (%s), }" % (dtype, "True" if fortran else "False", ", ".join(map(str, shape)) + ("," if len(shape) == 1 else ""))
    h = h.encode("latin-1")
    pad = (64 - (10 + len(h) + 1) % 64) % 64
    h = h + b" " * pad + b"\n"
    if version == 1:
        return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(h)) + h + body
    return b"\x93NUMPY" + bytes([version, 0]) + struct.pack("<I", len(h)) + h + body

COLORCHECK = ("colorcheck", "{tmp}/r")
NPYPLACE = r"\.npy: (header|byte|data)"
for label, data, pat in [
    ("npy-huge-shape", npy((10000, 10000, 20)), r"declares shape \(10000, 10000, 20\).*holds only"),
    ("npy-truncated-data", npy((6, 8, 20), body=b"\0" * 100), r"holds only 100 bytes"),
    ("npy-no-magic", b"NUMPY" + b"\0" * 100, r"not a \.npy file"),
    ("npy-short", b"\x93NUM", r"too short"),
    ("npy-version-9", b"\x93NUMPY\x09\x00" + b"\0" * 100, r"format version 9\.0 is not supported"),
    ("npy-header-length", b"\x93NUMPY\x01\x00\xff\xff" + b"{}", r"header claims 65535 bytes"),
    ("npy-header-length-v2", b"\x93NUMPY\x02\x00\xff\xff\xff\x7f" + b"{}", r"header claims 2147483647 bytes"),
    ("npy-int-dtype", npy((6, 8, 20), dtype="<i4", body=b"\0" * 3840), r"unsupported dtype"),
    ("npy-fortran", npy((6, 8, 20), fortran=True, body=b"\0" * 3840), r"Fortran-order"),
    ("npy-no-shape", npy((), header="{'descr': '<f4', 'fortran_order': False}"), r"header has no shape"),
    ("npy-bad-shape", npy((), header="{'descr': '<f4', 'fortran_order': False, 'shape': (6, x, 20), }"), r"bad shape entry 'x'"),
    ("npy-negative-shape", npy((6, -8, 20)), r"bad shape entry '-8'"),
    ("npy-2d", npy((48, 20), body=b"\0" * 3840), r"array has 2 dimensions"),
    ("npy-wrong-bands", npy((6, 8, 10), body=b"\0" * 1920), r"array has 10 bands"),
    ("npy-overflow-shape", npy((2147483647, 2147483647, 2147483647)), r"too large|holds only"),
    # Found by fuzzing (fuzz/run.sh npy): a header length that overflows int, and one cut short.
    ("npy-fuzz-length-overflow", bytes.fromhex("934e554d5059030051657386"), r"header claims 2255709521 bytes"),
    ("npy-fuzz-length-short", bytes.fromhex("934e554d5059010076"), r"truncated \(in the header length\)"),
    ("npy-ansi-dtype", npy((6, 8, 20), dtype="\x1b[31m", body=b"\0" * 3840), r"unsupported dtype"),
]:
    write(label + ".npy", data)
    folder_case(label, [f"copy {{in}}/{label}.npy r/spectral.npy"], pat, "spectral.npy", NPYPLACE)

def exr_header(attrs):
    out = struct.pack("<ii", 20000630, 2)
    for name, typ, value in attrs:
        out += name.encode() + b"\0" + typ.encode() + b"\0" + struct.pack("<i", len(value)) + value
    return out + b"\0"

def chlist(names, ptype=2):
    return b"".join(n.encode() + b"\0" + struct.pack("<iBBBBii", ptype, 0, 0, 0, 0, 1, 1) for n in names) + b"\0"

def box(x0, y0, x1, y1):
    return struct.pack("<4i", x0, y0, x1, y1)

EXRPLACE = r"\.exr: (byte|header|attribute|chunk)"
chans = [f"S0.{390 + 20 * i}nm" for i in range(20)]
for label, data, pat in [
    ("exr-no-magic", b"\0" * 64, r"not an OpenEXR file"),
    ("exr-version-1", struct.pack("<ii", 20000630, 1) + b"\0" * 32, r"version 1 is not supported"),
    ("exr-tiled", struct.pack("<ii", 20000630, 0x202) + b"\0" * 32, r"tiled"),
    ("exr-truncated-header", struct.pack("<ii", 20000630, 2) + b"channels\0chlist\0", r"truncated"),
    ("exr-no-channels", exr_header([("compression", "compression", b"\0"), ("dataWindow", "box2i", box(0, 0, 7, 5))]), r"lacks channels"),
    ("exr-huge-window", exr_header([("channels", "chlist", chlist(chans)), ("compression", "compression", b"\0"), ("dataWindow", "box2i", box(0, 0, 99999, 99999))]), r"empty or too large|more than the"),
    ("exr-big-window", exr_header([("channels", "chlist", chlist(chans)), ("compression", "compression", b"\3"), ("dataWindow", "box2i", box(0, 0, 4999, 4999))]) + b"\0" * 64, r"more than the \d+-byte file can hold"),
    ("exr-empty-window", exr_header([("channels", "chlist", chlist(chans)), ("compression", "compression", b"\0"), ("dataWindow", "box2i", box(0, 0, -1, -1))]), r"empty or too large"),
    ("exr-piz", exr_header([("channels", "chlist", chlist(chans)), ("compression", "compression", b"\4"), ("dataWindow", "box2i", box(0, 0, 7, 5))]), r"compression .* is not supported"),
    ("exr-bad-pixel-type", exr_header([("channels", "chlist", chlist(chans, ptype=7)), ("compression", "compression", b"\0"), ("dataWindow", "box2i", box(0, 0, 7, 5))]), r"unknown pixel type 7"),
    ("exr-missing-chunks", exr_header([("channels", "chlist", chlist(chans)), ("compression", "compression", b"\0"), ("dataWindow", "box2i", box(0, 0, 7, 5))]) + b"\0" * 48, r"chunk 0 of 6 is missing|truncated|more than"),
    # Found by fuzzing (fuzz/run.sh exr): deflate data zlib rejects, and a channel listed twice.
    ("exr-fuzz-zlib-error", open(os.path.join(HERE, "found", "exr-fuzz-zlib-error.exr"), "rb").read(), r"does not decompress|truncated|corrupt"),
    ("exr-fuzz-duplicate-channel", open(os.path.join(HERE, "found", "exr-fuzz-duplicate-channel.exr"), "rb").read(), r"appears twice"),
    ("exr-negative-size", exr_header([("channels", "chlist", chlist(chans)), ("compression", "compression", b"\0"), ("dataWindow", "box2i", box(0, 0, 7, 5))])[:-1] + b"x\0int\0" + struct.pack("<i", -5) + b"\0", r"truncated"),
]:
    write(label + ".exr", data)
    folder_case(label, ["remove r/spectral.npy", f"copy {{in}}/{label}.exr r/spectral.exr"], pat, "spectral.exr", EXRPLACE)

# A fluorescent material's re-radiation matrix as a bispectral OpenEXR (Fichet et al. 2021: T.<λ>nm the diagonal,
# T.<λin>nm.<λout>nm the re-radiation): one line naming the .exr and the channel (issue 26).
def exr_image(channels, w=1, h=1):
    names = sorted(channels)
    head = exr_header([("channels", "chlist", chlist(names)), ("compression", "compression", b"\0"), ("dataWindow", "box2i", box(0, 0, w - 1, h - 1))])
    line = 4 * w * len(names)
    out = head + b"".join(struct.pack("<Q", len(head) + 8 * h + y * (8 + line)) for y in range(h))
    for y in range(h):
        out += struct.pack("<ii", y, line) + b"".join(struct.pack("<f", v) for n in names for v in channels[n][y * w:(y + 1) * w])
    return out

MATRIXPLACE = r"\.exr: (channel 'T\.|header attribute 'channels')"
for label, channels, w, pat in [
    ("matrix-bad-name", {"T.400nm": [0.5], "T.410nm": [0.5], "T.400nm.41Onm": [0.1]}, 1, r"'T\.400nm\.41Onm': is not a reflective channel name"),
    ("matrix-no-diagonal", {"T.400nm": [0.5], "T.420nm": [0.5], "T.410nm.420nm": [0.01]}, 1, r"excitation 410 nm has no diagonal channel"),
    ("matrix-gap", {"T.400nm": [0.5], "T.410nm": [0.5], "T.430nm": [0.5]}, 1, r"'T\.430nm': follows T\.410nm: no diagonal channel at 420 nm"),
    ("matrix-nan", {"T.400nm": [float("nan")], "T.410nm": [0.5]}, 1, r"'T\.400nm': pixel \(0, 0\) is not finite"),
    ("matrix-negative", {"T.400nm": [0.5], "T.410nm": [0.5], "T.400nm.410nm": [-0.1]}, 1, r"is negative"),
    ("matrix-varying", {"T.400nm": [0.5, 0.6], "T.410nm": [0.5, 0.5]}, 2, r"differs between pixels \(0, 0\) and \(1, 0\)"),
    ("matrix-bright", {"T.400nm": [0.9], "T.410nm": [0.5], "T.400nm.410nm": [0.5]}, 1, r"excitation 400 nm re-emits"),
    ("matrix-rgb", {"R": [1.0], "G": [1.0], "B": [1.0]}, 1, r"no reflective diagonal channels"),
]:
    fname = write(f"exr-{label}.exr", exr_image(channels, w))
    s = deep(BASE); s["materials"]["green"] = {"type": "lambertian", "fluorescence": {"matrix": fname}}
    sname = write(f"exr-{label}.json", scene_text(s))
    case(f"exr/{label}", render("{in}/" + sname), pat, 2, fname, MATRIXPLACE)

ENVIPLACE = r"\.(hdr|img): (header|key|byte|line|data)"
def envi(samples=8, lines=6, bands=20, dtype=4, extra="", wl=True):
    w = "wavelength = {" + ", ".join(str(390 + 20 * i) for i in range(bands)) + "}\n" if wl else ""
    return f"ENVI\nsamples = {samples}\nlines = {lines}\nbands = {bands}\nheader offset = 0\ndata type = {dtype}\ninterleave = bsq\nbyte order = 0\n{w}{extra}"
for label, hdr, img, pat in [
    ("envi-huge", envi(100000, 100000), b"\0" * 3840, r"declares 100000×100000×20 samples.*holds only 3840 bytes"),
    ("envi-not-envi", "NOPE\n", b"\0" * 3840, r"not an ENVI header"),
    ("envi-no-samples", envi().replace("samples = 8\n", ""), b"\0" * 3840, r"lacks a numeric 'samples'"),
    ("envi-samples-text", envi().replace("samples = 8", "samples = eight"), b"\0" * 3840, r"lacks a numeric 'samples'"),
    ("envi-zero-size", envi(0), b"\0" * 3840, r"bad size 0×6×20"),
    ("envi-dtype-int", envi(dtype=2), b"\0" * 3840, r"data type 2 is not supported"),
    ("envi-interleave", envi().replace("bsq", "bxx"), b"\0" * 3840, r"unknown interleave 'bxx'"),
    ("envi-truncated", envi(), b"\0" * 100, r"holds only 100 bytes"),
    ("envi-offset-negative", envi().replace("header offset = 0", "header offset = -5"), b"\0" * 3840, r"'header offset' -5 is negative"),
    ("envi-wavelength-count", envi().replace("390, ", "", 1), b"\0" * 3840, r"lists 19 values for 20 bands"),
    ("envi-wavelength-text", envi().replace("410", "abc"), b"\0" * 3840, r"'wavelength' value 'abc' is not a number"),
    ("envi-unclosed", envi().replace("}", ""), b"\0" * 3840, r"unclosed"),
    ("envi-units", envi(extra="wavelength units = furlongs\n"), b"\0" * 3840, r"wavelength units 'furlongs'"),
    ("envi-uneven", envi().replace("410", "415"), b"\0" * 3840, r"breaks the even spacing"),
]:
    write(label + ".hdr", hdr)
    write(label + ".img", img)
    folder_case(label, ["remove r/spectral.npy", "remove r/spectral.exr", f"copy {{in}}/{label}.hdr r/spectral.hdr", f"copy {{in}}/{label}.img r/spectral.img"], pat, "spectral.", ENVIPLACE)

def png_chunk(t, data):
    return struct.pack(">I", len(data)) + t + data + struct.pack(">I", zlib.crc32(t + data) & 0xffffffff)
SIG = b"\x89PNG\r\n\x1a\n"
def png(w, h, depth=16, ctype=0, interlace=0, idat=None, crc_ok=True):
    ihdr = struct.pack(">IIBBBBB", w, h, depth, ctype, 0, 0, interlace)
    raw = b"".join(b"\0" + b"\0" * (w * 2) for _ in range(h)) if idat is None and w * h < 10**6 else b""
    body = idat if idat is not None else zlib.compress(raw)
    c = png_chunk(b"IHDR", ihdr)
    if not crc_ok:
        c = c[:-1] + bytes([c[-1] ^ 1])
    return SIG + c + png_chunk(b"IDAT", body) + png_chunk(b"IEND", b"")
PNGPLACE = r"\.png: (byte|chunk|IHDR|IDAT|row|header)"
for label, data, pat in [
    ("png-no-signature", b"GIF89a" + b"\0" * 50, r"not a PNG file"),
    ("png-truncated", png(8, 6)[:40], r"truncated"),
    ("png-crc", png(8, 6, crc_ok=False), r"CRC mismatch in chunk IHDR"),
    ("png-huge-ihdr", png(100000, 100000, idat=zlib.compress(b"\0" * 100)), r"declares 100000×100000 pixels"),
    ("png-negative-ihdr", png(0x80000000, 6, idat=zlib.compress(b"\0" * 100)), r"declares"),
    ("png-interlaced", png(8, 6, interlace=1), r"interlaced"),
    ("png-palette", png(8, 6, depth=8, ctype=3), r"a palette image without a PLTE chunk"),
    ("png-bad-depth", png(8, 6, depth=4, ctype=2), r"colour type 2 at 4 bits is not a valid PNG"),
    ("png-bad-zlib", png(8, 6, idat=b"\x78\x9c\xff\xff\xff"), r"truncated or corrupt"),
    ("png-short-data", png(8, 6, idat=zlib.compress(b"\0" * 20)), r"truncated or corrupt"),
    ("png-bad-filter", png(8, 6, idat=zlib.compress(b"\x09" + b"\0" * 16 + b"\0" * 17 * 5)), r"unknown filter type 9"),
    ("png-no-ihdr", SIG + png_chunk(b"IEND", b""), r"no IHDR chunk"),
    ("png-wrong-size", png(4, 3), r"is 4×3 but the cube is 8×6"),
]:
    write(label + ".png", data)
    folder_case(label, [f"copy {{in}}/{label}.png r/object-id.png"], pat, "object-id.png", PNGPLACE + r"|object-id\.png: ", cmd=COLORCHECK)


# ---- JPEG textures (issue 39): a baseline JPEG as a material's diffuse texture; each defect one line naming the .jpg and
# the byte where the decoder stopped. The good file is fuzz/seeds/jpeg/ycbcr-420.jpg (cjpeg -quality 75, 24×16, 4:2:0).
GOODJPEG = open(os.path.join(HERE, "..", "..", "fuzz", "seeds", "jpeg", "ycbcr-420.jpg"), "rb").read()
def jpeg_segment(marker, body):
    return bytes([0xFF, marker]) + struct.pack(">H", len(body) + 2) + body
def jpeg_replace_sof(data, sof):
    i = data.index(b"\xff\xc0")
    return data[:i + 1] + bytes([sof]) + data[i + 2:]
def jpeg_find(data, marker):
    return data.index(bytes([0xFF, marker]))
SOS = jpeg_find(GOODJPEG, 0xDA)
SOF = jpeg_find(GOODJPEG, 0xC0)
DHT = jpeg_find(GOODJPEG, 0xC4)
JPEGPLACE = r"\.jpg: byte \d+"
for label, data, pat in [
    ("jpeg-not-jpeg", b"GIF89a" + b"\0" * 50, r"not a JPEG file"),
    ("jpeg-progressive", jpeg_replace_sof(GOODJPEG, 0xC2), r"progressive JPEG is not supported"),
    ("jpeg-arithmetic", jpeg_replace_sof(GOODJPEG, 0xC9), r"arithmetic-coded JPEG is not supported"),
    ("jpeg-lossless", jpeg_replace_sof(GOODJPEG, 0xC3), r"lossless JPEG is not supported"),
    ("jpeg-12-bit", GOODJPEG[:SOF + 4] + b"\x0c" + GOODJPEG[SOF + 5:], r"12-bit JPEG is not supported"),
    ("jpeg-cmyk", b"\xff\xd8" + jpeg_segment(0xC0, b"\x08\x00\x10\x00\x10\x04" + b"\x01\x11\x00" * 4) + b"\xff\xd9",
     r"4 colour components are not supported"),
    ("jpeg-truncated-scan", GOODJPEG[:SOS + 40], r"ends before the last block|ends before its EOI"),
    ("jpeg-no-eoi", GOODJPEG[:-2], r"ends before its EOI marker"),
    ("jpeg-no-scan", GOODJPEG[:SOS] + b"\xff\xd9", r"no image data"),
    ("jpeg-scan-before-frame", GOODJPEG[:SOF] + GOODJPEG[SOS:], r"scan \(SOS\) before the frame header"),
    ("jpeg-huge-frame", GOODJPEG[:SOF + 5] + b"\xff\xff\xff\xff" + GOODJPEG[SOF + 9:], r"more than the file's \d+ bytes can code"),
    ("jpeg-zero-height", GOODJPEG[:SOF + 5] + b"\x00\x00" + GOODJPEG[SOF + 7:], r"no pixels"),
    ("jpeg-bad-sampling", GOODJPEG[:SOF + 11] + b"\x32" + GOODJPEG[SOF + 12:SOF + 14] + b"\x21" + GOODJPEG[SOF + 15:],
     r"sampling 2×1 is not a whole fraction of 3×2"),
    ("jpeg-segment-past-end", GOODJPEG[:DHT + 2] + b"\xff\xf0" + GOODJPEG[DHT + 4:], r"runs past the end of the file"),
    ("jpeg-huffman-overfull", GOODJPEG[:DHT + 5] + b"\x03" + GOODJPEG[DHT + 6:], r"more codes of length 1 than fit|shorter than its table"),
    ("jpeg-garbage-between-segments", GOODJPEG[:SOF] + b"\x00" + GOODJPEG[SOF:], r"expected a marker, found byte 0x00"),
    ("jpeg-restart-missing", b"\xff\xd8" + jpeg_segment(0xDD, b"\x00\x01") + GOODJPEG[2:], r"expected the restart marker RST0"),
]:
    write(label + ".jpg", data)
    scene = deep(BASE)
    scene["materials"]["green"] = {"diffuse": {"texture": label + ".jpg"}}
    scene_case(label, scene, pat, file=label + ".jpg", place=JPEGPLACE)


# ---- Environment maps (issue 39): "sky": { "type": "envmap", "file": … } reads Radiance RGBE (.hdr) and PFM (and OpenEXR);
# each defect one line naming the image (or the scene's $.sky.file for bad pixel values), exit 2.
ENVSCENE = deep(BASE)
ENVSCENE["radiometry"] = "physical"
def envmap_case(label, name, data, pat, place=r"\.(hdr|pfm|png): ", file=None):
    write(name, data)
    scene = deep(ENVSCENE)
    scene["sky"] = {"type": "envmap", "file": name}
    scene_case(label, scene, pat, file=file or name, place=place)
RGBE = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 3 +X 8\n"
RLEROW = bytes([2, 2, 0, 8, 128 + 8, 128, 128 + 8, 64, 128 + 8, 32, 128 + 8, 129])
def pfm(w, h, values, scale=b"-1.0"):
    return b"PF\n%d %d\n" % (w, h) + scale + b"\n" + struct.pack("<%df" % len(values), *values)
for label, name, data, pat in [
    ("hdr-not-rgbe", "not-rgbe.hdr", b"P6\n8 3\n255\n" + b"\0" * 72, r"not a Radiance HDR picture"),
    ("hdr-xyze", "xyze.hdr", RGBE.replace(b"rle_rgbe", b"rle_xyze"), r"pixel format '32-bit_rle_xyze' is not supported"),
    ("hdr-orientation", "flipped.hdr", RGBE.replace(b"-Y 3", b"+Y 3") + RLEROW * 3, r"is not '-Y H \+X W'"),
    ("hdr-no-resolution", "no-resolution.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", r"the header ends before the resolution line"),
    ("hdr-truncated", "truncated.hdr", RGBE + RLEROW + RLEROW[:7], r"scanline 1 is truncated"),
    ("hdr-run-past-end", "run-past-end.hdr", RGBE + bytes([2, 2, 0, 8, 128 + 9, 1]) + RLEROW * 2,
     r"scanline 0: a run passes the end of the line"),
    ("hdr-width-mismatch", "width-mismatch.hdr", RGBE + bytes([2, 2, 0, 9]) + RLEROW[4:] * 3, r"scanline 0 declares width 9, the picture 8"),
    ("hdr-zero-literal", "zero-literal.hdr", RGBE + bytes([2, 2, 0, 8, 0]) + RLEROW * 2, r"a literal count of 0 is invalid"),
    ("hdr-old-rle", "old-rle.hdr", b"#?RADIANCE\n\n-Y 3 +X 2\n" + bytes([9, 9, 9, 130, 1, 1, 1, 5]) + b"\0" * 16,
     r"scanline 0 uses the old run-length form"),
    ("hdr-huge", "huge.hdr", b"#?RADIANCE\n\n-Y 40000 +X 40000\n", r"image size 40000 × 40000 is outside 1–32767"),
    ("pfm-truncated", "truncated.pfm", pfm(4, 3, [1.0] * 10), r"the pixels need 144 bytes, the file has 40"),
    ("pfm-zero-scale", "zero-scale.pfm", pfm(2, 3, [1.0] * 18, b"0"), r"the scale is not a non-zero number"),
    ("pfm-not-pfm", "not-pfm.pfm", b"P7\n2 3\n-1\n", r"not a PFM picture"),
    ("envmap-png", "sky.png", b"\x89PNG\r\n\x1a\n", r"'\.png' is not a high-dynamic-range image format"),
]:
    envmap_case(label, name, data, pat)
for label, name, data, pat in [
    ("envmap-negative", "negative.pfm", pfm(2, 3, [1.0] * 7 + [-1.0] + [1.0] * 10), r"pixel \(0, 1\) holds -1"),
    ("envmap-nan", "nan.pfm", pfm(2, 3, [float("nan")] + [1.0] * 17), r"pixel \(0, 2\) holds NaN"),
    ("envmap-too-small", "tiny.pfm", pfm(2, 2, [1.0] * 12), r"is 2 × 2 pixels"),
]:
    envmap_case(label, name, data, pat, place=JSONPLACE, file="")
write("wide.pfm", pfm(4, 3, [1.0] * 36))   # also the pbrt cases' non-square infinite light
scene = deep(ENVSCENE)
scene["sky"] = {"type": "envmap", "file": "no-such-sky.hdr"}
scene_case("envmap-missing", scene, r"environment map 'no-such-sky\.hdr' not found")
scene = deep(BASE)
scene["sky"] = {"type": "envmap", "file": "x.hdr"}
scene_case("envmap-paper-radiometry", scene, r"a sky is a spectral radiance .* needs physical radiometry")


# ---- glTF 2.0 (issue 39): `spectral render FILE.gltf|.glb` converts in memory; each defect one line naming the file and the
# JSON path (a .glb's header by byte), exit 2, nothing written.
import base64 as _b64
GLTF_BIN = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
def gltf_base():
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]}],
            "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.0}}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                          {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
            "buffers": [{"byteLength": len(GLTF_BIN), "uri": "data:application/octet-stream;base64," + _b64.b64encode(GLTF_BIN).decode()}]}
def gltf_with(edit):
    g = gltf_base()
    edit(g)
    return json.dumps(g)
def glb(json_bytes, bin_bytes=GLTF_BIN, version=2):
    j = json_bytes + b" " * ((4 - len(json_bytes) % 4) % 4)
    b = bin_bytes + b"\0" * ((4 - len(bin_bytes) % 4) % 4)
    return (struct.pack("<III", 0x46546C67, version, 12 + 8 + len(j) + 8 + len(b)) + struct.pack("<II", len(j), 0x4E4F534A) + j
            + struct.pack("<II", len(b), 0x004E4942) + b)
GOODGLB = json.loads(gltf_with(lambda g: g["buffers"][0].pop("uri")))
GLTFPLACE = r"\.gl(tf|b): (\$|line \d+:\d+|byte \d+)"
def gltf_set(path, value):
    def edit(g):
        cur = g
        for k in path[:-1]:
            cur = cur[k]
        if value is DELETE:
            del cur[path[-1]]
        else:
            cur[path[-1]] = value
    return gltf_with(edit)
for label, data, pat in [
    ("gltf-not-json", "{ nope", r"JSON syntax error in the glTF"),
    ("gltf-not-utf8", b'{"asset": {"version": "2.0", "generator": "caf\xe9"}, "scenes": [{"nodes": []}]}',
     r"the glTF JSON is not valid UTF-8"),   # found by the gltf fuzz target in CI
    ("gltf-array-root", "[]", r"the glTF JSON is an array, not an object"),
    ("gltf-no-asset", gltf_set(["asset"], DELETE), r"missing \"asset\""),
    ("gltf-version-1", gltf_set(["asset", "version"], "1.0"), r"glTF version '1\.0' is not supported"),
    ("gltf-no-scenes", gltf_set(["scenes"], DELETE), r"the asset has no \"scenes\""),
    ("gltf-scene-index", gltf_set(["scene"], 4), r"\$\.scene: 4 is not an index into \"scenes\""),
    ("gltf-node-mesh-index", gltf_set(["nodes", 0, "mesh"], 7), r"\$\.nodes\[0\]\.mesh: 7 is not an index into \"meshes\""),
    ("gltf-node-cycle", gltf_set(["nodes", 0, "children"], [0]), r"node 0 appears twice in the hierarchy"),
    ("gltf-matrix-and-trs", gltf_set(["nodes", 0, "translation"], [0, 0, 0]) .replace('"mesh": 0,', '"mesh": 0, "matrix": [1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],'),
     r"both \"matrix\" and translation"),
    ("gltf-accessor-past-view", gltf_set(["accessors", 0, "count"], 30), r"\$\.accessors\[0\]: 30 elements of 12 bytes every 12 .* run past buffer view 0"),
    ("gltf-buffer-short", gltf_set(["buffers", 0, "byteLength"], 4000), r"\$\.buffers\[0\]\.byteLength: the buffer holds 44 bytes, fewer than its byteLength 4000"),
    ("gltf-buffer-file-missing", gltf_set(["buffers", 0, "uri"], "no-such.bin"), r"the buffer file 'no-such\.bin' was not found"),
    ("gltf-buffer-url", gltf_set(["buffers", 0, "uri"], "https://example.com/a.bin"), r"is a URL"),
    ("gltf-bad-base64", gltf_set(["buffers", 0, "uri"], "data:application/octet-stream;base64,@@@@"), r"not valid base64"),
    ("gltf-index-out-of-range", gltf_with(lambda g: g["buffers"][0].__setitem__("uri", "data:application/octet-stream;base64,"
        + _b64.b64encode(GLTF_BIN[:36] + struct.pack("<3H", 0, 1, 9) + b"\0\0").decode())), r"index 9 \(element 2\) is not below the 3 vertices"),
    ("gltf-position-bytes", gltf_set(["accessors", 0, "componentType"], 5121), r"componentType 5121 is not allowed for the attribute"),
    ("gltf-position-vec2", gltf_set(["accessors", 0, "type"], "VEC2"), r"needs type VEC3, the accessor is VEC2"),
    ("gltf-triangles-not-whole", gltf_set(["accessors", 1, "count"], 2), r"2 vertices do not make whole triangles"),
    ("gltf-no-position", gltf_set(["meshes", 0, "primitives", 0, "attributes"], {}), r"missing \"POSITION\""),
    ("gltf-yfov-zero", gltf_set(["cameras", 0, "perspective", "yfov"], 0), r"yfov: 0 is out of range"),
    ("gltf-orthographic", gltf_set(["cameras", 0], {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 9}}),
     r"an orthographic camera has no counterpart"),
    ("gltf-required-draco", gltf_set(["extensionsRequired"], ["KHR_draco_mesh_compression"]), r"requires the extension KHR_draco_mesh_compression"),
    ("gltf-light-index", gltf_set(["nodes", 1, "extensions"], {"KHR_lights_punctual": {"light": 2}}), r"is not an index into the KHR_lights_punctual lights"),
    ("gltf-spot-cones", gltf_with(lambda g: (g.__setitem__("extensions", {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.3}}]}}), g["nodes"][1].__setitem__("extensions",
        {"KHR_lights_punctual": {"light": 0}}))), r"innerConeAngle must be below outerConeAngle"),
    ("gltf-base-colour-range", gltf_with(lambda g: (g.__setitem__("materials", [{"pbrMetallicRoughness": {"baseColorFactor": [2, 0, 0, 1]}}]),
        g["meshes"][0]["primitives"][0].__setitem__("material", 0))), r"baseColorFactor\[0\]: expected a number in \[0, 1\]"),
    ("gltf-no-mesh", gltf_set(["scenes", 0, "nodes"], [1]), r"the scene holds no triangle mesh"),
]:
    fname = write(label + ".gltf", data)
    case(f"gltf/{label}", render("{in}/" + fname), pat, 2, fname, GLTFPLACE)
for label, data, pat in [
    ("glb-version-1", glb(json.dumps(GOODGLB).encode(), version=1), r"GLB version 1 is not supported"),
    ("glb-truncated", glb(json.dumps(GOODGLB).encode())[:40], r"the header says \d+ bytes, the file has 40"),
    ("glb-chunk-past-end", struct.pack("<III", 0x46546C67, 2, 24) + struct.pack("<II", 9999, 0x4E4F534A) + b"{}  ", r"runs past the end of the file"),
    ("glb-bin-short", glb(json.dumps(GOODGLB).encode(), GLTF_BIN[:20]), r"the buffer holds 20 bytes, fewer than its byteLength 44"),
]:
    fname = write(label + ".glb", data)
    case(f"gltf/{label}", render("{in}/" + fname), pat, 2, fname, GLTFPLACE)


MANIFEST_VALIDATION = True  # step 4: analysis commands validate the folder through the manifest
MANIFESTPLACE = r"render\.json(:\d+)?: (\$|line)|render\.json:\d+"
for label, text, pat in [] if not MANIFEST_VALIDATION else [
    ("manifest-not-json", "{ not json", r"render\.json.*(broken JSON|JSON syntax)"),
    ("manifest-array", "[]", r"is not a JSON object|expected an object"),
    ("manifest-empty-object", "{}", r"missing|lacks"),
]:
    write(label + ".json", text)
    folder_case(label, [f"copy {{in}}/{label}.json r/render.json"], pat, "render.json", MANIFESTPLACE, cmd=COLORCHECK)
if MANIFEST_VALIDATION:
    folder_case("manifest-missing", ["remove r/render.json"], r"has no render\.json", "r", r".")
folder_case("cube-missing", ["remove r/spectral.npy", "remove r/spectral.exr", "remove r/spectral.img", "remove r/spectral.hdr"], r"no spectral cube|has no", "r", r".")
folder_case("ids-missing", ["remove r/object-id.png"], r"has no object-id\.png", "r", r".", cmd=COLORCHECK)
for label, path, value, pat in [] if not MANIFEST_VALIDATION else [
    ("manifest-white-xyz-empty", "colour.white_xyz", [], r"white_xyz"),
    ("manifest-white-xyz-strings", "colour.white_xyz", ["a", "b", "c"], r"white_xyz"),
    ("manifest-weights-short", "colour.weights_x", [1, 2, 3], r"weights_x"),
    ("manifest-grid-bad", "bands.grid", "banana", r"not a band grid|grid"),
    ("manifest-width-string", "width", "eight", r"width"),
    ("manifest-width-wrong", "width", 9, r"describes 9×6|width"),
    ("manifest-objects-number", "objects", 5, r"objects"),
    ("manifest-object-name-number", "objects.0.name", 5, r"name"),
    ("manifest-observer-text", "colour.observer", "two", r"observer"),
]:
    folder_case(label, [f"json-set r/render.json {path} {json.dumps(value)}"], pat, "render.json", MANIFESTPLACE + r"|render\.json: ", cmd=COLORCHECK)
for label, args, pat in [
    ("probe-pixel-outside", ["probe", "{tmp}/r", "--pixel", "100,100"], r"outside the 8×6 image"),
    ("probe-pixel-text", ["probe", "{tmp}/r", "--pixel", "a,b"], r"is not X,Y"),
    ("probe-pixel-negative", ["probe", "{tmp}/r", "--pixel", "-1,2"], r"outside|is not X,Y"),
    ("reconstruct-no-white", ["reconstruct", "{tmp}/r"], r"exactly one of"),
    ("reconstruct-white-unknown", ["reconstruct", "{tmp}/r", "--white-object", "board"], r"no object 'board'"),
    ("reconstruct-region-outside", ["reconstruct", "{tmp}/r", "--white-region", "0,0,100,100"], r"is not a non-empty rectangle inside the 8×6 image"),
    ("reconstruct-region-one-past", ["reconstruct", "{tmp}/r", "--white-region", "0,0,9,6"], r"0,0,9,6 is not a non-empty rectangle inside the 8×6 image"),
    ("reconstruct-region-empty", ["reconstruct", "{tmp}/r", "--white-region", "2,2,2,4"], r"2,2,2,4 is not a non-empty rectangle"),
]:
    named = next((a for a in args if a in ("--pixel", "--white-object", "--white-region")), "command line")
    if "exactly one of" in pat: named = "command line"
    folder_case(label, [], pat, named, OPT, cmd=args)

# ---- G. our own files read back (issue 25): render.json, lights/lights.json, camera.json, sweep plans and job.json, ----
# shards for merge, crops for the analysis commands, traversal names in manifests, overflowing numbers on the command line.
# Nothing derived is trusted: each tampered field is one line naming the file and its JSON path, exit 2.
# Set-ups (CorpusTests): "base-render r" (good.json), "base-lights r" (…with --formats npy,aov,lights), "base-camera ."
# (r/ and cam/, a camera run on it), "base-shards ." (a/ and b/, shards 0/2 and 1/2 of good.json at 8×64),
# "base-crop r" (good.json --crop 0,0,4,3); "json-set FILE PATH VALUE", "json-del FILE PATH".
RJ = r"render\.json: \$"
def manifest_case(label, steps, pat, cmd=COLORCHECK, base="base-render r", file="render.json", place=RJ):
    case(f"manifest/{label}", list(cmd), pat, 2, file, place, [base, *steps])
T = r"is (the string|the number|an array|an object|true|false|null|missing)[^,]*, expected "
for label, path, value, pat in [
    ("width-string", "width", '"8"', r"\$\.width: is the string '8', expected a whole number 1–32768"),
    ("width-zero", "width", "0", r"\$\.width: is 0, outside 1–32768"),
    ("width-negative", "width", "-8", r"\$\.width: is -8, outside"),
    ("width-huge", "width", "1000000000", r"\$\.width: is 1000000000, outside"),
    ("width-fraction", "width", "8.5", r"\$\.width: is the number 8\.5, expected a whole number"),
    ("width-1e400", "width", "1e400", r"\$\.width: is the number 1e400, expected a whole number"),
    ("width-null", "width", "null", r"\$\.width: is missing, expected a whole number"),
    ("width-array", "width", "[8]", r"\$\.width: is an array of 1, expected"),
    ("height-bool", "height", "true", r"\$\.height: is true, expected a whole number"),
    ("height-wrong", "height", "7", r"describes 8×7×20 but the spectral cube is 8×6×20"),
    ("spp-zero", "spp", "0", r"\$\.spp: is 0, outside 1–1048576"),
    ("spp-string", "spp", '"1"', r"\$\.spp: is the string '1', expected"),
    ("bands-number", "bands", "5", r"\$\.bands: is the number 5, expected an object"),
    ("bands-grid-number", "bands.grid", "20", r"\$\.bands\.grid: is the number 20, expected a string"),
    ("bands-grid-text", "bands.grid", '"twenty"', r"bands\.grid.*not a band grid|bands\.grid"),
    ("bands-count-wrong", "bands.count", "7", r"\$\.bands\.count: is 7, but the grid 380:780:20 has 20 bands"),
    ("bands-count-zero", "bands.count", "0", r"\$\.bands\.count: is 0, expected ≥ 1"),
    ("band-scale-negative", "bands.band_image_scale", "-1", r"\$\.bands\.band_image_scale: is -1, outside 0–"),
    ("band-scale-string", "bands.band_image_scale", '"big"', r"\$\.bands\.band_image_scale: is the string 'big'"),
    ("colour-array", "colour", "[]", r"\$\.colour: is an array of 0, expected an object"),
    ("integration-number", "colour.integration", "1", r"\$\.colour\.integration: is the number 1, expected a string"),
    ("integration-unknown", "colour.integration", '"bogus"', r"colour\.integration.*unknown band integration"),
    ("observer-3", "colour.observer", "3", r"\$\.colour\.observer: is 3, expected 2 or 10"),
    ("observer-100", "colour.observer", "100", r"\$\.colour\.observer: is 100, outside 2–10"),
    ("observer-string", "colour.observer", '"2"', r"\$\.colour\.observer: is the string '2'"),
    ("white-two", "colour.white_xyz", "[1, 1]", r"\$\.colour\.white_xyz: has 2 entries, expected 3"),
    ("white-y-zero", "colour.white_xyz", "[0.95, 0, 1.08]", r"\$\.colour\.white_xyz\[1\]: is not positive"),
    ("white-y-negative", "colour.white_xyz", "[0.95, -1, 1.08]", r"\$\.colour\.white_xyz\[1\]: is not positive"),
    ("white-null-entry", "colour.white_xyz", "[0.95, null, 1.08]", r"\$\.colour\.white_xyz\[1\]: is missing, expected a finite number"),
    ("white-object", "colour.white_xyz", '{"x": 1}', r"\$\.colour\.white_xyz: is an object, expected an array"),
    ("weights-x-short", "colour.weights_x", "[1, 2, 3]", r"\$\.colour\.weights_x: has 3 entries, expected 20"),
    ("weights-y-empty", "colour.weights_y", "[]", r"\$\.colour\.weights_y: has 0 entries, expected 20"),
    ("weights-z-string", "colour.weights_z", '"z"', r"\$\.colour\.weights_z: is the string 'z', expected an array of 20"),
    ("weights-x-entry", "colour.weights_x.3", '"w"', r"\$\.colour\.weights_x\[3\]: is the string 'w', expected a finite number"),
    ("weights-y-overflow", "colour.weights_y.0", "1e999", r"\$\.colour\.weights_y\[0\]: is the number 1e999, expected a finite number"),
    ("kappa-negative", "colour.kappa", "-1", r"\$\.colour\.kappa: is -1, outside 0–"),
    ("kappa-string", "colour.kappa", '"k"', r"\$\.colour\.kappa: is the string 'k'"),
    ("exposure-negative", "colour.exposure", "-2", r"\$\.colour\.exposure: is -2, outside 0–"),
    ("exposure-overflow", "colour.exposure", "1e309", r"\$\.colour\.exposure: is the number 1e309, expected a finite number"),
    ("adapt-string", "colour.adapt", '"yes"', r"\$\.colour\.adapt: is the string 'yes', expected true or false"),
    ("rgb-number", "colour.rgb", "709", r"\$\.colour\.rgb: is the number 709, expected a string"),
    ("fallback-negative", "colour.fallback_pixels", "-1", r"\$\.colour\.fallback_pixels: is -1, outside 0–48"),
    ("fallback-too-many", "colour.fallback_pixels", "49", r"\$\.colour\.fallback_pixels: is 49, outside 0–48"),
    ("pixel-xyz-number", "colour.pixel_xyz", "5", r"\$\.colour\.pixel_xyz: is the number 5, expected a string"),
    ("white-spd-number", "colour.reference_white_spd", "5", r"\$\.colour\.reference_white_spd: is the number 5, expected an object"),
    ("white-spd-empty", "colour.reference_white_spd.wavelengths_nm", "[]", r"reference_white_spd\.wavelengths_nm: is empty"),
    ("white-spd-descending", "colour.reference_white_spd.wavelengths_nm.1", "1", r"reference_white_spd\.wavelengths_nm\[1\]: is 1, not above"),
    ("white-spd-zero-nm", "colour.reference_white_spd.wavelengths_nm.0", "0", r"reference_white_spd\.wavelengths_nm\[0\]: is 0, outside 1–100000"),
    ("white-spd-values-short", "colour.reference_white_spd.values", "[1, 2]", r"reference_white_spd\.values: has 2 entries, expected \d+"),
    ("objects-number", "objects", "5", r"\$\.objects: is the number 5, expected an array"),
    ("object-number", "objects.0", "5", r"\$\.objects\[0\]: is the number 5, expected an object"),
    ("object-id-two", "objects.0.id", "2", r"\$\.objects\[0\]\.id: is 2, expected 1 \(ids count from 1 in order\)"),
    ("object-id-zero", "objects.0.id", "0", r"\$\.objects\[0\]\.id: is 0, outside 1–65535"),
    ("object-id-string", "objects.0.id", '"1"', r"\$\.objects\[0\]\.id: is the string '1'"),
    ("object-name-number", "objects.0.name", "5", r"\$\.objects\[0\]\.name: is the number 5, expected a string"),
    ("object-material-null", "objects.0.material", "null", r"\$\.objects\[0\]\.material: is missing, expected a string"),
    ("object-reflectance-number", "objects.0.reflectance", "14", r"\$\.objects\[0\]\.reflectance: is the number 14, expected a string"),
    ("object-normal-two", "objects.0.flat_normal", "[0, 1]", r"\$\.objects\[0\]\.flat_normal: has 2 entries, expected 3"),
    ("lights-string", "lights", '"D65"', r"\$\.lights: is the string 'D65', expected an array"),
    ("light-number", "lights.0", "5", r"\$\.lights\[0\]: is the number 5, expected an object"),
    ("light-index-negative", "lights.0.index", "-1", r"\$\.lights\[0\]\.index: is -1, expected ≥ \d+"),
    ("light-intensity-string", "lights.0.intensity", '"1"', r"\$\.lights\[0\]\.intensity: is the string '1'"),
    ("light-ambient-string", "lights.0.has_ambient", '"no"', r"\$\.lights\[0\]\.has_ambient: is the string 'no', expected true or false"),
    ("light-position-one", "lights.0.position", "[1]", r"\$\.lights\[0\]\.position: has 1 entries, expected 3"),
    ("light-attenuation-text", "lights.0.attenuation", '"none"', r"\$\.lights\[0\]\.attenuation: is the string 'none'"),
    ("light-spd-unsorted", "lights.0.spd", '{"wavelengths_nm": [500, 400], "values": [1, 1]}', r"\$\.lights\[0\]\.spd\.wavelengths_nm\[1\]: is 400, not above"),
    ("light-spd-values-missing", "lights.0.spd", '{"wavelengths_nm": [400, 500]}', r"\$\.lights\[0\]\.spd\.values: is missing, expected an array of 2"),
    ("light-photometric-number", "lights.0.photometric", "5", r"\$\.lights\[0\]\.photometric: is the number 5, expected an object"),
    ("light-photometric-no-unit", "lights.0.photometric", '{"quantity": "luminous_flux", "value": 1}', r"\$\.lights\[0\]\.photometric\.unit: is missing"),
    ("files-number", "files", "5", r"\$\.files: is the number 5, expected an array"),
    ("files-entry-number", "files.0", "5", r"\$\.files\[0\]: is the number 5, expected a string"),
    ("files-parent", "files.0", '"../elsewhere/file"', r"\$\.files\[0\]: '\.\./elsewhere/file' has an empty, '\.' or '\.\.' part"),
    ("files-bands-parent", "files.0", '"bands/../../elsewhere/file"', r"\$\.files\[0\]: 'bands/\.\./\.\./elsewhere/file' has an empty"),
    ("files-absolute", "files.0", '"/etc/passwd"', r"\$\.files\[0\]: '/etc/passwd' is an absolute path"),
    ("files-empty", "files.0", '""', r"\$\.files\[0\]: '' is empty"),
    ("files-dot", "files.0", '"./preview.png"', r"\$\.files\[0\]: '\./preview\.png' has an empty"),
    ("files-double-slash", "files.0", '"bands//a.png"', r"\$\.files\[0\]: 'bands//a\.png' has an empty"),
    ("files-backslash", "files.0", '"..\\\\x"', r"\$\.files\[0\]: .* holds a backslash"),
    ("files-newline", "files.0", '"a\\nb"', r"\$\.files\[0\]: 'a\\nb' holds a backslash or a control character"),
    ("files-long", "files.0", json.dumps("x" * 2000), r"\$\.files\[0\]: .* is longer than 1024 characters"),
    ("crop-number", "crop", "5", r"\$\.crop: is the number 5, expected an object"),
    ("crop-negative", "crop", '{"x0": -1, "y0": 0, "x1": 8, "y1": 6}', r"\$\.crop\.x0: is -1, outside 0–7"),
    ("crop-beyond", "crop", '{"x0": 0, "y0": 0, "x1": 9, "y1": 6}', r"\$\.crop\.x1: is 9, outside 1–8"),
    ("crop-empty", "crop", '{"x0": 4, "y0": 0, "x1": 4, "y1": 6}', r"\$\.crop\.x1: is 4, outside 5–8"),
    ("crop-missing-y1", "crop", '{"x0": 0, "y0": 0, "x1": 8}', r"\$\.crop\.y1: is missing"),
    ("threads-negative", "threads", "-1", r"\$\.threads: is -1, expected ≥ \d+"),
    ("tiles-string", "tiles", '"4"', r"\$\.tiles: is the string '4'"),
    ("rays-number", "rays", "5", r"\$\.rays: is the number 5, expected an object"),
    ("rays-total-negative", "rays.total", "-5", r"\$\.rays\.total: is -5, expected ≥ \d+"),
    ("timings-negative", "timings_s.render", "-1", r"\$\.timings_s\.render: is -1, outside 0–1E\+300"),
    ("highlight-two", "aov.highlight_fraction", "2", r"\$\.aov\.highlight_fraction: is 2, outside 0–1"),
    ("radiometry-mode-number", "radiometry.mode", "1", r"\$\.radiometry\.mode: is the number 1, expected a string"),
    ("run-string", "run", '"fast"', r"\$\.run: is the string 'fast', expected an object"),
    ("run-load-negative", "run.load_s", "-3", r"\$\.run\.load_s: is -3, expected ≥ \d+"),
    ("run-overrides-width", "run.overrides", '{"width": 0}', r"\$\.run\.overrides\.width: is 0, outside 1–32768"),
    ("run-overrides-models", "run.overrides", '{"models": [5]}', r"\$\.run\.overrides\.models\[0\]: is the number 5"),
    ("run-relit-number", "run.relit", "5", r"\$\.run\.relit: is the number 5, expected an object"),
    ("run-relit-changes", "run.relit", '{"changes": [5]}', r"\$\.run\.relit\.changes\[0\]: is the number 5"),
    ("run-relit-copied-parent", "run.relit", '{"copied_files": ["../x"]}', r"\$\.run\.relit\.copied_files\[0\]: '\.\./x' has an empty"),
    ("resolved-scene-number", "resolved_scene", "5", r"\$\.resolved_scene: is the number 5, expected an object"),
    ("scene-hash-number", "scene_hash", "5", r"\$\.scene_hash: is the number 5, expected a string"),
    ("global-ambient-number", "global_ambient", "1", r"\$\.global_ambient: is the number 1, expected true or false"),
    ("tool-array", "tool", "[]", r"\$\.tool: is an array of 0, expected a string"),
    ("created-number", "created_utc", "2026", r"\$\.created_utc: is the number 2026, expected a string"),
]:
    manifest_case(label, [f"json-set r/render.json {path} {value}"], pat)
for label, key, pat in [("del-width", "width", r"\$\.width: is missing"), ("del-bands", "bands", r"\$\.bands: is missing, expected an object"),
                        ("del-colour", "colour", r"\$\.colour: is missing"), ("del-objects", "objects", r"\$\.objects: is missing, expected an array"),
                        ("del-lights", "lights", r"\$\.lights: is missing"), ("del-white", "colour.white_xyz", r"\$\.colour\.white_xyz: is missing"),
                        ("del-weights", "colour.weights_z", r"\$\.colour\.weights_z: is missing"), ("del-observer", "colour.observer", r"\$\.colour\.observer: is missing")]:
    manifest_case(label, [f"json-del r/render.json {key}"], pat)
for label, text, pat in [
    ("duplicate-key", '{"width": 8, "width": 8}', r"render\.json:\d+:\d+: broken JSON: .*(duplicate|Duplicate)"),
    ("deep", "[" * 200 + "]" * 200, r"render\.json:\d+:\d+: broken JSON: .*depth"),
    ("string-root", '"render"', r"render\.json: \$: is not a JSON object"),
    ("bom-empty-object", "\ufeff{}", r"\$\.width: is missing"),
]:
    write(f"manifest-{label}.json", text)
    manifest_case(label, [f"copy {{in}}/manifest-{label}.json r/render.json"], pat, place=r"render\.json(:\d+:\d+)?: ")
# The same damage met by every reader of render.json: probe, reconstruct, camera, view, relight, merge.
for cmd_label, cmd in [("probe", ("probe", "{tmp}/r", "--pixel", "1,1")), ("reconstruct", ("reconstruct", "{tmp}/r", "--white-object", "sphere-0")),
                       ("camera", ("camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out")), ("view", ("view", "{tmp}/r")),
                       ("relight", ("relight", "{tmp}/r", "--light", "light-0=A", "-o", "{tmp}/out", "--quiet")),
                       ("merge", ("merge", "{tmp}/r", "-o", "{tmp}/out", "--quiet"))]:
    manifest_case(f"{cmd_label}-weights-short", ["json-set r/render.json colour.weights_x [1]"], r"\$\.colour\.weights_x: has 1 entries, expected 20", cmd=cmd)
    manifest_case(f"{cmd_label}-files-traversal", ['json-set r/render.json files.0 "bands/../../../victim"'], r"\$\.files\[0\]: 'bands/\.\./\.\./\.\./victim' has an empty", cmd=cmd)
    manifest_case(f"{cmd_label}-files-link-out", ["remove r/preview.png", "symlink r/preview.png /etc/hostname"], r"\$\.files\[\d+\]: names 'preview\.png', a symbolic link leading out of the folder", cmd=cmd)
    # Issue 42: a light index that names no light's files (mask-lit-3.png of a one-light render) was accepted, and
    # reconstruct wrote its files with the masks silently left out.
    manifest_case(f"{cmd_label}-light-index-dangling", ["json-set r/render.json lights.0.index 3"], r"\$\.lights\[0\]\.index: is 3, expected 0", cmd=cmd)

# lights/lights.json, read by relight (and the viewer, the camera's exact route)
RELIGHT = ("relight", "{tmp}/r", "--light", "light-0=A", "-o", "{tmp}/out", "--quiet")
LJ = r"lights\.json: \$"
def lights_case(label, steps, pat, cmd=RELIGHT, file="lights.json", place=LJ):
    case(f"lights/{label}", list(cmd), pat, 2, file, place, ["base-lights r", *steps])
for label, path, value, pat in [
    ("width-string", "width", '"8"', r"\$\.width: is the string '8', expected a whole number 1–32768"),
    ("width-zero", "width", "0", r"\$\.width: is 0, outside 1–32768"),
    ("height-huge", "height", "99999", r"\$\.height: is 99999, outside 1–32768"),
    ("bands-wrong", "bands", "7", r"\$\.bands: is 7, but the render has 20 bands"),
    ("bands-float", "bands", "20.5", r"\$\.bands: is the number 20\.5, expected a whole number"),
    ("lights-empty", "lights", "[]", r"\$\.lights: has 0 entries, expected 1"),
    ("lights-number", "lights", "1", r"\$\.lights: is the number 1, expected an array of 1"),
    ("components-object", "components", "{}", r"\$\.components: is an object, expected an array"),
    ("component-number", "components.0", "5", r"\$\.components\[0\]: is the number 5, expected an object"),
    ("lobe-unknown", "components.0.lobe", '"glow"', r"\$\.components\[0\]\.lobe: is 'glow', not diffuse, specular"),
    ("lobe-number", "components.0.lobe", "0", r"\$\.components\[0\]\.lobe: is the number 0, expected a string"),
    ("light-out-of-range", "components.0.light", "9", r"\$\.components\[0\]\.light: is 9, outside 0–0"),
    ("light-string", "components.0.light", '"0"', r"\$\.components\[0\]\.light: is the string '0'"),
    ("material-unknown", "components.0.material", '"gold"', r"\$\.components\[0\]\.material: names material 'gold', which the scene does not have"),
    ("material-number", "components.0.material", "3", r"\$\.components\[0\]\.material: is the number 3, expected a string"),
    ("chain-string", "components.0.chain", '"mirror"', r"\$\.components\[0\]\.chain: is the string 'mirror', expected an array"),
    ("chain-weight", "components.0.chain", '[{"material": "green", "weight": "bounce"}]', r"\$\.components\[0\]\.chain\[0\]\.weight: is 'bounce', not mirror or transmit"),
    ("chain-material", "components.0.chain", '[{"material": "lead", "weight": "mirror"}]', r"\$\.components\[0\]\.chain\[0\]\.material: names material 'lead'"),
    ("chain-too-long", "components.0.chain", json.dumps([{"material": "green", "weight": "mirror"}] * 7), r"\$\.components\[0\]\.chain: has 7 entries, more than 6"),
    ("band-zero", "components.0.band", "0", r"\$\.components\[0\]\.band: is 0, outside 1–20"),
    ("band-99", "components.0.band", "99", r"\$\.components\[0\]\.band: is 99, outside 1–20"),
    ("offset-negative", "components.0.offset", "-1", r"\$\.components\[0\]\.offset: is -1, expected ≥ \d+"),
    ("offset-beyond", "components.0.offset", "100000", r"\$\.components\[0\]\.offset: entries 100000…\d+ lie outside the \d+ stored"),
    ("offset-huge", "components.0.offset", "2147483000", r"\$\.components\[0\]\.count: puts entries beyond|\$\.components\[0\]\.offset: entries"),
    ("count-negative", "components.0.count", "-1", r"\$\.components\[0\]\.count: is -1, outside 0–48"),
    ("count-beyond-image", "components.0.count", "49", r"\$\.components\[0\]\.count: is 49, outside 0–48"),
    ("count-fraction", "components.0.count", "1.5", r"\$\.components\[0\]\.count: is the number 1\.5, expected a whole number"),
    ("merged-zero", "components.0.merged_chains", "0", r"\$\.components\[0\]\.merged_chains: is 0, expected ≥ \d+"),
]:
    lights_case(label, [f"json-set r/lights/lights.json {path} {value}"], pat)
lights_case("del-components", ["json-del r/lights/lights.json components"], r"\$\.components: is missing, expected an array")
lights_case("del-width", ["json-del r/lights/lights.json width"], r"\$\.width: is missing")
lights_case("view-lobe-unknown", ['json-set r/lights/lights.json components.0.lobe "glow"'], r"\$\.components\[0\]\.lobe: is 'glow'", cmd=("view", "{tmp}/r"))
lights_case("view-light-out-of-range", ["json-set r/lights/lights.json components.0.light 5"], r"\$\.components\[0\]\.light: is 5, outside", cmd=("view", "{tmp}/r"))
lights_case("view-del-components", ["json-del r/lights/lights.json components"], r"\$\.components: is missing, expected an array",
            cmd=("view", "{tmp}/r"))   # issue 42: was an internal error in the viewer
for label, text, pat in [("not-json", "{ lights", r"lights\.json:\d+:\d+: broken JSON"), ("array", "[]", r"lights\.json: \$: is not a JSON object"),
                         ("duplicate", '{"width": 8, "width": 8}', r"lights\.json:\d+:\d+: broken JSON")]:
    write(f"lights-{label}.json", text)
    lights_case(label, [f"copy {{in}}/lights-{label}.json r/lights/lights.json"], pat, place=r"lights\.json(:\d+:\d+)?: ")
write("lights-ids-object-99.npy", npy((3, 6, 8), body=struct.pack("<f", 99) + b"\0" * (4 * 143)))
lights_case("ids-object-99", ["copy {in}/lights-ids-object-99.npy r/lights/ids.npy"], r"ids\.npy: pixel 0,0: object 99 is not 0 \(background\) or one of the scene's 1", file="ids.npy", place=r"ids\.npy: ")
write("lights-ids-nan.npy", npy((3, 6, 8), body=struct.pack("<f", float("nan")) + b"\0" * (4 * 143)))
lights_case("ids-nan", ["copy {in}/lights-ids-nan.npy r/lights/ids.npy"], r"ids\.npy: pixel 0,0: object NaN is not", file="ids.npy", place=r"ids\.npy: ")
write("lights-ids-shape.npy", npy((2, 6, 8), body=b"\0" * (4 * 96)))
lights_case("ids-shape", ["copy {in}/lights-ids-shape.npy r/lights/ids.npy"], r"ids\.npy: has shape \(2, 6, 8\), lights\.json says \(3, 6, 8\)", file="ids.npy", place=r"ids\.npy: ")

# camera.json, read by recover
RECOVER = ("recover", "{tmp}/cam")
CJ = r"camera\.json: \$"
def camera_case(label, steps, pat, file="camera.json", place=CJ):
    case(f"camera/{label}", list(RECOVER), pat, 2, file, place, ["base-camera .", *steps])
for label, path, value, pat in [
    ("render-folder-number", "render_folder", "5", r"\$\.render_folder: is the number 5, expected a string"),
    ("render-folder-gone", "render_folder", '"../nowhere"', r"\$\.render_folder: names '.*nowhere', which is not a folder"),
    ("sensor-number", "sensor_argument", "5", r"\$\.sensor_argument: is the number 5, expected a string"),
    ("simulation-array", "simulation", "[]", r"\$\.simulation: is an array of 0, expected an object"),
    ("exposure-string", "simulation.exposure_s", '"auto"', r"\$\.simulation\.exposure_s: is the string 'auto', expected an array"),
    ("exposure-zero", "simulation.exposure_s", "[0]", r"\$\.simulation\.exposure_s\[0\]: is 0, not a positive exposure"),
    ("exposure-negative", "simulation.exposure_s", "[-1]", r"\$\.simulation\.exposure_s\[0\]: is -1, expected ≥ 0"),
    ("exposure-overflow", "simulation.exposure_s", "[1e999]", r"\$\.simulation\.exposure_s\[0\]: is the number 1e999, expected a finite number"),
    ("exposure-count", "simulation.exposure_s", "[0.01, 0.01]", r"\$\.simulation\.exposure_s: has 2 exposures, the sensor 'isetcam' takes 1"),
    ("exposure-null-entry", "simulation.exposure_s", "[null]", r"\$\.simulation\.exposure_s\[0\]: is missing"),
    ("seed-negative", "simulation.seed", "-1", r"\$\.simulation\.seed: is the number -1, expected a whole number ≥ 0"),
    ("seed-fraction", "simulation.seed", "1.5", r"\$\.simulation\.seed: is the number 1\.5, expected a whole number"),
    ("seed-string", "simulation.seed", '"1"', r"\$\.simulation\.seed: is the string '1', expected a whole number"),
    ("seed-huge", "simulation.seed", "1e30", r"\$\.simulation\.seed: is the number 1e30, expected a whole number"),
    ("noise-bool", "simulation.noise", "true", r"\$\.simulation\.noise: is true, expected a string"),
    ("scale-zero", "simulation.radiance_scale_w_m2_sr_nm_per_band_unit", "0", r"radiance_scale_w_m2_sr_nm_per_band_unit: is 0, not a positive scale"),
    ("scale-negative", "simulation.radiance_scale_w_m2_sr_nm_per_band_unit", "-1", r"radiance_scale_w_m2_sr_nm_per_band_unit: is -1, expected ≥ 0"),
    ("scale-string", "simulation.radiance_scale_w_m2_sr_nm_per_band_unit", '"1"', r"radiance_scale_w_m2_sr_nm_per_band_unit: is the string '1'"),
    ("white-scale-zero", "simulation.white_radiance_scale", "0", r"\$\.simulation\.white_radiance_scale: is 0, not a positive scale"),
    ("route-number", "simulation.signal_route", "1", r"\$\.simulation\.signal_route: is the number 1, expected a string"),
    ("processing-number", "processing", "1", r"\$\.processing: is the number 1, expected an object"),
    ("demosaic-number", "processing.demosaic", "1", r"\$\.processing\.demosaic: is the number 1, expected a string"),
]:
    camera_case(label, [f"json-set cam/camera.json {path} {value}"], pat)
camera_case("del-simulation", ["json-del cam/camera.json simulation"], r"\$\.simulation: is missing, expected an object")
camera_case("del-scale", ["json-del cam/camera.json simulation.radiance_scale_w_m2_sr_nm_per_band_unit"], r"radiance_scale_w_m2_sr_nm_per_band_unit: is missing")
camera_case("render-damaged", ["json-set r/render.json colour.weights_y [1]"], r"\$\.colour\.weights_y: has 1 entries, expected 20", file="render.json", place=RJ)
for label, text, pat in [("not-json", "{ camera", r"camera\.json:\d+:\d+: broken JSON"), ("array", "[1]", r"camera\.json: \$: is not a JSON object")]:
    write(f"camera-{label}.json", text)
    camera_case(label, [f"copy {{in}}/camera-{label}.json cam/camera.json"], pat, place=r"camera\.json(:\d+:\d+)?: ")

# merge: shards whose manifests name files outside their folder, links, tampered crops
MERGE = ("merge", "{tmp}/a", "{tmp}/b", "-o", "{tmp}/out", "--quiet")
def merge_case(label, steps, pat, file="render.json", place=RJ, cmd=MERGE):
    case(f"merge/{label}", list(cmd), pat, 2, file, place, ["base-shards .", *steps])
for label, path, value, pat in [
    ("files-traversal", "files.0", '"bands/../../../victim"', r"\$\.files\[0\]: 'bands/\.\./\.\./\.\./victim' has an empty"),
    ("files-absolute", "files.0", '"/tmp/victim"', r"\$\.files\[0\]: '/tmp/victim' is an absolute path"),
    ("crop-number", "crop", '"top"', r"\$\.crop: is the string 'top', expected an object"),
    ("crop-outside", "crop", '{"x0": 0, "y0": 0, "x1": 8, "y1": 65}', r"\$\.crop\.y1: is 65, outside 1–64"),
    ("scene-hash-number", "scene_hash", "1", r"\$\.scene_hash: is the number 1, expected a string"),
    ("width-zero", "width", "0", r"\$\.width: is 0, outside"),
]:
    merge_case(label, [f"json-set a/render.json {path} {value}"], pat)
merge_case("files-duplicate", ['json-set a/render.json files.0 "x.png"', 'json-set a/render.json files.1 "x.png"'], r"\$\.files\[1\]: lists 'x\.png' a second time")
merge_case("files-link-out", ["remove a/spectral.npy", "symlink a/spectral.npy /etc/hostname"], r"\$\.files\[\d+\]: names 'spectral\.npy', a symbolic link leading out of the folder")
merge_case("hash-differs", ['json-set b/render.json scene_hash "sha256:0"'], r"is a shard of another scene or settings", file="b", place=r".")
merge_case("shard-missing", [], r"rows 32–63 are in no shard given|a shard is missing", file="a", place=r".", cmd=("merge", "{tmp}/a", "-o", "{tmp}/out", "--quiet"))
merge_case("shard-twice", [], r"overlaps", file="a", place=r".", cmd=("merge", "{tmp}/a", "{tmp}/a", "{tmp}/b", "-o", "{tmp}/out", "--quiet"))
merge_case("out-is-shard", [], r"is also the output folder", file="a", place=r".", cmd=("merge", "{tmp}/a", "{tmp}/b", "-o", "{tmp}/a", "--quiet"))
merge_case("crop-not-strip", ['json-set a/render.json crop {"x0": 0, "y0": 0, "x1": 4, "y1": 32}'], r"holds crop .*not full-width rows", file="a", place=r".")
merge_case("listed-file-missing", ["remove b/spectral.npy"], r"lacks spectral\.npy, which its render\.json lists", file="b", place=r".")
# the analysis commands on a crop say it is one and to merge first
for cmd_label, cmd in [("colorcheck", ("colorcheck", "{tmp}/r")), ("probe", ("probe", "{tmp}/r", "--pixel", "1,1")),
                       ("reconstruct", ("reconstruct", "{tmp}/r", "--white-object", "sphere-0")), ("view", ("view", "{tmp}/r")),
                       ("camera", ("camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out"))]:
    case(f"crop/{cmd_label}", list(cmd), r"holds a crop of the film \(pixels 0–3 × 0–2 of 8×6, from --crop or --shard\), not a whole render.*spectral merge",
         2, "r", r".", ["base-crop r"])

# sweep plans (beside good.json in inputs/): checked whole, every job's scene loaded, before the first job runs
SW = r"plan-[a-z0-9-]+\.json(:\d+:\d+)?: \$"
def plan_case(label, plan, pat, file=None, place=SW, exit=2):
    fname = f"plan-{label}.json"
    write(fname, plan if isinstance(plan, (str, bytes)) else json.dumps(plan))
    case(f"sweep/{label}", ["sweep", "{in}/" + fname, "-o", "{tmp}/sw", "--quiet"], pat, exit, file or fname, place)
AX = {"name": "light", "path": "lights[0].spectrum", "values": ["D65", "A"]}
plan_case("not-json", "{ scene", r"is not valid JSON", place=r".")
plan_case("array", "[]", r"\$: is not a JSON object")
plan_case("unknown-key", {"scene": "good.json", "axis": [AX]}, r"\$\.axis: is not a plan key.*did you mean 'axes'")
plan_case("scene-number", {"scene": 5, "axes": [AX]}, r"\$\.scene: is missing or not a file name")
plan_case("scene-missing", {"scene": "nothere.json", "axes": [AX]}, r"base scene not found", file="nothere.json", place=r".")
plan_case("axes-object", {"scene": "good.json", "axes": {"a": 1}}, r"\$\.axes: is not a list of axes")
plan_case("axis-number", {"scene": "good.json", "axes": [5]}, r"\$\.axes\[0\]: is not an object")
plan_case("axis-no-name", {"scene": "good.json", "axes": [{"path": "camera.fov", "values": [30]}]}, r"\$\.axes\[0\]\.name: is missing")
plan_case("axis-name-taken", {"scene": "good.json", "axes": [{**AX, "name": "status"}]}, r"\$\.axes\[0\]\.name: 'status' is taken")
plan_case("axis-values-empty", {"scene": "good.json", "axes": [{**AX, "values": []}]}, r"\$\.axes\[0\]\.values: is missing or empty")
plan_case("axis-labels-count", {"scene": "good.json", "axes": [{**AX, "labels": ["x"]}]}, r"\$\.axes\[0\]\.labels: has 1 labels for 2 values")
plan_case("axis-path-syntax", {"scene": "good.json", "axes": [{**AX, "path": "lights[0]..spectrum"}]}, r"\$\.axes\[0\]\.path: 'lights\[0\]\.\.spectrum' is not a scene path")
plan_case("edit-lands-nowhere", {"scene": "good.json", "axes": [{**AX, "path": "lights[5].spectrum"}]}, r"job 0000: 'lights' has 1 elements, so no \[5\]", place=r".")
plan_case("jobs-overflow", {"scene": "good.json", "axes": [{"name": f"a{i}", "path": "camera.fov", "values": list(range(30, 40))} for i in range(12)]},
          r"\$\.axes: makes more than 100,000 jobs, more than the limit")
plan_case("jobs-160000", {"scene": "good.json", "axes": [{"name": "a", "path": "camera.fov", "values": list(range(400))}, {"name": "b", "path": "spp", "values": list(range(400))}]},
          r"\$\.axes: makes more than 100,000 jobs")
plan_case("jobs-extra-over", {"scene": "good.json", "axes": [{"name": "a", "path": "camera.fov", "values": list(range(1000))}, {"name": "b", "path": "spp", "values": list(range(100))}],
                              "extra": [{"set": {"camera.fov": 20}}]}, r"\$\.extra: makes 100,001 jobs, more than the limit")
plan_case("extra-not-object", {"scene": "good.json", "extra": [5]}, r"\$\.extra\[0\]: is not")
plan_case("no-jobs", {"scene": "good.json"}, r"\$\.axes: makes no jobs")
# Found by fuzzing (fuzz/run.sh sweep): a plan whose strings are not UTF-8.
plan_case("fuzz-invalid-utf8", open(os.path.join(HERE, "found", "plan-fuzz-invalid-utf8.json"), "rb").read(), r"is not valid UTF-8", place=r".")
# Found by fuzzing (fuzz/run.sh sweep): a key twice in one object of the plan; and the same in the base scene.
plan_case("fuzz-duplicate-key", open(os.path.join(HERE, "found", "plan-fuzz-duplicate-key.json"), "rb").read(),
          r":2:\d+: \$\.axes\[0\]\.path: key 'path' appears a second time in this object", place=SW)
write("scene-duplicate-key.json", '{ "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 6, "width": 4 } }')
write("plan-scene-duplicate-key.json", json.dumps({"scene": "scene-duplicate-key.json", "axes": [AX]}))
case("sweep/scene-duplicate-key", ["sweep", "{in}/plan-scene-duplicate-key.json", "-o", "{tmp}/sw", "--quiet"],
     r"scene-duplicate-key\.json:1:\d+: .*'width'", 2, "scene-duplicate-key.json", r".")
# A key twice in a scene rendered with a bare band count (--bands N reads the scene's range first): found beside the sweep
# plan's fuzz finding, it was an internal error (exit 1).
write("scene-duplicate-bands.json", '{ "bands": "400:700:10", "bands": "400:700:5", "camera": { "position": [0, 0, 5], "look_at": [0, 0, 0] } }')
case("render/duplicate-key-bands-count", render("{in}/scene-duplicate-bands.json", "--bands", "4"),
     r"\$\.bands: key 'bands' appears a second time in this object", 2, "scene-duplicate-bands.json", JSONPLACE)
write("plan-latin1-scene.json", json.dumps({"scene": "scene-035-latin1-byte.json", "axes": [{"name": "light", "path": "lights[0].spectrum", "values": ["A"]}]}))
case("sweep/scene-latin1", ["sweep", "{in}/plan-latin1-scene.json", "-o", "{tmp}/sw", "--quiet"], r"is not valid UTF-8", 2, "scene-035-latin1-byte.json", r".")
plan_case("formats-number", {"scene": "good.json", "axes": [AX], "formats": 5}, r"\$\.formats: is not a list of formats")
plan_case("formats-unknown", {"scene": "good.json", "axes": [AX], "formats": ["npy", "bogus"]},
          r"plan-formats-unknown\.json:1:\d+: \$\.formats: unknown output format 'bogus'")   # issue 42: named no file
# a job's own scene is bad: named as OUT/jobs/ID/scene.json (written so its line is true), and no job renders
JOBSCENE = r"jobs/\d{4}/scene\.json:\d+:\d+: \$"
for label, plan, pat in [
    ("job-bands-and-wave", {"scene": "good.json", "axes": [AX], "extra": [{"name": "both", "set": {"bands": "400:700:10", "wave": "400:10:700"}}]}, r"sweep job 0002: .*wave"),
    ("job-unknown-spectrum", {"scene": "good.json", "axes": [{**AX, "values": ["D65", "A", "D66"]}]}, r"sweep job 0002: .*unknown spectrum 'D66'"),
    ("job-width-zero", {"scene": "good.json", "axes": [{"name": "w", "path": "camera.width", "values": [8, 0]}]}, r"\$\.camera\.width: sweep job 0001: .*not positive"),
    ("job-material-bad", {"scene": "good.json", "axes": [{"name": "m", "path": "materials.green.diffuse", "values": [0.5, -1]}]}, r"sweep job 0001: .*out of range"),
    ("job-mesh-missing", {"scene": "good.json", "set": {"objects[0]": {"type": "mesh", "file": "nothere.obj", "material": "green"}}, "axes": [AX]}, r"sweep job 0000: mesh 'nothere\.obj' not found"),
    ("job-mesh-far", {"scene": "good.json", "axes": [{"name": "o", "path": "objects[0]", "values": [{"type": "sphere", "radius": 1, "material": "green"},
        {"type": "mesh", "file": "tri.obj", "material": "green", "transform": {"scale": 1e6, "translate": [9.5e6, 0, 0]}}]}]}, r"sweep job 0001: the placed mesh reaches"),
    ("job-ray-budget", {"scene": "good.json", "axes": [{"name": "d", "path": "max_depth", "values": [3, 99]}]}, r"\$\.max_depth: sweep job 0001: .*out of range"),
]:
    fname = f"plan-{label}.json"
    write(fname, json.dumps(plan))
    case(f"sweep/{label}", ["sweep", "{in}/" + fname, "-o", "{tmp}/sw", "--quiet"], pat, 2, "scene.json", JOBSCENE)
case("sweep/emit-job-bad", ["sweep", "{in}/plan-job-unknown-spectrum.json", "-o", "{tmp}/sw", "--emit", "slurm", "--quiet"],
     r"sweep job 0002: .*unknown spectrum 'D66'", 2, "scene.json", JOBSCENE)
# a damaged job.json is no record: the job runs again (exit 0), never an internal error
for label, text in [("status-number", '{"status": 1, "job_hash": "x"}'), ("seconds-string", '{"status": "done", "seconds": "fast", "job_hash": "x"}'),
                    ("not-json", "{ done"), ("array", "[]"), ("status-unknown", '{"status": "great"}')]:
    write(f"job-{label}.json", text)
    case(f"sweep/job-record-{label}", ["sweep", "{in}/plan-one.json", "-o", "{tmp}/sw", "--quiet"], r"^$", 0, None, None,
         ["mkdir sw", "mkdir sw/jobs", "mkdir sw/jobs/0000", f"copy {{in}}/job-{label}.json sw/jobs/0000/job.json"])
write("plan-one.json", json.dumps({"scene": "good.json", "axes": [{"name": "light", "path": "lights[0].spectrum", "values": ["D65"]}], "formats": ["npy"]}))

# overflowing and out-of-range numbers on the command line
for label, args, pat, named in [
    ("camera-exposure-1e300", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--exposure", "1e300"], r"--exposure: '1e300' is outside", "--exposure"),
    ("camera-exposure-1e-300", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--exposure", "1e-300"], r"--exposure: '1e-300' is outside", "--exposure"),
    ("camera-exposure-negative", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--exposure", "-1"], r"--exposure: '-1' is outside", "--exposure"),
    ("camera-exposure-nan", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--exposure", "NaN"], r"--exposure: 'NaN' is not a finite number", "--exposure"),
    ("camera-scale-1e30", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--radiance-scale", "1e30"], r"--radiance-scale: '1e30' is outside", "--radiance-scale"),
    ("camera-scale-zero", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--radiance-scale", "0"], r"--radiance-scale: '0' is outside", "--radiance-scale"),
    ("camera-scale-inf", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--radiance-scale", "Infinity"], r"--radiance-scale: 'Infinity' is not a finite number", "--radiance-scale"),
    ("camera-seed-negative", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--seed", "-1"], r"--seed '-1' is not a whole number ≥ 0", "command line"),
    ("camera-seed-overflow", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--seed", "99999999999999999999999"], r"is not a whole number ≥ 0", "command line"),
    ("camera-threads-huge", ["camera", "{tmp}/r", "--sensor", "isetcam", "-o", "{tmp}/out", "--threads", "99999999999"], r"--threads: '99999999999' is not a whole number in 1–1024", "--threads"),
    ("view-for-1e300", ["view", "{tmp}/r", "--serve", "--for", "1e300"], r"--for: '1e300' is outside 0 \(exclusive\) to 1E\+07 seconds", "--for"),
    ("view-for-zero", ["view", "{tmp}/r", "--serve", "--for", "0"], r"--for: '0' is outside", "--for"),
    ("view-for-negative", ["view", "{tmp}/r", "--serve", "--for", "-5"], r"--for: '-5' is outside", "--for"),
    ("view-for-nan", ["view", "{tmp}/r", "--serve", "--for", "nan"], r"--for: 'nan' is not a finite number", "--for"),
    ("view-port-zero", ["view", "{tmp}/r", "--serve", "--port", "0"], r"--port: '0' is not a whole number in 1–65535", "--port"),
    ("view-port-70000", ["view", "{tmp}/r", "--serve", "--port", "70000"], r"--port: '70000' is not a whole number in 1–65535", "--port"),
    ("view-port-overflow", ["view", "{tmp}/r", "--serve", "--port", "1e10"], r"--port: '1e10' is not a whole number", "--port"),
    ("sweep-shards-zero", ["sweep", "{in}/plan-one.json", "-o", "{tmp}/sw", "--shards", "0"], r"--shards: '0' is not a whole number in 1–1048576", "--shards"),
    ("sweep-shards-overflow", ["sweep", "{in}/plan-one.json", "-o", "{tmp}/sw", "--shards", "99999999999"], r"--shards: '99999999999' is not a whole number", "--shards"),
    ("sweep-threads-overflow", ["sweep", "{in}/plan-one.json", "-o", "{tmp}/sw", "--threads", "4294967297"], r"--threads: '4294967297' is not a whole number", "--threads"),
    ("render-shard-overflow", ["render", "{in}/good.json", "-o", "{tmp}/out", "--shard", "99999999999/2"], r"--shard", "--shard"),
    ("render-shard-zero-count", ["render", "{in}/good.json", "-o", "{tmp}/out", "--shard", "0/0"], r"--shard", "--shard"),
    ("render-shard-beyond", ["render", "{in}/good.json", "-o", "{tmp}/out", "--shard", "5/2"], r"--shard", "--shard"),
    ("relight-intensity-1e300", ["relight", "{tmp}/r", "--intensity", "light-0=1e300", "-o", "{tmp}/out", "--quiet"], r"--intensity: '1e300' is not a non-negative number ≤ 1e30", "--intensity"),
    ("relight-intensity-negative", ["relight", "{tmp}/r", "--intensity", "light-0=-1", "-o", "{tmp}/out", "--quiet"], r"--intensity: '-1' is not a non-negative number ≤ 1e30", "--intensity"),
    ("relight-intensity-nan", ["relight", "{tmp}/r", "--intensity", "light-0=nan", "-o", "{tmp}/out", "--quiet"], r"--intensity: 'nan' is not a non-negative number ≤ 1e30", "--intensity"),
    # Issue 42: a dark new white named the rendered scene's $.white, not --white.
    ("relight-white-dark", ["relight", "{tmp}/r", "--white", "constant:0", "-o", "{tmp}/out", "--quiet"], r"^spectral relight: --white: the reference white 'constant:0' has no luminance", "--white"),
]:
    base = "base-lights r" if label.startswith("relight") or label.startswith("view") else "base-render r"
    case(f"numbers/{label}", args, pat, 2, named, OPT + r"|--[a-z-]+", [base])

# ---- H. sensor files (the two inputs fixed in 2c7cecf, found by the sensor fuzz target) and relight sweep CSVs ----------
# A sensor file's duplicate key is named at its second occurrence (line:column); a channel's name or spectrum that is
# not a string by its JSON path. A relight sweep CSV's bad cell by the sweep file's own row:column, before any row is written.
GAUSS = {"centre_nm": 450, "fwhm_nm": 40}
for label, text, pat, place in [
    ("duplicate-key", '{"name": "a",\n  "channels": [{"name": "F1", "gaussian": {"centre_nm": 450, "fwhm_nm": 40}}],\n  "name": "b"}',
     r"sensor-duplicate-key\.json:3:3: broken JSON: Duplicate property 'name'", r"\.json:3:3: "),
    ("duplicate-key-in-channel", '{"name": "a", "channels": [{"name": "F1", "name": "F2", "gaussian": {"centre_nm": 450, "fwhm_nm": 40}}]}',
     r"sensor-duplicate-key-in-channel\.json:1:43: broken JSON: Duplicate property 'name'", r"\.json:1:43: "),
    ("channel-name-number", json.dumps({"name": "x", "channels": [{"name": 5, "gaussian": GAUSS}]}),
     r"\$\.channels\[0\]\.name: must be a string", r"\.json: \$\.channels\[0\]\.name"),
    ("channel-spectrum-number", json.dumps({"name": "x", "channels": [{"name": "F1", "spectrum": 7}]}),
     r"\$\.channels\[0\]\.spectrum: must be a string", r"\.json: \$\.channels\[0\]\.spectrum"),
    # Found by the sensor fuzz target in CI after b59d92d: a box edge, a mosaic cell or a channel's first letter that
    # the reader took on trust (an exception instead of one line).
    ("box-edge-string", json.dumps({"name": "x", "channels": [{"name": "F1", "box": ["a", 500]}]}),
     r"\$\.channels\[0\]\.box\[0\]: must be a wavelength in nm", r"\.json: \$\.channels\[0\]\.box\[0\]"),
    ("box-edge-null", json.dumps({"name": "x", "channels": [{"name": "F1", "box": [400, None]}]}),
     r"\$\.channels\[0\]\.box\[1\]: must be a wavelength in nm", r"\.json: \$\.channels\[0\]\.box\[1\]"),
    ("box-not-a-pair", json.dumps({"name": "x", "channels": [{"name": "F1", "box": 3}]}),
     r"\$\.channels\[0\]\.box: must be two wavelengths", r"\.json: \$\.channels\[0\]\.box"),
    ("channel-name-empty", json.dumps({"name": "x", "channels": [{"name": "", "gaussian": GAUSS}], "arrangement": "mosaic",
                                       "pattern": "RGGB"}),
     r"\$\.channels\[0\]\.name: is empty", r"\.json: \$\.channels\[0\]\.name"),
    ("pattern-cell-fraction", json.dumps({"name": "x", "channels": [{"name": "F1", "gaussian": GAUSS}], "arrangement": "mosaic",
                                          "pattern": [[0, 1.5]]}),
     r"\$\.pattern\[0\]\[1\]: must be a channel index", r"\.json: \$\.pattern\[0\]\[1\]"),
    ("pattern-cell-null", json.dumps({"name": "x", "channels": [{"name": "F1", "gaussian": GAUSS}], "arrangement": "mosaic",
                                      "pattern": [[None]]}),
     r"\$\.pattern\[0\]\[0\]: must be a channel index", r"\.json: \$\.pattern\[0\]\[0\]"),
    ("pattern-cell-1e40", json.dumps({"name": "x", "channels": [{"name": "F1", "gaussian": GAUSS}], "arrangement": "mosaic",
                                      "pattern": [[0], [1e40]]}),
     r"\$\.pattern\[1\]\[0\]: must be a channel index", r"\.json: \$\.pattern\[1\]\[0\]"),
    ("pattern-empty-row", json.dumps({"name": "x", "channels": [{"name": "F1", "gaussian": GAUSS}], "arrangement": "mosaic",
                                      "pattern": [[]]}),
     r"\$\.pattern: a pattern is letters", r"\.json: \$\.pattern"),
    # Issue 42: a channel outside the render's bands was an internal error; a black level above the white level was accepted.
    ("channel-outside-bands", json.dumps({"name": "x", "channels": [{"name": "IR", "box": [900, 1000]}, {"name": "G", "gaussian": GAUSS}]}),
     r"channel 'IR' \(box 900–1000 nm\) has no response within the render's", r"\.json"),
    ("black-above-white", json.dumps({"name": "x", "adc_bits": 8, "black_level_dn": 300}),
     r"\$\.black_level_dn: black level 300 DN is not below the white level 255 DN", r"\.json: \$\.black_level_dn"),
]:
    fname = write(f"sensor-{label}.json", text)
    case(f"sensor/{label}", ["camera", "{tmp}/r", "--sensor", "{in}/" + fname, "-o", "{tmp}/out"], pat, 2, fname, place, ["base-render r"])
for label, text, pat, place in [
    ("unknown-spectrum-after-blank", "light-0\nD65\n\nD66\n", r"unknown spectrum", ":4:1: "),
    ("intensity-negative", "light-0.intensity\n1\n-1\n", r"'-1' is not a non-negative intensity", ":3:1: "),
    ("intensity-1e31", "light-0.intensity\n1e31\n", r"is not a non-negative intensity ≤ 1e30", ":2:1: "),
    ("white-unknown", "light-0,white\nD65,A\nA,nope\n", r"unknown spectrum", ":3:2: "),
    ("short-row", "light-0,white\nD65\n", r"1 cells, the header names 2", ":2:2: "),
    ("no-such-light", "light-9\nD65\n", r"column 'light-9' names no light", ":1:1: "),
    ("column-twice", "light-0,light-0\nD65,A\n", r"column 'light-0' appears twice", ":1:2: "),
    ("header-only", "light-0\n", r"a sweep needs a header and at least one row", ":2:1: "),
]:
    fname = write(f"relight-sweep-{label}.csv", text)
    case(f"relight-sweep/{label}", ["relight", "{tmp}/r", "--sweep", "{in}/" + fname, "-o", "{tmp}/out", "--quiet"], pat, 2, fname,
         r"\.csv" + place, ["base-lights r"])

# pbrt-v4 scenes (spectral render FILE.pbrt converts in memory): one line with file:line:column and a hint.
for label, text, pat, place in [
    ("unclosed-string", 'WorldBegin\nShape "sphere" "float radius\n', r"a string is not closed", r"\.pbrt:2:16: "),
    ("unknown-directive", 'WorldBegin\nShpe "sphere"\n', r"unknown directive 'Shpe'.*did you mean 'Shape'", r"\.pbrt:2:1: "),
    ("unknown-spectrum", 'WorldBegin\nMaterial "conductor" "spectrum eta" "metal-Au-eat"\nShape "sphere"\n',
     r"unknown named spectrum.*did you mean 'metal-Au-eta'", r"\.pbrt:2:22: "),
    ("index-out-of-range", 'WorldBegin\nShape "trianglemesh" "point3 P" [ 0 0 0 1 0 0 0 1 0 ] "integer indices" [ 0 1 3 ]\n',
     r"index 3 is not a vertex", r"\.pbrt:2:1: "),
    ("medium", 'WorldBegin\nMakeNamedMedium "fog" "string type" "homogeneous"\nShape "sphere"\n', r"participating media.*--lenient",
     r"\.pbrt:2:1: "),
    ("attribute-unclosed", 'WorldBegin\nAttributeBegin\nShape "sphere"\n', r"not closed by AttributeEnd", r"\.pbrt:2:1: "),
    ("projective-transform", 'Transform [ 1 0 0 1  0 1 0 0  0 0 1 0  0 0 0 1 ]\nWorldBegin\nShape "sphere"\n', r"a projective matrix",
     r"\.pbrt:1:1: "),
    ("missing-include", 'WorldBegin\nInclude "nothere.pbrt"\nShape "sphere"\n', r"nothere\.pbrt", r"\.pbrt:2:1: "),
    ("infinite-not-square", 'WorldBegin\nLightSource "infinite" "string filename" "wide.pfm"\nShape "sphere"\n',
     r"'wide\.pfm' is 4 × 3 pixels.*makeequiarea", r"\.pbrt:2:1: "),
    ("infinite-png", 'WorldBegin\nLightSource "infinite" "string filename" "sky.png"\nShape "sphere"\n',
     r"must be OpenEXR, PFM or Radiance.*--lenient", r"\.pbrt:2:1: "),
]:
    fname = write(f"pbrt-{label}.pbrt", text)
    case(f"pbrt/{label}", render("{in}/" + fname), pat, 2, fname, place)
# ---- I. Mitsuba 3 XML scenes (issue 39): spectral import and spectral render FILE.xml -------------------------------------
MI_SENSOR = ('<sensor type="perspective"><float name="fov" value="40"/>'
             '<transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>'
             '<film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="6"/></film></sensor>')
MI_SHAPE = '<shape type="sphere"><bsdf type="diffuse"/></shape>'

def mi_scene(body, sensor=MI_SENSOR, shape=MI_SHAPE):
    return f'<scene version="3.0.0">\n{sensor}\n{shape}\n{body}\n</scene>\n'

for label, text, pat in [
    ("not-closed", mi_scene("<bsdf type=\"diffuse\" id=\"a\">"), r"malformed XML"),
    ("text-content", mi_scene("<float name=\"x\">3</float>"), r"unexpected text"),
    ("root-not-scene", '<shape type="sphere"/>\n', r"the root element is <shape>, not <scene>"),
    ("unknown-ref", mi_scene("", shape='<shape type="sphere"><ref id="nope"/></shape>'), r"no element has id 'nope'"),
    ("id-twice", mi_scene('<bsdf type="diffuse" id="a"/>\n<bsdf type="diffuse" id="a"/>'), r"id 'a' is given twice"),
    ("parameter-undefined", mi_scene("", shape='<shape type="sphere"><float name="radius" value="$r"/></shape>'),
     r"parameter \$r has no value"),
    ("float-not-number", mi_scene("", shape='<shape type="sphere"><float name="radius" value="big"/></shape>'),
     r"radius: 'big' is not a number"),
    ("spectrum-not-ascending", mi_scene("", shape='<shape type="sphere"><bsdf type="diffuse">'
                                            '<spectrum name="reflectance" value="500:0.5, 400:0.2"/></bsdf></shape>'),
     r"wavelength 400 does not follow 500"),
    ("spectrum-bad-pair", mi_scene("", shape='<shape type="sphere"><bsdf type="diffuse">'
                                       '<spectrum name="reflectance" value="400:0.5:1, 500:0.2"/></bsdf></shape>'),
     r"is not wavelength:value"),
    ("serialized", mi_scene("", shape='<shape type="serialized"><string name="filename" value="m.serialized"/></shape>'),
     r"re-export it as PLY"),
    ("medium", mi_scene('<medium type="homogeneous" id="fog"/>'), r"participating medium.*--lenient"),
    ("hair-bsdf", mi_scene("", shape='<shape type="sphere"><bsdf type="hair"/></shape>'), r"the BSDF 'hair' has no counterpart"),
    ("fov-axis", mi_scene("", sensor=MI_SENSOR.replace('<float name="fov" value="40"/>',
                                                        '<float name="fov" value="40"/><string name="fov_axis" value="z"/>')),
     r"fov_axis 'z' is not x, y, diagonal"),
    ("lookat-degenerate", mi_scene("", sensor=MI_SENSOR.replace('target="0, 0, 0"', 'target="0, 0, 5"')), r"target equals origin"),
    ("matrix-short", mi_scene("", shape='<shape type="sphere"><transform name="to_world"><matrix value="1 0 0"/>'
                                        '</transform></shape>'), r"<matrix> has 3 numbers"),
    ("mesh-missing", mi_scene("", shape='<shape type="ply"><string name="filename" value="nowhere.ply"/></shape>'),
     r"mesh 'nowhere.ply' not found"),
    ("area-outside-shape", mi_scene('<emitter type="area"/>'), r"an area emitter outside a shape"),
    ("include-missing", mi_scene('<include filename="nowhere.xml"/>'), r"included file 'nowhere.xml' not found"),
    ("no-sensor", mi_scene("", sensor=""), r"the scene has no <sensor>"),
]:
    fname = write(f"mitsuba-{label}.xml", text)
    place = r"\.xml:\d+:\d+" if label != "no-sensor" else r"\.xml"
    case(f"mitsuba/{label}", ["import", "{in}/" + fname, "-o", "{tmp}/out/scene.json"], pat, 2, fname, place)
fname = write("mitsuba-render-unknown-bsdf.xml", mi_scene("", shape='<shape type="sphere"><bsdf type="measured"/></shape>'))
case("mitsuba/render-unknown-bsdf", render("{in}/" + fname), r"the BSDF 'measured' has no counterpart", 2, fname, r"\.xml:\d+:\d+")

# ---- Participating media (docs/scene-format.md, "Participating media") -------------------------------------------------
MEDIUM_INTEGRATOR = {"radiometry": "physical", "integrator": "path"}
for label, where, medium, pat in [
    ("medium-negative-sigma-a", "scene", {"sigma_a": -0.5}, r"\$\.medium\.sigma_a: -0\.5 is out of range"),
    ("medium-negative-sigma-s", "object", {"sigma_s": [[380, 1], [780, -1]]}, r"\$\.objects\[0\]\.medium\.sigma_s\[1\]\[1\]: negative value -1"),
    ("medium-huge-sigma-t", "scene", {"albedo": 0.5, "sigma_t": 987654321}, r"\$\.medium\.sigma_t: Infinity is out of range"),
    ("medium-albedo-above-1", "scene", {"albedo": 1.5, "sigma_t": 1}, r"\$\.medium\.albedo: the value 1\.5 is outside \[0, 1\]"),
    ("medium-both-forms", "scene", {"sigma_a": 1, "albedo": 0.5, "sigma_t": 1}, r"gives both σ_a/σ_s and albedo/σ_t"),
    ("medium-no-coefficients", "scene", {"phase": {"type": "hg", "g": 0.5}}, r"a medium has no coefficients"),
    ("medium-hg-g-1", "scene", {"sigma_s": 1, "phase": {"type": "hg", "g": 1}}, r"\$\.medium\.phase\.g: the asymmetry g = 1 is not inside"),
    ("medium-hg-g-minus-2", "object", {"sigma_s": 1, "phase": {"type": "hg", "g": -2}}, r"\$\.objects\[0\]\.medium\.phase\.g: the asymmetry"),
    ("medium-phase-unknown", "scene", {"sigma_s": 1, "phase": {"type": "rayleigh"}}, r"unknown phase function 'rayleigh'"),
    ("medium-unknown-type", "scene", {"type": "fgo", "sigma_a": 1}, r"unknown medium type 'fgo'"),
    ("medium-unknown-key", "scene", {"sigma_a": 1, "sigma": 2}, r"\$\.medium.*sigma"),
]:
    s = deep(BASE); s.update(MEDIUM_INTEGRATOR)
    if where == "scene": s["medium"] = medium
    else: s["objects"][0]["medium"] = medium
    scene_case(label, scene_text(s).replace("987654321", "1e400"), pat)   # 1e400: a JSON number beyond double
s = deep(BASE); s.update(MEDIUM_INTEGRATOR)
s["objects"].append({"type": "quad", "center": [0, 0, -2], "size": 4, "material": "green", "medium": {"sigma_a": 1}})
scene_case("medium-on-open-quad", s, r"\$\.objects\[1\]\.medium: object 'quad-1' is not closed")
s = deep(BASE); s.update(MEDIUM_INTEGRATOR)
s["objects"].append({"type": "mesh", "inline": {"positions": [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1],
                                                 "indices": [0, 2, 1, 0, 1, 3, 0, 3, 2]},
                     "material": "green", "medium": {"sigma_a": 1}})
scene_case("medium-on-open-mesh", s, r"\$\.objects\[1\]\.medium: object '.*' is not closed")

# ---- The CIE overcast sky (issue 43): "sky": { "type": "daylight", "distribution": "cie-overcast", "zenith": … }; an unknown
# distribution, a zenith on a uniform sky or of zero length, one line with the JSON path; the whitted integrator refuses it.
OVERCAST = {"type": "daylight", "cct": 6504, "luminance": 5000, "distribution": "cie-overcast"}
for label, sky, extra, pat in [
    ("sky-distribution-unknown", {**OVERCAST, "distribution": "cie-overcst"}, {"integrator": "path"},
     r"\$\.sky\.distribution: unknown sky distribution 'cie-overcst'.*did you mean 'cie-overcast'"),
    ("sky-distribution-not-text", {**OVERCAST, "distribution": 1}, {"integrator": "path"}, r"\$\.sky\.distribution"),
    ("sky-zenith-on-uniform", {**OVERCAST, "distribution": "uniform", "zenith": [0, 0, 1]}, {"integrator": "path"},
     r"\$\.sky\.zenith: a uniform sky has no zenith"),
    ("sky-zenith-zero", {**OVERCAST, "zenith": [0, 0, 0]}, {"integrator": "path"}, r"\$\.sky\.zenith: the direction is the zero vector"),
    ("sky-overcast-whitted", OVERCAST, {}, r"\$\.sky\.distribution: the whitted integrator .* cannot render a CIE overcast sky"),
]:
    s = deep(BASE)
    s["radiometry"] = "physical"
    s.update(extra)
    s["sky"] = sky
    scene_case(label, s, pat)

# Environment maps in pbrt-v4's equal-area layout ("mapping": "equal-area"; after the others, so their numbers stay).
scene = deep(ENVSCENE)
scene["sky"] = {"type": "envmap", "file": "wide.pfm", "mapping": "equal-area"}
scene_case("envmap-equal-area-not-square", scene, r"wide\.pfm is 4 × 3 pixels.*equal-area map .* is square", file="")
scene = deep(ENVSCENE)
scene["sky"] = {"type": "envmap", "file": "wide.pfm", "mapping": "octahedral"}
scene_case("envmap-unknown-mapping", scene, r"unknown mapping 'octahedral'.*equal-area", file="")

# Heterogeneous media (type "grid"; after the others, so their numbers stay): a .vol or .npy density grid beside the scene; each broken file or placement one line
# naming the grid file (byte or sample) or the scene's JSON path.
def vol(nx=2, ny=2, nz=2, values=None, version=3, encoding=1, channels=1, bbox=(0, 0, 0, 1, 1, 1), cut=0):
    values = [1.0] * (nx * ny * nz * max(channels, 0)) if values is None else values
    data = b"VOL" + bytes([version]) + struct.pack("<iiiii", encoding, nx, ny, nz, channels) + struct.pack("<6f", *bbox)
    data += struct.pack(f"<{len(values)}f", *values)
    return data[:len(data) - cut] if cut else data

VOLPLACE = r"\.(vol|npy): (byte \d+|sample \(x \d+, y \d+, z \d+\)|header|data)"
for label, fname, data, pat in [
    ("grid-vol-no-magic", "g.vol", b"VOX\x03" + b"\0" * 60, r"not a \.vol grid \(no \"VOL\" magic\)"),
    ("grid-vol-version-2", "g.vol", vol(version=2), r"\.vol version 2 is not supported"),
    ("grid-vol-encoding-3", "g.vol", vol(encoding=3), r"encoding 3 is not supported"),
    ("grid-vol-short-header", "g.vol", vol()[:20], r"truncated in its 48-byte header"),
    ("grid-vol-truncated", "g.vol", vol(cut=4), r"declares 2 × 2 × 2 = 8 float32 values \(32 bytes\), the file holds 28"),
    ("grid-vol-too-long", "g.vol", vol() + b"\0\0\0\0", r"the file holds 36 bytes of data"),
    ("grid-vol-zero-size", "g.vol", vol(nx=0, values=[]), r"resolution 0 × 2 × 2 is not positive"),
    ("grid-vol-3-channels", "g.vol", vol(channels=3), r"the grid has 3 channels"),
    ("grid-vol-empty-bbox", "g.vol", vol(bbox=(0, 0, 0, 1, 0, 1)), r"bounds .* are empty"),
    ("grid-vol-nan-bbox", "g.vol", vol(bbox=(0, 0, 0, float("nan"), 1, 1)), r"bounds .* are not finite"),
    ("grid-vol-negative", "g.vol", vol(values=[1, 1, 1, -0.5, 1, 1, 1, 1]), r"sample \(x 1, y 1, z 0\).*density -0\.5 is negative"),
    ("grid-vol-inf", "g.vol", vol(values=[1, 1, 1, 1, 1, 1, 1, float("inf")]), r"density ∞ is not finite|density Infinity is not finite"),
    ("grid-npy-2d", "g.npy", npy((4, 4), body=b"\0" * 64), r"the array's shape is \(4, 4\)"),
    ("grid-npy-int", "g.npy", npy((2, 2, 2), dtype="<i4", body=b"\0" * 32), r"unsupported dtype"),
    ("grid-npy-truncated", "g.npy", npy((2, 2, 2), body=b"\0" * 20), r"holds only 20 bytes"),
    ("grid-npy-nan", "g.npy", npy((1, 1, 2), body=struct.pack("<2f", 1, float("nan"))), r"sample \(x 1, y 0, z 0\).*not finite"),
]:
    gname = f"{label}-{fname}"
    write(gname, data)
    s = deep(BASE); s.update(MEDIUM_INTEGRATOR)
    s["objects"][0]["medium"] = {"type": "grid", "file": gname, "sigma_a": 1}
    sname = f"{label}.json"
    write(sname, scene_text(s))
    case(f"media/{label}", render("{in}/" + sname), pat, 2, gname, VOLPLACE)
for label, medium, pat in [
    ("grid-npy-no-bounds", {"file": "GOOD.npy"}, r"\$\.medium\.file: a \.npy grid in the scene's medium has no placement"),
    ("grid-bounds-empty", {"file": "GOOD.vol", "bounds": [[0, 0, 0], [1, -1, 1]]}, r"\$\.medium\.bounds: the grid's bounds .* are empty"),
    ("grid-resolution-mismatch", {"file": "GOOD.vol", "resolution": [2, 2, 3]},
     r"\$\.medium\.resolution: the grid declares 2 × 2 × 3 samples, grid-resolution-mismatch\.vol holds 2 × 2 × 2"),
    ("grid-file-missing", {"file": "nowhere.vol"}, r"\$\.medium\.file: file 'nowhere\.vol' not found"),
]:
    s = deep(BASE); s.update(MEDIUM_INTEGRATOR)
    s["medium"] = {"type": "grid", "sigma_s": 0.5, **medium}
    s["medium"]["file"] = s["medium"]["file"].replace("GOOD", label)
    if "nowhere" not in medium["file"]:
        write(s["medium"]["file"], vol() if s["medium"]["file"].endswith(".vol") else npy((2, 2, 2), body=b"\0" * 32))
    scene_case(label, s, pat)
# Window portals (issue 40: "portal": true on a quad; after the others, so their numbers stay): a portal that is not a
# quad, a portal with an emitting material.
s = deep(BASE)
s["objects"].append({"type": "sphere", "center": [0, 0, -3], "radius": 1, "portal": True})
scene_case("portal-not-quad", s, r"\$\.objects\[1\]\.portal: a portal must be a quad, found a sphere")
s = deep(BASE)
s["radiometry"] = "physical"
s["integrator"] = "path"
s["materials"]["glow"] = {"type": "lambertian", "reflectance": 0, "emission": {"spectrum": "D65", "radiance": 1}}
s["objects"].append({"type": "quad", "center": [0, 0, -3], "size": 1, "material": "glow", "portal": True})
scene_case("portal-emits", s, r"\$\.objects\[1\]\.portal: portal 'quad-1' has an emitting material")

names = [c["name"] for c in cases]
assert len(names) == len(set(names)), [x for x in names if names.count(x) > 1]
# instancing: "prototypes" and "instance" objects
TRI = {"inline": {"positions": [0, 0, 0, 1, 0, 0, 0, 1, 0], "indices": [0, 1, 2]}}
for label, protos, o, pat in [
    ("instance-unknown-prototype", {"tri": TRI}, {"type": "instance", "prototype": "tir", "material": "green"}, r"no prototype named 'tir'.*did you mean 'tri'"),
    ("instance-no-prototypes", None, {"type": "instance", "prototype": "tri", "material": "green"}, r"define it under the top-level \"prototypes\""),
    ("instance-no-prototype-field", {"tri": TRI}, {"type": "instance", "material": "green"}, r"missing required field 'prototype'"),
    ("instance-far", {"tri": TRI}, {"type": "instance", "prototype": "tri", "material": "green", "transform": {"scale": 1e6, "translate": [9.5e6, 0, 0]}}, r"outside ±10000000"),
    ("instance-file-key", {"tri": TRI}, {"type": "instance", "prototype": "tri", "file": "tri.obj", "material": "green"}, r"unknown field 'file'"),
    ("prototype-unknown-key", {"tri": dict(TRI, material="green")}, {"type": "sphere", "material": "green"}, r"unknown field 'material'"),
    ("prototypes-not-object", [TRI], {"type": "sphere", "material": "green"}, r"expected an object"),
    ("prototype-no-mesh", {"tri": {"shading": "flat"}}, {"type": "sphere", "material": "green"}, r"missing required field 'file'"),
]:
    s = deep(BASE); s["objects"] = [o]
    if protos is not None: s["prototypes"] = protos
    scene_case(label, s, pat)

for label, text, pat in [
    ("instance-no-group", mi_scene("", shape='<shape type="instance"><transform name="to_world"><translate x="1"/></transform></shape>'),
     r"an instance without a shapegroup"),
    ("instance-of-sphere", mi_scene('<shape type="sphere" id="ball"/>', shape='<shape type="instance"><ref id="ball"/></shape>'),
     r"an instance of a <shape type=\"sphere\">"),
]:
    fname = write(f"mitsuba-{label}.xml", text)
    case(f"mitsuba/{label}", ["import", "{in}/" + fname, "-o", "{tmp}/out/scene.json"], pat, 2, fname, r"\.xml:\d+:\d+")

with open(os.path.join(HERE, "cases.json"), "w", encoding="utf-8") as f:
    json.dump(cases, f, indent=1, ensure_ascii=True)
    f.write("\n")
print(f"{len(cases)} cases, {len(os.listdir(IN))} input files")
