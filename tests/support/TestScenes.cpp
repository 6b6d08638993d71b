#include "support/TestScenes.h"

namespace rad::test {

std::uint32_t addMaterial(Scene& scene, glm::dvec3 reflectance, glm::dvec3 emission, std::string name) {
    scene.materials.push_back({std::move(name), reflectance, emission});
    return static_cast<std::uint32_t>(scene.materials.size() - 1);
}

std::uint32_t addQuadObject(Scene& scene, const std::string& name, std::uint32_t material,
                            const std::vector<std::array<glm::dvec3, 4>>& quads, bool dynamic) {
    Object o;
    o.name = name;
    o.dynamic = dynamic;
    o.firstPolygon = static_cast<std::uint32_t>(scene.polygons.size());
    const auto index = static_cast<std::uint32_t>(scene.objects.size());
    for (const auto& q : quads) {
        Polygon p;
        p.vertexCount = 4;
        p.vertices = q;
        p.material = material;
        p.object = index;
        scene.polygons.push_back(p);
    }
    o.polygonCount = static_cast<std::uint32_t>(quads.size());
    scene.objects.push_back(o);
    return index;
}

std::vector<std::array<glm::dvec3, 4>> boxFaces(glm::dvec3 lo, glm::dvec3 hi, bool inward) {
    using V = glm::dvec3;
    // Outward-facing (counter-clockwise seen from outside).
    std::vector<std::array<V, 4>> f = {
        {V(lo.x, lo.y, lo.z), V(hi.x, lo.y, lo.z), V(hi.x, lo.y, hi.z), V(lo.x, lo.y, hi.z)},  // -y
        {V(lo.x, hi.y, lo.z), V(lo.x, hi.y, hi.z), V(hi.x, hi.y, hi.z), V(hi.x, hi.y, lo.z)},  // +y
        {V(lo.x, lo.y, lo.z), V(lo.x, lo.y, hi.z), V(lo.x, hi.y, hi.z), V(lo.x, hi.y, lo.z)},  // -x
        {V(hi.x, lo.y, lo.z), V(hi.x, hi.y, lo.z), V(hi.x, hi.y, hi.z), V(hi.x, lo.y, hi.z)},  // +x
        {V(lo.x, lo.y, lo.z), V(lo.x, hi.y, lo.z), V(hi.x, hi.y, lo.z), V(hi.x, lo.y, lo.z)},  // -z
        {V(lo.x, lo.y, hi.z), V(hi.x, lo.y, hi.z), V(hi.x, hi.y, hi.z), V(lo.x, hi.y, hi.z)},  // +z
    };
    if (inward)
        for (auto& q : f) std::swap(q[1], q[3]);
    return f;
}

Scene parallelSquares(double rho) {
    using V = glm::dvec3;
    Scene s;
    s.sourcePath = "parallel-squares";
    const auto light = addMaterial(s, V(0.0), V(1.0), "light");
    const auto grey = addMaterial(s, V(rho), V(0.0), "grey");
    addQuadObject(s, "emitter", light, {{V(0, 1, 0), V(1, 1, 0), V(1, 1, 1), V(0, 1, 1)}});
    addQuadObject(s, "receiver", grey, {{V(0, 0, 0), V(0, 0, 1), V(1, 0, 1), V(1, 0, 0)}});
    return s;
}

Scene perpendicularSquares(double rho) {
    using V = glm::dvec3;
    Scene s;
    s.sourcePath = "perpendicular-squares";
    const auto light = addMaterial(s, V(0.0), V(1.0), "light");
    const auto grey = addMaterial(s, V(rho), V(0.0), "grey");
    addQuadObject(s, "emitter", light, {{V(0, 0, 0), V(0, 1, 0), V(0, 1, 1), V(0, 0, 1)}});
    addQuadObject(s, "receiver", grey, {{V(0, 0, 0), V(0, 0, 1), V(1, 0, 1), V(1, 0, 0)}});
    return s;
}

Scene closedBox(double rho) {
    Scene s;
    s.sourcePath = "closed-box";
    const auto m = addMaterial(s, glm::dvec3(rho), glm::dvec3(1.0), "glowing");
    addQuadObject(s, "box", m, boxFaces(glm::dvec3(0.0), glm::dvec3(1.0), true));
    return s;
}

Scene roomWithBlock(double scale, glm::dvec3 blockOffset) {
    using V = glm::dvec3;
    Scene s;
    s.sourcePath = "room-with-block";
    const auto white = addMaterial(s, V(0.7), V(0.0), "white");
    const auto grey = addMaterial(s, V(0.5, 0.4, 0.3), V(0.0), "block");
    const auto light = addMaterial(s, V(0.0), V(10.0), "light");
    const auto faces = boxFaces(V(0.0), V(4.0, 3.0, 4.0), true);
    const char* names[] = {"floor", "ceiling", "wall-x0", "wall-x4", "wall-z0", "wall-z4"};
    for (int i = 0; i < 6; ++i) addQuadObject(s, names[i], white, {faces[i]});
    addQuadObject(s, "light", light, {{V(1.5, 2.999, 1.5), V(2.5, 2.999, 1.5), V(2.5, 2.999, 2.5), V(1.5, 2.999, 2.5)}});
    const std::uint32_t block = addQuadObject(s, "block", grey, boxFaces(V(1.5, 0.2, 1.5), V(2.2, 0.9, 2.2), false), true);
    for (Polygon& p : s.polygons)
        for (int k = 0; k < p.vertexCount; ++k)
            p.vertices[k] = scale * (p.vertices[k] + (p.object == block ? blockOffset : V(0.0)));
    return s;
}

std::string sourcePath(const std::string& relative) { return std::string(RADIOSITY_SOURCE_DIR) + "/" + relative; }

}  // namespace rad::test
