namespace SpectralRenderer.Tests.Rendering;

/// <summary>
/// Bounded work: Hall &amp; Greenberg's adaptive tree depth and the per-camera-ray budget, checked on a camera inside a
/// mirror sphere lit only by a uniform ambient a = 1: every surface point adds a·m_amb, and the n-th reflection
/// enters the pixel with weight k_r^n, so the pixel is m_amb · Σ_{n=0}^{N} k_r^n for the N reflections traced.
/// </summary>
public class BoundedWorkTests
{
    static string Inside(string extra) => $$"""
    {
      "bands": "400:700:3",
      "camera": { "position": [0, 0, 0], "look_at": [0, 0, -1], "width": 4, "height": 4 },
      "materials": { "m": { "diffuse": 0, "ambient": 0.2, "mirror": 0.5 } },
      "objects": [ { "type": "sphere", "radius": 10, "material": "m" } ],
      "ambient": 1,
      "max_depth": 64{{extra}}
    }
    """;

    static double Geometric(int reflections) => 0.2 * Enumerable.Range(0, reflections + 1).Sum(n => Math.Pow(0.5, n));

    [Fact]
    public void A_branch_ends_when_its_weight_falls_below_the_threshold()
    {
        // k_r^n ≥ 0.1 for n = 1, 2, 3 (0.5, 0.25, 0.125); the 4th reflection (0.0625) is not traced.
        var r = SceneText.Render(Inside(", \"min_ray_weight\": 0.1"));
        int pixels = 16;
        Assert.Equal(3L * pixels, r.Rays.Secondary);
        Assert.Equal(pixels, r.Rays.PrunedRays);
        Assert.Equal(0, r.Rays.OverBudgetRays);
        foreach (var v in r.Image.Data) Assert.Equal(Geometric(3), v, 1e-6);
    }

    [Fact]
    public void A_threshold_of_a_thousandth_keeps_nine_reflections()
    {
        // 0.5^9 = 0.00195 ≥ 1e-3 > 0.5^10: nine reflections.
        var r = SceneText.Render(Inside(", \"min_ray_weight\": 0.001"));
        Assert.Equal(9L * 16, r.Rays.Secondary);
        foreach (var v in r.Image.Data) Assert.Equal(Geometric(9), v, 1e-6);
    }

    [Fact]
    public void By_default_no_branch_is_pruned_and_max_depth_ends_the_tree()
    {
        var r = SceneText.Render(Inside(""));
        Assert.Equal(64L * 16, r.Rays.Secondary);
        Assert.Equal(0, r.Rays.PrunedRays);
        foreach (var v in r.Image.Data) Assert.Equal(Geometric(64), v, 1e-6);
    }

    [Fact]
    public void A_camera_ray_stops_at_its_ray_budget_and_is_counted()
    {
        // No weight threshold: only the budget of 10 rays (the camera ray and 9 reflections) ends the tree.
        var r = SceneText.Render(Inside(", \"min_ray_weight\": 0, \"ray_budget\": 10"));
        Assert.Equal(9L * 16, r.Rays.Secondary);
        Assert.Equal(16, r.Rays.OverBudgetRays);
        foreach (var v in r.Image.Data) Assert.Equal(Geometric(9), v, 1e-6);
    }

    [Fact]
    public void Without_threshold_or_budget_pressure_max_depth_ends_the_tree()
    {
        var r = SceneText.Render(Inside(", \"min_ray_weight\": 0, \"max_depth\": 4").Replace("\"max_depth\": 64", "\"ray_budget\": 1000"));
        Assert.Equal(4L * 16, r.Rays.Secondary);
        Assert.Equal(0, r.Rays.OverBudgetRays);
        foreach (var v in r.Image.Data) Assert.Equal(Geometric(4), v, 1e-6);
    }
}
