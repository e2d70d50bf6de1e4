namespace SpectralRenderer.Spectra;

/// <summary>What a tabulated spectrum is taken to be outside its table.</summary>
public enum Extrapolation
{
    /// <summary>Asking for a value outside the table is an error (the default).</summary>
    Error,
    /// <summary>The first/last tabulated value continues (CIE 015 recommends this for short tables).</summary>
    Clamp,
    /// <summary>Zero outside the table.</summary>
    Zero,
}
