// random_walk.cpp: the physics on the GPU. Volumetric path tracing of the scene exactly as the CPU reference
// `volpath` defines it (docs/references.md), progressively: each frame adds paths per pixel; a camera move, an
// edit or an animation step restarts. Geometry: a bounding volume hierarchy built on the CPU (binned SAH,
// triangle_bvh.h) over the scene's triangles in the order of the shared index buffer; deforming meshes are
// gathered from the shared vertex buffer and the hierarchy refitted on the GPU. Dense media: sphere jumps
// (sphere_jump_tables.h, docs/methods/random-walk.md). Shaders: src/methods/random_walk/shaders/.
#include "methods/method.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>

#include <fmt/format.h>

#include "gpu/gl_debug.h"
#include "gpu/shader_program.h"
#include "lucent/error.h"
#include "media/heterogeneous_field.h"
#include "platform/gl_capabilities.h"
#include "methods/random_walk/distance_grid.h"
#include "methods/random_walk/random_walk_io.h"
#include "methods/random_walk/triangle_bvh.h"
#include "methods/random_walk/walk_boundary.h"
#include "render/light_views.h"
#include "render/view_accumulator.h"
#include "shared/sphere_walk.h"
#include "scene/mesh_enclosure.h"

namespace lucent::methods {
namespace {

// Slots in the pool of paths in flight at most: 2^18 paths (32 MiB) keep a large GPU full (an H100 holds 270,336
// threads), and llvmpipe's storage blocks (128 MiB) bind them.
constexpr std::size_t kPoolSlots = std::size_t{1} << 18;
// The results of the frames in flight at most (16 bytes per path): 64 MiB, 4 frames of 1080p at one path per pixel.
constexpr std::size_t kResultBytes = std::size_t{64} << 20;
// Frames in flight at most (`frames_in_flight`, default 2: the current one and the next). Four against two on
// llvmpipe with the marble bunny: 12-15% more paths per second at 64 x 48 and 160 x 120, 18% fewer at 320 x 240,
// where every dispatch runs the pool of later frames' paths while the current frame's longest path advances one
// budget per dispatch (docs/methods/random-walk.md).
constexpr std::size_t kRingFrames = LUCENT_WALK_MAX_FRAMES_IN_FLIGHT;
constexpr int kMaxSurfaceBounces = 64;  // as volpath
constexpr int kRouletteAfter = 8;       // as volpath
// Events of one path at most (a path spans dispatches, so llvmpipe's loop cap does not bound it): far beyond any
// physical path's (roulette ends them), a guard against a path that never ends.
constexpr int kMaxPathEvents = 10000000;

float max_component(glm::vec3 v) { return std::max({v.x, v.y, v.z}); }

// Throws lucent::Error naming the buffer, its size, the driver's limit and what to change when `bytes` exceed the
// largest storage block the driver binds (GL_MAX_SHADER_STORAGE_BLOCK_SIZE; llvmpipe: 128 MiB).
void check_storage_block(std::size_t bytes, const std::string& what, const std::string& remedy) {
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  if (max_block > 0 && bytes > static_cast<std::size_t>(max_block))
    throw Error(fmt::format("method 'random-walk': {} take {} bytes, over the device's largest storage buffer "
                            "(GL_MAX_SHADER_STORAGE_BLOCK_SIZE {} bytes); {}",
                            what, bytes, max_block, remedy));
}

template <typename T>
GLuint storage_buffer(const std::vector<T>& data, const char* label) {
  check_storage_block(data.size() * sizeof(T), label, "use a mesh with fewer triangles");
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(std::max<std::size_t>(1, data.size()) * sizeof(T)),
                       data.empty() ? nullptr : data.data(), GL_DYNAMIC_STORAGE_BIT);
  gpu::label_object(GL_BUFFER, buffer, label);
  return buffer;
}

// Each object's medium or surface as the walk reads it (volpath's ObjectData, in float): a deforming mesh's box is
// the deformed one's, a field stays where the undeformed object is.
// The distinct Henyey-Greenstein g of the homogeneous media whose bands share one g: the sphere-jump banks (at most
// LUCENT_WALK_MAX_JUMP_BANKS; media beyond them step through every collision).
std::vector<float> jump_bank_g(const Scene& scene) {
  std::vector<float> banks;
  for (const SceneObject& object : scene.objects) {
    if (!object.material || object.material->field.heterogeneous()) continue;
    const glm::vec3 g = object.material->g;
    if (g.x != g.y || g.x != g.z || std::find(banks.begin(), banks.end(), g.x) != banks.end()) continue;
    if (banks.size() < LUCENT_WALK_MAX_JUMP_BANKS) banks.push_back(g.x);
  }
  return banks;
}

// `triangles`: the scene's triangles at the instant rendered (any order), whose boxes bound each object's walk;
// `boundary`: each object's entries in the area distribution and its flat faces (walk_boundary.h).
std::vector<shader::WalkObjectGPU> walk_objects(const Scene& scene, std::span<const shader::TriangleGPU> triangles,
                                                const random_walk::WalkBoundary& boundary) {
  const std::vector<float> banks = jump_bank_g(scene);
  std::vector<glm::vec3> mesh_lower(scene.objects.size(), glm::vec3(1e30f)), mesh_upper(scene.objects.size(), glm::vec3(-1e30f));
  for (const shader::TriangleGPU& t : triangles) {
    const std::size_t object = random_walk::triangle_object(t);
    for (const glm::vec3 p : {glm::vec3(t.p0), glm::vec3(t.p0 + t.e1), glm::vec3(t.p0 + t.e2)})
      mesh_lower[object] = glm::min(mesh_lower[object], p), mesh_upper[object] = glm::max(mesh_upper[object], p);
  }
  std::vector<shader::WalkObjectGPU> out(scene.objects.size(), shader::WalkObjectGPU{});
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    shader::WalkObjectGPU& o = out[i];
    o.albedo = glm::vec4(object.albedo, 1.0f);
    if (!object.material) continue;
    const Material& m = *object.material;
    if (m.field.type == MediumFieldType::Volume)
      throw Error(fmt::format("{}: /objects/{}/material/field: method 'random-walk' does not read volume fields (the "
                              "reference lucent reference --integrator volpath does)",
                              scene.source, i));
    const float scale = scene.scale_mm;
    o.sigma_a = glm::vec4(m.sigma_a * scale, m.eta);
    o.sigma_s = glm::vec4(m.sigma_s * scale, 1.0f);
    o.g = glm::vec4(m.g, static_cast<float>(static_cast<int>(m.field.type)));
    glm::vec3 lower = mesh_lower[i], upper = mesh_upper[i];
    o.mesh_lower = glm::vec4(lower, std::bit_cast<float>(boundary.ranges[i].x));
    o.mesh_upper = glm::vec4(upper, std::bit_cast<float>(boundary.ranges[i].y));
    o.faces = glm::ivec4(boundary.face_ranges[i], 0, 0);
    // A field stays where the undeformed object is (scene_at_time's rule, as volpath places it).
    if (m.field.has_bounds) {
      lower = m.field.bounds_lower, upper = m.field.bounds_upper;
    } else if (m.field.heterogeneous()) {
      lower = glm::vec3(1e30f), upper = glm::vec3(-1e30f);
      for (const glm::vec3& p : transformed(object.mesh, object.world_from_object).positions)
        lower = glm::min(lower, p), upper = glm::max(upper, p);
    }
    o.lower = glm::vec4(lower, m.field.scale_mm / scale);
    o.upper = glm::vec4(upper, m.field.contrast);
    const auto bank = std::find(banks.begin(), banks.end(), m.g.x);
    const bool jumps = !m.field.heterogeneous() && m.g.x == m.g.y && m.g.x == m.g.z && bank != banks.end();
    o.majorant = glm::vec4(m.field.max_multiplier() * (m.sigma_a + m.sigma_s) * scale,
                           jumps ? static_cast<float>(bank - banks.begin()) : -1.0f);
  }
  return out;
}

class RandomWalk final : public Method {
  // A frame's counts over every path of every batch, kept for the frames whose statistics are not read yet.
  struct FrameStats {
    std::uint64_t frame = 0;
    double paths = 0, steps = 0, traversals = 0, node_visits = 0, next_events = 0, next_event_traversals = 0;
    double dispatches = 0, sparse_dispatches = 0, read_backs = 0, loop_limited = 0, replayed = 0;
    double frame_paths = 0, frame_steps = 0;  // the frame's own paths (steps_per_path)
    double dispatch_ms = 0, sparse_ms = 0;    // time_dispatches: wall time of the dispatches, of the sparse ones
    double traversals_per_next_event() const { return next_event_traversals / next_events; }
  };

 public:
  RandomWalk(const Scene& scene, const render::SceneGpu& scene_gpu)
      : scene_(scene), params_(scene.method_params),
        program_(gpu::ShaderProgram::compute("methods/random_walk/shaders/trace.comp")),
        control_program_(gpu::ShaderProgram::compute("methods/random_walk/shaders/pool_control.comp")),
        resolve_program_(gpu::ShaderProgram::compute("methods/random_walk/shaders/resolve.comp")) {
    check_representable(scene);
    const render::LightViews light_views =
        render::build_light_views(scene, scene_gpu.translucent_bounds(), scene_gpu.scene_bounds(), 16);
    lights_ = light_views.lights;
    light_media_ = point_light_media(scene);

    random_walk::SceneTriangles gathered = random_walk::gather_scene_triangles(scene);
    bvh_ = random_walk::build_triangle_bvh(gathered.triangles);
    if (bvh_.nodes.empty()) throw Error(fmt::format("{}: method 'random-walk' needs at least one triangle", scene.source));
    rest_triangles_ = std::move(gathered.triangles);
    boundary_ = random_walk::build_walk_boundary(scene, bvh_.triangles);
    jump_banks_ = jump_bank_g(scene);
    if (!jump_banks_.empty()) {
      random_walk::DistanceGridOptions options;
      options.max_cells_per_axis = params_.integer("distance_grid");
      grid_ = random_walk::build_distance_grid(bvh_, gathered.translucent_lower, gathered.translucent_upper, options);
      upload_distance_grid();
      // A power of two (a path's records offset + k, modulo a level's count, stay distinct through the 32-bit wrap).
      records_per_level_ = 64;
      while (records_per_level_ * 2 <= params_.integer("sphere_walk_records")) records_per_level_ *= 2;
      for (int l = 0; l < shader::kSphereJumpLevelCount; ++l)
        jump_records_[l] = shader::sphere_walk_record_count(l, records_per_level_);
      // The levels a jump can use: no distance bound exceeds the grid's largest distance, so no sphere is larger
      // than it times the densest band of a medium with jumps; the frame's records are generated for those only.
      float largest_distance = 0.0f, densest = 0.0f;
      for (float d : grid_.distances) largest_distance = std::max(largest_distance, d);
      for (const SceneObject& object : scene.objects)
        if (object.material && !object.material->field.heterogeneous())
          densest = std::max(densest, scene.scale_mm * max_component(object.material->sigma_a + object.material->sigma_s));
      while (levels_used_ < shader::kSphereJumpLevelCount &&
             shader::sphere_jump_level_radius(levels_used_) <= largest_distance * densest)
        ++levels_used_;
      const std::size_t bytes = kRingFrames * jump_banks_.size() * shader::kSphereJumpLevelCount *
                                static_cast<std::size_t>(records_per_level_) * sizeof(shader::SphereWalkGPU);
      glCreateBuffers(1, &spheres_);
      glNamedBufferStorage(spheres_, static_cast<GLsizeiptr>(bytes), nullptr, 0);
      gpu::label_object(GL_BUFFER, spheres_, "random-walk sphere-walk records");
      sphere_bytes_ = bytes;
      sphere_program_ = gpu::ShaderProgram::compute("methods/random_walk/shaders/sphere_walks.comp");
    }
    nodes_ = storage_buffer(bvh_.nodes, "random-walk BVH nodes");
    triangles_ = storage_buffer(bvh_.triangles, "random-walk triangles");
    objects_ = storage_buffer(walk_objects(scene, rest_triangles_, boundary_), "random-walk objects");
    neighbours_ = storage_buffer(boundary_.neighbours, "random-walk triangle neighbours");
    areas_ = storage_buffer(boundary_.areas, "random-walk surface areas");
    faces_ = storage_buffer(boundary_.faces, "random-walk flat faces");
    glCreateBuffers(1, &block_buffer_);
    glNamedBufferStorage(block_buffer_, sizeof(shader::RandomWalkGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, block_buffer_, "random-walk block");
    glCreateBuffers(1, &counters_);
    glNamedBufferStorage(counters_, sizeof(shader::WalkCountersGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gpu::label_object(GL_BUFFER, counters_, "random-walk counters");
    const platform::GLCapabilities& caps = platform::current_capabilities();
    loop_cap_ = caps.is_llvmpipe ? platform::kLlvmpipeLoopIterations : 0u;
    // A quarter of the cap: an invocation's own count undercounts the SIMD loop's (8 or 16 lanes), so the cap then
    // cuts events in most busy work groups, and each is replayed exactly in the next dispatch; fewer dispatches made
    // the marble bunny's frames 1.25-1.4x faster than with a sixteenth at 160 x 120 and 320 x 240
    // (docs/performance.md).
    loop_budget_ = caps.is_llvmpipe ? platform::kLlvmpipeLoopIterations / 4 : 1u << 16;
    if (const int budget = params_.integer("loop_budget"); budget > 0) loop_budget_ = static_cast<unsigned>(budget);
  }
  ~RandomWalk() override {
    glDeleteBuffers(1, &block_buffer_);
    glDeleteBuffers(1, &paths_);
    glDeleteBuffers(1, &results_);
    glDeleteBuffers(1, &counters_);
    glDeleteBuffers(1, &nodes_);
    glDeleteBuffers(1, &triangles_);
    glDeleteBuffers(1, &objects_);
    glDeleteBuffers(1, &neighbours_);
    glDeleteBuffers(1, &areas_);
    glDeleteBuffers(1, &faces_);
    glDeleteBuffers(1, &spheres_);
    glDeleteTextures(1, &distance_texture_);
  }

  void prepare_frame(shader::FrameGPU& frame, bool restart) override {
    restart = accumulated_.begin_frame(frame, restart);
    frame.seeds.z = restart ? 1u : 0u;
    frame.light_counts = glm::ivec4(static_cast<int>(lights_.size()), 0, 0, 0);
    std::copy(lights_.begin(), lights_.end(), frame.lights);
    if (restart) samples_done_ = 0;
    const unsigned samples = static_cast<unsigned>(params_.integer("samples_per_frame"));
    // Paths of the next frame already under way were started for this frame's first sample and count: anything
    // else starts the pool afresh.
    if (restart || samples != samples_this_frame_) pool_reset_ = true;
    samples_this_frame_ = samples;

    shader::RandomWalkGPU block{};
    set_camera(frame, block);
    block.samples = glm::uvec4(samples_this_frame_, samples_done_, frame.seeds.x,
                               params_.boolean("sphere_jumps") ? LUCENT_WALK_SPHERE_JUMPS : 0u);
    block.limits = glm::ivec4(kMaxSurfaceBounces, kRouletteAfter, params_.integer("max_scatter"), kMaxPathEvents);
    block.jump_info = glm::ivec4(static_cast<int>(jump_banks_.size()), 0, 0, 0);
    block.distance_lower = glm::vec4(grid_.origin, grid_.cell_size);
    block.distance_size = glm::ivec4(grid_.cells, records_per_level_);
    for (std::size_t b = 0; b < jump_banks_.size(); ++b) block.jump_g[static_cast<int>(b)] = jump_banks_[b];
    block.jump_bound = glm::vec4(surface_moved_, distance_texture_ != 0 ? 1.0f : 0.0f, 0.0f, 0.0f);
    for (int l = 0; l < shader::kSphereJumpLevelCount; ++l) block.jump_records[l / 4][l % 4] = jump_records_[l];
    for (std::size_t l = 0; l < LUCENT_MAX_LIGHTS; ++l)
      block.light_media[l / 4][static_cast<int>(l % 4)] = l < light_media_.size() ? light_media_[l] : -1;
    glNamedBufferSubData(block_buffer_, 0, sizeof(block), &block);
    samples_done_ += samples_this_frame_;
  }

  void render(const FrameContext& context) override {
    if (context.scene_gpu.animated() && context.time_seconds != geometry_time_) follow_animation(context);
    // The frame's paths in batches of whole samples whose results fit the driver's largest storage buffer
    // (llvmpipe: 128 MiB, 8.4 million paths), each traced by the pool of slots. Where the whole frame fits in a
    // results region, more than once, and nothing moves (the usual case), it is one batch, and slots the frame's
    // paths no longer need start the next frames' paths in the ring's other regions: a frame does not wait idle
    // for its longest path (a path in marble can take 100 times the mean).
    const std::size_t pixels = static_cast<std::size_t>(accumulated_.width()) * accumulated_.height();
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    const std::size_t block_bytes = max_block > 0 ? static_cast<std::size_t>(max_block) : std::size_t{1} << 31;
    check_storage_block(pixels * sizeof(glm::vec4), fmt::format("the results of one path per pixel ({} pixels)", pixels),
                        "render fewer pixels (render.width x render.height)");
    const std::size_t frame_paths = pixels * samples_this_frame_;
    const std::size_t result_budget = std::min(block_bytes, kResultBytes);
    const std::size_t ring =
        context.scene_gpu.animated() ? 1
                                     : std::clamp<std::size_t>(result_budget / (frame_paths * sizeof(glm::vec4)), 1,
                                                               static_cast<std::size_t>(params_.integer("frames_in_flight")));
    // A path's index in its region has LUCENT_WALK_REGION_SHIFT bits (67 million paths).
    const std::size_t most_paths = std::min(block_bytes / sizeof(glm::vec4), (std::size_t{1} << LUCENT_WALK_REGION_SHIFT) - 1);
    if (pixels > most_paths)
      throw Error(fmt::format("method 'random-walk': {} x {} pixels; the results of one path per pixel must fit {} "
                              "paths (render fewer pixels: render.width x render.height)",
                              accumulated_.width(), accumulated_.height(), most_paths));
    const std::size_t batch_samples =
        ring > 1 ? samples_this_frame_ : std::clamp<std::size_t>(most_paths / pixels, 1, samples_this_frame_);
    const std::size_t batch_paths = batch_samples * pixels;
    const std::size_t slots = std::min({batch_paths, kPoolSlots, block_bytes / sizeof(shader::WalkPathGPU)});
    if (ring != ring_ || slots != path_capacity_ || ring * batch_paths > result_capacity_) pool_reset_ = true;
    if (slots != path_capacity_ || ring * batch_paths > result_capacity_) allocate_pool(slots, ring * batch_paths);
    if (pool_reset_) region_ = 0;
    ring_ = ring;
    const bool jumps = spheres_ != 0 && levels_used_ > 0 && params_.boolean("sphere_jumps");
    FrameStats& stats = frame_stats_[context.frame % frame_stats_.size()];
    stats = FrameStats{};
    stats.frame = context.frame;
    bind_trace_resources(context);
    for (std::size_t first = 0; first < samples_this_frame_; first += batch_samples) {
      const std::size_t samples = std::min<std::size_t>(batch_samples, samples_this_frame_ - first);
      const bool last = first + samples >= samples_this_frame_;
      const bool reset = pool_reset_;
      shader::RandomWalkGPU block{};
      block.pool = glm::uvec4(static_cast<unsigned>(slots), static_cast<unsigned>(samples * pixels), region_,
                              static_cast<unsigned>(pixels));
      // The sphere-walk banks made now: every region's after a reset, else the region the frame after the last
      // one in flight takes (the one the previous frame left).
      const unsigned regions = static_cast<unsigned>(ring);
      unsigned banks_first = 0, banks = 0;
      if (reset && first == 0) banks = regions;
      else if (!reset) banks_first = (region_ + regions - 1) % regions, banks = 1;
      block.ring = glm::uvec4(regions,
                              (first == 0 ? LUCENT_WALK_POOL_FIRST : 0u) | (last ? LUCENT_WALK_POOL_LAST : 0u),
                              banks_first, banks);
      // Region (current + k)'s paths: frame k after this one, whose samples follow this frame's.
      const unsigned current_first = samples_done_ - samples_this_frame_ + static_cast<unsigned>(first);
      for (unsigned k = 0; k < ring; ++k) {
        const unsigned r = (region_ + k) % static_cast<unsigned>(ring);
        block.region_first[r / 4][static_cast<int>(r % 4)] = current_first + k * samples_this_frame_;
      }
      glNamedBufferSubData(block_buffer_, offsetof(shader::RandomWalkGPU, pool),
                           offsetof(shader::RandomWalkGPU, distance_lower) - offsetof(shader::RandomWalkGPU, pool),
                           &block.pool);
      if (jumps && banks != 0) {
        auto pass = context.profiler.pass("sphere_walks");
        glUseProgram(sphere_program_.id());
        glDispatchCompute(static_cast<GLuint>((records_per_level_ + 63) / 64), static_cast<GLuint>(levels_used_),
                          static_cast<GLuint>(ring * jump_banks_.size()));
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      }
      auto pass = context.profiler.pass("trace");
      if (reset) {
        glClearNamedBufferData(counters_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      } else {
        glClearNamedBufferSubData(counters_, GL_R32UI, offsetof(shader::WalkCountersGPU, busy),
                                  sizeof(shader::WalkCountersGPU) - offsetof(shader::WalkCountersGPU, busy),
                                  GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      }
      trace_batch(slots, reset, stats);
      if (ring > 1) {  // the current region is free: the frame ring - 1 after the next starts in it
        const std::size_t offset = region_ * sizeof(unsigned);
        glClearNamedBufferSubData(counters_, GL_R32UI, offsetof(shader::WalkCountersGPU, next_path) + offset,
                                  sizeof(unsigned), GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        glClearNamedBufferSubData(counters_, GL_R32UI, offsetof(shader::WalkCountersGPU, finished) + offset,
                                  sizeof(unsigned), GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
        region_ = (region_ + 1) % static_cast<unsigned>(ring);
        pool_reset_ = false;
      } else {
        pool_reset_ = true;
      }
    }
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  }

  void bind_trace_resources(const FrameContext& context) {
    glBindBufferBase(GL_UNIFORM_BUFFER, LUCENT_BINDING_METHOD, block_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_NODES, nodes_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_TRIANGLES, triangles_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_OBJECTS, objects_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_NEIGHBOURS, neighbours_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_AREAS, areas_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_FACES, faces_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_PATHS, paths_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_RESULTS, results_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_COUNTERS, counters_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_WALK_SPHERES, spheres_ != 0 ? spheres_ : objects_);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, counters_);
    glBindTextureUnit(LUCENT_TEX_WALK_DISTANCE, distance_texture_);
    accumulated_.bind(LUCENT_IMAGE_WALK_SUM);
    glBindImageTexture(LUCENT_IMAGE_HDR, context.hdr_image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  }

  int accumulated_frames() const override { return accumulated_.frames(); }

  void statistics(const FrameRecord& record, std::vector<FrameStatistic>& out) const override {
    (void)record.counters;
    static const FrameStats kNone{};
    const FrameStats& kept = frame_stats_[record.frame % frame_stats_.size()];
    const FrameStats& f = kept.frame == record.frame ? kept : kNone;
    const double ms = record.pass_ms("trace"), paths = f.paths, steps = f.steps;
    out.push_back({"steps_per_path", f.frame_paths > 0.0 ? f.frame_steps / f.frame_paths : 0.0, ""});
    out.push_back({"walk_steps", f.frame_steps, ""});
    out.push_back({"walk_paths", f.frame_paths, ""});
    out.push_back({"paths_per_second", ms > 0.0 ? paths / (ms * 1e-3) : 0.0, "1/s"});
    out.push_back({"steps_per_second", ms > 0.0 ? steps / (ms * 1e-3) : 0.0, "1/s"});
    out.push_back({"traversals_per_step", steps > 0.0 ? f.traversals / steps : 0.0, ""});
    out.push_back({"traversals_per_next_event", f.next_events > 0.0 ? f.traversals_per_next_event() : 0.0, ""});
    out.push_back({"node_visits_per_step", steps > 0.0 ? f.node_visits / steps : 0.0, ""});
    out.push_back({"dispatches", f.dispatches, ""});
    out.push_back({"sparse_dispatches", f.sparse_dispatches, ""});
    out.push_back({"sparse_time_share", f.dispatch_ms > 0.0 ? f.sparse_ms / f.dispatch_ms : 0.0, ""});
    out.push_back({"read_backs", f.read_backs, ""});
    out.push_back({"loop_limited_paths", f.loop_limited, ""});
    out.push_back({"replayed_events", f.replayed, ""});
  }

  bool update_live_params(const Scene& scene) override {
    (void)scene;
    return true;
  }
  bool update_materials(const Scene& scene) override {
    const std::vector<shader::WalkObjectGPU> objects = walk_objects(scene, bvh_.triangles, boundary_);
    glNamedBufferSubData(objects_, 0, static_cast<GLsizeiptr>(objects.size() * sizeof(objects[0])), objects.data());
    return true;
  }
  std::size_t gpu_memory_bytes() const override {
    return accumulated_.gpu_memory_bytes() + sphere_bytes_ + grid_.distances.size() * sizeof(float) + path_capacity_ * sizeof(shader::WalkPathGPU) + result_capacity_ * sizeof(glm::vec4) + bvh_.nodes.size() * sizeof(shader::BvhNodeGPU) +
           bvh_.triangles.size() * sizeof(shader::TriangleGPU) + scene_.objects.size() * sizeof(shader::WalkObjectGPU) +
           boundary_.neighbours.size() * sizeof(glm::ivec4) + boundary_.areas.size() * sizeof(glm::vec2) +
           boundary_.faces.size() * sizeof(glm::vec4);
  }

 private:
  // Deforming meshes: the triangles at the frame's instant, the hierarchy refitted (same topology) and uploaded.
  void follow_animation(const FrameContext& context) {
    auto pass = context.profiler.pass("refit");
    const std::vector<shader::TriangleGPU> moved =
        random_walk::gather_scene_triangles(context.scene, context.time_seconds).triangles;
    // Every surface point moved at most as far as the corners (it is their convex combination): the distance grid
    // of the rest pose, minus that, still bounds the distance to the surfaces from below.
    float moved_most = 0.0f;
    for (std::size_t t = 0; t < moved.size() && t < rest_triangles_.size(); ++t) {
      const shader::TriangleGPU &a = moved[t], &b = rest_triangles_[t];
      moved_most = std::max({moved_most, glm::length(glm::vec3(a.p0) - glm::vec3(b.p0)),
                             glm::length(glm::vec3(a.p0 + a.e1) - glm::vec3(b.p0 + b.e1)),
                             glm::length(glm::vec3(a.p0 + a.e2) - glm::vec3(b.p0 + b.e2))});
    }
    surface_moved_ = moved_most;
    bvh_.refit(moved);
    glNamedBufferSubData(nodes_, 0, static_cast<GLsizeiptr>(bvh_.nodes.size() * sizeof(shader::BvhNodeGPU)), bvh_.nodes.data());
    glNamedBufferSubData(triangles_, 0, static_cast<GLsizeiptr>(bvh_.triangles.size() * sizeof(shader::TriangleGPU)),
                         bvh_.triangles.data());
    geometry_time_ = context.time_seconds;
    random_walk::update_walk_areas(boundary_, bvh_.triangles);
    glNamedBufferSubData(areas_, 0, static_cast<GLsizeiptr>(boundary_.areas.size() * sizeof(glm::vec2)),
                         boundary_.areas.data());
    const std::vector<shader::WalkObjectGPU> objects = walk_objects(context.scene, moved, boundary_);
    glNamedBufferSubData(objects_, 0, static_cast<GLsizeiptr>(objects.size() * sizeof(objects[0])), objects.data());
  }

  void upload_distance_grid() {
    if (grid_.distances.empty()) return;
    glCreateTextures(GL_TEXTURE_3D, 1, &distance_texture_);
    glTextureStorage3D(distance_texture_, 1, GL_R32F, grid_.cells.x, grid_.cells.y, grid_.cells.z);
    glTextureSubImage3D(distance_texture_, 0, 0, 0, 0, grid_.cells.x, grid_.cells.y, grid_.cells.z, GL_RED, GL_FLOAT,
                        grid_.distances.data());
    gpu::label_object(GL_TEXTURE, distance_texture_, "random-walk distance grid");
  }

  void allocate_pool(std::size_t slots, std::size_t results) {
    glDeleteBuffers(1, &paths_);
    glDeleteBuffers(1, &results_);
    const std::size_t bytes = slots * sizeof(shader::WalkPathGPU) + results * sizeof(glm::vec4);
    platform::require_device_memory(bytes, fmt::format("random-walk: {} paths in flight and {} results", slots, results));
    glCreateBuffers(1, &paths_);
    glNamedBufferStorage(paths_, static_cast<GLsizeiptr>(slots * sizeof(shader::WalkPathGPU)), nullptr, 0);
    gpu::label_object(GL_BUFFER, paths_, "random-walk paths in flight");
    glCreateBuffers(1, &results_);
    glNamedBufferStorage(results_, static_cast<GLsizeiptr>(results * sizeof(glm::vec4)), nullptr, 0);
    gpu::label_object(GL_BUFFER, results_, "random-walk path results");
    path_capacity_ = slots, result_capacity_ = results;
  }

  // One batch: the first dispatch starts a path in every slot; each control pass after a dispatch sets the next
  // one's work groups (none once the batch is done), so the host issues rounds of indirect dispatches and reads
  // the counters back once per round, the first round as long as the last batch needed (one read-back per batch
  // when the frames are alike).
  void trace_batch(std::size_t slots, bool reset, FrameStats& f) {
    const GLuint groups = static_cast<GLuint>((slots + LUCENT_WALK_POOL_GROUP - 1) / LUCENT_WALK_POOL_GROUP);
    constexpr GLbitfield kBarrier = GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT;
    auto set_dispatch = [&](unsigned first) {
      const glm::uvec4 control(first, loop_budget_, loop_cap_, 2u);
      glNamedBufferSubData(block_buffer_, offsetof(shader::RandomWalkGPU, dispatch), sizeof(control), &control);
    };
    auto control = [&] {
      glUseProgram(control_program_.id());
      glDispatchCompute(1, 1, 1);
      glMemoryBarrier(kBarrier);
    };
    // Measurement only: each dispatch waited for and timed by wall clock (where the work runs, on any driver), and
    // called sparse when the control pass after it counted it so.
    const bool timed = params_.boolean("time_dispatches");
    shader::WalkCountersGPU totals{};
    auto now = [&] { return timed ? (glFinish(), std::chrono::steady_clock::now()) : std::chrono::steady_clock::time_point{}; };
    auto since = [&](std::chrono::steady_clock::time_point start) {
      return std::chrono::duration<double, std::milli>(now() - start).count();
    };
    set_dispatch(reset ? 1u : 0u);
    const auto first_start = now();
    glUseProgram(program_.id());
    glDispatchCompute(groups, 1, 1);
    glMemoryBarrier(kBarrier);
    control();
    if (timed) f.dispatch_ms += since(first_start);
    set_dispatch(0u);
    unsigned round = timed ? 1u : std::max(1u, dispatch_estimate_);
    unsigned sparse_seen = 0;
    for (;;) {
      for (unsigned d = 0; d < round; ++d) {
        const auto start = now();
        glUseProgram(program_.id());
        glDispatchComputeIndirect(static_cast<GLintptr>(offsetof(shader::WalkCountersGPU, groups)));
        glMemoryBarrier(kBarrier);
        control();
        if (timed) {
          const double ms = since(start);
          glGetNamedBufferSubData(counters_, 0, sizeof(totals), &totals);
          f.dispatch_ms += ms;
          if (totals.sparse_dispatches != sparse_seen) f.sparse_ms += ms, sparse_seen = totals.sparse_dispatches;
        }
      }
      // The frame's paths into the image, if they have all finished (no work groups otherwise).
      glUseProgram(resolve_program_.id());
      glDispatchComputeIndirect(static_cast<GLintptr>(offsetof(shader::WalkCountersGPU, resolve_groups)));
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
      glGetNamedBufferSubData(counters_, 0, sizeof(totals), &totals);
      ++f.read_backs;
      if (totals.lost != 0)
        throw Error(fmt::format("random-walk: the frame lost {} of its {} paths (region {}: {} started, {} finished, "
                                "no slot holding one); the trace pass took a path index and did not trace it, which "
                                "the driver's loop cap can cause (docs/methods/random-walk.md, \"Paths in flight\")",
                                totals.lost, totals.finished[region_] + totals.lost,
                                region_, totals.next_path[region_], totals.finished[region_]));
      if (totals.groups.x == 0) break;
      // Bounded: nothing bounds a path's length (max_scatter 0), and a path that never leaves would keep the frame.
      const auto max_dispatches = static_cast<unsigned>(params_.integer("max_dispatches"));
      if (totals.dispatches >= max_dispatches)  // with the frame's counts, to tell a long path from a lost one
        throw Error(fmt::format("random-walk: paths still in flight after {} trace dispatches of up to {} steps "
                                "each (method.max_dispatches; the frame's region {} started {} paths and finished {}, "
                                "{} slots holding a path); a medium without absorption whose paths do not leave? Set "
                                "max_scatter, or give it some absorption",
                                totals.dispatches, loop_budget_, region_, totals.next_path[region_],
                                totals.finished[region_], totals.last_busy));
      round = std::max(round, 4u);  // not done: rounds of at least 4, few read-backs in the tail
    }
    // The next first round: as long as this batch needed, or 7/8 of the last round when that was longer (a frame of
    // short paths between two with long ones would otherwise cost the next long one several read-backs; a dispatch
    // with no work groups costs next to nothing).
    dispatch_estimate_ = std::max({1u, totals.dispatches, dispatch_estimate_ - dispatch_estimate_ / 8});
    auto wide = [](glm::uvec2 v) { return static_cast<double>(v.x) + 4294967296.0 * static_cast<double>(v.y); };
    f.paths += totals.paths, f.steps += wide(totals.steps), f.traversals += wide(totals.traversals);
    f.node_visits += wide(totals.node_visits), f.next_events += wide(totals.next_events);
    f.next_event_traversals += wide(totals.next_event_traversals);
    f.dispatches += 1 + totals.dispatches, f.sparse_dispatches += totals.sparse_dispatches;
    f.frame_paths += totals.frame_paths, f.frame_steps += wide(totals.frame_steps);
    f.loop_limited += totals.loop_limited, f.replayed += totals.replayed;
  }

  // The pinhole camera of the frame's projection: the ray through normalized device coordinates (x, y) is
  // forward + x tan_x right + y tan_y up, as the references' camera_ray.
  static void set_camera(const shader::FrameGPU& frame, shader::RandomWalkGPU& block) {
    const glm::dmat4 world_from_clip = glm::inverse(glm::dmat4(frame.clip_from_world));
    auto unproject = [&](double x, double y) {
      const glm::dvec4 p = world_from_clip * glm::dvec4(x, y, -1.0, 1.0);
      return glm::dvec3(p) / p.w;
    };
    const glm::dvec3 eye(frame.camera_position), centre = unproject(0.0, 0.0);
    const glm::dvec3 to_right = unproject(1.0, 0.0) - centre, to_top = unproject(0.0, 1.0) - centre;
    const double distance = glm::length(centre - eye);
    const double tan_x = glm::length(to_right) / distance, tan_y = glm::length(to_top) / distance;
    block.eye = glm::vec4(glm::vec3(eye), 1.0f);
    block.forward = glm::vec4(glm::vec3(glm::normalize(centre - eye)), static_cast<float>(tan_y));
    block.right = glm::vec4(glm::vec3(glm::normalize(to_right)), static_cast<float>(tan_x / tan_y));
    block.up = glm::vec4(glm::vec3(glm::normalize(to_top)), 0.0f);
  }

  // Media the walk cannot represent are refused: blob surfaces (extracted on the GPU, not in the shared index
  // buffer) and translucent objects whose boxes overlap (nested or intersecting media: a path inside one medium
  // would cross into the other without a boundary event, as in volpath, which does not support them either).
  static void check_representable(const Scene& scene) {
    std::vector<std::pair<glm::vec3, glm::vec3>> boxes(scene.objects.size());
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      const SceneObject& object = scene.objects[i];
      if (object.blob_resolution > 0)
        throw Error(fmt::format("{}: /objects/{}: method 'random-walk' does not trace blob surfaces (extracted on the "
                                "GPU each frame); the other methods and the references do",
                                scene.source, i));
      if (!object.translucent()) continue;
      const TriangleMesh world = transformed(object.mesh, object.world_from_object);
      glm::vec3 lower(1e30f), upper(-1e30f);
      for (const glm::vec3& p : world.positions) lower = glm::min(lower, p), upper = glm::max(upper, p);
      boxes[i] = {lower, upper};
      for (std::size_t j = 0; j < i; ++j) {
        if (!scene.objects[j].translucent()) continue;
        const bool overlap = glm::all(glm::lessThan(boxes[j].first, upper)) && glm::all(glm::lessThan(lower, boxes[j].second));
        if (overlap && world_meshes_intersect(scene, i, j))
          throw Error(fmt::format("{}: /objects/{} and /objects/{}: nested or intersecting media; method 'random-walk' "
                                  "(like the volpath reference) needs each translucent object's interior to be its own",
                                  scene.source, j, i));
      }
    }
  }

  // Whether object i has a vertex inside object j's closed surface or j one inside i's (nested or intersecting).
  static bool world_meshes_intersect(const Scene& scene, std::size_t i, std::size_t j) {
    const TriangleMesh a = transformed(scene.objects[i].mesh, scene.objects[i].world_from_object);
    const TriangleMesh b = transformed(scene.objects[j].mesh, scene.objects[j].world_from_object);
    auto any_inside = [](const TriangleMesh& points, const TriangleMesh& surface) {
      if (open_edge_count(surface) != 0) return false;
      const std::size_t step = std::max<std::size_t>(1, points.positions.size() / 64);
      for (std::size_t v = 0; v < points.positions.size(); v += step)
        if (encloses(surface, glm::dvec3(points.positions[v]))) return true;
      return false;
    };
    return any_inside(a, b) || any_inside(b, a);
  }

  // Per FrameGPU light (directional lights first, then point and spot lights in the scene's order): the
  // translucent object whose closed surface encloses it, or -1 (volpath's medium_of_point_light).
  std::vector<int> point_light_media(const Scene& scene) const {
    std::vector<int> media(lights_.size(), -1);
    const std::size_t first_point = lights_.size() - scene.point_lights.size();
    for (std::size_t l = 0; l < scene.point_lights.size(); ++l)
      for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        if (!object.translucent()) continue;
        const TriangleMesh world = transformed(object.mesh, object.world_from_object);
        if (open_edge_count(world) == 0 && encloses(world, glm::dvec3(scene.point_lights[l].position)))
          media[first_point + l] = static_cast<int>(i);
      }
    return media;
  }

  const Scene& scene_;
  const ParamValues& params_;
  gpu::ShaderProgram program_;
  std::vector<shader::LightGPU> lights_;
  std::vector<int> light_media_;
  render::ViewAccumulator accumulated_{"random-walk accumulated radiance"};
  gpu::ShaderProgram control_program_, resolve_program_;
  GLuint block_buffer_ = 0, nodes_ = 0, triangles_ = 0, objects_ = 0, paths_ = 0, results_ = 0, counters_ = 0;
  GLuint neighbours_ = 0, areas_ = 0, faces_ = 0;  // the surfaces the chain solvers walk on (walk_boundary.h)
  std::size_t path_capacity_ = 0, result_capacity_ = 0;
  unsigned loop_cap_ = 0, loop_budget_ = 0;
  unsigned dispatch_estimate_ = 8;
  bool pool_reset_ = true;  // the next frame starts with every slot free
  unsigned region_ = 0;     // the results region of the current frame's paths (the next frames': the following)
  std::size_t ring_ = 1;    // regions in the ring: frames in flight at most  // indirect dispatches the last batch had work for after its first
  std::array<FrameStats, 8> frame_stats_{};
  random_walk::TriangleBvh bvh_;
  random_walk::WalkBoundary boundary_;
  std::vector<shader::TriangleGPU> rest_triangles_;  // as gathered at time 0, in the scene's order
  double geometry_time_ = 0.0;
  float surface_moved_ = 0.0f;  // how far the surfaces moved from the rest pose the distance grid was built for
  std::vector<float> jump_banks_;
  random_walk::DistanceGrid grid_;
  GLuint distance_texture_ = 0, spheres_ = 0;
  gpu::ShaderProgram sphere_program_;
  int records_per_level_ = 0;
  int levels_used_ = 0;  // sphere-jump levels small enough to fit somewhere in a medium with jumps
  int jump_records_[shader::kSphereJumpLevelCount] = {};
  std::size_t sphere_bytes_ = 0;
  unsigned samples_done_ = 0, samples_this_frame_ = 1;
};

}  // namespace

std::unique_ptr<Method> create_random_walk(const MethodSetup& setup) {
  return std::make_unique<RandomWalk>(setup.scene, setup.scene_gpu);
}

}  // namespace lucent::methods
