// Tabulated NDFs: measured tables (text, HDF5) and the facet NDF of a height map, against the
// analytic distributions they sample. (The tabulated NDF is also in the battery of
// test_ndf_families.cpp: normalisation, Lambda against brute force, chi-square of both samplers.)
#include "core/random.h"
#include "heightfield/exr_io.h"
#include "heightfield/generate.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ndf_table.h"
#include "heightfield/ndf/piecewise_linear.h"
#include "heightfield/ndf/student_t.h"
#include "heightfield/ndf/tabulated_ndf.h"

#include <cmath>
#include <cstdio>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <unistd.h>

using namespace gonio;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("gonio_tab_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d / name;
}
} // namespace

TEST_CASE("a fine table of anisotropic Beckmann has Beckmann's D and Lambda") {
    const Beckmann beckmann(0.3, 0.5);
    const TabulatedNdf table(sample_ndf_table(beckmann, 180, 144), "beckmann");
    for (double t : {0.0, 0.2, 0.5, 0.9})
        for (double p : {0.0, 0.8, 1.6, 3.0}) {
            const Vec3 d = spherical_direction(t, p);
            CAPTURE(t);
            CAPTURE(p);
            // Bilinear interpolation error at 0.5 x 2.5 degrees, relative to the peak.
            CHECK(std::abs(table.D(d) - beckmann.D(d)) < 2e-3 * beckmann.D({0, 0, 1}));
        }
    for (double t : {0.3, 0.8, 1.2, 1.45})
        for (double p : {0.0, 0.8, 1.6}) {
            const Vec3 d = spherical_direction(t, p);
            CAPTURE(t);
            CAPTURE(p);
            CHECK(std::abs(table.lambda(d) - beckmann.lambda(d)) < 2e-3 * (1 + beckmann.lambda(d)));
        }
}

TEST_CASE("a one-column table is the isotropic piecewise-linear NDF of its rows") {
    const ControlPoints points = PiecewiseLinearNdf::sampled_from(StudentT(0.4, 0.4, 3.0), 45);
    const PiecewiseLinearNdf pl(points);
    const TabulatedNdf table(NdfTable{45, 1, points.value}, "column");
    for (double t : {0.0, 0.1, 0.45, 0.9, 1.3, 1.55})
        for (double p : {0.0, 2.0}) {
            const Vec3 d = spherical_direction(t, p);
            CHECK(table.D(d) == doctest::Approx(pl.D(d)).epsilon(1e-12));
            CHECK(std::abs(table.lambda(d) - pl.lambda(d)) < 1e-5 * (1 + pl.lambda(d)));
        }
}

TEST_CASE("NDF tables are read from text and HDF5, and bad ones are refused by name") {
    const NdfTable t = sample_ndf_table(Beckmann(0.3, 0.5), 18, 8);
    const fs::path text = scratch("t.txt"), h5 = scratch("t.h5");
    {
        std::ofstream f(text);
        f << "# Beckmann (0.3, 0.5): rows theta 0..90 step 5, columns phi 0..315 step 45\n";
        f.precision(17);
        for (int j = 0; j <= 18; ++j) {
            for (int k = 0; k < 8; ++k) f << (k ? ", " : "") << t.at(j, k);
            f << "\n";
        }
    }
    const hid_t file = H5Fcreate(h5.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t dims[2] = {19, 8};
    H5LTmake_dataset_double(file, "D", 2, dims, t.values.data());
    H5Fclose(file);
    for (const fs::path& p : {text, h5}) {
        const NdfTable r = read_ndf_table(p.string());
        CHECK(r.theta_intervals == 18);
        CHECK(r.phi_count == 8);
        CHECK(r.values == t.values);
    }
    auto refused = [&](const std::string& body, const std::string& message) {
        const fs::path bad = scratch("bad.txt");
        std::ofstream(bad) << body;
        CHECK_THROWS_WITH(
            read_ndf_table(bad.string()),
            doctest::Contains(("NDF table " + bad.string() + ": " + message).c_str()));
    };
    refused("1 2\n1 2\n1\n", "line 3 has 1 values, the first row 2");
    refused("1 2\n1 x\n1 1\n", "line 2: 'x' is not a number");
    refused("1\n-1\n1\n", "values must be finite and >= 0");
    refused("1\n1\n", "needs at least 3 theta rows");
    fs::remove_all(text.parent_path());
}

TEST_CASE("the facet table of normals drawn from Beckmann is Beckmann's") {
    const Beckmann beckmann(0.5);
    std::vector<Vec3> normals;
    Rng rng{3};
    const int count = 1 << 19;
    for (int i = 0; i < count; ++i)
        normals.push_back(beckmann.sample_m(rng.uniform(), rng.uniform()));
    const TabulatedNdf table(ndf_table_of_normals(normals, 45, 36), "iid", "height_map");
    // Each row's azimuthal mean within 4 sigma of the count it rests on (cloud-in-cell: about
    // Poisson), plus the deposit's O(h^2) bias (0.5 %), over the bulk of the lobe.
    const double dt = 0.5 * kPi / 45;
    for (int j = 1; j <= 20; ++j) {
        const double t = j * dt;
        double mean = 0;
        for (int k = 0; k < 36; ++k) mean += table.D(spherical_direction(t, kTwoPi * k / 36)) / 36;
        const double d = beckmann.D(spherical_direction(t, 0));
        const double expected = count * d * std::cos(t) * std::sin(t) * dt * kTwoPi;
        CAPTURE(t);
        CAPTURE(expected);
        CHECK(std::abs(mean / d - 1) < 4 / std::sqrt(expected) + 0.005);
    }
}

TEST_CASE("the facet NDF of an EXR height map: its triangles' normals, through the file") {
    const Beckmann beckmann(0.5);
    SurfaceSpec spec;
    spec.size = 128;
    spec.iterations = 100;
    const HeightField surface = generate_surface(beckmann, spec, 2);
    std::vector<Vec3> normals;
    for (int y = 0; y < surface.n; ++y)
        for (int x = 0; x < surface.n; ++x)
            for (int t = 0; t < 2; ++t) {
                double sp, sq;
                surface.triangle_slopes(x, y, t, sp, sq);
                normals.push_back(HeightField::normal_of_slopes(sp, sq));
            }
    const fs::path exr = scratch("h.exr");
    write_height_exr(exr.string(), surface, {});
    const NdfTable from_file = facet_ndf_table(read_height_exr(exr.string()), 45, 36);
    const NdfTable direct = ndf_table_of_normals(normals, 45, 36);
    REQUIRE(from_file.values.size() == direct.values.size());
    for (size_t i = 0; i < direct.values.size(); ++i)
        CHECK(from_file.values[i] == doctest::Approx(direct.values[i]).epsilon(1e-6));
    // A generated Beckmann surface looks like Beckmann in the bulk (the generator's residual at
    // 128^2 is a few percent per 2-degree row; the estimator's own error is tested above).
    const TabulatedNdf facets(from_file, exr.string(), "height_map");
    for (double t : {0.2, 0.4, 0.6}) {
        double mean = 0;
        for (int k = 0; k < 36; ++k) mean += facets.D(spherical_direction(t, kTwoPi * k / 36)) / 36;
        CAPTURE(t);
        CHECK(std::abs(mean / beckmann.D(spherical_direction(t, 0)) - 1) < 0.1);
    }
    fs::remove_all(exr.parent_path());
}
