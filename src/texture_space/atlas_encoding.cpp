// atlas_encoding.cpp: see atlas_encoding.h.
#include "texture_space/atlas_encoding.h"

#include <cstring>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent::texture_space {
namespace {

constexpr std::uint32_t kMagic = 0x53544C41;  // "ALTS"

class Writer {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(&v, sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(static_cast<std::uint64_t>(v.size()));
    append(v.data(), v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    value(static_cast<std::uint64_t>(s.size()));
    append(s.data(), s.size());
  }
  std::vector<std::byte> take() { return std::move(out_); }

 private:
  void append(const void* data, std::size_t n) {
    if (n == 0) return;
    std::size_t at = out_.size();
    out_.resize(at + n);
    std::memcpy(out_.data() + at, data, n);
  }
  std::vector<std::byte> out_;
};

class Reader {
 public:
  explicit Reader(std::span<const std::byte> in) : in_(in) {}
  template <class T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, take(sizeof(T)).data(), sizeof(T));
    return v;
  }
  template <class T>
  std::vector<T> array() {
    std::uint64_t n = count(sizeof(T));
    std::vector<T> v(static_cast<std::size_t>(n));
    if (n > 0) std::memcpy(v.data(), take(static_cast<std::size_t>(n) * sizeof(T)).data(), v.size() * sizeof(T));
    return v;
  }
  std::string text() {
    std::uint64_t n = count(1);
    std::span<const std::byte> bytes = take(static_cast<std::size_t>(n));
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
  }
  // An element count whose elements fit in what is left.
  std::uint64_t count(std::size_t element_bytes) {
    auto n = value<std::uint64_t>();
    if (n > (in_.size() - at_) / element_bytes)
      throw Error(fmt::format("scene atlas: a count of {} does not fit in the {} bytes left", n, in_.size() - at_));
    return n;
  }
  bool done() const { return at_ == in_.size(); }

 private:
  std::span<const std::byte> take(std::size_t n) {
    if (n > in_.size() - at_) throw Error(fmt::format("scene atlas: cut short at byte {}", at_));
    std::span<const std::byte> out = in_.subspan(at_, n);
    at_ += n;
    return out;
  }
  std::span<const std::byte> in_;
  std::size_t at_ = 0;
};

void write_metrics(Writer& w, const AtlasMetrics& m) {
  w.value(static_cast<std::int32_t>(m.chart_count));
  for (double d : {m.utilization, m.stretch_l2, m.stretch_max, m.angle_mean, m.angle_max, m.build_ms, m.texel_size})
    w.value(d);
}

AtlasMetrics read_metrics(Reader& r) {
  AtlasMetrics m;
  m.chart_count = r.value<std::int32_t>();
  for (double* d : {&m.utilization, &m.stretch_l2, &m.stretch_max, &m.angle_mean, &m.angle_max, &m.build_ms,
                    &m.texel_size})
    *d = r.value<double>();
  return m;
}

}  // namespace

std::vector<std::byte> encode_scene_atlas(const SceneAtlas& atlas) {
  Writer w;
  w.value(kMagic);
  w.value(kSceneAtlasEncodingVersion);
  w.value(static_cast<std::int32_t>(atlas.atlas.size));
  w.value(static_cast<std::uint64_t>(atlas.atlas.objects.size()));
  for (const AtlasObject& object : atlas.atlas.objects) {
    w.array(object.mesh.positions);
    w.array(object.mesh.normals);
    w.array(object.mesh.indices);
    w.array(object.mesh.uvs);
    w.array(object.source_vertex);
    w.array(object.chart);
  }
  write_metrics(w, atlas.atlas.metrics);
  std::vector<std::uint64_t> object_index(atlas.object_index.begin(), atlas.object_index.end());
  w.array(object_index);
  w.value(static_cast<std::uint8_t>(atlas.own_uvs ? 1 : 0));
  w.text(atlas.own_uv_problem);
  return w.take();
}

SceneAtlas decode_scene_atlas(std::span<const std::byte> bytes) {
  Reader r(bytes);
  if (r.value<std::uint32_t>() != kMagic) throw Error("scene atlas: not an encoded scene atlas");
  if (auto version = r.value<std::uint32_t>(); version != kSceneAtlasEncodingVersion)
    throw Error(fmt::format("scene atlas: encoding version {}, this build reads {}", version, kSceneAtlasEncodingVersion));
  SceneAtlas out;
  out.atlas.size = r.value<std::int32_t>();
  std::uint64_t objects = r.count(1);
  for (std::uint64_t k = 0; k < objects; ++k) {
    AtlasObject object;
    object.mesh.positions = r.array<glm::vec3>();
    object.mesh.normals = r.array<glm::vec3>();
    object.mesh.indices = r.array<std::uint32_t>();
    object.mesh.uvs = r.array<glm::vec2>();
    object.source_vertex = r.array<std::uint32_t>();
    object.chart = r.array<std::uint32_t>();
    const TriangleMesh& m = object.mesh;
    if (m.normals.size() != m.positions.size() || m.uvs.size() != m.positions.size() ||
        object.source_vertex.size() != m.positions.size() || m.indices.size() % 3 != 0 ||
        object.chart.size() != m.indices.size() / 3)
      throw Error(fmt::format("scene atlas: object {}: array sizes do not agree", k));
    for (std::uint32_t i : m.indices)
      if (i >= m.positions.size()) throw Error(fmt::format("scene atlas: object {}: index {} out of range", k, i));
    out.atlas.objects.push_back(std::move(object));
  }
  out.atlas.metrics = read_metrics(r);
  std::vector<std::uint64_t> object_index = r.array<std::uint64_t>();
  if (object_index.size() != out.atlas.objects.size())
    throw Error(fmt::format("scene atlas: {} object indices for {} objects", object_index.size(), out.atlas.objects.size()));
  for (std::uint64_t i : object_index) out.object_index.push_back(static_cast<std::size_t>(i));
  out.own_uvs = r.value<std::uint8_t>() != 0;
  out.own_uv_problem = r.text();
  if (!r.done()) throw Error("scene atlas: trailing bytes after the encoded atlas");
  return out;
}

}  // namespace lucent::texture_space
