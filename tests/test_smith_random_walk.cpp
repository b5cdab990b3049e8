// The Smith random walk of Heitz et al. 2016 (gonio/model/smith_random_walk.h), held against
// quantities it must reproduce: Model L1 with the height-correlated G2 for its single scattering
// (chi-square per cell), energy conservation for lossless facets, and, order by order, a second
// estimator written independently here.
#include "core/batch_means.h"
#include "core/chi_square.h"
#include "core/special_functions.h"
#include "gonio/model/cell_integrator.h"
#include "gonio/model/microfacet_model.h"
#include "gonio/model/smith_random_walk.h"
#include "heightfield/ndf/beckmann.h"
#include "heightfield/ndf/ggx.h"

#include <cmath>
#include <doctest/doctest.h>
#include <tbb/global_control.h>

using namespace gonio;

namespace {

// The second estimator. It shares only D and Lambda with the model: heights are Gaussian (H16
// shows that the walk does not depend on their distribution), the next height is found by
// bisection on the free-path CDF built from G1(w, h) = C1(h)^Lambda(w) itself (not its closed-form
// inverse), and facet normals are drawn from a mixture of D(m) m.z and the uniform hemisphere,
// weighted by max(0, v.m) D(m) / (A(v) q(m)), A(v) the projected area seen from v, instead of
// being sampled from the visible normals. A perfect mirror; albedo per order 1, 2, 3+ with the
// standard errors of 32 batches.
struct OrderAlbedos {
    double mean[3] = {0, 0, 0}, stderr_[3] = {0, 0, 0};
};

double gaussian_c1(double h) {
    return 0.5 * std::erfc(-h / std::sqrt(2.0));
}

// The height h' with C1(h') = c, by bisection (C1 is increasing).
double gaussian_height(double c) {
    double lo = -40, hi = 40;
    for (int k = 0; k < 200 && hi - lo > 1e-13; ++k) {
        const double mid = 0.5 * (lo + hi);
        (gaussian_c1(mid) < c ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// The projected area of the microsurface seen from v: (1 + Lambda(v)) v.z above the plane,
// Lambda(-v) |v.z| below it.
double projected_area(const Ndf& ndf, const Vec3& v) {
    return v.z > 0 ? (1 + ndf.lambda(v)) * v.z : ndf.lambda(-v) * -v.z;
}

OrderAlbedos independent_walk(const Ndf& ndf, const Vec3& wi, long long paths, std::uint64_t seed) {
    const int B = 32;
    std::vector<double> batches(size_t(B) * 3, 0.0);
    Rng rng{seed, 99, 0x1234, 0};
    const long long per_batch = paths / B;
    for (int b = 0; b < B; ++b)
        for (long long p = 0; p < per_batch; ++p) {
            Vec3 d = -wi;
            double h = 40, weight = 1; // above every facet
            for (int order = 0; order < 1000; ++order) {
                // The free-path CDF: going up, P(no hit before h') = (C1(h) / C1(h'))^Lambda;
                // going down, C1(h') / C1(h) is (1 - U)^(1 / (1 + Lambda(-d))) (the projected
                // area below the path is Lambda(-d) + 1 times |d.z|).
                const double U = rng.uniform(), c = gaussian_c1(h);
                if (d.z > 0) {
                    const double L = ndf.lambda(d);
                    if (U >= 1 - std::pow(c, L)) { // escapes
                        batches[size_t(b) * 3 + size_t(std::min(order, 3) - 1)] += weight;
                        break;
                    }
                    h = gaussian_height(c / std::pow(1 - U, 1 / L));
                } else {
                    h = gaussian_height(c * std::pow(1 - U, 1 / (1 + ndf.lambda(-d))));
                }
                const Vec3 v = -d; // towards where the path comes from
                Vec3 m;
                if (rng.uniform() < 0.5) {
                    const double u1 = rng.uniform(), u2 = rng.uniform();
                    m = ndf.sample_m(u1, u2);
                } else { // uniform on the hemisphere
                    const double z = rng.uniform(), phi = 2 * kPi * rng.uniform();
                    const double r = std::sqrt(std::max(0.0, 1 - z * z));
                    m = {r * std::cos(phi), r * std::sin(phi), z};
                }
                const double q = 0.5 * ndf.pdf_m(m) + 0.5 / (2 * kPi);
                const double vm = dot(v, m);
                if (vm <= 0 || q <= 0) break; // weight 0
                weight *= vm * ndf.D(m) / (projected_area(ndf, v) * q);
                d = 2 * vm * m - v; // mirror reflection
            }
        }
    OrderAlbedos a;
    for (double& x : batches) x /= double(per_batch);
    for (int k = 0; k < 3; ++k) {
        a.mean[k] = batch_mean(batches, B)[size_t(k)];
        a.stderr_[k] = batch_stderr(batches, B)[size_t(k)];
    }
    return a;
}

} // namespace

TEST_CASE("Smith random walk: orders 1, 2 and 3+ of Beckmann and GGX mirrors agree with an "
          "independent estimator within 4 sigma, and order 1 with Model L1") {
    const SpecularReflector mirror(FresnelTerm::mirror());
    const BeckersSensor sensor(145);
    int compared = 0;
    for (double alpha : {0.1, 0.5, 1.0, 1.5}) {
        const Beckmann beckmann(alpha, alpha);
        const Ggx ggx(alpha, alpha);
        for (const Ndf* ndf : std::vector<const Ndf*>{&beckmann, &ggx})
            for (double ti : {0.0, 40.0, 70.0, 85.0}) {
                CAPTURE(ndf->describe());
                CAPTURE(ti);
                const Vec3 wi = spherical_direction(radians(ti), radians(30.0));
                TraceSettings st;
                st.rays = 1 << 17;
                st.orders = 2;
                st.seed = 11;
                const TraceResult r = smith_random_walk(*ndf, mirror, sensor, wi, st);
                const OrderAlbedos x = independent_walk(*ndf, wi, 1 << 17, 5);
                for (int k = 0; k < 3; ++k) {
                    CAPTURE(k + 1);
                    CAPTURE(r.ledger.reflected[size_t(k)]);
                    CAPTURE(x.mean[k]);
                    const double sigma =
                        std::hypot(r.ledger_stderr.reflected[size_t(k)], x.stderr_[k]);
                    CAPTURE(sigma);
                    CHECK(std::abs(r.ledger.reflected[size_t(k)] - x.mean[k]) <= 4 * sigma + 1e-15);
                    ++compared;
                }
                // Order 1 is the microfacet BRDF with the height-correlated G2 [R19 Eq. 9].
                const MicrofacetModel l1(*ndf, FresnelTerm::mirror(),
                                         MaskingForm::height_correlated);
                double e1 = 0;
                for (double e : model_cell_energy(l1, wi, sensor, {})) e1 += e;
                CHECK(std::abs(r.ledger.reflected[0] - e1) <=
                      4 * r.ledger_stderr.reflected[0] + 1e-5 * e1);
            }
    }
    CHECK(compared == 2 * 4 * 4 * 3);
}

TEST_CASE("Smith random walk: single scattering is Model L1 with the height-correlated G2 per "
          "cell (chi-square)") {
    const BeckersSensor sensor(577);
    const Beckmann beckmann(0.5, 0.5);
    const Ggx ggx(0.3, 0.6);
    const SpecularReflector mirror(FresnelTerm::mirror());
    int tests = 0;
    for (const Ndf* ndf : std::vector<const Ndf*>{&beckmann, &ggx})
        for (double ti : {0.0, 60.0, 80.0}) {
            CAPTURE(ndf->describe());
            CAPTURE(ti);
            const Vec3 wi = spherical_direction(radians(ti), radians(40.0));
            TraceSettings st;
            st.rays = 1 << 18;
            st.orders = 2;
            st.seed = 3;
            const TraceResult r = smith_random_walk(*ndf, mirror, sensor, wi, st);
            const MicrofacetModel model(*ndf, FresnelTerm::mirror(),
                                        MaskingForm::height_correlated);
            std::vector<double> expected = model_cell_energy(model, wi, sensor, {});
            std::vector<double> observed(size_t(sensor.cell_count()));
            for (int c = 0; c < sensor.cell_count(); ++c) {
                observed[size_t(c)] = r.energy[size_t(c)] * double(st.rays); // order 1
                expected[size_t(c)] *= double(st.rays);
            }
            const ChiSquareResult chi = chi_square_test(observed, expected);
            CAPTURE(chi.statistic);
            CAPTURE(chi.p_value);
            CHECK(chi.failure.empty());
            CHECK(chi.p_value > sidak_level(0.01, 6));
            ++tests;
        }
    CHECK(tests == 6);
}

TEST_CASE("Smith random walk: lossless facets keep every path (L-infinity = 1), glass splits it "
          "between reflection and transmission, and threads do not change a bit") {
    const BeckersSensor sensor(145);
    const SpecularReflector mirror(FresnelTerm::mirror());
    const DielectricFacet glass(1.5);
    const LambertianFacet white({1.0});
    for (double alpha : {0.05, 1.0, 1.5}) {
        const Ggx ndf(alpha, alpha);
        for (double ti : {0.0, 60.0, 89.0})
            for (const Material* material : std::vector<const Material*>{&mirror, &glass, &white}) {
                CAPTURE(alpha);
                CAPTURE(ti);
                CAPTURE(material == &glass);
                TraceSettings st;
                st.rays = 1 << 14;
                st.orders = 2;
                st.max_bounces = 100000;
                const TraceResult r = smith_random_walk(ndf, *material, sensor,
                                                        spherical_direction(radians(ti), 0.2), st);
                double total = r.ledger.capped[0];
                for (double e : r.ledger.reflected) total += e;
                for (double e : r.ledger.transmitted) total += e;
                CHECK(total == doctest::Approx(1.0).epsilon(1e-12));
                CHECK(r.ledger.absorbed[0] == 0.0);
                CHECK(r.ledger.lost[0] == 0.0);
                CHECK(r.ledger.capped[0] == 0.0);
                if (material == &glass) {
                    double t = 0;
                    for (double e : r.ledger.transmitted) t += e;
                    CHECK(t > 0.05); // glass transmits at every incidence here
                } else {
                    CHECK(r.ledger.transmitted.empty());
                }
            }
    }
    // A conductor absorbs; the ledger closes. Threads: same bits.
    const SpecularReflector gold(FresnelTerm::conductor({{0.18, 3.4}, {0.43, 2.46}}));
    const Beckmann ndf(0.8, 0.3);
    TraceSettings st;
    st.rays = 1 << 15;
    st.orders = 2;
    const Vec3 wi = spherical_direction(radians(50.0), 0.7);
    TraceResult one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = smith_random_walk(ndf, gold, sensor, wi, st);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = smith_random_walk(ndf, gold, sensor, wi, st);
    }
    CHECK(one.energy == two.energy);
    for (int k = 0; k < 2; ++k) {
        CHECK(one.ledger.absorbed[size_t(k)] > 0.01);
        CHECK(std::abs(one.ledger.unaccounted[size_t(k)]) < 1e-12);
    }
}

TEST_CASE("visible normals from below the plane follow max(0, v.m) D(m) (chi-square)") {
    // Binned in (cos theta_m, phi_m): the rejection sampler against the density integrated by
    // quadrature over each bin.
    const Ggx ndf(0.7, 0.4);
    const Vec3 v = normalize(Vec3{0.6, 0.3, -0.4});
    const int nt = 8, np = 16;
    const long long n = 1 << 18;
    std::vector<double> observed(size_t(nt * np), 0.0), expected(size_t(nt * np), 0.0);
    Rng rng{1, 2, 3, 4};
    for (long long k = 0; k < n; ++k) {
        const Vec3 m = sample_visible_any(ndf, v, rng);
        double phi = std::atan2(m.y, m.x);
        if (phi < 0) phi += 2 * kPi;
        const int i = std::min(nt - 1, int(m.z * nt)),
                  j = std::min(np - 1, int(phi / (2 * kPi) * np));
        observed[size_t(i * np + j)] += 1;
    }
    const double area = projected_area(ndf, v);
    const int q = 24; // midpoint rule inside each bin
    for (int i = 0; i < nt; ++i)
        for (int j = 0; j < np; ++j) {
            double s = 0;
            for (int a = 0; a < q; ++a)
                for (int b = 0; b < q; ++b) {
                    const double z = (i + (a + 0.5) / q) / nt,
                                 phi = 2 * kPi * (j + (b + 0.5) / q) / np;
                    const double r = std::sqrt(1 - z * z);
                    const Vec3 m{r * std::cos(phi), r * std::sin(phi), z};
                    s += std::max(0.0, dot(v, m)) * ndf.D(m);
                }
            expected[size_t(i * np + j)] = s / (q * q) * (1.0 / nt) * (2 * kPi / np) / area * n;
        }
    const ChiSquareResult chi = chi_square_test(observed, expected);
    CAPTURE(chi.statistic);
    CAPTURE(chi.p_value);
    CHECK(chi.failure.empty());
    CHECK(chi.p_value > 0.01);
}
