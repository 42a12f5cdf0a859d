// viewer_app.cpp: the window loop: input -> orbit camera, panel, one renderer frame into an offscreen
// framebuffer shown right of the panel, file actions, reload on change.
#include "viewer/viewer_app.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>

#include <epoxy/gl.h>
// epoxy before GLFW, so that GLFW does not include the system GL header.
#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "denoise/denoise_params.h"
#include "lucent/lucent.h"
#include "lucent/scene_writer.h"
#include "viewer/viewer_layout.h"
#include "viewer/viewer_panel.h"
#include "viewer/viewer_session.h"

namespace lucent::viewer {
namespace {

constexpr int kMinWindowHeight = 480;  // [pixels] room for the panel

// Key presses from GLFW's key callback, taken once a frame (ImGui's callbacks, installed after it, chain to it).
KeyQueue* g_key_queue = nullptr;
void on_key(GLFWwindow*, int key, int, int action, int) {
  if (g_key_queue) g_key_queue->push(key, action == GLFW_PRESS);
}

// The screenshot of the view: PNG tone-mapped, EXR linear radiance; never over one of the scene's files.
OutputPath view_output(const std::string& path) { return {path, "screenshot", {".png", ".exr"}}; }

void write_view(const Renderer& renderer, const std::string& path) {
  check_outputs({view_output(path)}, scene_input_files(renderer.scene()));
  const OutputLock lock({view_output(path)});
  if (lowercase_extension(path) == ".exr") write_exr(path, renderer.read_radiance());
  else write_png(path, renderer.read_display());
}

// The whole window (framebuffer 0, back buffer), before the swap.
void write_window(const std::string& path, int width, int height) {
  ImageRGBA8 image{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 4)};
  std::vector<std::uint8_t> rows(image.pixels.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  for (int y = 0; y < height; ++y)
    std::copy_n(&rows[static_cast<std::size_t>(height - 1 - y) * width * 4], static_cast<std::size_t>(width) * 4, image.at(0, y));
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
  write_png(path, image);
}

// ImGui on a GLFW window with its OpenGL 3 backend; no imgui.ini written.
class ImGuiLayer {
 public:
  explicit ImGuiLayer(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 0.0f;
    if (!ImGui_ImplGlfw_InitForOpenGL(window, true) || !ImGui_ImplOpenGL3_Init("#version 450"))
      throw Error("viewer: Dear ImGui cannot initialise its GLFW or OpenGL 3 backend");
  }
  ~ImGuiLayer() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;
  void begin_frame() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
  }
  void draw() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }
};

// Mouse drags that start over the view move the camera until released; the panel keeps its own drags.
class CameraInput {
 public:
  void update(OrbitCamera& camera, float view_left, float view_height) {
    ImGuiIO& io = ImGui::GetIO();
    bool over_view = io.MousePos.x >= view_left && !io.WantCaptureMouse;
    for (int button = 0; button < 3; ++button) {
      if (ImGui::IsMouseClicked(button) && over_view) drag_button_ = button;
    }
    if (drag_button_ >= 0 && !ImGui::IsMouseDown(drag_button_)) drag_button_ = -1;
    if (drag_button_ >= 0 && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
      bool pan = drag_button_ != 0 || io.KeyShift;
      if (pan) camera.pan(io.MouseDelta.x, io.MouseDelta.y, view_height);
      else camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
    }
    if (over_view && io.MouseWheel != 0.0f) camera.zoom(io.MouseWheel);
  }

 private:
  int drag_button_ = -1;
};

// The view's size before the window exists: the options, else the scene's render size. A scene that does not
// load is an error with `frames` (like `lucent render`), else the window opens and shows the message.
glm::ivec2 initial_view_size(const ViewerOptions& o) {
  glm::ivec2 size(640, 480);
  try {
    Scene scene = o.scene_path.empty() ? default_scene(o.sets) : load_scene(o.scene_path, o.sets);
    size = {scene.render.width, scene.render.height};
  } catch (const std::exception&) {
    if (o.frames > 0) throw;
  }
  if (o.width) size.x = *o.width;
  if (o.height) size.y = *o.height;
  if (size.x < 1 || size.y < 1) throw Error(fmt::format("view size {}x{} is empty", size.x, size.y));
  return size;
}

class ViewerApp {
 public:
  explicit ViewerApp(const ViewerOptions& o) : options_(o), session_(o.scene_path, o.sets) {
    view_ = initial_view_size(o);
    std::string title = "lucent view: " + (o.scene_path.empty() ? std::string("built-in default scene") : o.scene_path);
    glm::ivec2 window = initial_window_size(view_, o.panel_width, kMinWindowHeight);
    if (o.window_width) window.x = *o.window_width;
    if (o.window_height) window.y = *o.window_height;
    window_ = create_window_context(window.x, window.y, title);
    glfwSwapInterval(o.frames > 0 ? 0 : 1);
    glfwGetFramebufferSize(window_->window(), &framebuffer_.x, &framebuffer_.y);
    panel_width_ = panel_width_for_window(framebuffer_.x, o.panel_width);
    g_key_queue = &keys_;
    glfwSetKeyCallback(window_->window(), on_key);  // before ImGui, which chains to it
    imgui_ = std::make_unique<ImGuiLayer>(window_->window());
    state_.screenshot_path = o.screenshot.empty() ? state_.screenshot_path : o.screenshot;
    session_.load(/*strict=*/o.frames > 0);
    // The batch outputs are checked before the first frame, as `lucent render` checks its own.
    if (o.frames > 0 && session_.renderer())
      check_outputs({view_output(o.screenshot), {o.screenshot_window, "--screenshot-window", {".png"}},
                     {o.save_scene, "--save-scene", {".json", ".gltf", ".glb"}}},
                    scene_input_files(session_.renderer()->scene()));
  }

  // Each pass of the loop shows the last finished frame with the panel, then submits the next frame: while a slow
  // frame renders (seconds on llvmpipe) the window shows what is being rendered, and the count of frames matches
  // the image on screen.
  ~ViewerApp() { g_key_queue = nullptr; }

  void run() {
    auto last = std::chrono::steady_clock::now();
    bool submitted = false;  // a frame was submitted in the previous pass
    for (int frame = 0; !glfwWindowShouldClose(window_->window()); ++frame) {
      if (options_.frames > 0 && frame == options_.frames) break;
      glfwPollEvents();
      if (options_.frames == 0) session_.reload_if_changed();
      follow_window_size();
      const bool render_now = needs_frame();
      const PanelActions actions = draw_window(render_now);
      handle(actions);
      window_->swap_buffers();  // waits for the frame submitted in the previous pass
      const auto now = std::chrono::steady_clock::now();
      const double seconds = std::chrono::duration<double>(now - last).count();
      last = now;
      if (submitted) clock_.frame_done(seconds);
      if (state_.playing) state_.time_seconds += static_cast<float>(seconds);
      if (render_now) render_scene();
      submitted = render_now && session_.renderer();
    }
    if (options_.frames > 0) {
      // The last frame on screen, then the window's screenshot.
      glfwPollEvents();
      handle(draw_window(false));
      if (!options_.screenshot_window.empty()) write_window(options_.screenshot_window, framebuffer_.x, framebuffer_.y);
      window_->swap_buffers();
      finish_batch();
    }
  }

 private:
  // A window resized by the user: the panel is sized from it, the view scaled into the rest (viewer_layout.h).
  void follow_window_size() {
    glm::ivec2 size;
    glfwGetFramebufferSize(window_->window(), &size.x, &size.y);
    if (size == framebuffer_ || size.x <= 0 || size.y <= 0) return;
    framebuffer_ = size;
    panel_width_ = panel_width_for_window(size.x, options_.panel_width);
  }

  PixelRect view_rect() const {
    return fit_view(view_, {panel_width_, 0, framebuffer_.x - panel_width_, framebuffer_.y});
  }

  // The panel (with what the next frame is) and the last finished frame, ready to swap.
  PanelActions draw_window(bool render_now) {
    imgui_->begin_frame();
    const PixelRect rect = view_rect();
    input_.update(session_.camera(), static_cast<float>(panel_width_), static_cast<float>(std::max(rect.height, 1)));
    PanelActions keys = handle_keys();
    state_.view_width = view_.x, state_.view_height = view_.y;
    state_.frame_rate = clock_.rate_text();
    state_.frame_status = frame_status_text(frame_status(render_now));
    PanelActions actions =
        draw_panel(session_, state_, static_cast<float>(panel_width_), static_cast<float>(framebuffer_.y));
    present();
    imgui_->draw();
    actions.screenshot |= keys.screenshot;
    return actions;
  }

  // The keys pressed since the last frame, however short the taps (GLFW callbacks, queued); none while a text field
  // has the keyboard.
  PanelActions handle_keys() {
    PanelActions actions;
    for (int key : keys_.take_presses()) {
      if (ImGui::GetIO().WantCaptureKeyboard) continue;
      if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window_->window(), GLFW_TRUE);
      if (key == GLFW_KEY_R) session_.camera().reset();
      if (key == GLFW_KEY_P) actions.screenshot = true;
      if (key == GLFW_KEY_D) toggle_denoise();
    }
    return actions;
  }

  // The denoising stage on or off (the filtered image or the method's raw average). The renderer reads the
  // stage's settings every frame, so the change goes to its scene directly (and to the panel's copy) without
  // restarting the method: the frames accumulated so far stay, and both images can be compared.
  void toggle_denoise() {
    Renderer* renderer = session_.renderer();
    if (!renderer) return;
    const bool enabled = !denoise::denoise_settings(renderer->scene().denoise).enabled;
    renderer->scene().denoise.set("enabled", enabled);
    session_.edit().denoise.set("enabled", enabled);
  }

  FrameStatus frame_status(bool render_now) {
    FrameStatus status;
    Renderer* renderer = session_.renderer();
    status.frames_accumulated = rendered_ && renderer ? renderer->accumulated_frames() : 0;
    status.rendering = render_now && renderer;
    status.seconds_per_frame = clock_.seconds_per_frame();
    if (renderer)
      for (const PassTiming& pass : renderer->timings().passes)
        if (pass.ms > status.slowest_pass_ms) status.slowest_pass = pass.name, status.slowest_pass_ms = pass.ms;
    return status;
  }

  // A frame is rendered unless the image has converged (`stop after frames`) and nothing changed.
  bool needs_frame() {
    Renderer* renderer = session_.renderer();
    if (!renderer || !rendered_ || renderer != last_renderer_ || session_.pending()) return true;
    const bool converged = state_.stop_after_frames > 0 && renderer->accumulated_frames() >= state_.stop_after_frames;
    const bool camera_moved = !same_camera(session_.camera().camera(), last_camera_);
    const bool time_changed = renderer->time() != static_cast<double>(state_.time_seconds);
    return !converged || camera_moved || time_changed;
  }

  // One renderer frame into the view's target.
  void render_scene() {
    if (!target_ || target_size_ != view_) target_ = std::make_unique<OffscreenFramebuffer>(view_.x, view_.y), target_size_ = view_, rendered_ = false;
    // No effect on static scenes.
    if (Renderer* renderer = session_.renderer()) renderer->set_time(state_.time_seconds);
    session_.render({target_->id(), view_.x, view_.y});
    last_camera_ = session_.camera().camera();
    last_renderer_ = session_.renderer();
    rendered_ = session_.renderer() != nullptr;
  }

  // The view scaled to fit right of the panel, centred (whole pixels at an integer scale); the rest dark.
  void present() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, framebuffer_.x, framebuffer_.y);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (!rendered_ || !target_) return;
    const PixelRect r = view_rect();
    if (r.width <= 0 || r.height <= 0) return;
    const bool whole = r.width % view_.x == 0 && r.height % view_.y == 0;
    const int y0 = framebuffer_.y - (r.y + r.height);  // GL rows from the bottom
    glBlitNamedFramebuffer(target_->id(), 0, 0, 0, view_.x, view_.y, r.x, y0, r.x + r.width, y0 + r.height,
                           GL_COLOR_BUFFER_BIT, whole ? GL_NEAREST : GL_LINEAR);
  }

  void handle(const PanelActions& actions) {
    try {
      if (actions.screenshot) {
        if (!session_.renderer()) throw Error("screenshot: nothing rendered");
        write_view(*session_.renderer(), state_.screenshot_path);
        state_.status = "wrote " + state_.screenshot_path;
      }
      if (actions.save_scene) {
        save_scene_as(session_.scene_for_saving(view_.x, view_.y), state_.scene_save_path);
        state_.status = fmt::format("wrote {} (lucent render {} reproduces the view)", state_.scene_save_path,
                                    state_.scene_save_path);
      }
      if (actions.reload) session_.load();
    } catch (const std::exception& e) {  // lucent::Error, a filesystem error, an allocation that failed
      state_.status.clear();
      session_.set_error(e.what());
    }
  }

  void finish_batch() {
    if (!session_.renderer() || !session_.error().empty())
      throw Error(session_.error().empty() ? "nothing rendered" : session_.error());
    if (!options_.screenshot.empty()) write_view(*session_.renderer(), options_.screenshot);
    if (!options_.save_scene.empty())
      save_scene_as(session_.scene_for_saving(view_.x, view_.y), options_.save_scene);
    fmt::print("{}: {}x{}, {} frame(s) accumulated{}{}\n", session_.scene_path().empty() ? "<built-in default scene>" : session_.scene_path(),
               view_.x, view_.y, session_.renderer()->accumulated_frames(),
               options_.screenshot.empty() ? "" : " -> " + options_.screenshot,
               options_.screenshot_window.empty() ? "" : ", window -> " + options_.screenshot_window);
  }

  // Declared so that GL objects (target, renderer) go before ImGui, and ImGui before the window's context.
  ViewerOptions options_;
  std::unique_ptr<WindowContext> window_;
  std::unique_ptr<ImGuiLayer> imgui_;
  ViewerSession session_;
  std::unique_ptr<OffscreenFramebuffer> target_;
  glm::ivec2 view_{1}, target_size_{0}, framebuffer_{0};
  PanelState state_;
  CameraInput input_;
  KeyQueue keys_;
  FrameClock clock_;
  int panel_width_ = 0;
  Camera last_camera_;
  const Renderer* last_renderer_ = nullptr;
  bool rendered_ = false;
};

}  // namespace

void run_viewer(const ViewerOptions& options) {
  ViewerApp app(options);
  app.run();
}

}  // namespace lucent::viewer
