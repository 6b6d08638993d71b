// Form factors against published closed forms (KNOWN-ANSWERS.md: Cohen & Wallace 1993,
// Siegel & Howell) and physical identities (reciprocity, the full hemisphere).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "links/FormFactor.h"

namespace rad {
namespace {

constexpr double kPi = std::numbers::pi;

PatchGeometry quad(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d) {
    PatchGeometry p;
    p.v = {a, b, c, d};
    p.n = 4;
    return p;
}

PatchGeometry tri(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    PatchGeometry p;
    p.v = {a, b, c, glm::dvec3(0.0)};
    p.n = 3;
    return p;
}

// Parallel, directly opposed, equal a x b rectangles at distance c (KNOWN-ANSWERS).
double parallelRectangles(double a, double b, double c) {
    const double X = a / c, Y = b / c;
    const double X2 = X * X, Y2 = Y * Y;
    return 2.0 / (kPi * X * Y) *
           (std::log(std::sqrt((1 + X2) * (1 + Y2) / (1 + X2 + Y2))) +
            X * std::sqrt(1 + Y2) * std::atan(X / std::sqrt(1 + Y2)) +
            Y * std::sqrt(1 + X2) * std::atan(Y / std::sqrt(1 + X2)) - X * std::atan(X) -
            Y * std::atan(Y));
}

// Perpendicular rectangles sharing an edge l, from the W (width w) rectangle to the H one.
double perpendicularRectangles(double l, double h, double w) {
    const double H = h / l, W = w / l;
    const double H2 = H * H, W2 = W * W;
    const double A = (1 + W2) * (1 + H2) / (1 + W2 + H2);
    const double B = W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2));
    const double C = H2 * (1 + W2 + H2) / ((1 + H2) * (H2 + W2));
    const double s = std::sqrt(H2 + W2);
    return 1.0 / (kPi * W) *
           (W * std::atan(1 / W) + H * std::atan(1 / H) - s * std::atan(1 / s) +
            0.25 * (std::log(A) + W2 * std::log(B) + H2 * std::log(C)));
}

// Receiver a x b at z = 0 facing +z; source a x b at z = c facing -z.
std::pair<PatchGeometry, PatchGeometry> opposedRectangles(double a, double b, double c) {
    return {quad({0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}),
            quad({0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c})};
}

TEST(FormFactor, ParallelUnitSquaresMatchPublishedValue) {
    const auto [r, s] = opposedRectangles(1, 1, 1);
    const double f = polygonToPolygonFormFactor(r, s);  // default order 4: 0.199826
    EXPECT_NEAR(f, 0.199825, 0.005 * 0.199825) << f;
    EXPECT_NEAR(parallelRectangles(1, 1, 1), 0.199825, 1e-6);
    // The reverse direction is the same by symmetry.
    EXPECT_NEAR(polygonToPolygonFormFactor(s, r), f, 1e-9);
}

TEST(FormFactor, ParallelRectanglesGeneralSizes) {
    struct Case {
        double a, b, c;
    };
    for (const Case& k : {Case{2, 1, 1}, Case{0.5, 3, 2}, Case{4, 4, 0.5}, Case{0.1, 0.2, 5},
                          Case{1e-3, 2e-3, 1e-3}, Case{1e3, 5e2, 7e2}}) {
        const auto [r, s] = opposedRectangles(k.a, k.b, k.c);
        const double expected = parallelRectangles(k.a, k.b, k.c);
        // Large rectangles close together need more points: the integrand varies on the scale c.
        const double f = polygonToPolygonFormFactor(r, s, 12);
        EXPECT_NEAR(f, expected, 0.005 * expected) << k.a << "x" << k.b << " at " << k.c;
    }
}

TEST(FormFactor, PerpendicularUnitSquaresSharingAnEdge) {
    // W square in z = 0 facing +z, H square in y = 0 facing +y; shared edge along x.
    const PatchGeometry w = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    const PatchGeometry h = quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
    EXPECT_NEAR(perpendicularRectangles(1, 1, 1), 0.200044, 1e-6);
    // Only the receiver is sampled (the inner integral is analytic), so even though the
    // integrand behaves like y log y near the shared edge, Gauss-Legendre converges fast:
    // order 4 (16 points) gives 0.200043, order 8 (64 points) 0.200044. Order 8 is the one we
    // rely on; order 4 is checked too because it is the default.
    const double f4 = polygonToPolygonFormFactor(w, h, 4);
    const double f8 = polygonToPolygonFormFactor(w, h, 8);
    EXPECT_NEAR(f8, 0.200044, 0.01 * 0.200044) << f8;
    EXPECT_NEAR(f4, 0.200044, 0.01 * 0.200044) << f4;
    EXPECT_NEAR(polygonToPolygonFormFactor(h, w, 8), 0.200044, 0.01 * 0.200044);
}

TEST(FormFactor, PerpendicularRectanglesGeneralSizes) {
    struct Case {
        double l, h, w;
    };
    for (const Case& k : {Case{1, 2, 1}, Case{2, 1, 0.5}, Case{1, 0.3, 3}}) {
        const PatchGeometry w = quad({0, 0, 0}, {k.l, 0, 0}, {k.l, k.w, 0}, {0, k.w, 0});
        const PatchGeometry h = quad({0, 0, 0}, {0, 0, k.h}, {k.l, 0, k.h}, {k.l, 0, 0});
        const double expected = perpendicularRectangles(k.l, k.h, k.w);
        EXPECT_NEAR(polygonToPolygonFormFactor(w, h, 12), expected, 0.01 * expected)
            << k.l << " " << k.h << " " << k.w;
    }
}

// A regular N-gon disk of radius R centred at c in the plane z = c.z, fanned into triangles,
// facing +z or -z.
std::vector<PatchGeometry> diskFan(glm::dvec3 c, double radius, int n, bool facingUp) {
    std::vector<PatchGeometry> fan;
    for (int i = 0; i < n; ++i) {
        const double a0 = 2 * kPi * i / n, a1 = 2 * kPi * (i + 1) / n;
        const glm::dvec3 p0 = c + radius * glm::dvec3(std::cos(a0), std::sin(a0), 0);
        const glm::dvec3 p1 = c + radius * glm::dvec3(std::cos(a1), std::sin(a1), 0);
        fan.push_back(facingUp ? tri(c, p0, p1) : tri(c, p1, p0));
    }
    return fan;
}

TEST(FormFactor, DifferentialAreaToCoaxialDisk) {
    // F(dA -> coaxial disk of radius R at height h) = R^2 / (h^2 + R^2).
    for (const auto& [radius, height] :
         {std::pair{1.0, 1.0}, std::pair{0.2, 0.5}, std::pair{3.0, 0.1}}) {
        double f = 0.0;
        for (const PatchGeometry& t : diskFan({0, 0, height}, radius, 256, false))
            f += pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, t);
        const double expected = radius * radius / (height * height + radius * radius);
        // The inscribed 256-gon has 1e-4 less area than the disk.
        EXPECT_NEAR(f, expected, 1e-3 * expected) << radius << " " << height;
    }
}

TEST(FormFactor, CoaxialDisks) {
    // r1 = 0.1, r2 = 0.2, h = 0.5: F12 = 0.1339 (KNOWN-ANSWERS), both as 64-gon fans.
    const double r1 = 0.1, r2 = 0.2, h = 0.5;
    const double R1 = r1 / h, R2 = r2 / h;
    const double X = 1 + (1 + R2 * R2) / (R1 * R1);
    const double expected = (X - std::sqrt(X * X - 4 * (R2 / R1) * (R2 / R1))) / 2;
    EXPECT_NEAR(expected, 0.1339, 1e-4);
    const auto d1 = diskFan({0, 0, 0}, r1, 64, true);
    const auto d2 = diskFan({0, 0, h}, r2, 64, false);
    double a1 = 0.0, sum = 0.0;
    for (const PatchGeometry& t1 : d1) {
        const double at = polygonArea(t1);
        a1 += at;
        for (const PatchGeometry& t2 : d2) sum += at * polygonToPolygonFormFactor(t1, t2, 3);
    }
    const double f = sum / a1;
    EXPECT_NEAR(f, expected, 0.01 * expected) << f;
}

PatchGeometry randomPatch(std::mt19937& rng, glm::dvec3 centre, double size) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    glm::dvec3 e1, e2;
    do {
        e1 = glm::dvec3(u(rng), u(rng), u(rng));
        e2 = glm::dvec3(u(rng), u(rng), u(rng));
    } while (glm::length(glm::cross(e1, e2)) < 0.2);
    e1 *= size;
    e2 *= size;
    if (rng() % 2)
        return quad(centre - e1 - e2, centre + e1 - e2, centre + e1 + e2, centre - e1 + e2);
    return tri(centre - e1, centre + e1, centre + e2);
}

TEST(FormFactor, ReciprocityForRandomPairs) {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int checked = 0;
    for (int k = 0; k < 400 && checked < 100; ++k) {
        const glm::dvec3 c1(u(rng), u(rng), u(rng));
        glm::dvec3 dir(u(rng), u(rng), u(rng));
        if (glm::length(dir) < 0.1) continue;
        const glm::dvec3 c2 = c1 + 3.0 * glm::normalize(dir) * (1.5 + u(rng));
        const PatchGeometry p1 = randomPatch(rng, c1, 0.5);
        const PatchGeometry p2 = randomPatch(rng, c2, 0.5);
        const double a12 = polygonArea(p1) * polygonToPolygonFormFactor(p1, p2, 12);
        const double a21 = polygonArea(p2) * polygonToPolygonFormFactor(p2, p1, 12);
        if (a12 < 1e-4 && a21 < 1e-4) continue;  // facing away, or nearly so
        // A pair that partly clips each other (one crosses the other's plane) makes the integrand
        // kinked; order 8 still keeps the imbalance within 1%.
        EXPECT_NEAR(a12, a21, 0.01 * std::max(a12, a21)) << "pair " << k;
        ++checked;
    }
    EXPECT_GE(checked, 50);
}

TEST(FormFactor, HugeSquareAboveCoversTheHemisphere) {
    const double L = 1e4;
    const PatchGeometry big = quad({-L, -L, 1}, {-L, L, 1}, {L, L, 1}, {L, -L, 1});
    const double f = pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, big);
    EXPECT_NEAR(f, 1.0, 1e-6);
    EXPECT_LE(f, 1.0);
    // Tilted receiver: the square still covers the upper hemisphere except a thin sliver
    // near the horizon (clipping keeps the part above the tangent plane).
    const glm::dvec3 n = glm::normalize(glm::dvec3(1, 0, 1));
    const double ft = pointToPolygonFormFactor({0, 0, 0}, n, big);
    // Exactly: for an infinite plane at height 1 and a normal tilted 45°, F = (1 + cos 45°)/2.
    EXPECT_NEAR(ft, 0.5 * (1 + std::sqrt(0.5)), 1e-3);
}

TEST(FormFactor, ZeroBehindFacingAwayAndInPlane) {
    const glm::dvec3 x(0, 0, 0), nx(0, 0, 1);
    // Below the tangent plane (facing up towards x's plane from below).
    EXPECT_EQ(
        pointToPolygonFormFactor(x, nx, quad({-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1})),
        0.0);
    // Above, but facing away (normal +z): x is behind the one-sided emitter.
    EXPECT_EQ(pointToPolygonFormFactor(x, nx, quad({-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1})),
              0.0);
    // x in the polygon's plane (a vertical polygon whose plane contains x).
    EXPECT_EQ(pointToPolygonFormFactor(x, nx, quad({0, 1, 0}, {0, 2, 0}, {0, 2, 1}, {0, 1, 1})),
              0.0);
    // x lies inside the polygon itself.
    EXPECT_EQ(pointToPolygonFormFactor(x, nx, quad({-1, -1, 0}, {-1, 1, 0}, {1, 1, 0}, {1, -1, 0})),
              0.0);
}

// Plane element at the origin (normal +z) to the rectangle x in [0,a], z in [0,b] in the plane
// y = c facing -y: Lambert's formula has only two non-zero edge terms (the vertical edges lie in
// planes containing the z axis), giving the catalogue form
//   F = 1/(2 pi) * ( atan(a/c) - c / sqrt(b^2+c^2) * atan(a / sqrt(b^2+c^2)) ).
double elementToPerpendicularRectangle(double a, double b, double c) {
    const double s = std::sqrt(b * b + c * c);
    return (std::atan(a / c) - c / s * std::atan(a / s)) / (2 * kPi);
}

TEST(FormFactor, PolygonCrossingTheTangentPlaneIsClipped) {
    const double a = 1.5, b = 0.7, c = 0.9;
    // Facing -y: counter-clockwise seen from y < 0.
    const PatchGeometry upper = quad({0, c, 0}, {a, c, 0}, {a, c, b}, {0, c, b});
    const PatchGeometry crossing = quad({0, c, -2}, {a, c, -2}, {a, c, b}, {0, c, b});
    const double expected = elementToPerpendicularRectangle(a, b, c);
    // Edge angles are evaluated to 2e-8 rad (FormFactor.cpp, vectorAngle).
    EXPECT_NEAR(pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, upper), expected, 1e-8);
    EXPECT_NEAR(pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, crossing), expected, 1e-8);
    // A triangle crossing diagonally: clipping makes a quad; compare with additivity over the
    // closed form (the part above is the same rectangle once the lower vertex is cut away).
    const PatchGeometry triangleCrossing = tri({0, c, b}, {0.5 * a, c, -b}, {a, c, b});
    const double f = pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, triangleCrossing);
    EXPECT_GT(f, 0.0);
    EXPECT_LT(f, elementToPerpendicularRectangle(a, b, c) +
                     elementToPerpendicularRectangle(0.0 + 1e-300, b, c) + 1e-12);
}

TEST(FormFactor, NoNanForDegenerateInputs) {
    const PatchGeometry sq = quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1});
    std::vector<PatchGeometry> polys = {
        sq,
        tri({0, 0, 1}, {0, 0, 1}, {1, 0, 1}),              // coincident vertices
        tri({0, 0, 1}, {1, 0, 1}, {2, 0, 1}),              // collinear: zero area
        quad({0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}),  // a point
        quad({0, 0, 1}, {0, 1, 1}, {0, 1, 1}, {1, 0, 1}),  // quad collapsed to a triangle
        PatchGeometry{},                                   // all zero
        PatchGeometry{{glm::dvec3(1), glm::dvec3(2), glm::dvec3(3), glm::dvec3(4)}, 7},  // bad n
    };
    const std::vector<glm::dvec3> points = {
        {0.5, 0.5, 0},       {0, 0, 1},          {0.5, 0, 1},
        {0.5, 0.5, 1},       {0, 0, 1 - 1e-300}, {0.5, 0.5, 1 - 1e-14},
        {0, 0, 0.999999999}, {2, 2, 1},          {0.3, 0.2, 0.99}};
    const std::vector<glm::dvec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 0, 0}};
    for (const PatchGeometry& p : polys) {
        EXPECT_TRUE(std::isfinite(polygonArea(p)));
        const glm::dvec3 n = polygonNormal(p);
        EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
        for (const glm::dvec3& x : points)
            for (const glm::dvec3& nx : normals) {
                const double f = pointToPolygonFormFactor(x, nx, p);
                EXPECT_TRUE(std::isfinite(f) && f >= 0.0 && f <= 1.0) << f;
            }
        for (const PatchGeometry& q : polys) {
            const double f = polygonToPolygonFormFactor(p, q, 3);
            EXPECT_TRUE(std::isfinite(f) && f >= 0.0 && f <= 1.0) << f;
        }
        for (const SamplePoint& s : patchSamples(p, 3))
            EXPECT_TRUE(std::isfinite(s.w) && std::isfinite(s.p.x));
    }
    // A point very close above the middle of the square sees almost the full hemisphere.
    EXPECT_NEAR(pointToPolygonFormFactor({0.5, 0.5, 1 - 1e-9}, {0, 0, 1}, sq), 1.0, 1e-8);
}

TEST(FormFactor, PatchSamplesIntegrateLinearFunctionsExactly) {
    const PatchGeometry q = quad({0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {0, 2, 0});  // non-parallelogram
    const PatchGeometry t = tri({0, 0, 0}, {2, 0, 1}, {0, 3, 0});
    for (const PatchGeometry& p : {q, t}) {
        // Linear functions times the (linear) Jacobian are quadratics: exact from order 2.
        for (int order : {2, 4, 7}) {
            const auto s = patchSamples(p, order);
            EXPECT_EQ(s.size(), std::size_t(order * order));
            double wsum = 0.0;
            glm::dvec3 c(0.0);
            for (const SamplePoint& sp : s) {
                wsum += sp.w;
                c += sp.w * sp.p;
                EXPECT_GT(sp.w, 0.0);
            }
            EXPECT_NEAR(wsum, 1.0, 1e-12);
            // The weighted mean of the points is the area centroid.
            glm::dvec3 centroid(0.0);
            double area = 0.0;
            for (int i = 1; i + 1 < p.n; ++i) {
                const double a =
                    0.5 * glm::length(glm::cross(p.v[i] - p.v[0], p.v[i + 1] - p.v[0]));
                centroid += a * (p.v[0] + p.v[i] + p.v[i + 1]) / 3.0;
                area += a;
            }
            centroid /= area;
            EXPECT_NEAR(glm::length(c - centroid), 0.0, 1e-12) << order;
        }
    }
    // Second moment over the unit square: mean of x^2 is 1/3, exact from order 2.
    const PatchGeometry unit = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    double m2 = 0.0;
    for (const SamplePoint& sp : patchSamples(unit, 2)) m2 += sp.w * sp.p.x * sp.p.x;
    EXPECT_NEAR(m2, 1.0 / 3.0, 1e-14);
}

TEST(FormFactor, PointApproximation) {
    // Small source square (side 0.05) at distance 10, both tilted: the point form matches the
    // exact polygon factor to well under 1%.
    const double s = 0.05, d = 10.0;
    const glm::dvec3 x(0, 0, 0);
    const glm::dvec3 nx = glm::normalize(glm::dvec3(0.3, 0, 1));
    const PatchGeometry src = quad({0, 0, d}, {0, s, d}, {s, s, d + 0.5 * s}, {s, 0, d + 0.5 * s});
    const glm::dvec3 c = 0.25 * (src.v[0] + src.v[1] + src.v[2] + src.v[3]);
    const glm::dvec3 dir = glm::normalize(c - x);
    const double gs = std::max(0.0, glm::dot(polygonNormal(src), -dir));
    const double gr = std::max(0.0, glm::dot(nx, dir));
    const double exact = pointToPolygonFormFactor(x, nx, src);
    const double approx = pointApproxFormFactor(polygonArea(src), gs, gr, glm::dot(c - x, c - x));
    EXPECT_NEAR(approx, exact, 1e-3 * exact);
    // Isotropic cluster on both ends: A / (16 pi d^2).
    EXPECT_NEAR(pointApproxFormFactor(2.0, 0.25, 0.25, 9.0), 2.0 / (16 * kPi * 9.0), 1e-15);
    // Never above one, never NaN.
    EXPECT_EQ(pointApproxFormFactor(100.0, 1.0, 1.0, 1e-6), 1.0);
    EXPECT_EQ(pointApproxFormFactor(1.0, 1.0, 1.0, 0.0), 1.0);
    EXPECT_EQ(pointApproxFormFactor(1.0, 0.0, 1.0, 0.0), 0.0);
}

}  // namespace
}  // namespace rad
