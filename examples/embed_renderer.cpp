// embed_renderer.cpp: how an application embeds lucent: its own GL context (here headless EGL), its own
// framebuffer and its own orbiting camera; lucent renders frames into that framebuffer and reports timings.
//
//   embed_renderer [SCENE] [OUTPUT.ppm]
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include <epoxy/gl.h>

#include "lucent/lucent.h"

int main(int argc, char** argv) {
  try {
    auto context = lucent::create_headless_context();
    lucent::Scene scene = argc > 1 ? lucent::load_scene(argv[1]) : lucent::default_scene({"render.width=160",
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

    // Read the application's framebuffer back and write it as a binary PPM.
    std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * 4);
    glNamedFramebufferReadBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    double sum = 0.0;
    for (std::size_t i = 0; i < pixels.size(); i += 4) sum += pixels[i] + pixels[i + 1] + pixels[i + 2];
    std::printf("mean pixel value %.2f\n", sum / (3.0 * width * height));
    if (argc > 2) {
      std::ofstream ppm(argv[2], std::ios::binary);
      ppm << "P6\n" << width << " " << height << "\n255\n";
      for (int y = height - 1; y >= 0; --y)
        for (int x = 0; x < width; ++x) ppm.write(reinterpret_cast<const char*>(&pixels[(static_cast<std::size_t>(y) * width + x) * 4]), 3);
    }
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteRenderbuffers(1, &color);
    if (renderer.accumulated_frames() != 4) return 4;  // only the camera moved: all frames accumulate
    return sum > 0.0 ? 0 : 3;                          // a black image is a failure
  } catch (const lucent::Error& e) {
    std::fprintf(stderr, "embed_renderer: %s\n", e.what());
    return 1;
  }
}
