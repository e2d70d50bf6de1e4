"""Notebook use: a Render and a Capture show as their sRGB pictures; plot_spectrum draws with Matplotlib when installed."""
import numpy as np
import pytest

from conftest import read_png

CHART = "scenes/paper-3.1-colorchecker-d65.json"


def test_repr_png_is_the_srgb_preview(sr, repo):
    r = sr.render(repo / CHART, width=24, height=16)
    assert np.array_equal(read_png(r._repr_png_()), r.srgb)
    cap = sr.camera(r, sensor="cie-xyz", noise=False, signals="bands")
    assert np.array_equal(read_png(cap._repr_png_()), cap.srgb)


def test_plot_spectrum_draws_each_spectrum_or_says_matplotlib_is_missing(sr):
    x = np.linspace(400, 700, 31)
    y = np.stack([np.sin(x / 50), np.cos(x / 50)])
    try:
        import matplotlib
        matplotlib.use("Agg")
    except ImportError:
        with pytest.raises(ImportError, match="pip install matplotlib"):
            sr.plot_spectrum(x, y)
        pytest.skip("Matplotlib is not installed: plot_spectrum raised its hint (checked); the drawing is not")
    ax = sr.plot_spectrum(x, y, label=["a", "b"], ylabel="value")
    lines = ax.get_lines()
    assert len(lines) == 2 and np.array_equal(lines[1].get_xdata(), x) and np.array_equal(lines[1].get_ydata(), y[1])
    assert ax.get_xlabel() == "wavelength (nm)"


def test_spectra_as_arrays_in_a_scene_dict(sr, repo):
    """A scene dict may hold NumPy arrays: the light's D65 table given as (nm, value) rows renders as the named D65 does
    wherever the table's linear interpolant is D65's own (data/illuminants.csv's rows: the same knots)."""
    import json
    import re
    text = re.sub(r"//[^\n]*", "", (repo / CHART).read_text())
    scene = json.loads(re.sub(r",(\s*[}\]])", r"\1", text))
    rows = [line.split(",") for line in (repo / "data/illuminants.csv").read_text().splitlines()[1:] if line.strip()]
    d65 = np.array([[float(r[0]), float(r[2])] for r in rows])   # wavelength_nm, D65
    scene["lights"][0]["spectrum"] = d65
    scene["white"] = sr.spectrum(d65[:, 0], d65[:, 1])
    named = sr.render(repo / CHART, width=24, height=16)
    arrays = sr.render(scene, width=24, height=16)
    assert arrays.cube.tobytes() == named.cube.tobytes()
