#include "render/VulkanContext.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace rad {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
    auto* count = static_cast<std::atomic<std::size_t>*>(user);
    count->fetch_add(1);
    const char* level =
        severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    std::fprintf(stderr, "vulkan %s: %s\n", level,
                 data && data->pMessage ? data->pMessage : "(no text)");
    return VK_FALSE;  // never abort the call: the count is how failures are reported
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(std::atomic<std::size_t>* count) {
    auto info = vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = onDebugMessage;
    info.pUserData = count;
    return info;
}

bool hasLayer(const char* name) {
    std::uint32_t n = 0;
    vkCheck(vkEnumerateInstanceLayerProperties(&n, nullptr), "vkEnumerateInstanceLayerProperties");
    std::vector<VkLayerProperties> layers(n);
    vkCheck(vkEnumerateInstanceLayerProperties(&n, layers.data()),
            "vkEnumerateInstanceLayerProperties");
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

std::vector<std::string> instanceExtensionNames(const char* layer) {
    std::uint32_t n = 0;
    vkCheck(vkEnumerateInstanceExtensionProperties(layer, &n, nullptr),
            "vkEnumerateInstanceExtensionProperties");
    std::vector<VkExtensionProperties> props(n);
    vkCheck(vkEnumerateInstanceExtensionProperties(layer, &n, props.data()),
            "vkEnumerateInstanceExtensionProperties");
    std::vector<std::string> names;
    for (const auto& p : props) names.emplace_back(p.extensionName);
    return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

std::vector<const char*> cStrings(const std::vector<std::string>& names) {
    std::vector<const char*> out;
    for (const auto& n : names) out.push_back(n.c_str());
    return out;
}

void addUnique(std::vector<std::string>& names, const std::string& name) {
    if (!contains(names, name)) names.push_back(name);
}

}  // namespace

bool validationRequestedByEnvironment() {
    const char* value = std::getenv("RADIOSITY_VALIDATION");
    return value && std::strcmp(value, "1") == 0;
}

VulkanContext::VulkanContext(VulkanContextOptions options) {
    const bool validation = options.validation || validationRequestedByEnvironment();
    // The destructor does not run when a constructor throws: clean up here.
    try {
        createInstance(options, validation);
        if (options.onInstanceCreated) options.onInstanceCreated(instance_);
        pickPhysicalDevice(options);
        createDevice(options);
    } catch (...) {
        destroy();
        throw;
    }
}

VulkanContext::~VulkanContext() { destroy(); }

void VulkanContext::destroy() {
    if (device_) {
        vkDeviceWaitIdle(device_);  // unchecked: nothing to do about a failure while tearing down
        commandPool_ = CommandPool();
        vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (messenger_) {
        auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroyMessenger) destroyMessenger(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) {
        vkDestroyInstance(instance_, nullptr);
        instance_ = VK_NULL_HANDLE;
    }
}

void VulkanContext::createInstance(const VulkanContextOptions& options, bool validation) {
    std::vector<std::string> extensions = options.instanceExtensions;
    std::vector<const char*> layers;
    if (validation) {
        if (!hasLayer(kValidationLayer))
            throw std::runtime_error(
                std::string("validation requested but ") + kValidationLayer +
                " is not installed (Debian: apt-get install vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        addUnique(extensions, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    const std::vector<std::string> available = instanceExtensionNames(nullptr);
    const std::vector<std::string> fromLayer =
        validation ? instanceExtensionNames(kValidationLayer) : std::vector<std::string>{};
    for (const auto& e : extensions)
        if (!contains(available, e) && !contains(fromLayer, e))
            throw std::runtime_error("Vulkan instance extension " + e + " is not available");

    auto app = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = options.applicationName.c_str();
    app.pEngineName = "radiosity";
    app.apiVersion = VK_API_VERSION_1_1;

    // Chained into the create info so that vkCreateInstance/vkDestroyInstance
    // are validated too, before and after the messenger exists.
    VkDebugUtilsMessengerCreateInfoEXT debugInfo = messengerInfo(counter_.get());
    const std::vector<const char*> extensionNames = cStrings(extensions);
    auto info = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pNext = validation ? &debugInfo : nullptr;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensionNames.size());
    info.ppEnabledExtensionNames = extensionNames.data();
    vkCheck(vkCreateInstance(&info, nullptr, &instance_), "vkCreateInstance");

    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create)
            throw std::runtime_error(
                "vkGetInstanceProcAddr(vkCreateDebugUtilsMessengerEXT) failed");
        vkCheck(create(instance_, &debugInfo, nullptr, &messenger_),
                "vkCreateDebugUtilsMessengerEXT");
    }
}

void VulkanContext::pickPhysicalDevice(const VulkanContextOptions& options) {
    std::uint32_t n = 0;
    vkCheck(vkEnumeratePhysicalDevices(instance_, &n, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(n);
    vkCheck(vkEnumeratePhysicalDevices(instance_, &n, devices.data()),
            "vkEnumeratePhysicalDevices");

    int bestScore = -1;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(pd, &props);

        std::uint32_t extCount = 0;
        vkCheck(vkEnumerateDeviceExtensionProperties(pd, nullptr, &extCount, nullptr),
                "vkEnumerateDeviceExtensionProperties");
        std::vector<VkExtensionProperties> exts(extCount);
        vkCheck(vkEnumerateDeviceExtensionProperties(pd, nullptr, &extCount, exts.data()),
                "vkEnumerateDeviceExtensionProperties");
        const bool hasExtensions = std::all_of(
            options.deviceExtensions.begin(), options.deviceExtensions.end(),
            [&](const std::string& e) {
                return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& p) {
                    return e == p.extensionName;
                });
            });
        if (!hasExtensions) continue;

        std::uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, families.data());
        for (std::uint32_t f = 0; f < familyCount; ++f) {
            if (!(families[f].queueFlags & VK_QUEUE_GRAPHICS_BIT)) continue;
            if (options.queueFamilyFilter && !options.queueFamilyFilter(instance_, pd, f)) continue;
            const bool software = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
            int score = 1;
            if (software == options.preferSoftwareDevice) score += 4;
            if (props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU) score += 2;
            if (score > bestScore) {
                bestScore = score;
                physicalDevice_ = pd;
                queueFamily_ = f;
            }
            break;
        }
    }
    if (!physicalDevice_)
        throw std::runtime_error(
            "no Vulkan device with a graphics queue" +
            std::string(options.queueFamilyFilter ? " passing the queue filter" : "") +
            (options.deviceExtensions.empty() ? "" : " and the requested extensions") +
            " (install mesa-vulkan-drivers for lavapipe)");
    vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
}

void VulkanContext::createDevice(const VulkanContextOptions& options) {
    VkPhysicalDeviceFeatures supported;
    vkGetPhysicalDeviceFeatures(physicalDevice_, &supported);
    // Overlays draw wide link lines and wireframe element outlines.
    enabledFeatures_.wideLines = supported.wideLines;
    enabledFeatures_.fillModeNonSolid = supported.fillModeNonSolid;

    const float priority = 1.0f;
    auto queueInfo = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queueInfo.queueFamilyIndex = queueFamily_;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    const std::vector<const char*> extensions = cStrings(options.deviceExtensions);
    auto info = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.pEnabledFeatures = &enabledFeatures_;
    vkCheck(vkCreateDevice(physicalDevice_, &info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

    commandPool_ = CommandPool(device_, queueFamily_, VK_COMMAND_POOL_CREATE_TRANSIENT_BIT);
}

std::uint32_t VulkanContext::findMemoryType(std::uint32_t typeBits,
                                            VkMemoryPropertyFlags required) const {
    for (std::uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) &&
            (memoryProperties_.memoryTypes[i].propertyFlags & required) == required)
            return i;
    throw std::runtime_error("no Vulkan memory type with flags " + std::to_string(required));
}

void VulkanContext::submit(const VkSubmitInfo& info, VkFence fence) const {
    std::lock_guard lock(queueMutex_);
    vkCheck(vkQueueSubmit(queue_, 1, &info, fence), "vkQueueSubmit");
}

void VulkanContext::submit(VkCommandBuffer cmd, VkFence fence) const {
    auto info = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    info.commandBufferCount = 1;
    info.pCommandBuffers = &cmd;
    submit(info, fence);
}

void VulkanContext::runOneShot(const std::function<void(VkCommandBuffer)>& record) const {
    std::lock_guard poolLock(poolMutex_);
    VkCommandBuffer cmd = commandPool_.allocate();
    // Freed on every path, including a throwing record().
    struct FreeOnExit {
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cmd;
        ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } freeOnExit{device_, commandPool_.get(), cmd};

    beginRecording(cmd);
    record(cmd);
    endRecording(cmd);
    const Fence done(device_);
    submit(cmd, done.get());
    done.wait();
}

}  // namespace rad
