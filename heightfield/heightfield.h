#pragma once
// The explicit microsurface: an n x n periodic grid of heights h(x, y) with a spacing between
// samples. Rays see it as two triangles per cell, split along the (x+1, y)-(x, y+1) diagonal as
// Embree splits a quad (v0, v1, v3) and (v2, v3, v1):
//   triangle A of cell (x, y) has slopes (p(x, y),   q(x, y)),
//   triangle B of cell (x, y) has slopes (p(x, y+1), q(x+1, y)),
// with the forward differences p(x, y) = (h(x+1, y) - h(x, y)) / spacing and
// q(x, y) = (h(x, y+1) - h(x, y)) / spacing (indices wrap). A facet of slopes (p, q) has the normal
// m = (-p, -q, 1) / |(-p, -q, 1)|, and both triangles of a cell have the same projected area.
#include "core/math.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace gonio {

struct HeightField {
    int n = 0;            // samples per side
    double spacing = 1.0; // distance between samples, in the units of the heights
    std::vector<float> h; // row-major: h[y * n + x]

    HeightField() = default;
    HeightField(int size, double spacing_)
        : n(size), spacing(spacing_), h(size_t(size) * size, 0.0f) {}

    int wrap(int i) const { return ((i % n) + n) % n; }
    float at(int x, int y) const { return h[size_t(wrap(y)) * n + wrap(x)]; }
    double p(int x, int y) const { return (double(at(x + 1, y)) - at(x, y)) / spacing; }
    double q(int x, int y) const { return (double(at(x, y + 1)) - at(x, y)) / spacing; }
    // Slopes of triangle t (0: A, 1: B) of cell (x, y).
    void triangle_slopes(int x, int y, int t, double& sp, double& sq) const {
        if (t == 0)
            sp = p(x, y), sq = q(x, y);
        else
            sp = p(x, y + 1), sq = q(x + 1, y);
    }
    static Vec3 normal_of_slopes(double sp, double sq) { return normalize(Vec3{-sp, -sq, 1.0}); }

    // The triangulated surface at grid coordinates (gx, gy) = (x, y) / spacing (any: the patch
    // repeats), with the same split as the traced geometry: its height, and if asked the
    // triangle's height differences per sample along x and y (its slopes times the spacing).
    double height_at_grid(double gx, double gy, double* dx = nullptr, double* dy = nullptr) const {
        return triangulated_height(gx, gy, n, dx, dy, [this](int x, int y) {
            return h[size_t(y == n ? 0 : y) * n + (x == n ? 0 : x)];
        });
    }

    // The same over any storage of the n x n samples: sample(x, y) for x, y in [0, n], where n
    // stands for 0 (so a buffer with the first row and column repeated can be read directly).
    template <class Sample>
    static double triangulated_height(double gx, double gy, int n, double* dx, double* dy,
                                      const Sample& sample) {
        const double fx = std::floor(gx), fy = std::floor(gy);
        const double u = gx - fx, v = gy - fy;
        int x0 = int(fx), y0 = int(fy); // one wrap per axis (no modulo on the hot path)
        if (x0 < 0 || x0 >= n) x0 = ((x0 % n) + n) % n;
        if (y0 < 0 || y0 >= n) y0 = ((y0 % n) + n) % n;
        const double h00 = sample(x0, y0), h10 = sample(x0 + 1, y0);
        const double h01 = sample(x0, y0 + 1), h11 = sample(x0 + 1, y0 + 1);
        double a, b, z;
        if (u + v <= 1.0) { // triangle A: (x, y), (x+1, y), (x, y+1)
            a = h10 - h00, b = h01 - h00;
            z = h00 + (u * a + v * b);
        } else { // triangle B: (x+1, y+1), (x, y+1), (x+1, y)
            a = h11 - h01, b = h11 - h10;
            z = h11 - ((1 - u) * a + (1 - v) * b);
        }
        if (dx) *dx = a;
        if (dy) *dy = b;
        return z;
    }
};

} // namespace gonio
