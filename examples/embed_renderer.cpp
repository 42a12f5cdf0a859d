// embed_renderer.cpp: how an application embeds lucent: its own GL context (here headless EGL), its own
// framebuffer and its own orbiting camera; lucent renders frames into that framebuffer and reports timings.
//
//   embed_renderer [SCENE|-] [OUTPUT.png]       (- : the built-in default scene)
//
// It builds inside lucent's tree and, as any other program would, against an installed lucent: see
// examples/CMakeLists.txt (find_package) and docs/install.md (pkg-config).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "lucent/lucent.h"

int main(int argc, char** argv) {
  try {
    auto context = lucent::create_headless_context();
    const bool own_scene = argc > 1 && std::string(argv[1]) != "-";
    lucent::Scene scene = own_scene ? lucent::load_scene(argv[1]) : lucent::default_scene({"render.width=160",
        "render.height=100", "method.K=6", "method.N=4", "method.map_size=64", "method.light_map_size=128"});
    const int width = scene.render.width, height = scene.render.height;

    // The application's framebuffer.
    GLuint color = 0, framebuffer = 0;
    glCreateRenderbuffers(1, &color);
    glNamedRenderbufferStorage(color, GL_RGBA8, width, height);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);

    lucent::Renderer renderer(scene);
    lucent::Camera camera = scene.camera;
    const glm::vec3 offset = camera.eye - camera.target;
    for (int frame = 0; frame < 4; ++frame) {
      // The application's own camera: orbit about the target. Only the camera moves, so lucent keeps
      // accumulating its scattered-radiosity maps.
      float angle = 0.1f * static_cast<float>(frame);
      camera.eye = camera.target + glm::vec3(std::cos(angle) * offset.x + std::sin(angle) * offset.z, offset.y,
                                             -std::sin(angle) * offset.x + std::cos(angle) * offset.z);
      renderer.render(camera, {framebuffer, width, height});
      std::printf("frame %d: %.3f ms GPU, %d frame(s) accumulated\n", frame, renderer.last_frame_timings().total_ms,
                  renderer.accumulated_frames());
    }

    // Read the application's framebuffer back (OpenGL's rows bottom first) and write it as a PNG.
    lucent::ImageRGBA8 image{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 4)};
    std::vector<unsigned char> rows(image.pixels.size());
    glNamedFramebufferReadBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    const std::size_t row_bytes = static_cast<std::size_t>(width) * 4;
    double sum = 0.0;
    for (int y = 0; y < height; ++y)
      for (std::size_t i = 0; i < row_bytes; ++i) {
        const unsigned char value = rows[static_cast<std::size_t>(height - 1 - y) * row_bytes + i];
        image.pixels[static_cast<std::size_t>(y) * row_bytes + i] = value;
        if (i % 4 != 3) sum += value;
      }
    std::printf("mean pixel value %.2f\n", sum / (3.0 * width * height));
    if (argc > 2) lucent::write_png(argv[2], image);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteRenderbuffers(1, &color);
    if (renderer.accumulated_frames() != 4) return 4;  // only the camera moved: all frames accumulate
    return sum > 0.0 ? 0 : 3;                          // a black image is a failure
  } catch (const lucent::Error& e) {
    std::fprintf(stderr, "embed_renderer: %s\n", e.what());
    return 1;
  }
}
