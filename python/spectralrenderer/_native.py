"""ctypes bindings of libspectral's C ABI (src/SpectralRenderer.Native/NativeExports.cs and NativeCamera.cs, ABI 1.3).

The ABI's major version (spectral_abi_version) changes when a function's signature or meaning does: this package refuses
another major. Functions added beside them raise the minor (spectral_abi_minor, absent in 1.0): relight, camera and
recover need minor 1; noise, the masks and the camera's off_axis and psf minor 2; render's options beyond the first eleven
(the options table) and a path render's relight and lights minor 3; each says so when the library is older."""
import ctypes
import os
from pathlib import Path

ABI_VERSION = 1
ABI_MINOR = 3   # the minor this package's newest calls need (every render option; a path render's relight and lights)
PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int, ctypes.c_int)

_lib = None


def _locate():
    """libspectral.so: $SPECTRAL_LIBRARY, else the copy bundled in the package (the wheel's)."""
    env = os.environ.get("SPECTRAL_LIBRARY")
    if env:
        return Path(env)
    return Path(__file__).with_name("libspectral.so")


def lib():
    """The loaded library (once per process); its data/ tables are found beside it (SPECTRAL_DATA)."""
    global _lib
    if _lib is not None:
        return _lib
    path = _locate()
    if not path.exists():
        raise ImportError(f"libspectral not found at {path} (build the wheel with scripts/build-wheel.sh, "
                          "or set SPECTRAL_LIBRARY to a published libspectral.so)")
    data = path.parent / "data"
    # The engine looks for its CIE tables in $SPECTRAL_DATA first: set before the library's first read of the environment.
    if "SPECTRAL_DATA" not in os.environ and (data / "cie1931-2deg-cmf.csv").exists():
        os.environ["SPECTRAL_DATA"] = str(data)
    l = ctypes.CDLL(str(path))
    l.spectral_abi_version.restype = ctypes.c_int
    l.spectral_render.restype = ctypes.c_void_p
    l.spectral_render.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.POINTER(ctypes.c_int),
                                  PROGRESS, ctypes.c_void_p]
    l.spectral_status.restype = ctypes.c_int
    l.spectral_status.argtypes = [ctypes.c_void_p]
    l.spectral_message.restype = ctypes.c_char_p
    l.spectral_message.argtypes = [ctypes.c_void_p]
    l.spectral_shape.restype = None
    l.spectral_shape.argtypes = [ctypes.c_void_p] + [ctypes.POINTER(ctypes.c_int)] * 3
    for name, t in [("spectral_cube", ctypes.c_float), ("spectral_wavelengths", ctypes.c_double),
                    ("spectral_band_edges", ctypes.c_double), ("spectral_xyz", ctypes.c_float),
                    ("spectral_rgb8", ctypes.c_uint8), ("spectral_ids", ctypes.c_int32)]:
        f = getattr(l, name)
        f.restype = ctypes.POINTER(t)
        f.argtypes = [ctypes.c_void_p]
    l.spectral_manifest.restype = ctypes.c_char_p
    l.spectral_manifest.argtypes = [ctypes.c_void_p]
    l.spectral_save.restype = ctypes.c_int
    l.spectral_save.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)]
    l.spectral_free.restype = None
    l.spectral_free.argtypes = [ctypes.c_void_p]
    try:
        l.spectral_abi_minor.restype = ctypes.c_int
        l.minor = l.spectral_abi_minor()
    except AttributeError:   # a 1.0 library: render and save only
        l.minor = 0
    if l.minor >= 1:
        l.spectral_relight.restype = ctypes.c_void_p
        l.spectral_relight.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(ctypes.c_int)]
        for name in ("spectral_camera", "spectral_recover"):
            getattr(l, name).restype = ctypes.c_void_p
            getattr(l, name).argtypes = [ctypes.c_void_p, ctypes.c_char_p]
        l.spectral_capture_shape.restype = None
        l.spectral_capture_shape.argtypes = [ctypes.c_void_p] + [ctypes.POINTER(ctypes.c_int)] * 4
        for name, t in [("spectral_capture_raw", ctypes.c_float), ("spectral_capture_rgb8", ctypes.c_uint8),
                        ("spectral_capture_rates", ctypes.c_float)]:
            getattr(l, name).restype = ctypes.POINTER(t)
            getattr(l, name).argtypes = [ctypes.c_void_p]
        for name in ("spectral_capture_manifest", "spectral_recovery_manifest"):
            getattr(l, name).restype = ctypes.c_char_p
            getattr(l, name).argtypes = [ctypes.c_void_p]
        l.spectral_recovery_count.restype = ctypes.c_int
        l.spectral_recovery_count.argtypes = [ctypes.c_void_p]
        l.spectral_recovery_reflectance.restype = ctypes.POINTER(ctypes.c_float)
        l.spectral_recovery_reflectance.argtypes = [ctypes.c_void_p, ctypes.c_int]
    if l.minor >= 2:
        l.spectral_noise.restype = ctypes.POINTER(ctypes.c_float)
        l.spectral_noise.argtypes = [ctypes.c_void_p]
        l.spectral_mask_count.restype = ctypes.c_int
        l.spectral_mask_count.argtypes = [ctypes.c_void_p]
        l.spectral_mask_name.restype = ctypes.c_char_p
        l.spectral_mask_name.argtypes = [ctypes.c_void_p, ctypes.c_int]
        l.spectral_mask.restype = ctypes.POINTER(ctypes.c_uint8)
        l.spectral_mask.argtypes = [ctypes.c_void_p, ctypes.c_int]
    version = l.spectral_abi_version()
    if version != ABI_VERSION:
        raise ImportError(f"{path} has ABI version {version}; this package speaks version {ABI_VERSION}")
    _lib = l
    return l


def need(minor, what):
    """The loaded library, checked to have ABI minor ≥ minor (what: the call that needs it, for the message)."""
    l = lib()
    if l.minor < minor:
        raise ImportError(f"{what} needs libspectral ABI {ABI_VERSION}.{minor}; the loaded library is {ABI_VERSION}.{l.minor} "
                          "(rebuild it: scripts/build-wheel.sh)")
    return l
