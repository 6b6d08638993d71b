#include "radiosity/Scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace rad {

namespace {

// sRGB-encoded 8-bit values to linear, once: every element of a textured
// polygon samples its texels.
const std::array<double, 256>& linearOfSrgb() {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double c = i / 255.0;
            t[i] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        }
        return t;
    }();
    return table;
}

// A texel index along one axis of n texels, wrapped.
std::uint32_t wrapIndex(std::int64_t i, std::uint32_t n, Texture::Wrap wrap) {
    const auto m = static_cast<std::int64_t>(n);
    switch (wrap) {
        case Texture::Wrap::Clamp: return static_cast<std::uint32_t>(std::clamp<std::int64_t>(i, 0, m - 1));
        case Texture::Wrap::Mirror: {
            const std::int64_t p = ((i % (2 * m)) + 2 * m) % (2 * m);
            return static_cast<std::uint32_t>(p < m ? p : 2 * m - 1 - p);
        }
        case Texture::Wrap::Repeat: break;
    }
    return static_cast<std::uint32_t>(((i % m) + m) % m);
}

}  // namespace

glm::dvec3 Texture::texel(const glm::dvec2& uv) const {
    if (width == 0 || height == 0) return glm::dvec3(1.0);
    const double x = std::floor(uv.x * width), y = std::floor(uv.y * height);
    if (!std::isfinite(x) || !std::isfinite(y) || std::abs(x) > 1e15 || std::abs(y) > 1e15) return glm::dvec3(0.0);
    const std::size_t at = (std::size_t(wrapIndex(static_cast<std::int64_t>(y), height, wrapV)) * width +
                            wrapIndex(static_cast<std::int64_t>(x), width, wrapU)) * 4;
    const std::array<double, 256>& linear = linearOfSrgb();
    return glm::dvec3(linear[srgba[at]], linear[srgba[at + 1]], linear[srgba[at + 2]]);
}

glm::dvec3 Texture::mean() const {
    if (width == 0 || height == 0) return glm::dvec3(1.0);
    const std::array<double, 256>& linear = linearOfSrgb();
    glm::dvec3 sum(0.0);
    const std::size_t n = std::size_t(width) * height;
    for (std::size_t i = 0; i < n; ++i)
        sum += glm::dvec3(linear[srgba[4 * i]], linear[srgba[4 * i + 1]], linear[srgba[4 * i + 2]]);
    return sum / double(n);
}

glm::dvec3 Polygon::normal() const {
    // Newell's method: robust for any planar polygon. Relative to the first
    // vertex, so that its rounding is relative to the polygon's size, not to
    // its distance from the origin (a 8 cm facet 1 km away lost 1e-8 of its
    // normal to cancellation, 2% at 1000 km).
    glm::dvec3 n(0.0);
    for (int i = 1; i + 1 < vertexCount; ++i) n += glm::cross(vertices[i] - vertices[0], vertices[i + 1] - vertices[0]);
    const double len = glm::length(n);
    return len > 0.0 ? n / len : glm::dvec3(0.0);
}

double Polygon::area() const {
    glm::dvec3 n(0.0);
    for (int i = 1; i + 1 < vertexCount; ++i) n += glm::cross(vertices[i] - vertices[0], vertices[i + 1] - vertices[0]);
    return 0.5 * glm::length(n);  // as normal(): relative to the first vertex
}

glm::dvec3 Polygon::centroid() const {
    // Fan triangulation from vertex 0, weighted by triangle area.
    glm::dvec3 c(0.0);
    double total = 0.0;
    for (int i = 1; i + 1 < vertexCount; ++i) {
        const double a = 0.5 * glm::length(glm::cross(vertices[i] - vertices[0], vertices[i + 1] - vertices[0]));
        c += a * (vertices[0] + vertices[i] + vertices[i + 1]) / 3.0;
        total += a;
    }
    if (total <= 0.0) return vertices[0];
    return c / total;
}

Aabb Scene::bounds() const {
    Aabb box;
    for (const Polygon& p : polygons)
        for (int i = 0; i < p.vertexCount; ++i) box.extend(p.vertices[i]);
    return box;
}

double Scene::area() const {
    double a = 0.0;
    for (const Polygon& p : polygons) a += p.area();
    return a;
}

namespace {

// Per axis, the value at `share` of the polygons' centroids, in order.
glm::dvec3 centroidQuantile(const std::vector<Polygon>& polygons, double share) {
    glm::dvec3 out(0.0);
    std::vector<double> values(polygons.size());
    for (int axis = 0; axis < 3; ++axis) {
        for (std::size_t i = 0; i < polygons.size(); ++i) values[i] = polygons[i].centroid()[axis];
        const auto at = values.begin() + static_cast<std::ptrdiff_t>(share * double(values.size() - 1) + 0.5);
        std::nth_element(values.begin(), at, values.end());
        out[axis] = *at;
    }
    return out;
}

}  // namespace

glm::dvec3 Scene::detailCentre() const {
    return polygons.empty() ? bounds().center() : centroidQuantile(polygons, 0.5);
}

Aabb Scene::detailBounds() const {
    if (polygons.empty()) return bounds();
    Aabb box;
    box.extend(centroidQuantile(polygons, 0.01));
    box.extend(centroidQuantile(polygons, 0.99));
    return box;
}

Aabb Scene::objectBounds(std::uint32_t object) const {
    Aabb box;
    const Object& o = objects.at(object);
    for (std::uint32_t i = o.firstPolygon; i < o.firstPolygon + o.polygonCount; ++i)
        for (int k = 0; k < polygons[i].vertexCount; ++k) box.extend(polygons[i].vertices[k]);
    return box;
}

std::optional<std::uint32_t> Scene::findObject(const std::string& name) const {
    for (std::uint32_t i = 0; i < objects.size(); ++i)
        if (objects[i].name == name) return i;
    return std::nullopt;
}

std::optional<std::uint32_t> Scene::findLight(const std::string& name) const {
    for (std::uint32_t i = 0; i < lights.size(); ++i)
        if (lights[i].name == name) return i;
    return std::nullopt;
}

double PunctualLight::falloff(const glm::dvec3& toward) const { return cone()(toward); }

PunctualLight::Cone PunctualLight::cone() const {
    if (type == Type::Point) return {};
    return {direction, std::cos(innerCone), std::cos(outerCone), true};
}

double PunctualLight::Cone::operator()(const glm::dvec3& toward) const {
    if (!spot) return 1.0;
    const double c = glm::dot(direction, toward);
    if (c >= cosInner) return 1.0;
    if (c <= cosOuter) return 0.0;
    const double t = (c - cosOuter) / std::max(1e-12, cosInner - cosOuter);
    return t * t;
}

double PunctualLight::solidAngle() const {
    if (type == Type::Point) return 4.0 * std::numbers::pi;
    // Inside the inner cone 2 pi (1 - cos inner); over the ramp, the square
    // of a linear ramp in cos integrates to a third of its width.
    const double cosInner = std::cos(innerCone), cosOuter = std::cos(outerCone);
    return 2.0 * std::numbers::pi * ((1.0 - cosInner) + (cosInner - cosOuter) / 3.0);
}

bool Scene::hasEmitter() const {
    for (const PunctualLight& l : lights)
        if (l.power() > 0.0) return true;
    for (const Polygon& p : polygons) {
        const glm::dvec3& e = materials[p.material].emission;
        if (e.x > 0.0 || e.y > 0.0 || e.z > 0.0) return true;
    }
    return false;
}

const Aabb& ObjectBoxes::of(const Scene& scene, std::uint32_t object) {
    if (scene_ != &scene || boxes_.size() != scene.objects.size()) {
        scene_ = &scene;
        boxes_.assign(scene.objects.size(), Aabb{});
        at_.assign(scene.objects.size(), glm::dmat4(std::numeric_limits<double>::quiet_NaN()));  // equals nothing
    }
    if (at_[object] != scene.objects[object].worldFromLocal) {
        boxes_[object] = scene.objectBounds(object);
        at_[object] = scene.objects[object].worldFromLocal;
    }
    return boxes_[object];
}

Aabb ObjectBoxes::all(const Scene& scene) {
    Aabb box;
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) box.extend(of(scene, o));
    return box;
}

}  // namespace rad
