using System.Text;
using SpectralRenderer.Rendering;
using SpectralRenderer.Rendering.Registry;
using SpectralRenderer.Scenes;
using SpectralRenderer.Scenes.Loading;

namespace SpectralRenderer.Tests.Rendering;

static class SceneText
{
    public static Scene Load(string json, SceneOverrides? o = null) => SceneLoader.Parse(Encoding.UTF8.GetBytes(json), "test.json", o);

    public static RenderResult Render(string json, int threads = 0) => Integrators.Render(Load(json), threads);
}
