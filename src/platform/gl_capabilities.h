// gl_capabilities.h: the one place for driver capabilities, required limits and workarounds.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace lucent::platform {

struct GLCapabilities {
  std::string renderer;  // GL_RENDERER
  std::string version;   // GL_VERSION
  bool is_llvmpipe = false;  // Mesa software rasterizer: slow; tests keep resolutions small
  bool is_nvidia = false;
  int max_array_texture_layers = 0;
  std::uint64_t device_memory_bytes = 0;  // NVIDIA: the GPU's memory (GL_NVX_gpu_memory_info); llvmpipe: the
                                          // machine's RAM; 0 when the driver does not say
};

// Mesa's llvmpipe ends every loop of a shader invocation, silently, once the loops' iterations together reach
// this many (one counter, decremented by each iteration of any loop and never reset; it counts the iterations of
// the SIMD loop over 8 or 16 invocations at once, so divergent invocations run it down faster than any one of
// them counts: random-walk saw it fire at a per-invocation count of 7,162). Shaders
// whose loop counts come from data bound them below it, or split their work over dispatches (the random-walk
// method counts its iterations and starts another event only well under it). Every shader loop whose count comes
// from data states its bound in a `// loop bound: ...` comment, checked against this cap by a scan of the embedded
// sources (tests/cpu/test_shader_loops.cpp); a bound that only parameters can keep under it is refused at run time
// by check_loop_iterations.
// Where the cap ends a loop, the invocation leaves it at the end of the body, an exit the shader compiler does not
// know of: a value it computed once for the loop's exit test and the code after it is stale there (random-walk's
// search for a slot's next path took a path index and then, testing the stale "none found", dropped it). Code after
// a loop the cap may cut must not depend on how the loop ended, or must be checked after it (as random-walk's
// replay of a cut event is).
inline constexpr unsigned kLlvmpipeLoopIterations = 65535;
// The iterations a shader's loops may be planned for: under half the cap, the worst measured (llvmpipe, Mesa
// 22.3.6, 2 cores). The per-pixel invocation with two lights runs 2 x (1 + 3 x (1 + N)) loop iterations by its own
// count and renders 2% darker from N 5,459 (32,762) on, unchanged at N 5,450 (32,708): there the driver's counter
// ran out at about half. The voxel-paths triangle loop, by contrast, lost its columns only past the full 65,535.
// Why the counter runs faster in some loop nests is not known; the budget covers the worst case seen.
inline constexpr unsigned kLlvmpipeLoopBudget = 32000;

// Mesa's llvmpipe stamps a GL_TIMESTAMP query when it next flushes its queue, not where the query was issued
// (a compute dispatch runs at once, so the stamp after it came only with the next pass's flush: a 1,289 ms trace
// dispatch was charged to the pass before it). The frame profiler flushes after each timestamp where this holds.
inline bool timestamps_need_flush(const GLCapabilities& caps) { return caps.is_llvmpipe; }

// Queries the current context and throws lucent::Error naming the missing version or limit.
GLCapabilities check_capabilities();
const GLCapabilities& current_capabilities();

// Throws lucent::Error("<what>: 49.3 GiB of GPU memory needed; the device (llvmpipe) has 23.4 GiB") when `bytes`
// exceed the device's memory, so a too-large allocation fails at once with the parameters that asked for it
// instead of as an incomplete framebuffer (or, on llvmpipe, the kernel's out-of-memory killer).
void require_device_memory(std::uint64_t bytes, const std::string& what);

// On llvmpipe, throws lucent::Error("<what> = 393224 shader loop iterations per invocation; llvmpipe ends an
// invocation's loops past 32000 (<advice>)") when `iterations` pass kLlvmpipeLoopBudget, instead of an image
// that darkens silently where the driver cut the loops short. Other drivers have no such cap: nothing is checked.
// `what` names the parameters and their product ("per-pixel: N 65536 x 3 bands x 2 lights").
void check_loop_iterations(std::string_view what, std::uint64_t iterations, std::string_view advice);

}  // namespace lucent::platform
