using System.Numerics;

namespace SpectralRenderer.Scenes;

/// <summary>
/// A calculation grid, as lighting software has it (EN 12464-1 §4.4's grid of points on a task area): the parallelogram
/// O + s·U + t·V (s, t ∈ [0, 1], metres in scene coordinates) cut into <see cref="PointsU"/> × <see cref="PointsV"/>
/// equal cells, the illuminance measured at each cell's centre on the side U × V points to.
/// </summary>
public sealed record CalculationGrid(string Name, Vector3 Origin, Vector3 U, Vector3 V, int PointsU, int PointsV)
{
    /// <summary>The most points along one edge.</summary>
    public const int MaxPoints = 1000;

    /// <summary>The unit normal U × V / |U × V|: the side the illuminance is measured on.</summary>
    public Vector3 Normal => Vector3.Normalize(Vector3.Cross(U, V));

    /// <summary>Point (i, j): the centre O + (i + ½)/NU·U + (j + ½)/NV·V of its cell.</summary>
    public Vector3 Point(int i, int j) => Origin + (i + 0.5f) / PointsU * U + (j + 0.5f) / PointsV * V;

    /// <summary>Every point, i fastest (the CSV's row order).</summary>
    public Vector3[] Points()
    {
        var points = new Vector3[PointsU * PointsV];
        for (int j = 0; j < PointsV; j++)
            for (int i = 0; i < PointsU; i++) points[j * PointsU + i] = Point(i, j);
        return points;
    }
}
