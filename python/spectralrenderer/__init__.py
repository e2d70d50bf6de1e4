"""spectralrenderer: the SpectralRenderer engine from Python, through libspectral (Native AOT, no .NET runtime).

    import spectralrenderer as sr
    r = sr.render("scenes/paper-3.1-colorchecker-d65.json", width=120, height=80)
    r.cube          # H x W x N float32, the values of `spectral render`'s spectral.npy (a view of the library's buffer)
    r.wavelengths   # N band centres, nm
    r.ids, r.masks  # object ids (object-id.png), {"lit-0": …, "highlight": …} (mask-*.png), uint8 0/255
    r.noise         # H x W x (N + 1) standard errors (noise.npy): render with formats="npy,noise" and spp >= 2
    r.save("out/chart")   # the folder `spectral render -o out/chart` writes
    warm = sr.relight(r, lights={"D65": "blackbody:3000"})   # `spectral relight`, from the render in memory
    cap = sr.camera(r, sensor="nikon-d5100")                  # `spectral camera`: cap.raw, cap.srgb, cap.manifest
    rec = sr.recover(cap, method="wiener")                    # `spectral recover`: rec["wiener"], rec.metrics

Spectra are names ("D65", "blackbody:3000", "colorchecker:14", "file.csv:column") or NumPy arrays: an N x 2 array of
(nm, value) rows, or a pair (wavelengths, values) — see spectrum(). Scene dicts may hold NumPy arrays anywhere.
Rendering runs in the library with the GIL released; Ctrl-C cancels it (KeyboardInterrupt). Bad input raises
SpectralError whose message is the one line the command line prints.
"""
import ctypes
import json
import os
import struct
import threading
import warnings
import zlib
from pathlib import Path

import numpy as np

from . import _native

__all__ = ["render", "relight", "camera", "recover", "spectrum", "plot_spectrum", "Render", "Capture", "Recovery",
           "SpectralError", "abi_version"]
__version__ = "0.1.0"


class SpectralError(Exception):
    """A render that failed: .status is the CLI's exit code (2 bad input, 1 work failed or interrupted), str() its line."""

    def __init__(self, message, status):
        super().__init__(message)
        self.status = status


def abi_version():
    """The loaded libspectral's C ABI version."""
    return _native.lib().spectral_abi_version()


def spectrum(wavelengths, values=None, scale=None):
    """A spectrum value of the scene format from arrays: inline [[nm, value], …] pairs (linear in between).

    spectrum(wl, v) with two 1-D arrays of one length, or spectrum(a) with an N x 2 array of (nm, value) rows. Names
    ("D65", "blackbody:3000", …) and such pairs are what render(), relight() and scene dicts take as a spectrum.
    Arrays are taken as given, as a CSV column is: a light's values multiply its intensity as they are. scale: a number
    (a factor), or "luminous" to put a light's shape on the built-in lights' scale (∫V·S dλ = D65's, as led-blue and
    FL11 are: at the same intensity it gives the luminance D65 gives); either makes the object {"values": …, "scale": …}."""
    if values is None:
        a = np.asarray(wavelengths, dtype=float)
        if a.ndim != 2 or a.shape[1] != 2:
            raise ValueError(f"a spectrum array is N x 2 (nm, value) rows, not {a.shape}")
        pairs = a.tolist()
    else:
        wl, v = np.asarray(wavelengths, dtype=float), np.asarray(values, dtype=float)
        if wl.ndim != 1 or wl.shape != v.shape:
            raise ValueError(f"wavelengths {wl.shape} and values {v.shape} must be 1-D of one length")
        pairs = np.stack([wl, v], axis=1).tolist()
    return pairs if scale is None else {"values": pairs, "scale": scale}


def _spectrum_value(value):
    """A spectrum given as a name, a number, pairs, an N x 2 array, a (wavelengths, values) pair or a spectrum object (a
    dict, e.g. from spectrum(wl, v, scale=…)), as JSON."""
    if isinstance(value, (str, int, float, dict)) or value is None:
        return value
    if isinstance(value, tuple) and len(value) == 2 and np.ndim(value[0]) == 1:
        return spectrum(value[0], value[1])
    return spectrum(value)


def _json_default(o):
    """NumPy arrays and scalars in a scene dict, as JSON lists and numbers."""
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, np.generic):
        return o.item()
    raise TypeError(f"{type(o).__name__} is not JSON serializable")


# Scene files of other renderers (docs/import.md): the library reads and converts them from their path.
IMPORTED = (".xml", ".pbrt", ".gltf", ".glb")


def _scene_text(scene):
    """(UTF-8 JSON, the name it is loaded under): a dict, JSON text, or a scene file's path; for a Mitsuba, pbrt or glTF
    file (None, its path): the library converts it as `spectral render FILE` does."""
    if isinstance(scene, dict):
        return json.dumps(scene, default=_json_default).encode(), "<dict>"
    if isinstance(scene, str) and scene.lstrip().startswith("{"):
        return scene.encode(), "<text>"
    path = os.fspath(scene)
    if not Path(path).is_file():   # the CLI's words (InputFile)
        raise SpectralError(f"spectral render: {path}: scene file not found (hint: check the path)", 2)
    if Path(path).suffix.lower() in IMPORTED:
        return None, path
    try:
        return Path(path).read_bytes(), path
    except OSError as e:
        raise SpectralError(f"spectral render: {path}: cannot read the scene file: {e.strerror} "
                            "(hint: choose files and folders you can read and write)", 2) from None


def _error(lib, handle):
    status = lib.spectral_status(handle)
    message = (lib.spectral_message(handle) or b"").decode()
    lib.spectral_free(handle)
    return SpectralError(message, status)


def render(scene, progress=None, **options):
    """Renders a scene (dict, JSON text, or path — our JSON, or a Mitsuba 3 .xml converted as `spectral import` does) as
    `spectral render` does, in memory. The keywords are the command's
    options (`spectral render --help`, one table for the command line, libspectral and this package), with '_' for '-':
    width, height, bands (a count or "start:end:count"), band_range, wave, spp, target_error, threads, rgb, exposure, integration,
    formats, exr_compression, models (a folder or a list of them), crop ("x0,y0,x1,y1" or (x0, y0, x1, y1)), shard
    ("i/n"), shards, integrator; None leaves an option out. Values are checked by the library with the command line's
    messages. progress(done, total) is called after each tile.
    Raises SpectralError (the CLI's one-line message) on bad input or failure; KeyboardInterrupt cancels."""
    lib = _native.lib()
    text, name = _scene_text(scene)
    opts = {k: _option_value(v) for k, v in options.items() if v is not None}
    callback = _native.PROGRESS(lambda _user, done, total: progress(done, total)) if progress else _native.PROGRESS()
    return Render(_handle=_call(lib, "spectral_render", lambda cancel: lib.spectral_render(
        text, name.encode(), json.dumps(opts, default=_json_default).encode(), cancel, callback, None)))


def _option_value(value):
    """An option's value as the library's JSON takes it: a text or a number, a list of them (paths as text)."""
    if isinstance(value, (list, tuple)):
        return [_option_value(v) for v in value]
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def _call(lib, what, call):
    """A handle from call(cancel flag) run in a worker thread (the foreign call releases the GIL, so the main thread stays
    free to see Ctrl-C, which sets the flag the library polls after each tile and every 20 ms); an error raised."""
    cancel = ctypes.c_int(0)
    out = {}

    def run():
        out["handle"] = call(ctypes.byref(cancel))

    worker = threading.Thread(target=run, name=what, daemon=True)
    worker.start()
    try:
        while worker.is_alive():
            worker.join(0.05)
    except KeyboardInterrupt:
        cancel.value = 1
        worker.join()
        handle = out.get("handle")
        if handle:
            lib.spectral_free(handle)
        raise
    handle = out["handle"]
    if lib.spectral_status(handle) != 0:
        raise _error(lib, handle)
    return handle


def relight(render, lights=None, white=None):
    """The render under other lights, as `spectral relight` computes it (no ray traced into the picture): a new Render.

    lights: {name: spectrum} or {name: {"spectrum": spectrum, "intensity": F}} (either key); white: a new reference white
    (κ and the colour weights follow it). A spectrum is a name or arrays (see spectrum()): arrays are taken as given, as a
    CSV column is, so a shape with peak 1 replacing D65 (100 at 560 nm) is about a hundred times darker; put it on the
    built-in lights' scale with spectrum(wl, v, scale="luminous"). A relit picture under 1/20 of the render's mean
    luminance after arrays without a scale warns (RuntimeWarning) with that hint. The render's per-light transfer
    (the Whitted model's factors, or a path render's weights on its fine grid) is traced once, on the first relight, and
    kept with it (or taken from an earlier save with lights). Raises SpectralError with the command's one line."""
    lib = _native.need(1, "relight")
    if render._handle is None:
        raise SpectralError("spectral relight: a render read from a folder has no render in memory "
                            "(hint: relight a render from sr.render, or run 'spectral relight' on the folder)", 2)
    changes = {}
    for name, value in (lights or {}).items():
        if isinstance(value, dict) and ("spectrum" in value or "intensity" in value):
            value = {k: (_spectrum_value(v) if k == "spectrum" else v) for k, v in value.items()}
        else:
            value = {"spectrum": _spectrum_value(value)}
        changes[name] = value
    body = json.dumps({"lights": changes, **({} if white is None else {"white": _spectrum_value(white)})},
                      default=_json_default).encode()
    relit = Render(_handle=_call(lib, "spectral_relight", lambda cancel: lib.spectral_relight(render._handle, body, cancel)))
    bare = [name for name, value in changes.items() if isinstance(value.get("spectrum"), list)]
    if bare:
        before, after = float(np.mean(render.xyz[..., 1])), float(np.mean(relit.xyz[..., 1]))
        if before > 0 and after < before / 20:
            warnings.warn(f"sr.relight: the relit picture's mean luminance is {after / before:.2g}× the render's: the "
                          f"spectra of {', '.join(bare)} given as arrays are taken as given, not on the built-in lights' "
                          "scale (hint: sr.spectrum(wl, v, scale=\"luminous\"), or an intensity)", RuntimeWarning, stacklevel=2)
    return relit


def camera(render, sensor=None, exposure=None, seed=None, noise=None, radiance_scale=None, demosaic=None, signals=None,
           threads=None, off_axis=None, psf=None):
    """The render seen by a simulated camera, as `spectral camera` (docs/camera.md): a Capture (raw, srgb, manifest).

    sensor: a preset's name (isetcam, nikon-d5100, wheel-6, mosaic-16, cie-xyz, …), a sensor JSON file, or None for the
    scene's camera "sensor"; exposure "auto" or seconds; noise True/False; signals "exact" (default: each eq. 2 term
    integrated at full spectral resolution from the render's per-light transfer) or "bands". The lens, as --off-axis and
    --psf (overriding the sensor's): off_axis "cos4th" (default: cos⁴ fall-off of the field angle) or "none"; psf
    "diffraction" (default: the Airy pattern of the f-number per band) or "none"."""
    lib = _native.need(2 if off_axis is not None or psf is not None else 1, "camera")
    if render._handle is None:
        raise SpectralError("spectral camera: a render read from a folder has no render in memory "
                            "(hint: run 'spectral camera' on the folder, or render with sr.render)", 2)
    opts = {k: v for k, v in dict(sensor=None if sensor is None else os.fspath(sensor), exposure=exposure, seed=seed,
                                  noise=None if noise is None else ("on" if noise else "off"), radiance_scale=radiance_scale,
                                  demosaic=demosaic, signals=signals, threads=threads, off_axis=off_axis,
                                  psf=psf).items() if v is not None}
    handle = lib.spectral_camera(render._handle, json.dumps(opts).encode())
    if lib.spectral_status(handle) != 0:
        raise _error(lib, handle)
    return Capture(handle, render)


def recover(capture, method="all", training=None, white_object=None, white_region=None, range=None):
    """Reflectance recovered from a capture, as `spectral recover` (pinv, wiener, linear, tikhonov, wiener-local): a
    Recovery holding each method's H x W x N cube (rec["wiener"]) and the metrics against the render's ground truth.

    method: a name, a list of names, or "all"; training: rawtoaces-190 (default), cie224-ces99, colorchecker or a CSV;
    white_object / white_region (x0, y0, x1, y1; x1 and y1 exclusive, as --crop): a white reference (§3.4); range (lo, hi) nm for RMSE and GFC."""
    lib = _native.need(1, "recover")
    if not isinstance(method, str):
        method = ",".join(method)
    opts = {k: v for k, v in dict(method=method, training=None if training is None else os.fspath(training),
                                  white_object=white_object, white_region=None if white_region is None else list(white_region),
                                  range=None if range is None else list(range)).items() if v is not None}
    handle = lib.spectral_recover(capture._owner.ptr, json.dumps(opts).encode())
    if lib.spectral_status(handle) != 0:
        raise _error(lib, handle)
    return Recovery(handle, capture)


class Render:
    """A render: arrays are views of the library's buffers, valid as long as this object (they keep it alive)."""

    def __init__(self, _handle=None, _folder=None):
        self._owner = _Handle(_handle) if _handle else None
        self._handle = _handle
        self._folder = Path(_folder) if _folder is not None else None
        self._cache = {}

    @property
    def shape(self):
        """(height, width, bands)."""
        if self._handle is None:
            return self.cube.shape
        h, w, n = ctypes.c_int(), ctypes.c_int(), ctypes.c_int()
        _native.lib().spectral_shape(self._handle, ctypes.byref(h), ctypes.byref(w), ctypes.byref(n))
        return h.value, w.value, n.value

    def _array(self, name, shape, dtype):
        if name not in self._cache:
            ptr = getattr(_native.lib(), "spectral_" + name)(self._handle)
            if not ptr:
                raise SpectralError(f"spectral render: {name} is not available for this render", 1)
            a = np.ctypeslib.as_array(ptr, shape=shape)
            a.flags.writeable = False
            # The view's base holds the handle (not this Render: no reference cycle), so the buffer outlives both.
            holder = _Owner(a, self._owner)
            self._cache[name] = np.asarray(holder).view(dtype)
        return self._cache[name]

    @property
    def cube(self):
        """H x W x N float32 band values (spectral.npy's), zero-copy."""
        if self._handle is None:
            return self._load("cube", lambda: np.load(self._folder / "spectral.npy", mmap_mode="r"))
        return self._array("cube", self.shape, np.float32)

    @property
    def wavelengths(self):
        """The N band centres, nm."""
        if self._handle is None:
            return self._load("wavelengths", lambda: _csv_centres(self._folder / "wavelengths.csv"))
        return self._array("wavelengths", (self.shape[2],), np.float64)

    @property
    def band_edges(self):
        """The N + 1 band edges, nm."""
        return self._array("band_edges", (self.shape[2] + 1,), np.float64)

    @property
    def xyz(self):
        """H x W x 3 float32 CIE 1931 XYZ (the colours the preview is encoded from)."""
        h, w, _ = self.shape
        return self._array("xyz", (h, w, 3), np.float32)

    @property
    def srgb(self):
        """H x W x 3 uint8 display RGB: preview.png's pixels."""
        h, w, _ = self.shape
        return self._array("rgb8", (h, w, 3), np.uint8)

    @property
    def ids(self):
        """H x W int32 object ids: 0 background, k the scene's k-th object (object-id.png's values)."""
        h, w, _ = self.shape
        return self._array("ids", (h, w), np.int32)

    @property
    def noise(self):
        """H x W x (N + 1) float32: each pixel's standard error s/sqrt(n) per band (the band unit), then of luminance Y
        (render.json's colour unit) — noise.npy's values. A render whose formats name noise (spp >= 2) has it."""
        if self._handle is None:
            return self._load("noise", lambda: np.load(self._folder / "noise.npy", mmap_mode="r"))
        if "noise" not in self._cache:
            h, w, n = self.shape
            ptr = _native.need(2, "Render.noise").spectral_noise(self._handle)
            if not ptr:
                raise SpectralError("spectral render: this render has no noise product (hint: render with formats "
                                    "naming noise, e.g. formats=\"npy,noise\", and spp=2 or more)", 2)
            self._cache["noise"] = _view(ptr, (h, w, n + 1), np.float32, self._owner, "spectral render", "noise")
        return self._cache["noise"]

    @property
    def masks(self):
        """The analysis masks, {name: H x W uint8}: "lit-K" where the manifest's K-th light reaches the surface seen
        (mask-lit-K.png, 255 or 0; lights 0…31) and "highlight" (mask-highlight.png) — the aov product's pixels."""
        if self._handle is None:
            raise SpectralError(f"spectral render: a render read from a folder has its masks in {self._folder}/mask-*.png "
                                "(hint: read the PNGs, or render with sr.render)", 2)
        if "masks" not in self._cache:
            lib = _native.need(2, "Render.masks")
            h, w, _ = self.shape
            self._cache["masks"] = {
                lib.spectral_mask_name(self._handle, i).decode():
                    _view(lib.spectral_mask(self._handle, i), (h, w), np.uint8, self._owner, "spectral render", "mask")
                for i in range(lib.spectral_mask_count(self._handle))}
        return self._cache["masks"]

    @property
    def manifest(self):
        """render.json as a dict (in memory: its "files" empty and "run" absent until saved)."""
        if "manifest" not in self._cache:
            if self._handle is None:
                self._cache["manifest"] = json.loads((self._folder / "render.json").read_text())
            else:
                self._cache["manifest"] = json.loads(_native.lib().spectral_manifest(self._handle).decode())
        return self._cache["manifest"]

    def save(self, folder):
        """Writes the folder `spectral render -o FOLDER` writes (same bytes; render.json's run fields aside), lights/ too
        when the formats name lights (a Whitted or a path render)."""
        lib = _native.lib()
        err = ctypes.c_void_p()
        if lib.spectral_save(self._handle, os.fspath(folder).encode(), ctypes.byref(err)) != 0:
            raise _error(lib, err.value)
        return Path(folder)

    @classmethod
    def load(cls, folder):
        """A render folder read back (cube, wavelengths, manifest)."""
        folder = Path(folder)
        if not (folder / "render.json").exists():
            raise SpectralError(f"spectral render: {folder}: has no render.json "
                                "(hint: give the -o folder of a 'spectral render' run)", 2)
        return cls(_folder=folder)

    def _load(self, key, make):
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    def _repr_png_(self):
        """The sRGB preview as PNG bytes (Jupyter shows it)."""
        return _png(self.srgb)

    def __repr__(self):
        h, w, n = self.shape
        return f"<spectralrenderer.Render {w}x{h}, {n} bands>"


class Capture:
    """A camera capture (sr.camera): arrays are views of the library's buffers, valid as long as they are held."""

    def __init__(self, handle, render):
        self._owner = _Handle(handle)
        self._render = render   # the render it looked at (recover scores against its ground truth)
        self._cache = {}
        h, w, p, c = (ctypes.c_int() for _ in range(4))
        _native.lib().spectral_capture_shape(handle, *(ctypes.byref(v) for v in (h, w, p, c)))
        self.height, self.width, self.planes, self.channels = h.value, w.value, p.value, c.value

    def _array(self, name, shape, dtype):
        if name not in self._cache:
            ptr = getattr(_native.lib(), "spectral_capture_" + name)(self._owner.ptr)
            self._cache[name] = _view(ptr, shape, dtype, self._owner, "spectral camera", name)
        return self._cache[name]

    @property
    def raw(self):
        """The raw digital numbers, float32: H x W (one plane: a mosaic) or H x W x planes — raw.npy's values."""
        shape = (self.height, self.width) if self.planes == 1 else (self.height, self.width, self.planes)
        return self._array("raw", shape, np.float32)

    @property
    def srgb(self):
        """H x W x 3 uint8: processed.png's pixels (demosaicked, white-balanced, colour-corrected sRGB)."""
        return self._array("rgb8", (self.height, self.width, 3), np.uint8)

    @property
    def rates(self):
        """H x W x channels float32: the demosaicked channel signals in electrons per second (what recovery reads)."""
        return self._array("rates", (self.height, self.width, self.channels), np.float32)

    @property
    def manifest(self):
        """camera.json as a dict (sensor, exposures, channel weights, colour matrix, patches; no "files")."""
        if "manifest" not in self._cache:
            self._cache["manifest"] = json.loads(_native.lib().spectral_capture_manifest(self._owner.ptr).decode())
        return self._cache["manifest"]

    @property
    def patches(self):
        """Per ColorChecker patch: ΔE00 of the corrected colour against the exact colour, SNR per channel (patches.csv)."""
        return self.manifest.get("patches", [])

    def _repr_png_(self):
        return _png(self.srgb)

    def __repr__(self):
        return f"<spectralrenderer.Capture {self.manifest.get('sensor', {}).get('name', '?')} {self.width}x{self.height}>"


class Recovery:
    """Reflectance recovered from a capture (sr.recover): rec[method] is an H x W x N float32 cube (recovered-<method>.npy)."""

    def __init__(self, handle, capture):
        self._owner = _Handle(handle)
        self._capture = capture
        info = json.loads(_native.lib().spectral_recovery_manifest(handle).decode())
        self.methods = info["methods"]
        self.shape = tuple(info["shape"])
        self.wavelengths = np.array(info["wavelengths"])
        self.training = info["training"]
        self.forward_model = info.get("forward_model")   # "exact" or "bands": the capture's signal route's model
        self.metrics_csv = info["metrics_csv"]
        self._cache = {}

    @property
    def metrics(self):
        """recovery-metrics.csv's rows as dicts: method, region, count, rmse, gfc, dE00_D65, dE00_A, metric_range_nm."""
        lines = self.metrics_csv.strip().splitlines()
        keys = lines[0].split(",")
        conv = lambda k, v: v if k in ("method", "region", "metric_range_nm") else float(v)   # noqa: E731
        return [{k: conv(k, v) for k, v in zip(keys, line.split(","))} for line in lines[1:]]

    def __getitem__(self, method):
        if method not in self.methods:
            raise KeyError(f"{method!r}: this recovery holds {', '.join(self.methods)}")
        if method not in self._cache:
            i = self.methods.index(method)
            ptr = _native.lib().spectral_recovery_reflectance(self._owner.ptr, i)
            self._cache[method] = _view(ptr, self.shape, np.float32, self._owner, "spectral recover", method)
        return self._cache[method]

    @property
    def cube(self):
        """The one method's cube (a recovery of several methods: rec[name])."""
        if len(self.methods) != 1:
            raise ValueError(f"this recovery holds {len(self.methods)} methods: index it by name ({', '.join(self.methods)})")
        return self[self.methods[0]]

    def __repr__(self):
        return f"<spectralrenderer.Recovery {', '.join(self.methods)} {self.shape}>"


def _view(ptr, shape, dtype, owner, command, name):
    """A read-only NumPy view of a library buffer whose base holds the handle that owns it."""
    if not ptr:
        raise SpectralError(f"{command}: {name} is not available", 1)
    a = np.ctypeslib.as_array(ptr, shape=shape)
    a.flags.writeable = False
    return np.asarray(_Owner(a, owner)).view(dtype)


def plot_spectrum(x, y, ax=None, label=None, xlabel="wavelength (nm)", ylabel=None, **kwargs):
    """Plots spectra with Matplotlib (an optional dependency: pip install matplotlib): y against wavelengths x in nm.

    y is one spectrum (N values) or several (K x N, one line each; label a list of K names). Returns the Axes."""
    try:
        import matplotlib
        if not getattr(matplotlib, "__version__", None):   # colour-science's stand-in when Matplotlib is missing
            raise ImportError
        import matplotlib.pyplot as plt
    except ImportError:
        raise ImportError("plot_spectrum needs Matplotlib (pip install matplotlib, or Debian's python3-matplotlib)") from None
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if y.ndim == 1:
        y = y[None, :]
    if y.shape[-1] != x.shape[0]:
        raise ValueError(f"{y.shape[-1]} values per spectrum for {x.shape[0]} wavelengths")
    labels = label if isinstance(label, (list, tuple)) else [label] * len(y)
    if ax is None:
        _, ax = plt.subplots()
    for row, name in zip(y, labels):
        ax.plot(x, row, label=name, **kwargs)
    ax.set_xlabel(xlabel)
    if ylabel:
        ax.set_ylabel(ylabel)
    if any(labels):
        ax.legend()
    return ax


class _Handle:
    """Owns one libspectral handle; spectral_free when the last Render or array view holding it goes."""

    def __init__(self, ptr):
        self.ptr = ptr

    def __del__(self):
        if self.ptr:
            _native.lib().spectral_free(self.ptr)
            self.ptr = None


class _Owner:
    """Gives a NumPy view a base object that holds the Render whose buffer it shows."""

    def __init__(self, array, owner):
        self.__array_interface__ = array.__array_interface__
        self._array, self._owner = array, owner


def _csv_centres(path):
    rows = [line.split(",") for line in path.read_text().splitlines()[1:] if line.strip()]
    return np.array([float(r[2]) for r in rows])


def _png(rgb):
    """8-bit RGB PNG (filter 0, deflate)."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))
