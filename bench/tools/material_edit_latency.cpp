// material_edit_latency.cpp: the time from a material edit to the next finished frame, as the viewer sees it:
// edit Scene::objects[i].material, Renderer::scene_changed(), render one frame, glFinish. Uses the public API
// only, so the same source measures any version of the library.
//
//   material_edit_latency [SCENE|-] [EDITS] [key=value ...]   (default: the built-in scene at 320x240, 10 edits;
//                                                             further arguments are --set overrides)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "lucent/lucent.h"

int main(int argc, char** argv) {
  try {
    auto context = lucent::create_headless_context();
    std::vector<std::string> sets = {"render.width=320", "render.height=240"};
    for (int i = 3; i < argc; ++i) sets.push_back(argv[i]);
    lucent::Scene scene = argc > 1 && std::string(argv[1]) != "-" ? lucent::load_scene(argv[1], sets)
                                                                  : lucent::default_scene(sets);
    const int edits = argc > 2 ? std::stoi(argv[2]) : 10;
    lucent::OffscreenFramebuffer target(scene.render.width, scene.render.height);
    lucent::Renderer renderer(scene);
    renderer.render(scene.camera, {target.id(), scene.render.width, scene.render.height});
    glFinish();
    std::size_t object = 0;
    while (object < renderer.scene().objects.size() && !renderer.scene().objects[object].material) ++object;
    if (object == renderer.scene().objects.size()) throw lucent::Error("the scene has no translucent object");
    std::vector<double> ms;
    for (int e = 0; e < edits; ++e) {
      auto start = std::chrono::steady_clock::now();
      renderer.scene().objects[object].material->sigma_a *= (e % 2 ? 1.25f : 0.8f);
      renderer.scene_changed();
      renderer.render(scene.camera, {target.id(), scene.render.width, scene.render.height});
      glFinish();
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    // The same frame without an edit (everything recomputed, nothing rebuilt), for the share the edit itself adds.
    std::vector<double> frame_ms;
    for (int e = 0; e < edits; ++e) {
      auto start = std::chrono::steady_clock::now();
      renderer.restart();
      renderer.render(scene.camera, {target.id(), scene.render.width, scene.render.height});
      glFinish();
      frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(frame_ms.begin(), frame_ms.end());
    std::sort(ms.begin(), ms.end());
    std::printf("restarted frame without an edit: median %.1f ms\n", frame_ms[frame_ms.size() / 2]);
    std::printf("material edit to finished frame: median %.1f ms, min %.1f, max %.1f over %d edits (%s)\n",
                ms[ms.size() / 2], ms.front(), ms.back(), edits, lucent::Renderer::device_of_current_context().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "material_edit_latency: %s\n", e.what());
    return 1;
  }
}
