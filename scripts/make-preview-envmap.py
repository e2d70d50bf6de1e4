#!/usr/bin/env python3
"""Writes scenes/mitsuba-material-preview-sky.pfm, the small lat-long environment map of the Mitsuba material-preview scene
(issue 39): 64 × 32 pixels in Mitsuba 3's envmap layout (row y at θ = π·y/31 from the zenith, column x at φ = 2π(x + ½)/64,
direction (sin φ sin θ, cos θ, −cos φ sin θ)). A blue sky brighter towards the horizon, a warm sun of 3 × 3 pixels high in
the +X/−Z quarter, and a brown ground. Every pixel's colour divided by twice its largest component is a multiple of 1/16, so
our importer uplifts it exactly (Scenes/EnvironmentMap.cs). No dependencies; same bytes on every run."""
import math
import os
import struct

W, H = 64, 32
SKY, SUN, GROUND = (4, 6, 8), (8, 7, 5), (8, 6, 4)   # rgb ∝ these; max 8 → rgb/(2·max) in sixteenths


def pixel(x, y):
    theta = math.pi * y / (H - 1)
    phi = 2 * math.pi * (x + 0.5) / W
    if theta <= math.pi / 2:
        k = 0.6 + 0.8 * math.sin(theta) ** 2 + 0.25 * math.cos(phi)   # brighter at the horizon, a slow swing in azimuth
        colour = SKY
        if abs(x - 20) <= 1 and abs(y - 8) <= 1:
            k, colour = 30.0, SUN
    else:
        k, colour = 0.35 + 0.1 * math.sin(2 * phi), GROUND
    return [k * c / 8 for c in colour]


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "mitsuba-material-preview-sky.pfm")
    with open(out, "wb") as f:
        f.write(f"PF\n{W} {H}\n-1.0\n".encode("ascii"))
        for y in range(H - 1, -1, -1):   # PFM rows bottom to top
            for x in range(W):
                f.write(struct.pack("<3f", *pixel(x, y)))
    print(out)


if __name__ == "__main__":
    main()
