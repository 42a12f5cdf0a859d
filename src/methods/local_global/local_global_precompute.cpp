// local_global_precompute.cpp: see local_global_precompute.h.
#include "methods/local_global/local_global_precompute.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>

#include <fmt/format.h>

#include "bssrdf/model.h"
#include "cache/precompute_cache.h"
#include "lucent/error.h"
#include "methods/local_global/remesh.h"
#include "texture_space/scene_atlas.h"
#include "texture_space/uv_raster.h"

namespace lucent::methods::local_global {
namespace {

constexpr std::uint32_t kMagic = 0x4c474c31u;  // "LGL1"
constexpr int kRadialSamples = 4096;
// Tikhonov weight of the blending fit per ring texel: a basis function whose values on the ring sum (squared) to
// less than about this per ring texel is left at weight 0. Without it, a ring that barely touches a hat (phi ~ 1e-3
// on one texel) gave weights of 9 and more, whose kernel correction cancels only at texel centres: negative
// radiance in spots. Plain least squares otherwise (the normal matrix of a ring inside the hats is ~0.1-1 per texel).
constexpr double kRidge = 1e-3;

// Runs body(i) for i in [0, n) on every hardware thread; the calling thread takes part and reports
// progress(done / n) after each of its chunks. The first exception thrown by a body is rethrown.
template <typename Body>
void parallel_for(std::size_t n, const std::function<void(double)>& progress, Body&& body) {
  const std::size_t chunk = std::max<std::size_t>(1, n / 512);
  std::atomic<std::size_t> next{0}, done{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](bool report) {
    for (;;) {
      const std::size_t begin = next.fetch_add(chunk);
      if (begin >= n) return;
      const std::size_t end = std::min(n, begin + chunk);
      try {
        for (std::size_t i = begin; i < end; ++i) body(i);
        const std::size_t total = done.fetch_add(end - begin) + (end - begin);
        // A progress callback may throw to abandon the work (lucent.Renderer's Ctrl-C): caught here like a body's
        // exception, so that the pool's threads are joined before it is rethrown.
        if (report && progress) progress(static_cast<double>(total) / static_cast<double>(n));
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = n;
        return;
      }
    }
  };
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, false);
  work(true);
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

// One covered atlas texel.
struct Texel {
  std::uint32_t object;      // atlas object
  std::uint32_t triangle;    // of that object's mesh
  glm::dvec3 lambda;         // barycentric coordinates of the centre
  glm::dvec3 x;              // world position of the centre
  double area;               // world area per texel
  std::array<std::uint32_t, 3> vertex;  // welded global vertices of the triangle
};

struct ObjectGeometry {
  std::vector<glm::dvec3> vertex_position;  // welded, world
  std::vector<double> vertex_area;          // A_i: area of the triangles around i
  std::vector<glm::dvec3> vertex_normal;    // area-weighted mean of the triangles' normals around i
  std::vector<std::uint32_t> corner_vertex; // welded vertex per corner (local numbering)
};

std::function<void(double)> sub_progress(const std::function<void(double)>& progress, double from, double to) {
  return [progress, from, to](double f) {
    if (progress) progress(from + (to - from) * std::clamp(f, 0.0, 1.0));
  };
}

// Byte writer and reader of the encoding.
struct Writer {
  std::vector<std::byte> bytes;
  template <typename T>
  void value(const T& v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  template <typename T>
  void array(const std::vector<T>& v) {
    value(static_cast<std::uint64_t>(v.size()));
    if (v.empty()) return;
    const auto* p = reinterpret_cast<const std::byte*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
  }
};

struct Reader {
  std::span<const std::byte> bytes;
  std::size_t at = 0;
  void need(std::size_t n) const {
    if (bytes.size() - at < n) throw Error("local-global: precomputed data is truncated");
  }
  template <typename T>
  T value() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  template <typename T>
  std::vector<T> array() {
    const auto n = value<std::uint64_t>();
    if (n > (bytes.size() - at) / sizeof(T)) throw Error("local-global: precomputed data is truncated");
    std::vector<T> v(static_cast<std::size_t>(n));
    if (!v.empty()) std::memcpy(v.data(), bytes.data() + at, v.size() * sizeof(T));
    at += v.size() * sizeof(T);
    return v;
  }
};

}  // namespace

RadialProfile::RadialProfile(int model, float sigma_a, float sigma_s, float g, float eta, float thickness, double r_end)
    : model_(model), eta_(eta), sigma_a_(sigma_a), sigma_s_(sigma_s), g_(g), thickness_(thickness) {
  const shader::BandMedium m = shader::make_band_medium(sigma_a, sigma_s, g);
  // Geometric radii from a small fraction of the mean free path (the profile is flat below it) to r_end; the
  // integral over [0, r_0] is the disk's area times R_d(r_0).
  const double r0 = std::min(1e-4 / static_cast<double>(m.sigma_t_prime), 1e-6 * r_end);
  radius_.resize(kRadialSamples);
  cumulative_.resize(kRadialSamples);
  const double ratio = std::pow(r_end / r0, 1.0 / (kRadialSamples - 1));
  double r = r0;
  for (int i = 0; i < kRadialSamples; ++i, r *= ratio) radius_[static_cast<std::size_t>(i)] = r;
  radius_.back() = r_end;
  double previous = 2.0 * M_PI * r0 * Rd(r0);
  cumulative_[0] = M_PI * r0 * r0 * Rd(r0);
  for (std::size_t i = 1; i < radius_.size(); ++i) {
    const double f = 2.0 * M_PI * radius_[i] * Rd(radius_[i]);
    cumulative_[i] = cumulative_[i - 1] + 0.5 * (f + previous) * (radius_[i] - radius_[i - 1]);
    previous = f;
  }
}

double RadialProfile::Rd(double r) const {
  shader::BandMedium m = shader::make_band_medium(sigma_a_, sigma_s_, g_);
  m.thickness = thickness_;
  return static_cast<double>(shader::bssrdf_radial_Rd(model_, m, eta_, static_cast<float>(r)));
}

double RadialProfile::Rd(glm::dvec3 x_i, glm::dvec3 n_i, glm::dvec3 x_o, glm::dvec3 n_o) const {
  if (model_ != LUCENT_MODEL_MULTIPOLE) return Rd(glm::length(x_o - x_i));  // the distance in double, as before
  shader::BandMedium m = shader::make_band_medium(sigma_a_, sigma_s_, g_);
  m.thickness = thickness_;
  // The difference in double (far from the origin float loses it), x_i at the origin.
  return static_cast<double>(
      shader::bssrdf_pair_Rd(model_, m, eta_, glm::vec3(0.0f), glm::vec3(n_i), glm::vec3(x_o - x_i), glm::vec3(n_o)));
}

double RadialProfile::disk_integral(double rho) const {
  if (rho <= radius_.front()) return M_PI * rho * rho * Rd(radius_.front());
  if (rho >= radius_.back()) return cumulative_.back();
  const auto it = std::upper_bound(radius_.begin(), radius_.end(), rho);
  const std::size_t i = static_cast<std::size_t>(it - radius_.begin());
  const double t = (rho - radius_[i - 1]) / (radius_[i] - radius_[i - 1]);
  return cumulative_[i - 1] + t * (cumulative_[i] - cumulative_[i - 1]);
}

double RadialProfile::tail_radius(double fraction) const {
  const double keep = (1.0 - fraction) * cumulative_.back();
  const auto it = std::lower_bound(cumulative_.begin(), cumulative_.end(), keep);
  if (it == cumulative_.end()) return radius_.back();
  return radius_[static_cast<std::size_t>(it - cumulative_.begin())];
}

Settings settings_from(const ParamValues& params) {
  Settings s;
  s.cutoff = params.number("cutoff");
  s.blend = params.boolean("blend");
  s.max_form_factors = params.number("max_form_factors");
  s.remesh = params.boolean("remesh");
  s.vertex_spacing_mm = params.number("vertex_spacing");
  s.max_vertices = params.number("max_vertices");
  return s;
}

double vertex_spacing(const Scene& scene, const SceneObject& object) {
  const TriangleMesh world = transformed(object.mesh, object.world_from_object);
  glm::dvec3 lower(1e300), upper(-1e300);
  for (const glm::vec3& p : world.positions) {
    lower = glm::min(lower, glm::dvec3(p));
    upper = glm::max(upper, glm::dvec3(p));
  }
  double spacing = glm::length(upper - lower) / 50.0;
  if (object.material) {
    const glm::vec3 sigma_tr = object.material->sigma_tr() * scene.scale_mm;  // [1/scene unit]
    const double largest = std::max({sigma_tr.x, sigma_tr.y, sigma_tr.z});
    if (largest > 0.0) spacing = std::min(spacing, 1.0 / largest);
  }
  return spacing;
}

namespace {

constexpr std::uint32_t kRemeshVersion = 1;

std::vector<std::byte> encode_mesh(const TriangleMesh& mesh) {
  Writer w;
  w.array(mesh.positions);
  w.array(mesh.normals);
  w.array(mesh.indices);
  return std::move(w.bytes);
}

TriangleMesh decode_mesh(std::span<const std::byte> bytes) {
  Reader r{bytes};
  TriangleMesh mesh;
  mesh.positions = r.array<glm::vec3>();
  mesh.normals = r.array<glm::vec3>();
  mesh.indices = r.array<std::uint32_t>();
  if (r.at != bytes.size() || mesh.normals.size() != mesh.positions.size())
    throw Error("local-global: cached remeshed mesh is damaged");
  return mesh;
}

}  // namespace

Scene remeshed_scene(const Scene& scene, const Settings& settings, const std::function<void(double)>& progress) {
  check_rigid(scene);
  Scene out = scene;
  if (!settings.remesh) return out;
  std::vector<std::size_t> translucent;
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].translucent()) translucent.push_back(i);
  for (std::size_t n = 0; n < translucent.size(); ++n) {
    SceneObject& object = out.objects[translucent[n]];
    const double spacing = settings.vertex_spacing_mm > 0.0 ? settings.vertex_spacing_mm / scene.scale_mm
                                                            : vertex_spacing(scene, object);
    TriangleMesh world = transformed(object.mesh, object.world_from_object);
    // Round triangles of edge e have area sqrt(3) e^2 / 4, and a closed surface has half as many vertices as triangles.
    const double area = surface_area(world);
    const double estimate = area / (std::sqrt(3.0) / 4.0 * spacing * spacing) / 2.0;
    if (estimate > settings.max_vertices)
      throw Error(fmt::format(
          "{}: object '{}': /method/vertex_spacing: remeshing to {:.3g} mm edges{} would give about {:.3g} vertices, more "
          "than /method/max_vertices = {:.4g}; set /method/vertex_spacing to at least {:.3g} mm or raise max_vertices",
          scene.source, object.name, spacing * scene.scale_mm,
          settings.vertex_spacing_mm > 0.0 ? "" : " (the material's shortest diffusion length)", estimate,
          settings.max_vertices, spacing * std::sqrt(estimate / settings.max_vertices) * scene.scale_mm * 1.01));
    RemeshOptions options;
    options.target_edge = spacing;
    cache::Key key("local-global-remesh", kRemeshVersion);
    key.mesh(object.mesh).number(options.target_edge).number(options.feature_deg).integer(options.iterations);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) key.number(object.world_from_object[c][r]);
    TriangleMesh remeshed;
    std::optional<std::vector<std::byte>> cached = cache::load(key);
    bool decoded = false;
    if (cached) {
      try {
        remeshed = decode_mesh(*cached);
        decoded = true;
      } catch (const Error&) {
        decoded = false;
      }
    }
    if (!decoded) {
      try {
        remeshed = remesh_isotropic(world, options);
      } catch (const Error& e) {
        throw Error(fmt::format("{}: object '{}': {}", scene.source, object.name, e.what()));
      }
      cache::store(key, encode_mesh(remeshed));
    }
    // Back to object space: the transform stays the object's.
    const glm::mat4 object_from_world = glm::inverse(object.world_from_object);
    object.mesh = transformed(remeshed, object_from_world);
    if (progress) progress(static_cast<double>(n + 1) / static_cast<double>(translucent.size()));
  }
  return out;
}

void check_rigid(const Scene& scene) {
  for (const SceneObject& object : scene.objects) {
    if (!object.translucent()) continue;
    if (object.blob_resolution > 0)
      throw Error(fmt::format("{}: object '{}': local-global precomputes transport over a fixed mesh; a blob surface "
                              "is re-extracted every frame",
                              scene.source, object.name));
    if (object.deformation.type != DeformationType::None)
      throw Error(fmt::format("{}: object '{}': local-global precomputes transport over a fixed mesh; deforming "
                              "objects are not supported (rigid objects only)",
                              scene.source, object.name));
  }
}

LocalGlobalData compute(const Scene& scene, const texture_space::SceneAtlas& atlas, const Settings& settings,
                        const std::function<void(double)>& progress) {
  check_rigid(scene);
  LocalGlobalData out;
  const int size = atlas.atlas.size;
  out.atlas_size = size;
  const std::size_t object_count = atlas.object_index.size();

  // Welded vertices, their areas, the materials' profiles.
  std::vector<ObjectGeometry> geometry(object_count);
  std::vector<std::array<RadialProfile, 3>> profiles;
  profiles.reserve(object_count);
  std::uint32_t vertex_base = 0;
  for (std::size_t k = 0; k < object_count; ++k) {
    const SceneObject& object = scene.objects[atlas.object_index[k]];
    const TriangleMesh& mesh = object.mesh;
    if (mesh.uvs.size() != mesh.positions.size())
      throw Error(fmt::format("{}: object '{}': local-global needs the atlas mesh (texture coordinates)", scene.source,
                              object.name));
    ObjectGeometry& g = geometry[k];
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> buckets;
    std::vector<std::uint32_t> welded(mesh.positions.size());
    glm::dvec3 lower(1e300), upper(-1e300);
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec3 p = mesh.positions[v];
      std::uint32_t bits[3];
      std::memcpy(bits, &p, sizeof(bits));
      const std::uint64_t h = (static_cast<std::uint64_t>(bits[0]) * 0x9e3779b97f4a7c15ull) ^
                              (static_cast<std::uint64_t>(bits[1]) * 0xc2b2ae3d27d4eb4full) ^ bits[2];
      std::vector<std::uint32_t>& bucket = buckets[h];
      const glm::dvec3 w(object.world_from_object * glm::vec4(p, 1.0f));
      std::uint32_t id = UINT32_MAX;
      for (std::uint32_t candidate : bucket)
        if (g.vertex_position[candidate] == w) id = candidate;
      if (id == UINT32_MAX) {
        id = static_cast<std::uint32_t>(g.vertex_position.size());
        g.vertex_position.push_back(w);
        bucket.push_back(id);
        lower = glm::min(lower, w);
        upper = glm::max(upper, w);
      }
      welded[v] = id;
    }
    g.vertex_area.assign(g.vertex_position.size(), 0.0);
    // The mesh's own normals (outward, as the GPU methods read them), to world space and summed over welded copies;
    // the triangles' winding where the mesh has none (the loader may flip normals without reordering triangles, and
    // a mirroring transform reverses the winding).
    g.vertex_normal.assign(g.vertex_position.size(), glm::dvec3(0.0));
    const bool own_normals = mesh.normals.size() == mesh.positions.size();
    const glm::dmat3 normal_to_world = glm::transpose(glm::inverse(glm::dmat3(glm::mat3(object.world_from_object))));
    if (own_normals)
      for (std::size_t v = 0; v < mesh.normals.size(); ++v)
        g.vertex_normal[welded[v]] += normal_to_world * glm::dvec3(mesh.normals[v]);
    g.corner_vertex.resize(mesh.indices.size());
    for (std::size_t c = 0; c + 2 < mesh.indices.size(); c += 3) {
      const std::uint32_t a = welded[mesh.indices[c]], b = welded[mesh.indices[c + 1]], d = welded[mesh.indices[c + 2]];
      const double area = 0.5 * glm::length(glm::cross(g.vertex_position[b] - g.vertex_position[a],
                                                        g.vertex_position[d] - g.vertex_position[a]));
      g.vertex_area[a] += area;
      g.vertex_area[b] += area;
      g.vertex_area[d] += area;
      if (!own_normals) {
        const glm::dvec3 n = glm::cross(g.vertex_position[b] - g.vertex_position[a], g.vertex_position[d] - g.vertex_position[a]);
        g.vertex_normal[a] += n, g.vertex_normal[b] += n, g.vertex_normal[d] += n;
      }
      g.corner_vertex[c] = a;
      g.corner_vertex[c + 1] = b;
      g.corner_vertex[c + 2] = d;
    }
    for (glm::dvec3& n : g.vertex_normal) n = glm::length(n) > 0.0 ? glm::normalize(n) : n;
    for (std::uint32_t v : g.corner_vertex) out.corner_vertex.push_back(vertex_base + v);
    const Material& material = *object.material;
    const double diameter = std::max(glm::length(upper - lower), 1e-30);
    const glm::vec3 sa = material.sigma_a * scene.scale_mm, ss = material.sigma_s * scene.scale_mm;
    const int model = static_cast<int>(material.model);
    const float thickness = material.thickness_mm / scene.scale_mm;
    profiles.push_back({RadialProfile(model, sa.x, ss.x, material.g.x, material.eta, thickness, diameter),
                        RadialProfile(model, sa.y, ss.y, material.g.y, material.eta, thickness, diameter),
                        RadialProfile(model, sa.z, ss.z, material.g.z, material.eta, thickness, diameter)});
    ObjectSummary summary;
    summary.scene_object = static_cast<std::uint32_t>(atlas.object_index[k]);
    summary.first_vertex = vertex_base;
    summary.vertex_count = static_cast<std::uint32_t>(g.vertex_position.size());
    double cutoff_radius = settings.cutoff > 0.0 ? 0.0 : diameter;
    for (int b = 0; b < 3; ++b) {
      summary.total_reflectance[b] = static_cast<float>(profiles.back()[static_cast<std::size_t>(b)].total());
      if (settings.cutoff > 0.0)
        cutoff_radius = std::max(cutoff_radius, profiles.back()[static_cast<std::size_t>(b)].tail_radius(settings.cutoff));
    }
    summary.cutoff_radius = static_cast<float>(cutoff_radius);
    out.objects.push_back(summary);
    vertex_base += summary.vertex_count;
  }
  if (progress) progress(0.02);

  // Covered texels: centre on a triangle (the first triangle that claims it).
  std::vector<std::int32_t> texel_at(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), -1);
  std::vector<Texel> texels;
  for (std::size_t k = 0; k < object_count; ++k) {
    const SceneObject& object = scene.objects[atlas.object_index[k]];
    const TriangleMesh& mesh = object.mesh;
    const ObjectGeometry& g = geometry[k];
    const std::uint32_t base = out.objects[k].first_vertex;
    for (std::size_t c = 0; c + 2 < mesh.indices.size(); c += 3) {
      const glm::dvec2 ua(mesh.uvs[mesh.indices[c]]), ub(mesh.uvs[mesh.indices[c + 1]]), uc(mesh.uvs[mesh.indices[c + 2]]);
      const glm::dvec3 pa = g.vertex_position[g.corner_vertex[c]], pb = g.vertex_position[g.corner_vertex[c + 1]],
                       pc = g.vertex_position[g.corner_vertex[c + 2]];
      const double world_area = 0.5 * glm::length(glm::cross(pb - pa, pc - pa));
      const double texel_area = 0.5 * std::abs(texture_space::signed_area2(ua, ub, uc)) * size * size;
      if (texel_area <= 0.0 || world_area <= 0.0) continue;
      const double area2 = texture_space::signed_area2(ua, ub, uc);
      texture_space::for_each_cell_inside(ua, ub, uc, size, -1e-12, [&](int x, int y) {
        std::int32_t& slot = texel_at[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)];
        if (slot >= 0) return;
        const glm::dvec2 p((x + 0.5) / size, (y + 0.5) / size);
        const double l0 = texture_space::signed_area2(ub, uc, p) / area2, l1 = texture_space::signed_area2(uc, ua, p) / area2;
        Texel t;
        t.object = static_cast<std::uint32_t>(k);
        t.triangle = static_cast<std::uint32_t>(c / 3);
        t.lambda = glm::dvec3(l0, l1, 1.0 - l0 - l1);
        t.x = t.lambda.x * pa + t.lambda.y * pb + t.lambda.z * pc;
        t.area = world_area / texel_area;
        t.vertex = {base + g.corner_vertex[c], base + g.corner_vertex[c + 1], base + g.corner_vertex[c + 2]};
        slot = static_cast<std::int32_t>(texels.size());
        texels.push_back(t);
        out.texel_xy.push_back(static_cast<std::uint32_t>(x) | (static_cast<std::uint32_t>(y) << 16));
      });
    }
  }
  for (const Texel& t : texels) ++out.objects[t.object].texel_count;
  if (progress) progress(0.05);

  // Flat vertex tables over all objects.
  const std::size_t vertex_count = vertex_base;
  std::vector<glm::dvec3> position(vertex_count);
  std::vector<double> vertex_area(vertex_count);
  std::vector<std::uint32_t> vertex_object(vertex_count);
  std::vector<glm::dvec3> vertex_normal(vertex_count);
  for (std::size_t k = 0; k < object_count; ++k)
    for (std::size_t v = 0; v < geometry[k].vertex_position.size(); ++v) {
      position[out.objects[k].first_vertex + v] = geometry[k].vertex_position[v];
      vertex_normal[out.objects[k].first_vertex + v] = geometry[k].vertex_normal[v];
      vertex_area[out.objects[k].first_vertex + v] = geometry[k].vertex_area[v];
      vertex_object[out.objects[k].first_vertex + v] = static_cast<std::uint32_t>(k);
    }

  // F'_ij = (A_i / 3) R_d(v_i, v_j), i != j, within the cutoff radius; row j lists its sources i. R_d of the pair
  // (bssrdf_pair_Rd): the radial profile at their distance, or the multipole's transmittance across a thin part.
  auto form_factor = [&](std::uint32_t i, std::uint32_t j) {
    glm::dvec3 f(0.0);
    if (i == j || vertex_object[i] != vertex_object[j]) return f;
    const std::uint32_t k = vertex_object[i];
    const double r = glm::length(position[i] - position[j]);
    if (r > out.objects[k].cutoff_radius) return f;
    for (int b = 0; b < 3; ++b)
      f[b] = vertex_area[i] / 3.0 * profiles[k][static_cast<std::size_t>(b)].Rd(position[i], vertex_normal[i], position[j], vertex_normal[j]);
    return f;
  };
  // Neighbour candidates by a uniform grid per object.
  struct Grid {
    glm::dvec3 lower{0.0};
    double cell = 1.0;
    glm::ivec3 dims{1};
    std::vector<std::uint32_t> start, items;
  };
  std::vector<Grid> grids(object_count);
  for (std::size_t k = 0; k < object_count; ++k) {
    Grid& grid = grids[k];
    const ObjectSummary& o = out.objects[k];
    glm::dvec3 lower(1e300), upper(-1e300);
    for (std::uint32_t v = 0; v < o.vertex_count; ++v) {
      lower = glm::min(lower, position[o.first_vertex + v]);
      upper = glm::max(upper, position[o.first_vertex + v]);
    }
    const double extent = std::max({upper.x - lower.x, upper.y - lower.y, upper.z - lower.z, 1e-30});
    grid.cell = std::max(static_cast<double>(o.cutoff_radius), extent / 64.0);
    grid.lower = lower;
    grid.dims = glm::max(glm::ivec3(1), glm::ivec3(glm::ceil((upper - lower) / grid.cell)) + 1);
    const std::size_t cells = static_cast<std::size_t>(grid.dims.x) * grid.dims.y * grid.dims.z;
    grid.start.assign(cells + 1, 0);
    auto cell_of = [&](const glm::dvec3& p) {
      const glm::ivec3 c = glm::clamp(glm::ivec3((p - grid.lower) / grid.cell), glm::ivec3(0), grid.dims - 1);
      return (static_cast<std::size_t>(c.z) * grid.dims.y + c.y) * grid.dims.x + c.x;
    };
    for (std::uint32_t v = 0; v < o.vertex_count; ++v) ++grid.start[cell_of(position[o.first_vertex + v]) + 1];
    for (std::size_t c = 0; c < cells; ++c) grid.start[c + 1] += grid.start[c];
    grid.items.resize(o.vertex_count);
    std::vector<std::uint32_t> fill(grid.start.begin(), grid.start.end() - 1);
    for (std::uint32_t v = 0; v < o.vertex_count; ++v) grid.items[fill[cell_of(position[o.first_vertex + v])]++] = o.first_vertex + v;
  }
  auto for_each_neighbour = [&](std::uint32_t j, auto&& visit) {
    const std::uint32_t k = vertex_object[j];
    const Grid& grid = grids[k];
    const double rc = out.objects[k].cutoff_radius;
    const glm::ivec3 lo = glm::clamp(glm::ivec3(glm::floor((position[j] - rc - grid.lower) / grid.cell)), glm::ivec3(0), grid.dims - 1);
    const glm::ivec3 hi = glm::clamp(glm::ivec3(glm::floor((position[j] + rc - grid.lower) / grid.cell)), glm::ivec3(0), grid.dims - 1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const std::size_t c = (static_cast<std::size_t>(z) * grid.dims.y + y) * grid.dims.x + x;
          for (std::uint32_t n = grid.start[c]; n < grid.start[c + 1]; ++n) {
            const std::uint32_t i = grid.items[n];
            if (i != j && glm::length(position[i] - position[j]) <= rc) visit(i);
          }
        }
  };
  std::vector<std::uint32_t> row_count(vertex_count, 0);
  parallel_for(vertex_count, sub_progress(progress, 0.05, 0.1), [&](std::size_t j) {
    std::uint32_t n = 0;
    for_each_neighbour(static_cast<std::uint32_t>(j), [&](std::uint32_t) { ++n; });
    row_count[j] = n;
  });
  out.row_offsets.assign(vertex_count + 1, 0);
  for (std::size_t j = 0; j < vertex_count; ++j) out.row_offsets[j + 1] = out.row_offsets[j] + row_count[j];
  {
    double nnz = 0.0;
    for (std::uint32_t n : row_count) nnz += n;
    if (nnz > settings.max_form_factors)
      throw Error(fmt::format("{}: /method/max_form_factors: the global matrix would hold {:.4g} form factors ({:.2f} GiB) "
                              "for {} vertices, more than max_form_factors = {:.4g}; raise it, raise /method/cutoff "
                              "(cutoff radius {:.4g} scene units) or /method/vertex_spacing",
                              scene.source, nnz, nnz * sizeof(FormFactor) / 1073741824.0, vertex_count,
                              settings.max_form_factors, out.objects.empty() ? 0.0 : out.objects[0].cutoff_radius));
  }
  out.form_factors.resize(out.row_offsets.back());
  parallel_for(vertex_count, sub_progress(progress, 0.1, 0.5), [&](std::size_t j) {
    std::uint32_t at = out.row_offsets[j];
    for_each_neighbour(static_cast<std::uint32_t>(j), [&](std::uint32_t i) {
      out.form_factors[at++] = FormFactor{i, glm::vec3(form_factor(i, static_cast<std::uint32_t>(j)))};
    });
  });

  // Local kernels, dual weights and, when blending, the direct weights and corrected kernels.
  const std::size_t texel_count = texels.size();
  out.kernels.assign(texel_count * kKernelTaps * 3, 0.0f);
  std::vector<std::array<glm::dvec3, 3>> direct(texel_count);
  std::vector<std::array<double, 3>> dual(texel_count);
  parallel_for(texel_count, sub_progress(progress, 0.5, 0.98), [&](std::size_t qi) {
    const Texel& q = texels[qi];
    const auto& profile = profiles[q.object];
    for (int a = 0; a < 3; ++a)
      dual[qi][static_cast<std::size_t>(a)] = 3.0 / vertex_area[q.vertex[static_cast<std::size_t>(a)]] *
                                              (4.0 * q.lambda[a] - 1.0) * q.area;
    const int qx = static_cast<int>(out.texel_xy[qi] & 0xffffu), qy = static_cast<int>(out.texel_xy[qi] >> 16);
    // The 9 x 9 neighbourhood's texels of the same object.
    struct Neighbour {
      int dx, dy;
      const Texel* t;
    };
    std::vector<Neighbour> near;
    near.reserve(81);
    for (int dy = -kRingRadius; dy <= kRingRadius; ++dy)
      for (int dx = -kRingRadius; dx <= kRingRadius; ++dx) {
        const int x = qx + dx, y = qy + dy;
        if (x < 0 || y < 0 || x >= size || y >= size) continue;
        const std::int32_t pi = texel_at[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)];
        if (pi < 0 || texels[static_cast<std::size_t>(pi)].object != q.object) continue;
        near.push_back({dx, dy, &texels[static_cast<std::size_t>(pi)]});
      }
    float* kernel = &out.kernels[qi * kKernelTaps * 3];
    for (const Neighbour& n : near) {
      if (std::max(std::abs(n.dx), std::abs(n.dy)) > kKernelRadius) continue;
      const std::size_t tap = static_cast<std::size_t>((n.dy + kKernelRadius) * kKernelWidth + n.dx + kKernelRadius);
      for (std::size_t b = 0; b < 3; ++b) {
        const double value = (n.dx == 0 && n.dy == 0) ? profile[b].disk_integral(std::sqrt(q.area / M_PI))
                                                      : q.area * profile[b].Rd(glm::length(q.x - n.t->x));
        kernel[tap * 3 + b] = static_cast<float>(value);
      }
    }
    if (!settings.blend) return;
    // Global response to unit irradiance on q at the vertices of the neighbourhood's triangles (Eq. 9).
    std::vector<std::pair<std::uint32_t, glm::dvec3>> global;
    auto global_at = [&](std::uint32_t j) {
      for (const auto& [v, value] : global)
        if (v == j) return value;
      glm::dvec3 value(0.0);
      for (std::size_t a = 0; a < 3; ++a) value += dual[qi][a] * form_factor(q.vertex[a], j);
      global.emplace_back(j, value);
      return value;
    };
    auto interpolated_global = [&](const Texel& p) {
      glm::dvec3 value(0.0);
      for (std::size_t c = 0; c < 3; ++c) value += p.lambda[static_cast<int>(c)] * global_at(p.vertex[c]);
      return value;
    };
    // phi_a(x_c(p)): q's vertex a's hat at p's centre.
    auto hats = [&](const Texel& p) {
      glm::dvec3 phi(0.0);
      for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t c = 0; c < 3; ++c)
          if (p.vertex[c] == q.vertex[a]) phi[static_cast<int>(a)] += p.lambda[static_cast<int>(c)];
      return phi;
    };
    // Least squares over the ring of the 9 x 9 kernel: w minimises sum (K9 - B^g' - phi . w)^2 per band.
    glm::dmat3 normal(0.0);
    std::array<glm::dvec3, 3> rhs{};
    int ring = 0;
    for (const Neighbour& n : near) {
      if (std::max(std::abs(n.dx), std::abs(n.dy)) != kRingRadius) continue;
      ++ring;
      const glm::dvec3 phi = hats(*n.t);
      const glm::dvec3 g = interpolated_global(*n.t);
      const double r = glm::length(q.x - n.t->x);
      normal += glm::outerProduct(phi, phi);
      for (std::size_t b = 0; b < 3; ++b) rhs[b] += phi * (q.area * profile[b].Rd(r) - g[static_cast<int>(b)]);
    }
    const double trace = normal[0][0] + normal[1][1] + normal[2][2];
    std::array<glm::dvec3, 3> w{};  // w[b][a]
    if (trace > 0.0) {
      const glm::dmat3 regular = normal + glm::dmat3(kRidge * ring);
      const glm::dmat3 inverse = glm::inverse(regular);
      for (std::size_t b = 0; b < 3; ++b) w[b] = inverse * rhs[b];
    }
    for (std::size_t a = 0; a < 3; ++a) direct[qi][a] = glm::dvec3(w[0][static_cast<int>(a)], w[1][static_cast<int>(a)], w[2][static_cast<int>(a)]);
    // Corrected kernels: the interpolated global and direct responses subtracted where the kernel acts.
    for (const Neighbour& n : near) {
      if (std::max(std::abs(n.dx), std::abs(n.dy)) > kKernelRadius) continue;
      const std::size_t tap = static_cast<std::size_t>((n.dy + kKernelRadius) * kKernelWidth + n.dx + kKernelRadius);
      const glm::dvec3 phi = hats(*n.t);
      const glm::dvec3 g = interpolated_global(*n.t);
      for (std::size_t b = 0; b < 3; ++b)
        kernel[tap * 3 + b] -= static_cast<float>(g[static_cast<int>(b)] + glm::dot(phi, w[b]));
    }
  });

  // Per vertex: the texels feeding it.
  out.vertex_offsets.assign(vertex_count + 1, 0);
  for (const Texel& t : texels)
    for (std::uint32_t v : t.vertex) ++out.vertex_offsets[v + 1];
  for (std::size_t v = 0; v < vertex_count; ++v) out.vertex_offsets[v + 1] += out.vertex_offsets[v];
  out.vertex_texels.resize(out.vertex_offsets.back());
  {
    std::vector<std::uint32_t> fill(out.vertex_offsets.begin(), out.vertex_offsets.end() - 1);
    for (std::size_t qi = 0; qi < texel_count; ++qi)
      for (std::size_t a = 0; a < 3; ++a)
        out.vertex_texels[fill[texels[qi].vertex[a]]++] =
            VertexTexel{static_cast<std::uint32_t>(qi), static_cast<float>(dual[qi][a]), glm::vec3(direct[qi][a])};
  }
  if (progress) progress(1.0);
  return out;
}

std::vector<std::byte> encode(const LocalGlobalData& data) {
  Writer w;
  w.value(kMagic);
  w.value(static_cast<std::int32_t>(data.atlas_size));
  w.array(data.objects);
  w.array(data.texel_xy);
  w.array(data.kernels);
  w.array(data.vertex_offsets);
  w.array(data.vertex_texels);
  w.array(data.row_offsets);
  w.array(data.form_factors);
  w.array(data.corner_vertex);
  return std::move(w.bytes);
}

LocalGlobalData decode(std::span<const std::byte> bytes) {
  Reader r{bytes};
  if (r.value<std::uint32_t>() != kMagic) throw Error("local-global: precomputed data of another format");
  LocalGlobalData data;
  data.atlas_size = r.value<std::int32_t>();
  data.objects = r.array<ObjectSummary>();
  data.texel_xy = r.array<std::uint32_t>();
  data.kernels = r.array<float>();
  data.vertex_offsets = r.array<std::uint32_t>();
  data.vertex_texels = r.array<VertexTexel>();
  data.row_offsets = r.array<std::uint32_t>();
  data.form_factors = r.array<FormFactor>();
  data.corner_vertex = r.array<std::uint32_t>();
  if (data.kernels.size() != data.texel_xy.size() * kKernelTaps * 3 || data.row_offsets.size() != data.vertex_offsets.size())
    throw Error("local-global: precomputed data is inconsistent");
  return data;
}

}  // namespace lucent::methods::local_global
