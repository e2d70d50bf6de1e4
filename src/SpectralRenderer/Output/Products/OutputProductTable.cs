using SpectralRenderer.Diagnostics;
using SpectralRenderer.Scenes;

namespace SpectralRenderer.Output.Products;

/// <summary>
/// The products a render can write, in the order their files are listed in render.json: the one registration point.
/// A new output format is a new <see cref="OutputProduct"/> file and one line here (or one <see cref="Register"/> call
/// for a product asked for by name, e.g. from a plug-in or a test: <see cref="Named"/>).
/// </summary>
public static class OutputProductTable
{
    static readonly List<OutputProduct> Products =
    [
        new PreviewProduct(),
        new BandsProduct(),
        new AovProduct(),
        new ExrProduct(),
        new EnviProduct(),
        new NpyProduct(),
        new WavelengthsProduct(),
        new LightsProduct(),
        new ColourProduct(),
        new PhotometryProduct(),
        new NoiseProduct(),
        new GridsProduct(),
    ];

    /// <summary>Every registered product in order.</summary>
    public static IReadOnlyList<OutputProduct> All { get { lock (Products) return Products.ToArray(); } }

    /// <summary>Adds a product after the others (its files listed after theirs); a name already taken is refused.</summary>
    public static void Register(OutputProduct product)
    {
        lock (Products)
        {
            if (Products.Any(p => p.Name == product.Name))
                throw new ArgumentException($"an output product '{product.Name}' is registered already", nameof(product));
            Products.Add(product);
        }
    }

    /// <summary>The products a render writes: those the scene's formats ask for, then the ones named beyond them.</summary>
    public static List<OutputProduct> For(OutputProducts asked, IReadOnlyList<OutputProduct>? named = null) =>
        [.. All.Where(p => p.Wanted(asked)), .. (named ?? []).Where(p => !p.Wanted(asked))];

    /// <summary>The registered products of these names (a request's products beyond the scene's formats).</summary>
    public static List<OutputProduct> Named(IEnumerable<string> names)
    {
        var all = All;
        var known = all.Select(p => p.Name).ToArray();
        return names.Select(n => all.FirstOrDefault(p => p.Name == n) ?? throw new InputException("--formats", $"no output product '{n}'",
            InputException.DidYouMean(n, known) ?? $"products: {string.Join(", ", known)}")).ToList();
    }

    /// <summary>The product that writes <paramref name="file"/> (relative, as render.json lists it), or null.</summary>
    public static OutputProduct? Owner(string file) => All.FirstOrDefault(p => p.Owns(file));
}
