using System.Text.Json;
using SpectralRenderer.Spectra;

namespace SpectralRenderer.Scenes.Loading;

// Fluorescence (issue 26): a material's re-radiation matrix, and the UV-cut filter of a light (ISO 13655 M2).
public sealed partial class SceneLoader
{
    /// <summary>The key of a material's re-radiation matrix: <c>"fluorescence": { "matrix": "file.csv" }</c> (or "file.exr").</summary>
    public const string FluorescenceKey = "fluorescence";
    /// <summary>The key of a light's filter: <c>"filter": "uv-cut"</c>.</summary>
    public const string FilterKey = "filter";

    /// <summary>The material models whose diffuse term a matrix can replace, and the key the matrix's diagonal stands for.</summary>
    static readonly Dictionary<string, string> FluorescentModels = new(StringComparer.Ordinal)
    {
        ["eq2"] = "diffuse",
        ["lambertian"] = "reflectance"
    };

    /// <summary>
    /// The material's re-radiation matrix, or null. Its diagonal is the diffuse reflectance (so a "diffuse" spectrum is not
    /// given as well) — unless "diffuse" is a texture (<paramref name="texelDiagonal"/>): then each texel is the reflective
    /// diagonal there and the matrix gives the shifted part alone, the same everywhere (<see cref="CheckTexelPhotons"/>).
    /// The matrix is read relative to the scene's folder, from CSV (<see cref="ReradiationCsvReader"/>: file:line errors,
    /// photon balance) or a bispectral OpenEXR (<see cref="Imaging.ReradiationExrReader"/>: file and channel named).
    /// </summary>
    ReradiationMatrix? ParseFluorescence(JsonElement e, string path, string model, out bool texelDiagonal)
    {
        texelDiagonal = false;
        if (!TryGet(e, FluorescenceKey, out var f)) return null;
        string where = $"{path}.{FluorescenceKey}";
        if (!FluorescentModels.TryGetValue(model, out var diagonalKey))
            throw Error(where, $"material type '{model}' has no diffuse term for a re-radiation matrix",
                $"fluorescence applies to the {string.Join(" and ", FluorescentModels.Keys)} models");
        if (TryGet(e, diagonalKey, out var given))
        {
            if (!IsTexture(given))
                throw Error($"{path}.{diagonalKey}",
                    $"\"{diagonalKey}\" and \"{FluorescenceKey}\" are both given: the matrix's diagonal is the reflectance",
                    $"remove \"{diagonalKey}\" (or put its values on the matrix's diagonal); a texture there is the diagonal per texel");
            texelDiagonal = true;   // a texture: the texels are the diagonal (checked against the shift after it is read)
        }
        Object(f, where);
        Keys(f, where, "matrix");
        var name = String(Required(f, "matrix", where), $"{where}.matrix");
        var full = Path.IsPathRooted(name) ? name : Path.Combine(_dir, name);
        if (!File.Exists(full))
            throw Error($"{where}.matrix", $"re-radiation matrix {Diagnostics.MessageText.Quote(name, 80)} not found",
                "a relative path starts at the scene's folder");
        if (full.EndsWith(".exr", StringComparison.OrdinalIgnoreCase)) return Imaging.ReradiationExrReader.Read(full);
        if (!full.EndsWith(".csv", StringComparison.OrdinalIgnoreCase))
            throw Error($"{where}.matrix", $"{Diagnostics.MessageText.Quote(name, 80)} is neither a .csv nor an .exr file",
                "give the matrix as CSV or as a bispectral OpenEXR (T.<λin>nm.<λout>nm channels; docs/scene-format.md, \"Fluorescence\")");
        return ReradiationCsvReader.Read(full);
    }

    /// <summary>
    /// Photon balance per texel for a texture that is a matrix's reflective diagonal: at each excitation wavelength λ_i of the
    /// matrix, the photons its shifted part re-emits, Σ_{o≠i} D[o, i]·λ_o (the same for every texel), may not exceed those the
    /// texel absorbs, (1 − T(λ_i))·λ_i, T the texel's linear interpolant (as <see cref="ReradiationMatrix.PhotonExcess"/>, with
    /// the texel for D[i, i]). Checked for every texel, not a bound over them; a filtered lookup (bilinear, mip levels) is a
    /// convex combination of texels, so it keeps the balance too. The first texel (row by row) that breaks it is bad input.
    /// </summary>
    void CheckTexelPhotons(Scenes.Textures.SpectralTexture tex, ReradiationMatrix matrix, string path)
    {
        int n = matrix.Count;
        var wl = matrix.Wavelengths.ToArray();
        var emitted = new double[n];
        for (int i = 0; i < n; i++)
            for (int o = 0; o < n; o++) if (o != i) emitted[i] += matrix[o, i] * wl[o];
        int samples = tex.Samples;
        tex.ForEachBlock((y0, rows, block) =>
        {
            for (int y = y0; y < y0 + rows; y++)
                for (int x = 0; x < tex.Width; x++)
                    CheckTexel(tex.Spectrum(block.AsSpan(((y - y0) * tex.Width + x) * samples, samples), x, y), x, y);
        });

        void CheckTexel(TabulatedSpectrum texel, int x, int y)
        {
            for (int i = 0; i < n; i++)
            {
                if (emitted[i] == 0) continue;   // no shift from this column: the texel's own checks apply (≥ 2, negative)
                double r = texel.Evaluate(wl[i]);
                double absorbed = (1 - r) * wl[i];
                if (emitted[i] <= absorbed + ReradiationCsvReader.PhotonTolerance * wl[i]) continue;
                var inv = System.Globalization.CultureInfo.InvariantCulture;
                throw Error($"{path}.texture", string.Create(inv,
                    $"texel ({x}, {y}) reflects {r:G4} at {wl[i]:0.###} nm: it absorbs {1 - r:G4} photons per photon, " +
                    $"the matrix re-emits {emitted[i] / wl[i]:G4}"),
                    "lower the texture there (≤ 1 − Σ_o≠i D[o,i]·λo/λi) or the matrix's shift");
            }
        }
    }

    /// <summary>
    /// A light's spectrum through its filter: <c>"uv-cut"</c> is ISO 13655:2017 measurement condition M2 (no substantial
    /// radiation below 400 nm), modelled as a filter edge whose transmittance rises linearly from 0 at 395 nm to 1 at 405 nm
    /// (half at 400 nm); the filtered table is the light's at its own knots and the edge's, so band means stay exact.
    /// </summary>
    TabulatedSpectrum FilteredLight(JsonElement e, string path, TabulatedSpectrum spectrum)
    {
        if (!TryGet(e, FilterKey, out var f)) return spectrum;
        var name = String(f, $"{path}.{FilterKey}").ToLowerInvariant();
        if (name != UvCut.Name)
            throw Error($"{path}.{FilterKey}", $"unknown light filter '{name}'",
                $"use \"{UvCut.Name}\" (ISO 13655 M2: no radiation below 400 nm)");
        return UvCut.Apply(spectrum);
    }
}
