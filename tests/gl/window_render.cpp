// window_render.cpp: renders the default scene into a GLFW window's default framebuffer (under Xvfb in the
// tests) and checks that the pixels read back from the window equal the renderer's own tone-mapped image:
// the window context works and lucent draws into an application's framebuffer 0.
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <epoxy/gl.h>

#include "lucent/lucent.h"

int main() {
  try {
    const int width = 96, height = 64;
    auto window = lucent::create_window_context(width, height, "lucent window test");
    lucent::Scene scene = lucent::default_scene({"render.width=96", "render.height=64", "method.K=4", "method.N=4",
                                                 "method.map_size=32", "method.light_map_size=64"});
    lucent::Renderer renderer(scene);
    renderer.render(scene.camera, {0, width, height});
    std::vector<unsigned char> window_pixels(static_cast<std::size_t>(width) * height * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, window_pixels.data());
    window->swap_buffers();
    lucent::ImageRGBA8 own = renderer.read_display();
    int mismatches = 0;
    double sum = 0.0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        for (int c = 0; c < 3; ++c) {
          unsigned char a = window_pixels[(static_cast<std::size_t>(height - 1 - y) * width + x) * 4 + c];
          mismatches += a != own.at(x, y)[c];
          sum += a;
        }
    std::printf("window: %s; %d of %d channel values differ from the renderer's image; mean %.1f\n",
                window->description().c_str(), mismatches, width * height * 3, sum / (width * height * 3));
    return mismatches == 0 && sum > 0.0 ? 0 : 1;
  } catch (const lucent::Error& e) {
    std::fprintf(stderr, "window_render: %s\n", e.what());
    return 1;
  }
}
