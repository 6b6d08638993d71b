// The window: GLFW + Vulkan swapchain + Dear ImGui, drawing the engine
// thread's newest snapshot every frame.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "cli/Warnings.h"
#include "image/Image.h"
#include "render/CameraView.h"
#include "render/GpuTextures.h"
#include "render/MeshRenderer.h"
#include "render/OffscreenRenderer.h"
#include "render/VulkanContext.h"
#include "render/WindowRenderer.h"
#include "radiosity/Gltf.h"
#include "ui/Gizmo.h"
#include "ui/Panels.h"
#include "viewer/EngineThread.h"
#include "viewer/LightMarkers.h"
#include "viewer/OrbitCamera.h"
#include "viewer/UndoHistory.h"
#include "viewer/ViewerOptions.h"
#include "image/Exposure.h"

namespace rad::viewer {
namespace {

// After a light's name in the panel (the list, "selected:").
constexpr const char* kLightMark = " (light)";

constexpr const char* kNoDisplay =
    "radiosity-viewer: no display (DISPLAY is not set); use radiosity-cli for headless work "
    "(radiosity-cli --help)";

// What a frame draws: the engine's newest mesh and the textures of its
// snapshot, held together so that WindowRenderer::endFrame keeps both alive
// until the GPU has finished the frame. A new mesh shares the textures of the
// one before when its snapshot has the same texture list (the usual case:
// moves and edits change colours, not images).
struct GpuScene {
    std::shared_ptr<const GpuMesh> mesh;
    std::shared_ptr<const GpuTextures> textures;
};

struct KeyEvents {
    bool toggleLinks = false, toggleChanged = false, quit = false, undo = false, redo = false, widen = false;
};

struct GlfwSession {
    GlfwSession() : ok(glfwInit() == GLFW_TRUE) {}
    ~GlfwSession() {
        if (ok) glfwTerminate();
    }
    bool ok;
};

struct WindowHandle {
    GLFWwindow* window = nullptr;
    ~WindowHandle() {
        if (window) glfwDestroyWindow(window);
    }
};

// Owns the ImGui context and its backends for the window's lifetime.
struct ImGuiSession {
    VkDevice device = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    bool glfw = false, vulkan = false;
    ~ImGuiSession() {
        if (vulkan) ImGui_ImplVulkan_Shutdown();
        if (glfw) ImGui_ImplGlfw_Shutdown();
        if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
        if (pool != VK_NULL_HANDLE) vkDestroyDescriptorPool(device, pool, nullptr);
    }
};

void checkImGuiVk(VkResult r) {
    if (r < 0) throw std::runtime_error("ImGui Vulkan backend: " + vkResultName(r));
}

// dir/stem-suffix.ext, then -1, -2 ... until the name is free. Beside the
// scene when that folder is writable, else in the current directory.
std::string freeOutputPath(const std::string& scenePath, const std::string& suffix, const std::string& ext) {
    namespace fs = std::filesystem;
    fs::path dir = fs::path(scenePath).parent_path();
    if (dir.empty()) dir = ".";
    if (access(dir.c_str(), W_OK) != 0) dir = ".";
    const std::string stem = fs::path(scenePath).stem().string();
    for (int i = 0;; ++i) {
        std::string name = stem;
        name += suffix;
        if (i > 0) {
            name += '-';
            name += std::to_string(i);
        }
        name += ext;
        const fs::path p = dir / name;
        if (!fs::exists(p)) return p.string();
    }
}

}  // namespace

int runViewer(const ViewerOptions& options) {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
        std::puts(kNoDisplay);
        return 1;
    }
    glfwSetErrorCallback(nullptr);
    GlfwSession glfw;
    if (!glfw.ok) {
        std::string line = "radiosity-viewer: no display (cannot open DISPLAY=";
        line += display;
        line += "); use radiosity-cli for headless work (radiosity-cli --help)";
        std::puts(line.c_str());
        return 1;
    }
    if (!glfwVulkanSupported()) throw std::runtime_error("GLFW finds no Vulkan loader");

    ImportNotes notes;
    Scene scene = loadGltf(options.scene, &notes);
    std::vector<std::string> importWarnings;
    for (const Warning& w : cli::importWarnings(notes)) importWarnings.push_back(w.message);
    const Aabb sceneBounds = scene.bounds();
    const std::string sceneName = std::filesystem::path(options.scene).filename().string();

    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    WindowHandle win;
    std::string title = "radiosity-viewer - ";
    title += sceneName;
    win.window = glfwCreateWindow(options.width, options.height, title.c_str(), nullptr, nullptr);
    if (!win.window) throw std::runtime_error("cannot create a window");
    GLFWwindow* window = win.window;
    // Keys arrive through a callback (ImGui chains to it), so short taps are
    // never missed or seen twice.
    KeyEvents keys;
    glfwSetWindowUserPointer(window, &keys);
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
        if (action != GLFW_PRESS) return;
        auto* k = static_cast<KeyEvents*>(glfwGetWindowUserPointer(w));
        if (key == GLFW_KEY_L) k->toggleLinks = true;
        if (key == GLFW_KEY_C) k->toggleChanged = true;
        if (key == GLFW_KEY_Q && (mods & GLFW_MOD_CONTROL)) k->quit = true;
        if (key == GLFW_KEY_Z && (mods & GLFW_MOD_CONTROL)) ((mods & GLFW_MOD_SHIFT) ? k->redo : k->undo) = true;
        if (key == GLFW_KEY_P && !(mods & (GLFW_MOD_CONTROL | GLFW_MOD_ALT | GLFW_MOD_SUPER))) k->widen = true;
    });

    // Vulkan: instance with the surface extensions, a device that presents.
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VulkanContextOptions vo;
    vo.applicationName = "radiosity-viewer";
    std::uint32_t extCount = 0;
    const char** exts = glfwGetRequiredInstanceExtensions(&extCount);
    for (std::uint32_t i = 0; i < extCount; ++i) vo.instanceExtensions.emplace_back(exts[i]);
    vo.deviceExtensions.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    vo.onInstanceCreated = [&](VkInstance instance) {
        vkCheck(glfwCreateWindowSurface(instance, window, nullptr, &surface), "glfwCreateWindowSurface");
    };
    vo.queueFamilyFilter = [&](VkInstance, VkPhysicalDevice pd, std::uint32_t family) {
        VkBool32 supported = VK_FALSE;
        return vkGetPhysicalDeviceSurfaceSupportKHR(pd, family, surface, &supported) == VK_SUCCESS &&
               supported == VK_TRUE;
    };
    auto context = std::make_unique<VulkanContext>(vo);
    const auto validationMessages = context->validationMessageCounter();
    struct SurfaceGuard {
        VkInstance instance;
        VkSurfaceKHR& surface;
        ~SurfaceGuard() {
            if (surface != VK_NULL_HANDLE) vkDestroySurfaceKHR(instance, surface, nullptr);
        }
    };
    int exitCode = 0;
    {
        SurfaceGuard surfaceGuard{context->instance(), surface};
        auto framebufferSize = [window] {
            int w = 0, h = 0;
            glfwGetFramebufferSize(window, &w, &h);
            return VkExtent2D{static_cast<std::uint32_t>(std::max(w, 0)), static_cast<std::uint32_t>(std::max(h, 0))};
        };
        WindowRenderer windowRenderer(*context, surface, framebufferSize);
        MeshRenderer meshRenderer(*context, windowRenderer.renderPass(), windowRenderer.shaderOutput());
        std::optional<OffscreenRenderer> offscreen;

        // Dear ImGui.
        ImGuiSession imgui;
        imgui.device = context->device();
        {
            const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8};
            auto info = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
            info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
            info.maxSets = 8;
            info.poolSizeCount = 1;
            info.pPoolSizes = &size;
            vkCheck(vkCreateDescriptorPool(context->device(), &info, nullptr, &imgui.pool), "vkCreateDescriptorPool");
        }
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        ImGui::StyleColorsDark();
        if (windowRenderer.srgb()) ui::linearizeStyleColors();
        imgui.glfw = ImGui_ImplGlfw_InitForVulkan(window, true);
        ImGui_ImplVulkan_InitInfo ii{};
        ii.Instance = context->instance();
        ii.PhysicalDevice = context->physicalDevice();
        ii.Device = context->device();
        ii.QueueFamily = context->queueFamily();
        ii.Queue = context->queue();
        ii.DescriptorPool = imgui.pool;
        ii.Subpass = 0;
        ii.MinImageCount = windowRenderer.minImageCount();
        ii.ImageCount = windowRenderer.imageCount();
        ii.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
        ii.CheckVkResultFn = checkImGuiVk;
        imgui.vulkan = ImGui_ImplVulkan_Init(&ii, windowRenderer.renderPass());
        context->runOneShot([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
        ImGui_ImplVulkan_DestroyFontUploadObjects();
        std::uint64_t imguiGeneration = windowRenderer.swapchainGeneration();

        // The engine thread.
        EngineThreadOptions eo;
        eo.targetFps = options.targetFps;
        eo.overlays = options.overlays;
        eo.select = options.select;
        if (options.logTransforms)
            eo.log = [](const std::string& line) {
                std::printf("%s\n", line.c_str());
                std::fflush(stdout);
            };
        EngineThread engine(Scene(scene), options.engine, eo);

        // View state.
        int fbw = 0, fbh = 0;
        glfwGetFramebufferSize(window, &fbw, &fbh);
        OrbitCamera camera(sceneCameraOrAutoFit(scene, double(fbw) / std::max(fbh, 1)), sceneBounds);
        ui::PanelControls controls;
        controls.targetFps = static_cast<float>(options.targetFps);
        controls.epsilon = static_cast<float>(options.engine.epsilon);
        controls.exposure = static_cast<float>(options.exposure);
        bool exposureChosen = options.exposureGiven;
        controls.showLinks = options.overlays.modifiedLinks;
        controls.showChanged = options.overlays.changedElements;
        ui::Gizmo gizmo;
        std::map<std::uint32_t, glm::dmat4> sent;  // the last transform sent per object
        std::string controlsOf;           // the object whose colour and light the controls hold
        UndoHistory history;
        std::vector<std::pair<std::uint32_t, glm::dmat4>> dragFrom;  // a gizmo drag: where the selection began
        std::set<std::string> emitters;   // objects seen emitting: dimmed to 0 they keep their light controls
        std::string lastMessage;
        bool leftOnScene = false, leftDragged = false;
        std::optional<std::uint32_t> gizmoPrintedFor;  // --print-gizmo: the selection last printed
        bool objectsPrinted = false;

        // The GPU copy of the engine's newest mesh and its textures. Exposure
        // is a draw option: moving the slider uploads nothing.
        std::shared_ptr<const GpuScene> gpuScene;
        std::shared_ptr<const MeshSnapshot> gpuSource;
        // --log-transforms: lines printed once a frame drawing what they say
        // has finished (scripts wait for them before a screenshot):
        // "viewer: shown overlays links=L changed=C" for a mesh with other
        // overlays than the last such line said, and "viewer: shown caught up
        // after M moves" for the picture of an engine with nothing left to do.
        struct ShownLine {
            std::string text;           // empty: nothing waits to be shown
            std::uint64_t drawnIn = 0;  // the frame that draws it, once recorded
        };
        ShownLine overlaysShown, caughtUpShown;
        SnapshotOverlays overlaysLogged, overlaysToLog;
        std::optional<std::uint64_t> caughtUpQueued;  // moves of the last caught-up picture queued

        auto pending = options.screenshots;
        std::sort(pending.begin(), pending.end());
        const auto start = std::chrono::steady_clock::now();
        double firstMeshAt = -1.0;

        while (!glfwWindowShouldClose(window)) {
            glfwPollEvents();
            const double now = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const std::shared_ptr<const ViewerSnapshot> snap = engine.latest();

            // Upload a new picture when the engine published one.
            if (snap->mesh && snap->mesh != gpuSource) {
                gpuSource = snap->mesh;
                // The textures a frame in flight may still sample stay alive
                // with that frame's GpuScene.
                std::shared_ptr<const GpuTextures> textures = gpuScene ? gpuScene->textures : nullptr;
                if (!textures || !textures->sameSources(snap->mesh->textures))
                    textures = std::make_shared<const GpuTextures>(*context, snap->mesh->textures);
                gpuScene = std::make_shared<const GpuScene>(
                    GpuScene{std::make_shared<const GpuMesh>(*context, *snap->mesh), std::move(textures)});
                if (firstMeshAt < 0.0) firstMeshAt = now;
                if (options.logTransforms && (snap->overlays.modifiedLinks != overlaysLogged.modifiedLinks ||
                                              snap->overlays.changedElements != overlaysLogged.changedElements)) {
                    overlaysToLog = snap->overlays;
                    overlaysShown = {"viewer: shown overlays links=" + std::to_string(int(overlaysToLog.modifiedLinks)) +
                                         " changed=" + std::to_string(int(overlaysToLog.changedElements)),
                                     0};
                }
            }
            // A caught-up snapshot may bring no new mesh: it is shown once
            // the picture drawn is its mesh.
            if (options.logTransforms && snap->caughtUp && snap->mesh && snap->mesh == gpuSource &&
                caughtUpQueued != snap->moves) {
                caughtUpQueued = snap->moves;
                caughtUpShown = {"viewer: shown caught up after " + std::to_string(snap->moves) + " moves", 0};
            }
            for (ShownLine* line : {&overlaysShown, &caughtUpShown})
                if (!line->text.empty() && line->drawnIn > 0 && windowRenderer.finishedFrames() >= line->drawnIn) {
                    std::printf("%s\n", line->text.c_str());
                    std::fflush(stdout);
                    if (line == &overlaysShown) overlaysLogged = overlaysToLog;
                    line->text.clear();
                }

            if (windowRenderer.swapchainGeneration() != imguiGeneration) {
                ImGui_ImplVulkan_SetMinImageCount(windowRenderer.minImageCount());
                imguiGeneration = windowRenderer.swapchainGeneration();
            }
            ImGui_ImplVulkan_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();

            // The panel.
            ui::PanelState ps;
            ps.sceneName = sceneName;
            ps.solving = snap->solving;
            // A finished solve that did not converge (diverged, memory limit)
            // shows its message as an error: the picture is not the answer.
            const bool solved = !snap->solving && snap->error.empty() && snap->solve.polygons > 0;
            ps.error = !snap->error.empty() || (solved && !snap->solve.converged);
            if (!snap->error.empty()) {
                ps.status = snap->error;
            } else if (snap->solving) {
                ps.status = "solving: ";
                ps.status += snap->progress;
                ps.progress = static_cast<float>(snap->progressFraction);
                ps.progressText = std::to_string(static_cast<int>(std::floor(100.0 * snap->progressFraction))) + "%";
                if (snap->secondsLeft)
                    ps.progressText += ", about " + std::to_string(std::max(1L, std::lround(*snap->secondsLeft))) + " s left";
            } else {
                ps.status = snap->progress;
            }
            // A scene in photometric units (Blender's) is white at exposure
            // 0: without --exposure, the first solution picks the exposure
            // that shows nine in ten of its vertices under white.
            if (solved && !exposureChosen && snap->mesh) {
                exposureChosen = true;
                // The vertices drawn (not the room the mesh's slots keep to grow in).
                const std::vector<glm::vec3> colors = compactMesh(*snap->mesh).colors;
                std::vector<float> peaks(colors.size());
                for (std::size_t i = 0; i < peaks.size(); ++i) peaks[i] = std::max({colors[i].r, colors[i].g, colors[i].b});
                if (const std::optional<double> ev = exposureThatShows(std::move(peaks), 0.0)) {
                    controls.exposure = static_cast<float>(*ev);
                    char text[96];
                    std::snprintf(text, sizeof text, "exposure set to %g EV: most of the light was past white", *ev);
                    lastMessage = text;
                }
            }
            // First, about the selected object: one the import cut (not
            // marked dynamic, sunk into others) shows its holes once dragged,
            // said as the CLI says it.
            ps.warnings.clear();
            if (snap->selected && *snap->selected < snap->objects.size() && !snap->objects[*snap->selected].light)
                for (const Warning& w : cli::movedCutObjects(scene, {snap->objects[*snap->selected].name}))
                    ps.warnings.push_back(w.message);
            ps.warnings.insert(ps.warnings.end(), importWarnings.begin(), importWarnings.end());
            if (solved)
                for (const Warning& w : snap->solve.warnings) ps.warnings.push_back(w.message);
            ps.polygons = snap->solve.polygons;
            ps.elements = snap->solve.elements;
            ps.links = snap->solve.links;
            ps.passiveLinks = snap->solve.passiveLinks;
            ps.memoryBytes = snap->memory.total();
            ps.solveSeconds = snap->solve.refineSeconds + snap->solve.solveSeconds;
            ps.budget = snap->budget;
            ps.budgetUnlimited = snap->budget == kUnlimited;
            ps.moves = snap->moves;
            ps.pending = snap->frame.pending + snap->frame.stale + snap->frame.unsent;
            ps.linksUpdated = snap->frame.linksUpdated;
            ps.lastUpdateMs = snap->frame.totalSeconds * 1e3;
            ps.publishMs = snap->publishSeconds * 1e3;
            ps.estimatedError = snap->frame.estimatedError;
            if (snap->mesh) {
                ps.overlayLinks = snap->mesh->modifiedLinks;
                ps.overlayLinksShown = snap->mesh->modifiedLinksShown;
            }
            for (const UpdateSample& u : snap->updateTimes)
                if (u.time >= snap->updateTimes.back().time - 5.0) ps.updateMs.push_back(static_cast<float>(u.seconds * 1e3));
            const ObjectInfo* selected =
                snap->selected && *snap->selected < snap->objects.size() ? &snap->objects[*snap->selected] : nullptr;
            // Lights are listed and shown with a mark (they cannot be clicked:
            // the list selects them).
            const auto label = [](const ObjectInfo& o) {
                std::string text = o.name;
                if (o.light) text += kLightMark;
                return text;
            };
            if (selected) {
                ps.selected = label(*selected);
                ps.movable = selected->movable;
                ps.light = selected->light;
                ps.emitter = selected->light ||
                             std::max({selected->emission.x, selected->emission.y, selected->emission.z}) > 0.0 ||
                             emitters.count(selected->name);
                if (selected->emission != glm::dvec3(0.0)) emitters.insert(selected->name);  // dimmed to 0, still a light
                // A new selection: its colour and light fill the controls.
                if (controlsOf != selected->name) {
                    controlsOf = selected->name;
                    for (int k = 0; k < 3; ++k) controls.reflectance[k] = static_cast<float>(selected->reflectance[k]);
                    const double intensity = std::max({selected->emission.x, selected->emission.y, selected->emission.z});
                    controls.emissionIntensity = static_cast<float>(intensity);
                    for (int k = 0; k < 3; ++k)
                        controls.emissionColor[k] =
                            intensity > 0.0 ? static_cast<float>(selected->emission[k] / intensity) : 1.0f;
                }
            } else {
                controlsOf.clear();
            }
            for (const ObjectInfo& o : snap->objects)
                if (o.movable) ps.movableObjects.push_back(label(o));
            ps.selectionCount = snap->selection.size();
            ps.selectionNote = snap->selectionNote;
            ps.lastMessage = lastMessage;
            ui::PanelActions actions = ui::drawPanels(ps, controls);
            // An edit, with the command that takes it back.
            const auto edit = [&](const EditMaterial& e, const EditMaterial& before) {
                engine.post(e);
                history.record(Command(std::in_place_type<EditMaterial>, before), Command(std::in_place_type<EditMaterial>, e));
            };
            if (selected && selected->light && actions.reflectanceEdited) {
                lastMessage = selected->name;
                lastMessage += " is a light: it has no reflectance";
                actions.reflectanceEdited = false;
            }
            // An edit gives every polygon of the object one value; its undo
            // gives each polygon back its material (an object has several).
            const auto undoOf = [&](const ObjectInfo& o, EditMaterial values) {
                if (o.materials) values = EditMaterial{o.name, std::nullopt, std::nullopt, *o.materials};
                return values;
            };
            if (selected && actions.reflectanceEdited)
                edit(EditMaterial{selected->name, std::nullopt,
                                  glm::dvec3(controls.reflectance[0], controls.reflectance[1], controls.reflectance[2])},
                     undoOf(*selected, EditMaterial{selected->name, std::nullopt, selected->reflectance}));
            if (selected && actions.emissionEdited)
                edit(EditMaterial{selected->name,
                                  double(controls.emissionIntensity) *
                                      glm::dvec3(controls.emissionColor[0], controls.emissionColor[1], controls.emissionColor[2]),
                                  std::nullopt},
                     undoOf(*selected, EditMaterial{selected->name, selected->emission, std::nullopt}));
            if (actions.select) {
                std::string name = *actions.select;  // a light's label back to its name
                for (const ObjectInfo& o : snap->objects)
                    if (o.light && label(o) == name) name = o.name;
                engine.post(SelectObject{name});
            }
            if (actions.targetFpsChanged) engine.post(SetTargetFps{controls.targetFps});
            if (actions.epsilonCommitted) engine.post(SetEpsilon{controls.epsilon});
            // Keys: L and C toggle the overlays, P widens the selection to the
            // parent node, Ctrl+Q closes the window.
            if (!io.WantCaptureKeyboard) {
                if (keys.toggleLinks) controls.showLinks = !controls.showLinks;
                if (keys.toggleChanged) controls.showChanged = !controls.showChanged;
                actions.overlaysChanged |= keys.toggleLinks || keys.toggleChanged;
                if (keys.quit) glfwSetWindowShouldClose(window, GLFW_TRUE);
                if (keys.widen) engine.post(WidenSelection{});
            }
            // Ctrl+Z, Ctrl+Shift+Z: post what takes the last action back (or
            // does it again); the gizmo and the colour controls follow.
            if (!io.WantCaptureKeyboard && (keys.undo || keys.redo) && !gizmo.dragging())
                if (const std::optional<Command> c = keys.undo ? history.undo() : history.redo()) {
                    if (const auto* t = std::get_if<SetTransform>(&*c)) sent[t->object] = t->worldFromLocal;
                    if (const auto* t = std::get_if<SetTransforms>(&*c))
                        for (const SetTransform& m : t->moves) sent[m.object] = m.worldFromLocal;
                    engine.post(*c);
                    controlsOf.clear();
                }
            keys = KeyEvents{};
            if (actions.overlaysChanged) engine.post(SetOverlays{{controls.showLinks, controls.showChanged}});

            // Camera and view.
            const glm::dvec2 viewport(io.DisplaySize.x, io.DisplaySize.y);
            const double aspect = viewport.y > 0.0 ? viewport.x / viewport.y : 1.0;
            CameraView view = camera.view(aspect);
            const Camera cam = camera.camera();

            // Transforms the engine has applied need no memory any more: a
            // light moved by its lamp (PunctualLight::object) then shows,
            // and drags from, where the engine put it.
            if (!gizmo.dragging())
                std::erase_if(sent, [&](const auto& e) {
                    return e.first < snap->objects.size() && snap->objects[e.first].worldFromLocal == e.second;
                });
            // The gizmo on a movable selection.
            ui::GizmoView gv{view.viewProjection(), viewport, cam.position, cam.up};
            if (selected && selected->movable && gpuScene && !selected->bounds.empty()) {
                const std::uint32_t id = *snap->selected;
                glm::dmat4 current = selected->worldFromLocal;
                glm::dvec3 center = selected->bounds.center();
                if (auto it = sent.find(id); it != sent.end()) {  // the engine may lag behind
                    center = glm::dvec3(it->second * glm::inverse(current) * glm::dvec4(center, 1.0));
                    current = it->second;
                }
                // Where each selected object stands now (what was last sent
                // for it, the engine may lag behind).
                const auto transformOf = [&](std::uint32_t o) {
                    const auto it = sent.find(o);
                    return it != sent.end() ? it->second : snap->objects[o].worldFromLocal;
                };
                std::vector<std::uint32_t> group{id};  // the gizmo's object first
                for (std::uint32_t o : snap->selection)
                    if (o != id && o < snap->objects.size() && snap->objects[o].movable) group.push_back(o);
                const bool wasDragging = gizmo.dragging();
                if (!wasDragging) {
                    dragFrom.clear();
                    for (std::uint32_t o : group) dragFrom.push_back({o, transformOf(o)});
                }
                if (const auto moved = gizmo.update(gv, center, current)) {
                    if (sent.find(id) == sent.end() || sent[id] != *moved) {
                        // The same world motion for the whole selection.
                        const glm::dmat4 delta = *moved * glm::inverse(current);
                        SetTransforms moves;
                        for (std::uint32_t o : group) {
                            const glm::dmat4 m = o == id ? *moved : delta * transformOf(o);
                            moves.moves.push_back({o, m});
                        }
                        for (const SetTransform& m : moves.moves) sent[m.object] = m.worldFromLocal;
                        if (moves.moves.size() == 1)
                            engine.post(moves.moves.front());
                        else
                            engine.post(std::move(moves));
                    }
                }
                // A drag is one step of the undo history, from where it began.
                if (wasDragging && !gizmo.dragging() && !dragFrom.empty()) {
                    SetTransforms back, again;
                    for (const auto& [o, from] : dragFrom) {
                        back.moves.push_back({o, from});
                        again.moves.push_back({o, transformOf(o)});
                    }
                    if (again.moves.front().worldFromLocal != back.moves.front().worldFromLocal) {
                        if (back.moves.size() == 1)
                            history.record(Command(std::in_place_type<SetTransform>, back.moves.front()),
                                           Command(std::in_place_type<SetTransform>, again.moves.front()));
                        else
                            history.record(Command(std::in_place_type<SetTransforms>, back),
                                           Command(std::in_place_type<SetTransforms>, again));
                    }
                    dragFrom.clear();
                }
                if (options.printGizmo && gizmoPrintedFor != id && !snap->solving) {
                    if (const auto h = ui::Gizmo::handlePosition(gv, center, ui::GizmoPart::AxisX)) {
                        int wx = 0, wy = 0;
                        glfwGetWindowPos(window, &wx, &wy);
                        const auto c = ui::Gizmo::handlePosition(gv, center, ui::GizmoPart::None);
                        std::printf("gizmo: x-handle %d %d center %d %d\n", wx + int(std::lround(h->x)),
                                    wy + int(std::lround(h->y)), wx + int(std::lround(c->x)),
                                    wy + int(std::lround(c->y)));
                        std::fflush(stdout);
                        gizmoPrintedFor = id;
                    }
                }
            }

            // Where the lights are (they have no polygons to see): a marker
            // each, over the scene and under the panel and the gizmo, where
            // it was last sent (the engine may lag behind a drag).
            for (std::uint32_t id = 0; id < snap->objects.size() && gpuScene; ++id) {
                const ObjectInfo& o = snap->objects[id];
                if (!o.light) continue;
                const auto it = sent.find(id);
                const glm::dmat4 m = it != sent.end() ? it->second : o.worldFromLocal;
                const glm::dvec3 at(m[3]);
                const auto c = ui::Gizmo::handlePosition(gv, at, ui::GizmoPart::None);
                if (!c) continue;
                std::optional<glm::dvec2> axis;
                if (o.spot) {
                    const double step = 0.05 * std::max(glm::length(at - cam.position), 1e-6);
                    const glm::dvec3 dir = glm::normalize(glm::dmat3(m) * glm::dvec3(0.0, 0.0, -1.0));
                    if (const auto tip = ui::Gizmo::handlePosition(gv, at + step * dir, ui::GizmoPart::None))
                        axis = *tip - *c;
                }
                glm::dvec3 colour = lightMarkerColour(o.emission);
                if (!windowRenderer.srgb())  // ImGui's colours go out as they are: encode them here
                    for (int k = 0; k < 3; ++k)
                        colour[k] = colour[k] <= 0.0031308 ? 12.92 * colour[k] : 1.055 * std::pow(colour[k], 1.0 / 2.4) - 0.055;
                const ImU32 fill = IM_COL32(int(std::lround(255.0 * colour.r)), int(std::lround(255.0 * colour.g)),
                                            int(std::lround(255.0 * colour.b)), 255);
                ImDrawList* draw = ImGui::GetBackgroundDrawList();
                const auto im = [](const glm::dvec2& p) { return ImVec2(float(p.x), float(p.y)); };
                const std::vector<ScreenSegment> marker = lightMarker(*c, axis);
                for (const ScreenSegment& s : marker) draw->AddLine(im(s.a), im(s.b), IM_COL32(0, 0, 0, 255), 4.0f);
                for (const ScreenSegment& s : marker) draw->AddLine(im(s.a), im(s.b), fill, 2.0f);
            }

            // Test hook: where each object's box centre shows, to click on it.
            if (options.printGizmo && !objectsPrinted && !snap->solving && gpuScene) {
                int wx = 0, wy = 0;
                glfwGetWindowPos(window, &wx, &wy);
                for (const ObjectInfo& o : snap->objects)
                    if (o.movable && !o.bounds.empty())
                        if (const auto c = ui::Gizmo::handlePosition(gv, o.bounds.center(), ui::GizmoPart::None))
                            std::printf("object: %s %d %d\n", o.name.c_str(), wx + int(std::lround(c->x)),
                                        wy + int(std::lround(c->y)));
                std::fflush(stdout);
                objectsPrinted = true;
            }

            // Mouse on the scene: orbit, pan, zoom, pick.
            const bool sceneMouse = !io.WantCaptureMouse && gizmo.hovered() == ui::GizmoPart::None && !gizmo.dragging();
            if (ImGui::IsMouseClicked(0)) {
                leftOnScene = sceneMouse;
                leftDragged = false;
            }
            if (leftOnScene && ImGui::IsMouseDown(0)) {
                if (ImGui::IsMouseDragging(0, 3.0f)) leftDragged = true;
                if (leftDragged) camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
            }
            if (leftOnScene && ImGui::IsMouseReleased(0)) {
                if (!leftDragged && viewport.x > 0 && viewport.y > 0) {
                    const glm::dmat4 inv = glm::inverse(view.viewProjection());
                    const glm::dvec2 ndc(2.0 * io.MousePos.x / viewport.x - 1.0, 2.0 * io.MousePos.y / viewport.y - 1.0);
                    const glm::dvec4 n = inv * glm::dvec4(ndc, 0.0, 1.0);
                    const glm::dvec4 f = inv * glm::dvec4(ndc, 1.0, 1.0);
                    const glm::dvec3 dir = glm::normalize(glm::dvec3(f) / f.w - glm::dvec3(n) / n.w);
                    engine.post(PickObject{glm::dvec3(n) / n.w, dir, io.KeyShift});
                }
                leftOnScene = false;
            }
            if (sceneMouse) {
                if (ImGui::IsMouseDragging(1, 1.0f) || ImGui::IsMouseDragging(2, 1.0f))
                    camera.pan(io.MouseDelta.x, io.MouseDelta.y, viewport.y);
                if (io.MouseWheel != 0.0f) camera.zoom(io.MouseWheel);
            }
            view = camera.view(aspect);
            MeshDrawOptions drawOptions;
            drawOptions.exposure = controls.exposure;

            // Buttons.
            if ((actions.saveScreenshot || actions.exportMesh) && !snap->mesh) lastMessage = "nothing to save yet";
            else if (actions.saveScreenshot) {
                try {
                    if (!offscreen) offscreen.emplace(*context);
                    // The mesh on screen, as on screen: exposure included.
                    const Image image = offscreen->render(*gpuScene->mesh, *gpuScene->textures, view.viewProjection(),
                                                          std::max(fbw, 1), std::max(fbh, 1), drawOptions);
                    const std::string path = freeOutputPath(options.scene, "-screenshot", ".png");
                    writeImage(image, path);
                    lastMessage = "saved ";
                    lastMessage += path;
                } catch (const std::exception& e) {
                    lastMessage = e.what();
                }
            } else if (actions.exportMesh) {
                try {
                    const std::string path = freeOutputPath(options.scene, "-lit", ".glb");
                    MeshSnapshot mesh = *snap->mesh;
                    mesh.linePositions.clear();
                    mesh.lineColors.clear();
                    exportGltf(mesh, path);
                    lastMessage = "exported ";
                    lastMessage += path;
                } catch (const std::exception& e) {
                    lastMessage = e.what();
                }
            }

            ImGui::Render();
            glfwGetFramebufferSize(window, &fbw, &fbh);

            // Screenshot hooks wait for the first picture (30 s at most).
            std::string capture;
            if (!pending.empty() && now >= pending.front().first && (firstMeshAt >= 0.0 || now > pending.front().first + 30.0)) {
                capture = pending.front().second;
                pending.erase(pending.begin());
            }
            if (VkCommandBuffer cmd = windowRenderer.beginFrame({0.02f, 0.02f, 0.025f, 1.0f})) {
                if (gpuScene)
                    meshRenderer.draw(cmd, *gpuScene->mesh, *gpuScene->textures, view.viewProjection(),
                                      windowRenderer.extent(), drawOptions);
                ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
                const std::uint64_t serial = windowRenderer.endFrame(gpuScene, capture);
                for (ShownLine* line : {&overlaysShown, &caughtUpShown})
                    if (!line->text.empty() && line->drawnIn == 0 && gpuScene) line->drawnIn = serial;
                if (!capture.empty()) {
                    std::printf("screenshot: %s\n", capture.c_str());
                    std::fflush(stdout);
                }
            } else if (!capture.empty()) {
                pending.insert(pending.begin(), {now, capture});  // try again next frame
            }

            if (options.quitAfter && now >= *options.quitAfter &&
                (pending.empty() || pending.front().first > *options.quitAfter || now > *options.quitAfter + 30.0))
                glfwSetWindowShouldClose(window, GLFW_TRUE);
        }
        engine.stop();
        windowRenderer.waitIdle();
        gpuScene.reset();
    }
    context.reset();  // leaked objects are reported as the device goes
    if (const std::size_t n = *validationMessages; n > 0) {
        std::fprintf(stderr, "radiosity-viewer: the Vulkan validation layer reported %zu message(s)\n", n);
        exitCode = 1;
    }
    return exitCode;
}

}  // namespace rad::viewer
