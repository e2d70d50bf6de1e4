"""Every option of `spectral render` reaches the library from Python's keywords (one options table, issue 38), and a path
render relights and saves its lights/ as the command line does, bit for bit."""
import json
import re

import numpy as np
import pytest

from conftest import read_png

CHART = "scenes/paper-3.1-colorchecker-d65.json"
# The command's own options, which shape no render: where its files go (Python: Render.save) and its stderr summary.
COMMAND_ONLY = {"out", "quiet", "help"}


def _cli_options(cli):
    """The options `spectral render --help` defines (a line of its own starting with the option), by name."""
    p = cli("render", "--help")
    assert p.returncode == 0, p.stderr
    names = set(re.findall(r"^\s+(?:-\w, )?--([a-z][a-z-]*)", p.stdout, flags=re.M))
    # Every option the usage line names is defined below it (the usage is read independently of the option lines).
    usage = p.stdout.split("\n\n")[0]
    assert set(re.findall(r"\[--([a-z][a-z-]*)", usage)) <= names
    return names


def test_render_takes_every_option_of_spectral_render_with_the_cli_message(sr, cli, repo, tmp_path):
    """For each option the command's help lists, a value no option accepts: the package's error is the command line's line
    and exit code — so the keyword reached the same check (an option Python did not take would say "unknown option")."""
    names = _cli_options(cli) - COMMAND_ONLY
    assert len(names) >= 17 and {"target-error", "crop", "shard", "models", "exr-compression"} <= names
    scene = str(repo / CHART)
    for name in sorted(names):
        p = cli("render", scene, "-o", tmp_path / name, f"--{name}", "bogus!", "--quiet")
        with pytest.raises(sr.SpectralError) as e:
            sr.render(scene, **{name.replace("-", "_"): "bogus!"})
        assert p.returncode == 2, (name, p.stderr)
        assert (e.value.status, str(e.value)) == (2, p.stderr.strip()), name
        assert "unknown option" not in str(e.value), name


def test_an_unknown_keyword_is_one_line_with_a_hint(sr, repo):
    with pytest.raises(sr.SpectralError) as e:
        sr.render(repo / CHART, widht=8)
    assert e.value.status == 2 and "\n" not in str(e.value)
    assert str(e.value) == "spectral render: options.widht: unknown option (hint: did you mean 'width'?)"


def test_crop_adaptive_sampling_models_and_compression_equal_the_cli_bit_for_bit(sr, cli, repo, tmp_path):
    scene = str(repo / CHART)
    out = tmp_path / "cli"
    p = cli("render", scene, "-o", out, "--width", 96, "--height", 64, "--spp", 8, "--target-error", 0.05, "--crop",
            "16,8,80,56", "--formats", "npy,exr", "--exr-compression", "none", "--models", tmp_path, "--quiet")
    assert p.returncode == 0, p.stderr
    r = sr.render(scene, width=96, height=64, spp=8, target_error=0.05, crop=(16, 8, 80, 56), formats=["npy", "exr"],
                  exr_compression="none", models=[tmp_path])
    assert r.cube.shape == (48, 64, 20)
    assert r.cube.tobytes() == np.load(out / "spectral.npy").tobytes()
    saved = r.save(tmp_path / "py")
    assert (saved / "spectral.exr").read_bytes() == (out / "spectral.exr").read_bytes()
    run = json.loads((saved / "render.json").read_text())
    assert run["crop"] == json.loads((out / "render.json").read_text())["crop"]


def test_a_shard_equals_the_cli_shard(sr, cli, repo, tmp_path):
    scene = str(repo / CHART)
    out = tmp_path / "cli"
    p = cli("render", scene, "-o", out, "--width", 64, "--height", 80, "--shard", "1/2", "--formats", "npy", "--quiet")
    assert p.returncode == 0, p.stderr
    r = sr.render(scene, width=64, height=80, shard="1/2", formats="npy")
    assert r.cube.shape == (48, 64, 20)   # tile rows 32…79 of 80 (strips of whole 32-row tiles)
    assert r.cube.tobytes() == np.load(out / "spectral.npy").tobytes()


# A small path scene with two scene lights (a point and a spot), an emitting quad and a sky (PathRelightTests' kind).
PATH_SCENE = {
    "radiometry": "physical", "bands": "400:700:6", "integrator": "path",
    "camera": {"position": [0, 1, 3.2], "look_at": [0, 1, 0], "fov": 50, "width": 16, "height": 12, "spp": 2},
    "background": {"spectrum": "D65", "luminance": 20},
    "materials": {
        "white": {"type": "lambertian", "reflectance": 0.75},
        "red": {"type": "lambertian", "reflectance": "colorchecker:red"},
        "lamp": {"type": "lambertian", "reflectance": 0, "emission": {"spectrum": "D65", "radiance": 0.05}},
        "gloss": {"diffuse": 0.05, "specular": 0.2, "shininess": 60, "mirror": 0.7}},
    "lights": [
        {"type": "point", "name": "bulb", "position": [0.5, 1.6, 0.5], "spectrum": "A", "intensity": 0.2},
        {"type": "spot", "name": "spot", "position": [-0.5, 1.8, 0.5], "look_at": [0, 0, 0], "spectrum": "D65",
         "intensity": 0.3}],
    "objects": [
        {"type": "quad", "name": "floor", "center": [0, 0, 0], "size": [2, 2], "normal": [0, 1, 0], "up": [0, 0, -1],
         "material": "white"},
        {"type": "quad", "name": "back", "center": [0, 1, -1], "size": [2, 2], "normal": [0, 0, 1], "material": "white"},
        {"type": "quad", "name": "left", "center": [-1, 1, 0], "size": [2, 2], "normal": [1, 0, 0], "material": "red"},
        {"type": "quad", "name": "lamp", "center": [0, 1.99, 0], "size": [0.5, 0.5], "normal": [0, -1, 0], "up": [0, 0, -1],
         "material": "lamp"},
        {"type": "sphere", "name": "ball", "center": [0.4, 0.3, -0.3], "radius": 0.3, "material": "gloss"}]}


@pytest.fixture(scope="module")
def path_pair(sr, cli, tmp_path_factory):
    """The path scene rendered by the command line (with lights/) and by the package (in memory), from one file."""
    tmp = tmp_path_factory.mktemp("path")
    scene = tmp / "path.json"
    scene.write_text(json.dumps(PATH_SCENE))
    out = tmp / "cli"
    p = cli("render", scene, "-o", out, "--formats", "png,npy,aov,lights", "--quiet")
    assert p.returncode == 0, p.stderr
    return sr.render(scene, formats="png,npy,aov,lights"), out, tmp


def test_save_of_a_path_render_writes_its_lights_as_the_cli_does(path_pair):
    r, out, tmp = path_pair
    assert r.cube.tobytes() == np.load(out / "spectral.npy").tobytes()
    saved = r.save(tmp / "py")
    lights = sorted(f.relative_to(out) for f in (out / "lights").rglob("*") if f.is_file())
    assert "lights/transfer.npy" in {str(f) for f in lights}
    assert lights == sorted(f.relative_to(saved) for f in (saved / "lights").rglob("*") if f.is_file())
    for f in lights:
        assert (saved / f).read_bytes() == (out / f).read_bytes(), f


def test_relight_of_a_path_render_equals_spectral_relight_bit_for_bit(sr, cli, path_pair):
    r, out, tmp = path_pair
    relit_dir = tmp / "relit"
    p = cli("relight", out, "--light", "bulb=D65", "--intensity", "bulb=0.5", "--intensity", "spot=0", "--white", "A",
            "-o", relit_dir, "--quiet")
    assert p.returncode == 0, p.stderr
    relit = sr.relight(r, lights={"bulb": {"spectrum": "D65", "intensity": 0.5}, "spot": {"intensity": 0}}, white="A")
    expected = np.load(relit_dir / "spectral.npy")
    assert relit.cube.tobytes() == expected.tobytes()
    assert relit.xyz.tobytes() == np.load(relit_dir / "xyz.npy").tobytes()
    assert np.array_equal(relit.srgb, read_png(relit_dir / "preview.png"))
    assert not np.array_equal(expected, r.cube)   # the lights changed the picture
    # Its folder is the command's (render.json aside: it records the relight's source and time), lights/ included.
    saved = relit.save(tmp / "relit-py")
    files = sorted(f.relative_to(relit_dir) for f in relit_dir.rglob("*") if f.is_file() and f.name != "render.json")
    assert files == sorted(f.relative_to(saved) for f in saved.rglob("*") if f.is_file() and f.name != "render.json")
    for f in files:
        assert (saved / f).read_bytes() == (relit_dir / f).read_bytes(), f
    method = json.loads((saved / "render.json").read_text())["run"]["relit"]["method"]
    assert method.startswith("per-light transfer of a path render: on the fine grid")
    # Relit again, from the same transfer, back to the scene's own lights: `spectral relight` of the relit folder, bit for
    # bit, and the traced render within issue 23's bar for a path relight (1e-5 relative: the sums are regrouped).
    back_dir = tmp / "back"
    p = cli("relight", relit_dir, "--light", "bulb=A", "--intensity", "bulb=0.2", "--intensity", "spot=0.3", "--white",
            "D65", "-o", back_dir, "--quiet")
    assert p.returncode == 0, p.stderr
    back = sr.relight(relit, lights={"bulb": {"spectrum": "A", "intensity": 0.2}, "spot": {"intensity": 0.3}}, white="D65")
    assert back.cube.tobytes() == np.load(back_dir / "spectral.npy").tobytes()
    assert np.allclose(back.cube, r.cube, rtol=1e-5, atol=0)
