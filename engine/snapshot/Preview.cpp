#include "radiosity/Scene.h"
#include "radiosity/Snapshot.h"

namespace rad {

MeshSnapshot makePreviewSnapshot(const Scene& scene) {
    MeshSnapshot mesh;
    mesh.origin = displayOrigin(scene);
    mesh.fileOrigin = scene.fileOrigin;
    for (const Polygon& p : scene.polygons) {
        const Material& m = scene.materials[p.material];
        const glm::vec3 color(m.reflectance + m.emission);
        const glm::vec3 normal(p.normal());
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        for (int i = 0; i < p.vertexCount; ++i) {
            mesh.positions.emplace_back(p.vertices[i] - mesh.origin);
            mesh.normals.push_back(normal);
            mesh.colors.push_back(color);
        }
        for (int i = 1; i + 1 < p.vertexCount; ++i) {
            mesh.indices.insert(mesh.indices.end(), {base, base + i, base + i + 1});
        }
    }
    return mesh;
}

}  // namespace rad
