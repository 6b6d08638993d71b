// Camera matrices: where known points land in Vulkan clip space.

#include <gtest/gtest.h>

#include <cmath>

#include "render/CameraView.h"

namespace rad {
namespace {

// Normalised device coordinates (x right, y down, z depth 0..1).
glm::dvec3 project(const CameraView& view, const glm::dvec3& world) {
    const glm::dvec4 clip = view.viewProjection() * glm::dvec4(world, 1.0);
    return glm::dvec3(clip) / clip.w;
}

Camera lookingAt(const glm::dvec3& position, const glm::dvec3& target) {
    Camera c;
    c.position = position;
    c.forward = glm::normalize(target - position);
    const glm::dvec3 right = glm::normalize(glm::cross(c.forward, glm::dvec3(0, 1, 0)));
    c.up = glm::cross(right, c.forward);
    c.yfov = 0.8;
    c.znear = 0.05;
    return c;
}

Aabb box(glm::dvec3 lo, glm::dvec3 hi) {
    Aabb b;
    b.extend(lo);
    b.extend(hi);
    return b;
}

glm::dvec3 corner(const Aabb& b, int i) {
    return {(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z};
}

TEST(CameraView, LookAtPointMapsToImageCentre) {
    const glm::dvec3 target(0.3, 1.0, -2.0);
    const Camera camera = lookingAt({1.0, 2.0, 5.0}, target);
    const CameraView view = makeCameraView(camera, box({-3, -3, -3}, {3, 3, 3}), 1.5);
    const glm::dvec3 ndc = project(view, target);
    EXPECT_NEAR(ndc.x, 0.0, 1e-9);
    EXPECT_NEAR(ndc.y, 0.0, 1e-9);
    EXPECT_GT(ndc.z, 0.0);
    EXPECT_LT(ndc.z, 1.0);
}

TEST(CameraView, LeftIsLeftAndUpIsUpInTheImage) {
    const glm::dvec3 target(0.0, 0.0, 0.0);
    const Camera camera = lookingAt({4.0, 1.0, 3.0}, target);
    const CameraView view = makeCameraView(camera, box({-1, -1, -1}, {1, 1, 1}), 1.0);
    const glm::dvec3 right = glm::cross(camera.forward, camera.up);
    EXPECT_LT(project(view, target - 0.3 * right).x, 0.0);
    EXPECT_GT(project(view, target + 0.3 * right).x, 0.0);
    // Vulkan's y points down: the image's first row is the top of the view.
    EXPECT_LT(project(view, target + 0.3 * camera.up).y, 0.0);
    EXPECT_GT(project(view, target - 0.3 * camera.up).y, 0.0);
    // Nearer points have smaller depth.
    EXPECT_LT(project(view, target - 0.5 * camera.forward).z, project(view, target).z);
}

TEST(CameraView, AutoFitContainsAllBoundsCornersAtAnyScale) {
    const Aabb boxes[] = {
        box({-1, -1, -1}, {1, 1, 1}),
        box({0, 0, 0}, {0.556, 0.548, 0.559}),               // the Cornell box
        box({0.010, 0.020, -0.001}, {0.012, 0.021, 0.001}),  // millimetres, off the origin
        box({-5000, 0, -3000}, {5000, 800, 3000}),           // kilometres, flat
        box({2, 2, 2}, {2, 2, 2}),                           // a single point
    };
    for (const Aabb& b : boxes) {
        for (double aspect : {1.0, 2.0, 0.5}) {
            SCOPED_TRACE("bounds hi.x " + std::to_string(b.hi.x) + ", aspect " +
                         std::to_string(aspect));
            const Camera camera = autoFitCamera(b, aspect);
            EXPECT_GT(camera.position.z, b.center().z);  // from the +z side
            EXPECT_GT(camera.position.y, b.center().y);  // and a bit above
            const CameraView view = makeCameraView(camera, b, aspect);
            EXPECT_GT(view.znear, 0.0);
            EXPECT_LT(view.znear, view.zfar);
            for (int i = 0; i < 8; ++i) {
                const glm::dvec3 ndc = project(view, corner(b, i));
                EXPECT_GE(ndc.x, -1.0);
                EXPECT_LE(ndc.x, 1.0);
                EXPECT_GE(ndc.y, -1.0);
                EXPECT_LE(ndc.y, 1.0);
                EXPECT_GT(ndc.z, 0.0);
                EXPECT_LT(ndc.z, 1.0);
            }
            const glm::dvec3 centre = project(view, b.center());
            EXPECT_NEAR(centre.x, 0.0, 1e-6);
            EXPECT_NEAR(centre.y, 0.0, 1e-6);
        }
    }
}

TEST(CameraView, NearAndFarFollowTheSceneScale) {
    // Kilometres seen from a camera with the glTF default znear: near grows
    // with far so depth keeps its precision; the whole scene stays inside.
    const Aabb city = box({-5000, 0, -5000}, {5000, 300, 5000});
    const Camera camera = lookingAt({0, 2000, 12000}, {0, 0, 0});
    const CameraView view = makeCameraView(camera, city, 1.0);
    EXPECT_GE(view.znear, view.zfar * 1e-7 * 0.999);
    for (int i = 0; i < 8; ++i) {
        const double z = project(view, corner(city, i)).z;
        EXPECT_GT(z, 0.0);
        EXPECT_LT(z, 1.0);
    }
    // Millimetres: the camera's own small znear is kept.
    Camera close = lookingAt({0, 0, 0.01}, {0, 0, 0});
    close.znear = 0.001;
    const CameraView small =
        makeCameraView(close, box({-0.001, -0.001, -0.001}, {0.001, 0.001, 0.001}), 1.0);
    EXPECT_DOUBLE_EQ(small.znear, 0.001);
    EXPECT_LT(small.zfar, 0.02);
}

TEST(CameraView, SceneCameraWinsOverAutoFit) {
    Scene scene;
    scene.camera = lookingAt({1, 2, 3}, {0, 0, 0});
    EXPECT_EQ(sceneCameraOrAutoFit(scene, 1.0).position, glm::dvec3(1, 2, 3));
    scene.camera.reset();
    const Camera fitted = sceneCameraOrAutoFit(scene, 1.0);  // no polygons: still a usable camera
    EXPECT_TRUE(std::isfinite(fitted.position.x));
}

}  // namespace
}  // namespace rad
