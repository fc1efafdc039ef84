#include "panel.hpp"

#include "params.hpp"

#include <tressvk/engine/check.hpp>
#include <tressvk/model/planner.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <cstdio>
#include <exception>

namespace tressvk::viewer {

namespace {

void check_result(VkResult r) {
  if (r < 0) std::fprintf(stderr, "tressvk-viewer: ImGui Vulkan backend: VkResult %d\n", static_cast<int>(r));
}

PFN_vkVoidFunction load(const char* name, void* instance) {
  // Through the loader's instance-level entry point (volk loaded it): device functions come back as trampolines.
  return vkGetInstanceProcAddr(*static_cast<VkInstance*>(instance), name);
}

}  // namespace

Panel::Panel(engine::Device& device, Window& window, const Presenter& presenter) : device_(device) {
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8};
  VkDescriptorPoolCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pci.maxSets = 8;
  pci.poolSizeCount = 1;
  pci.pPoolSizes = &size;
  engine::vk_check(vkCreateDescriptorPool(device.device(), &pci, nullptr, &pool_), "vkCreateDescriptorPool");

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  VkInstance instance = device.instance();
  if (!ImGui_ImplVulkan_LoadFunctions(load, &instance))
    throw engine::Error("the ImGui Vulkan backend could not load its Vulkan functions");
  ImGui_ImplGlfw_InitForVulkan(window.handle(), /*install_callbacks=*/true);  // chains the window's callbacks
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = instance;
  info.PhysicalDevice = device.physical_device();
  info.Device = device.device();
  info.QueueFamily = device.queue_family();
  info.Queue = device.queue();
  info.DescriptorPool = pool_;
  info.MinImageCount = 2;
  info.ImageCount = std::max(presenter.image_count(), 2u);
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = check_result;
  ImGui_ImplVulkan_Init(&info, presenter.render_pass());
  device.run_commands([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

Panel::~Panel() {
  vkDeviceWaitIdle(device_.device());
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(device_.device(), pool_, nullptr);
}

void Panel::build(demo::DemoApp& app, const demo::FrameReport& frame, Window& window) {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("TressVK");
  if (!message.empty()) ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "%s", message.c_str());
  const TvkAssetInfo& info = app.asset_info();
  ImGui::TextWrapped("%s", app.scene().asset_name.c_str());
  ImGui::Text("%u strands (%u guides x %u), %u vertices each", info.total_strands, info.guide_count,
              1 + info.follow_per_guide, info.vertices_per_strand);
  ImGui::Text("t = %.2f s, %u strands drawn", app.time(), frame.strands_drawn);
  if (ImGui::Button(window.view.paused ? "Play (space)" : "Pause (space)")) window.view.paused = !window.view.paused;
  ImGui::SameLine();
  if (ImGui::Button("Reset (R)")) window.reset_requested = true;

  demo::Params& p = app.tuning();
  bool changed = false;
  if (ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) {
    // The model, the step rate and the iteration count: follow-the-leader's look changes with the last two, the
    // conservative model's does not (docs/accuracy.md, "The settled look against the settings").
    static const char* const kModels[] = {"follow-the-leader", "conservative", "compliant"};
    static const TvkSimModel kModelValues[] = {TVK_SIM_MODEL_FOLLOW_THE_LEADER, TVK_SIM_MODEL_CONSERVATIVE,
                                               TVK_SIM_MODEL_COMPLIANT};
    const TvkSimModel current = model::resolved_sim_model(p.settings.model);
    int model = 0;
    for (int i = 0; i < 3; ++i)
      if (current == kModelValues[i]) model = i;
    if (ImGui::Combo("model", &model, kModels, 3)) {
      p.settings.model = kModelValues[model];
      changed = true;
    }
    static const char* const kRates[] = {"the model's", "60 Hz", "120 Hz", "240 Hz", "480 Hz"};
    static const float kRateValues[] = {TVK_STEP_RATE_BY_MODEL, 60.0f, 120.0f, 240.0f, 480.0f};
    int rate = 0;
    for (int i = 0; i < 5; ++i)
      if (p.settings.time.step_rate == kRateValues[i]) rate = i;
    if (ImGui::Combo("step rate", &rate, kRates, 5)) {
      p.settings.time.step_rate = kRateValues[rate];
      changed = true;
    }
    bool model_iterations = p.simulation.local_iterations == TVK_ITERATIONS_BY_MODEL;
    if (ImGui::Checkbox("the model's local iterations", &model_iterations)) {
      p.simulation.local_iterations = model_iterations ? TVK_ITERATIONS_BY_MODEL : 2u;
      changed = true;
    }
    if (!model_iterations) {
      int iterations = static_cast<int>(p.simulation.local_iterations);
      if (ImGui::SliderInt("local iterations", &iterations, 1, 8)) {
        p.simulation.local_iterations = static_cast<uint32_t>(iterations);
        changed = true;
      }
    }
    changed |= ImGui::SliderFloat("damping", &p.simulation.damping, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("global stiffness", &p.simulation.global_stiffness, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("global range", &p.simulation.global_range, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("local stiffness", &p.simulation.local_stiffness, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("VSP coefficient", &p.simulation.vsp_coefficient, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat3("gravity (m/s^2)", p.settings.gravity, -20.0f, 20.0f);
    ImGui::SliderFloat("wind (m/s^2)", &p.wind.strength, 0.0f, 30.0f);
    ImGui::SliderFloat3("wind direction", p.wind.direction, -1.0f, 1.0f);
  }
  if (ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) {
    changed |= ImGui::ColorEdit3("root colour", p.material.base_color);
    changed |= ImGui::ColorEdit3("tip colour", p.material.tip_color);
    float width_mm = p.material.strand_width * 1000.0f;
    if (ImGui::SliderFloat("strand width (mm)", &width_mm, 0.02f, 2.0f)) {
      p.material.strand_width = width_mm / 1000.0f;
      changed = true;
    }
    changed |= ImGui::SliderFloat("opacity", &p.material.opacity, 0.05f, 1.0f);
    changed |= ImGui::SliderFloat("colour variation", &p.material.color_variation, 0.0f, 1.0f);
  }
  if (ImGui::CollapsingHeader("LOD")) {
    bool lod_changed = ImGui::SliderFloat("start (m)", &p.lod.start_distance, 0.0f, 10.0f);
    lod_changed |= ImGui::SliderFloat("end (m)", &p.lod.end_distance, 0.0f, 20.0f);
    lod_changed |= ImGui::SliderFloat("min fraction", &p.lod.min_fraction, 0.01f, 1.0f);
    lod_changed |= ImGui::SliderFloat("target width (px, 0 = by distance)", &p.lod.target_width_px, 0.0f, 4.0f);
    if (lod_changed) p.has_lod = true;
  }
  if (ImGui::CollapsingHeader("GPU time", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (frame.simulation_ms && frame.shadow_ms && frame.shading_ms)
      ImGui::Text("simulation %.2f ms, shadow %.2f ms, shading %.2f ms", *frame.simulation_ms, *frame.shadow_ms,
                  *frame.shading_ms);
    for (const TvkPassTiming& t : app.pass_timings())
      ImGui::Text("  %-24s %3u x  %.3f ms", t.name, t.dispatches, t.milliseconds);
  }
  if (ImGui::CollapsingHeader("Accuracy", ImGuiTreeNodeFlags_DefaultOpen)) {
    // One frame against the double-precision reference (as tressvk-bench compare): seconds on the CPU, so on
    // request, or every 120 frames with the box ticked.
    static bool every = false;
    static uint32_t frames_since = 0;
    if (ImGui::Button("Measure step error")) app.request_step_error();
    ImGui::SameLine();
    ImGui::Checkbox("every 120 frames", &every);
    if (every && ++frames_since >= 120) {
      app.request_step_error();
      frames_since = 0;
    }
    if (const auto e = app.step_error())
      ImGui::Text("step error: %.3g %% of the median strand length", 100.0 * *e);
    else
      ImGui::TextDisabled("step error: not measured yet");
  }
  if (ImGui::CollapsingHeader("Parameter file", ImGuiTreeNodeFlags_DefaultOpen)) {
    static char path[512] = "";
    if (path[0] == '\0') std::snprintf(path, sizeof(path), "%s", params_path.c_str());
    ImGui::InputText("file", path, sizeof(path));
    params_path = path;
    if (ImGui::Button("Save")) {
      try {
        demo::save_params(params_path, p);
        message.clear();
        std::printf("parameters: %s\n", params_path.c_str());
      } catch (const std::exception& e) {
        message = e.what();
      }
    }
    ImGui::SameLine();
    if (ImGui::Button("Load")) {
      try {
        p = demo::load_params(params_path);
        changed = true;
        message.clear();
      } catch (const std::exception& e) {
        message = e.what();
        std::fprintf(stderr, "tressvk-viewer: error: %s\n", e.what());
      }
    }
  }
  ImGui::End();
  ImGui::Render();
  window.ui_has_mouse = ImGui::GetIO().WantCaptureMouse;
  window.ui_has_keyboard = ImGui::GetIO().WantCaptureKeyboard;
  if (changed) {
    try {
      app.apply_params();
    } catch (const std::exception& e) {
      message = e.what();
    }
  }
  built_ = true;
}

void Panel::record(VkCommandBuffer cmd) {
  if (built_) ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

}  // namespace tressvk::viewer
