#include "support/TestScenes.h"

#include "radiosity/Gltf.h"

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

namespace {

using Quad = std::array<glm::dvec3, 4>;

// An axis-aligned rectangle in the plane `axis` = c, spanning [a0,a1] x [b0,b1]
// in the other two axes (in x, y, z order), facing +axis or -axis.
Quad rectangle(int axis, double c, double a0, double a1, double b0, double b1, bool positive) {
    const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    const auto at = [&](double a, double b) {
        glm::dvec3 p(0.0);
        p[axis] = c;
        p[u] = a;
        p[v] = b;
        return p;
    };
    Quad q = {at(a0, b0), at(a1, b0), at(a1, b1), at(a0, b1)};
    // Turned so that its winding faces the side asked for.
    const glm::dvec3 n = glm::cross(q[1] - q[0], q[3] - q[0]);
    if ((n[axis] > 0.0) != positive) std::swap(q[1], q[3]);
    return q;
}

}  // namespace

glm::dvec3 doorHinge() { return glm::dvec3(1.45, 0.0, 1.96); }

Scene doorwayScene(bool doorDynamic, DoorPlacement placement) {
    using V = glm::dvec3;
    Scene s;
    s.sourcePath = "doorway";
    const auto wall = addMaterial(s, V(0.7), V(0.0), "wall");
    const auto floor = addMaterial(s, V(0.4), V(0.0), "floor");
    const auto light = addMaterial(s, V(0.0), V(12.0), "light");
    const auto paint = addMaterial(s, V(0.6), V(0.0), "door");
    // The corridor: z from 0 to 2, the doorway in its far wall (z = 2).
    addQuadObject(s, "corridor-floor", floor, {rectangle(1, 0.0, 0, 4, 0, 2, true)});
    addQuadObject(s, "corridor-ceiling", wall, {rectangle(1, 2.5, 0, 4, 0, 2, false)});
    addQuadObject(s, "corridor-walls", wall,
                  {rectangle(0, 0.0, 0, 2.5, 0, 2, true), rectangle(0, 4.0, 0, 2.5, 0, 2, false),
                   rectangle(2, 0.0, 0, 4, 0, 2.5, true),
                   rectangle(2, 2.0, 0, 1.5, 0, 2.5, false), rectangle(2, 2.0, 2.5, 4, 0, 2.5, false),
                   rectangle(2, 2.0, 1.5, 2.5, 2, 2.5, false)});
    addQuadObject(s, "corridor-light", light, {rectangle(1, 2.499, 1.5, 2.5, 0.8, 1.2, false)});
    // The doorway's reveal through the wall (z from 2 to 2.1).
    addQuadObject(s, "reveal", wall,
                  {rectangle(0, 1.5, 0, 2, 2.0, 2.1, true), rectangle(0, 2.5, 0, 2, 2.0, 2.1, false),
                   rectangle(1, 2.0, 1.5, 2.5, 2.0, 2.1, false), rectangle(1, 0.0, 1.5, 2.5, 2.0, 2.1, true)});
    // The dark room: z from 2.1 to 5.
    addQuadObject(s, "dark-floor", floor, {rectangle(1, 0.0, 0, 4, 2.1, 5, true)});
    addQuadObject(s, "dark-ceiling", wall, {rectangle(1, 2.5, 0, 4, 2.1, 5, false)});
    addQuadObject(s, "dark-walls", wall,
                  {rectangle(0, 0.0, 0, 2.5, 2.1, 5, true), rectangle(0, 4.0, 0, 2.5, 2.1, 5, false),
                   rectangle(2, 5.0, 0, 4, 0, 2.5, false),
                   rectangle(2, 2.1, 0, 1.5, 0, 2.5, true), rectangle(2, 2.1, 2.5, 4, 0, 2.5, true),
                   rectangle(2, 2.1, 1.5, 2.5, 2, 2.5, true)});
    addQuadObject(s, "dark-block", wall, boxFaces(V(2.8, 0.0, 3.5), V(3.4, 0.8, 4.1), false));
    // The door, faces out, no bottom: in front of the wall x 1.45..2.55, up
    // to 2.05, z 1.96..1.998 (or 2.0, touching); in the reveal x 1.5..2.5,
    // up to 2.0, z 2.03..2.07; behind the wall z 2.102..2.14.
    auto door = placement == DoorPlacement::InTheReveal ? boxFaces(V(1.5, 0.0, 2.03), V(2.5, 2.0, 2.07), false)
                : placement == DoorPlacement::GapBehind   ? boxFaces(V(1.45, 0.0, 2.102), V(2.55, 2.05, 2.14), false)
                                                          : boxFaces(V(1.45, 0.0, placement == DoorPlacement::GapInFront ? 1.96 : 1.962),
                                                                     V(2.55, 2.05, placement == DoorPlacement::GapInFront ? 1.998 : 2.0), false);
    door.erase(door.begin());  // the -y face rests on the floor
    addQuadObject(s, "door", paint, door, doorDynamic);
    return s;
}

Scene roomsThroughAnOpening() {
    using V = glm::dvec3;
    Scene s;
    s.sourcePath = "rooms-through-an-opening";
    const auto white = addMaterial(s, V(0.85), V(0.0), "white");
    const auto floor = addMaterial(s, V(0.5), V(0.0), "floor");
    const auto light = addMaterial(s, V(0.0), V(10.0), "light");
    // A wall in the plane z = c, 4 x 2.6 m, with the opening x 1.6..2.4,
    // y 1.6..2.2, facing +z or -z.
    const auto wallWithOpening = [](double c, bool positive) {
        return std::vector<Quad>{rectangle(2, c, 0, 4, 0, 1.6, positive), rectangle(2, c, 0, 4, 2.2, 2.6, positive),
                                 rectangle(2, c, 0, 1.6, 1.6, 2.2, positive),
                                 rectangle(2, c, 2.4, 4, 1.6, 2.2, positive)};
    };
    // The lit room: z from 0 to 4.
    addQuadObject(s, "lit-floor", floor, {rectangle(1, 0.0, 0, 4, 0, 4, true)});
    std::vector<Quad> lit = {rectangle(1, 2.6, 0, 4, 0, 4, false), rectangle(0, 0.0, 0, 2.6, 0, 4, true),
                             rectangle(0, 4.0, 0, 2.6, 0, 4, false), rectangle(2, 0.0, 0, 4, 0, 2.6, true)};
    for (const Quad& q : wallWithOpening(4.0, false)) lit.push_back(q);
    addQuadObject(s, "lit-walls", white, lit);
    addQuadObject(s, "light", light, {rectangle(1, 2.59, 1.2, 2.8, 1.2, 2.8, false)});
    // The opening's reveal through the wall (z from 4 to 4.2).
    addQuadObject(s, "reveal", white,
                  {rectangle(1, 1.6, 1.6, 2.4, 4.0, 4.2, true), rectangle(1, 2.2, 1.6, 2.4, 4.0, 4.2, false),
                   rectangle(0, 1.6, 1.6, 2.2, 4.0, 4.2, true), rectangle(0, 2.4, 1.6, 2.2, 4.0, 4.2, false)});
    // The dark room: z from 4.2 to 8.2.
    addQuadObject(s, "dark-floor", floor, {rectangle(1, 0.0, 0, 4, 4.2, 8.2, true)});
    addQuadObject(s, "dark-ceiling", white, {rectangle(1, 2.6, 0, 4, 4.2, 8.2, false)});
    std::vector<Quad> dark = {rectangle(0, 0.0, 0, 2.6, 4.2, 8.2, true), rectangle(0, 4.0, 0, 2.6, 4.2, 8.2, false),
                              rectangle(2, 8.2, 0, 4, 0, 2.6, false)};
    for (const Quad& q : wallWithOpening(4.2, true)) dark.push_back(q);
    addQuadObject(s, "dark-walls", white, dark);
    addQuadObject(s, "dark-block", white, boxFaces(V(2.5, 0.0, 6.0), V(3.3, 0.8, 6.8), false));
    return s;
}

std::string sourcePath(const std::string& relative) { return std::string(RADIOSITY_SOURCE_DIR) + "/" + relative; }

Scene office() { return loadGltf(sourcePath("scenes/office.gltf")); }

}  // namespace rad::test
