using System.Numerics;
using SpectralRenderer.Geometry;

namespace SpectralRenderer.Rendering;

// Texture coordinates at a hit: a mesh's own (OBJ vt, PLY u v) interpolated with the hit's barycentrics, or the
// generated ones of the analytic shapes (TextureCoordinates); a mesh without them gets the barycentrics themselves.
public sealed partial class SceneGeometry
{
    readonly AnalyticShape[] _planeShapes;

    /// <summary>The (u, v) of <paramref name="hit"/> and the mapping's density there (uv units per world length, for the mip
    /// level).</summary>
    public Vector2 TexCoord(in SurfaceHit hit, out float uvPerLength)
    {
        switch (hit.Kind)
        {
            case 1:
                {
                    int k = hit.Primitive;
                    var m = _meshes[_triangles.MeshOf[k]];
                    int tri = _triangles.TriangleOf[k];
                    var (p0, p1, p2) = _triangles.Corners(k);
                    var uvs = m.TexCoords;
                    return uvs is null
                        ? TextureCoordinates.OfTriangle(Vector2.Zero, Vector2.UnitX, Vector2.UnitY, hit.B1, hit.B2, p0, p1, p2,
                            out uvPerLength)
                        : TextureCoordinates.OfTriangle(uvs[3 * tri], uvs[3 * tri + 1], uvs[3 * tri + 2], hit.B1, hit.B2, p0, p1, p2,
                            out uvPerLength);
                }
            case 2: return TextureCoordinates.OfShape(_analytic[hit.Primitive], hit.Position, out uvPerLength);
            case 3: return TextureCoordinates.OfShape(_planeShapes[hit.Primitive], hit.Position, out uvPerLength);
            case 4: return InstanceTexCoord(hit, out uvPerLength);
            default: uvPerLength = 0; return default;
        }
    }
}
