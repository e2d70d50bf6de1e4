namespace SpectralRenderer.Scenes.Textures;

/// <summary>A texture on a material's lobe, placed on the surface's (u, v) by <paramref name="Transform"/>.</summary>
public sealed record TextureBinding(SpectralTexture Texture, UvTransform Transform);
