"""spectralrenderer: the SpectralRenderer engine from Python, through libspectral (Native AOT, no .NET runtime).

    import spectralrenderer as sr
    r = sr.render("scenes/paper-3.1-colorchecker-d65.json", width=120, height=80)
    r.cube          # H x W x N float32, the values of `spectral render`'s spectral.npy (a view of the library's buffer)
    r.wavelengths   # N band centres, nm
    r.save("out/chart")   # the folder `spectral render -o out/chart` writes

Rendering runs in the library with the GIL released; Ctrl-C cancels it (KeyboardInterrupt). Bad input raises
SpectralError whose message is the one line the command line prints.
"""
import ctypes
import json
import os
import struct
import threading
import zlib
from pathlib import Path

import numpy as np

from . import _native

__all__ = ["render", "Render", "SpectralError", "abi_version"]
__version__ = "0.1.0"


class SpectralError(Exception):
    """A render that failed: .status is the CLI's exit code (2 bad input, 1 work failed or interrupted), str() its line."""

    def __init__(self, message, status):
        super().__init__(message)
        self.status = status


def abi_version():
    """The loaded libspectral's C ABI version."""
    return _native.lib().spectral_abi_version()


def _scene_text(scene):
    """(UTF-8 JSON, the name it is loaded under): a dict, JSON text, or a scene file's path."""
    if isinstance(scene, dict):
        return json.dumps(scene).encode(), "<dict>"
    if isinstance(scene, str) and scene.lstrip().startswith("{"):
        return scene.encode(), "<text>"
    path = os.fspath(scene)
    if not Path(path).is_file():   # the CLI's words (InputFile)
        raise SpectralError(f"spectral render: {path}: scene file not found (hint: check the path)", 2)
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


def render(scene, width=None, height=None, bands=None, wave=None, spp=None, integrator=None, threads=None,
           rgb=None, integration=None, formats=None, progress=None):
    """Renders a scene (dict, JSON text, or path) as `spectral render` does, in memory. Options are the command
    line's overrides; bands is a count or "start:end:count". progress(done, total) is called after each tile.
    Raises SpectralError (the CLI's one-line message) on bad input or failure; KeyboardInterrupt cancels."""
    lib = _native.lib()
    text, name = _scene_text(scene)
    opts = {k: v for k, v in dict(width=width, height=height, bands=None if bands is None else str(bands), wave=wave,
                                  spp=spp, integrator=integrator, threads=threads, rgb=rgb, integration=integration,
                                  formats=formats).items() if v is not None}
    cancel = ctypes.c_int(0)
    callback = _native.PROGRESS(lambda _user, done, total: progress(done, total)) if progress else _native.PROGRESS()
    out = {}

    def run():  # the foreign call releases the GIL: the main thread stays free to see Ctrl-C
        out["handle"] = lib.spectral_render(text, name.encode(), json.dumps(opts).encode(), ctypes.byref(cancel),
                                            callback, None)

    worker = threading.Thread(target=run, name="spectral_render", daemon=True)
    worker.start()
    try:
        while worker.is_alive():
            worker.join(0.05)
    except KeyboardInterrupt:
        cancel.value = 1   # polled by the render after each tile and every 20 ms
        worker.join()
        handle = out.get("handle")
        if handle:
            lib.spectral_free(handle)
        raise
    handle = out["handle"]
    if lib.spectral_status(handle) != 0:
        raise _error(lib, handle)
    return Render(_handle=handle)


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
    def manifest(self):
        """render.json as a dict (in memory: its "files" empty and "run" absent until saved)."""
        if "manifest" not in self._cache:
            if self._handle is None:
                self._cache["manifest"] = json.loads((self._folder / "render.json").read_text())
            else:
                self._cache["manifest"] = json.loads(_native.lib().spectral_manifest(self._handle).decode())
        return self._cache["manifest"]

    def save(self, folder):
        """Writes the folder `spectral render -o FOLDER` writes (same bytes; render.json's run fields aside)."""
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
