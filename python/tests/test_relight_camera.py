"""relight, camera and recover (ABI 1.1) against `spectral relight|camera|recover` on the folders the CLI writes: the same
engine calls on the same values, so the same bits. Tiny renders (48 x 32, the flat chart: no mesh needed)."""
import json

import numpy as np
import pytest

from conftest import read_png

CHART = "scenes/paper-3.1-colorchecker-d65.json"
SIZE = dict(width=48, height=32)
ARGS = ["--width", 48, "--height", 32, "--quiet"]


@pytest.fixture(scope="module")
def chart(sr, repo):
    """The chart rendered in memory with the per-light outputs (relight) and the analysis images (camera, recover)."""
    return sr.render(repo / CHART, formats="png,npy,aov,lights", **SIZE)


@pytest.fixture(scope="module")
def cli_chart(cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "chart"
    p = cli("render", CHART, "-o", out, "--formats", "png,npy,aov,lights", *ARGS)
    assert p.returncode == 0, p.stderr
    return out


def test_the_abi_minor_version_adds_relight_camera_and_recover_then_noise_masks_and_the_lens_then_every_option(sr):
    from spectralrenderer import _native
    assert sr.abi_version() == 1 and _native.lib().minor >= _native.ABI_MINOR == 3


def test_save_writes_lights_as_the_cli_does(chart, cli_chart, tmp_path):
    saved = chart.save(tmp_path / "py")
    for name in ("lights/lights.json", "lights/factors.npy", "lights/pixels.npy", "lights/centre.npy", "lights/ids.npy"):
        assert (saved / name).read_bytes() == (cli_chart / name).read_bytes(), name


def test_relight_equals_the_cli_relight_bit_for_bit(sr, cli, chart, cli_chart, tmp_path):
    relit_dir = tmp_path / "relit"
    p = cli("relight", cli_chart, "--light", "D65=blackbody:3000", "--intensity", "D65=0.5", "--white", "A", "-o", relit_dir,
            "--quiet")
    assert p.returncode == 0, p.stderr
    r = sr.relight(chart, lights={"D65": {"spectrum": "blackbody:3000", "intensity": 0.5}}, white="A")
    assert r.cube.tobytes() == np.load(relit_dir / "spectral.npy").tobytes()
    assert r.xyz.tobytes() == np.load(relit_dir / "xyz.npy").tobytes()
    assert np.array_equal(r.srgb, read_png(relit_dir / "preview.png"))
    # Its folder is the CLI's (render.json aside: it records the relight's source and time), lights/ included.
    saved = r.save(tmp_path / "py")
    files = sorted(f.relative_to(relit_dir) for f in relit_dir.rglob("*") if f.is_file() and f.name != "render.json")
    assert files == sorted(f.relative_to(saved) for f in saved.rglob("*") if f.is_file() and f.name != "render.json")
    for f in files:
        assert (saved / f).read_bytes() == (relit_dir / f).read_bytes(), f
    assert json.loads((saved / "render.json").read_text())["run"]["relit"]["changes"][0]["spectrum"] == "blackbody:3000"
    # Relit again (from the same transfer) back to the scene's own light: the original render's bits.
    back = sr.relight(r, lights={"D65": {"spectrum": "D65", "intensity": 1}}, white="D65")
    assert back.cube.tobytes() == chart.cube.tobytes()


def test_a_spectrum_as_arrays_equals_the_same_table_from_a_csv_file(sr, cli, chart, cli_chart, tmp_path):
    # A warm LED-like table (nm, value): NumPy arrays in Python, a CSV column for the command line.
    wl = np.arange(380.0, 781.0, 5.0)
    values = 50 + 40 * np.exp(-0.5 * ((wl - 600) / 40) ** 2)
    csv = tmp_path / "warm.csv"
    csv.write_text("wavelength_nm,warm\n" + "".join(f"{a!r},{b!r}\n" for a, b in zip(wl, values)))
    relit_dir = tmp_path / "relit"
    p = cli("relight", cli_chart, "--light", f"D65={csv}:warm", "-o", relit_dir, "--quiet")
    assert p.returncode == 0, p.stderr
    for given in ((wl, values), np.stack([wl, values], axis=1)):
        r = sr.relight(chart, lights={"D65": given})
        assert r.cube.tobytes() == np.load(relit_dir / "spectral.npy").tobytes()


def _table(repo, name, column):
    rows = [l.split(",") for l in (repo / "data" / name).read_text().splitlines()]
    c = rows[0].index(column)
    return np.array([float(r[0]) for r in rows[1:] if r[0]]), np.array([float(r[c]) for r in rows[1:] if r[0]])


def test_arrays_are_taken_as_given_warn_when_dark_and_scale_luminous_puts_them_on_the_lights_scale(sr, repo, chart):
    """Issue 42: the README's blue LED shape (peak 1) in place of D65 (100 at 560 nm) relights as given — a hundred times
    darker, with a RuntimeWarning and its hint — and with scale="luminous" on the built-in lights' scale: the two relit
    pictures differ by ∫V·G / ∫V·D65, both integrals computed here (0.01 nm midpoint sums on the data tables)."""
    wl = np.arange(380.0, 781.0, 5.0)
    values = np.exp(-0.5 * ((wl - 450.0) / 12.0) ** 2)
    with pytest.warns(RuntimeWarning, match='scale="luminous"'):
        dark = sr.relight(chart, lights={"D65": (wl, values)})
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        lit = sr.relight(chart, lights={"D65": sr.spectrum(wl, values, scale="luminous")})
    v_wl, v = _table(repo, "cie1931-2deg-cmf.csv", "ybar")
    d_wl, d65 = _table(repo, "illuminants.csv", "D65")

    def luminous(s_wl, s):
        lo, hi = max(s_wl[0], v_wl[0]), min(s_wl[-1], v_wl[-1])
        x = lo + (np.arange(int(round((hi - lo) / 0.01))) + 0.5) * 0.01
        return float(np.sum(np.interp(x, v_wl, v) * np.interp(x, s_wl, s)) * 0.01)
    expected = luminous(wl, values) / luminous(d_wl, d65)
    ratio = float(dark.xyz[..., 1].sum() / lit.xyz[..., 1].sum())
    assert expected < 0.05 and abs(ratio / expected - 1) < 1e-3, (ratio, expected)


def test_relight_errors_are_the_cli_lines(sr, cli, chart, cli_chart, tmp_path):
    p = cli("relight", cli_chart, "--light", "D66=A", "-o", tmp_path / "x")
    assert p.returncode == 2
    with pytest.raises(sr.SpectralError) as e:
        sr.relight(chart, lights={"D66": "A"})
    assert (e.value.status, str(e.value)) == (2, p.stderr.strip())
    p = cli("relight", cli_chart, "--light", "D65=blackbody:nope", "-o", tmp_path / "y")
    with pytest.raises(sr.SpectralError) as e:
        sr.relight(chart, lights={"D65": "blackbody:nope"})
    assert (e.value.status, str(e.value)) == (p.returncode, p.stderr.strip())


def test_camera_equals_the_cli_camera_bit_for_bit_and_recover_its_recovery(sr, cli, chart, cli_chart):
    cam = cli_chart / "camera-nikon"
    p = cli("camera", cli_chart, "--sensor", "nikon-d5100", "--seed", 7, "-o", cam)
    assert p.returncode == 0, p.stderr
    cap = sr.camera(chart, sensor="nikon-d5100", seed=7)
    assert cap.raw.dtype == np.float32 and cap.raw.shape == (32, 48)
    assert cap.raw.tobytes() == np.load(cam / "raw.npy").tobytes()
    assert np.array_equal(cap.srgb, read_png(cam / "processed.png"))
    cli_json = json.loads((cam / "camera.json").read_text())
    # The exact route, with the same components (the CLI names the folder's lights/ as their source, the package memory).
    route, cli_route = cap.manifest["simulation"]["signal_route"], cli_json["simulation"]["signal_route"]
    assert route.startswith("exact") and route.split(" components from ")[0] == cli_route.split(" components from ")[0]
    assert [q["delta_e00"] for q in cap.patches] == [q["delta_e00"] for q in cli_json["patches"]]
    # recover reads the camera folder back (CameraCapture.Open); the package the capture in memory, the same way.
    p = cli("recover", cam, "--method", "wiener,pinv", "--range", "400:700")
    assert p.returncode == 0, p.stderr
    rec = sr.recover(cap, method=["wiener", "pinv"], range=(400, 700))
    assert rec.methods == ["wiener", "pinv"] and rec.shape == (32, 48, 20)
    for m in rec.methods:
        assert rec[m].tobytes() == np.load(cam / f"recovered-{m}.npy").tobytes(), m
    assert rec.metrics_csv == (cam / "recovery-metrics.csv").read_text()
    assert {row["region"] for row in rec.metrics} >= {"all", "colorchecker"}


def test_the_lens_options_equal_the_cli_camera_off_axis_and_psf(sr, cli, chart, cli_chart):
    # Both away from the preset's lens (cos4th, diffraction): the raw frame equals the CLI's only if each is applied.
    off_axis, psf = "none", "none"
    cam = cli_chart / "camera-flat"
    p = cli("camera", cli_chart, "--sensor", "nikon-d5100", "--noise", "off", "--off-axis", off_axis, "--psf", psf, "-o", cam)
    assert p.returncode == 0, p.stderr
    cap = sr.camera(chart, sensor="nikon-d5100", noise=False, off_axis=off_axis, psf=psf)
    assert cap.raw.tobytes() == np.load(cam / "raw.npy").tobytes()
    optics = json.loads((cam / "camera.json").read_text())["sensor"]["optics"]
    assert (optics["off_axis"], optics["psf"]) == (off_axis, psf) == (cap.manifest["sensor"]["optics"]["off_axis"],
                                                                     cap.manifest["sensor"]["optics"]["psf"])
    # The preset's lens (cos4th and diffraction) gives another picture: the option took effect.
    assert not np.array_equal(cap.raw, sr.camera(chart, sensor="nikon-d5100", noise=False).raw)
    with pytest.raises(sr.SpectralError, match="off-axis model"):
        sr.camera(chart, sensor="nikon-d5100", off_axis="cos3rd")


def test_camera_and_recover_errors_raise_the_one_line(sr, chart):
    with pytest.raises(sr.SpectralError) as e:
        sr.camera(chart, sensor="nikon-d5101")
    assert e.value.status == 2 and "\n" not in str(e.value) and str(e.value).startswith("spectral camera: ")
    cap = sr.camera(chart, sensor="cie-xyz", noise=False, signals="bands")
    with pytest.raises(sr.SpectralError) as e:
        sr.recover(cap, method="nope")
    assert e.value.status == 2 and str(e.value).startswith("spectral recover: ") and "hint" in str(e.value)
