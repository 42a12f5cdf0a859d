// medium_vdb_load.cpp: load_medium_vdb (lucent/medium_vdb.h): the file's layout checked here
// (media/vdb_header_check.h), then OpenVDB's reader (media/medium_vdb_reader.h) run in a guarded child process
// (scene/import_guard.h) under CPU, wall-clock and memory limits, the dense volume handed back as bytes. OpenVDB
// allocates from the sizes a file declares, and a hostile or damaged file could otherwise take the program's
// memory or crash it.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "lucent/error.h"
#include "lucent/medium_vdb.h"
#include "media/medium_vdb_reader.h"
#include "media/vdb_header_check.h"
#include "scene/import_guard.h"

namespace lucent {
namespace {

// The start of a volume's bytes; the values (float, x fastest) follow.
struct VdbVolumeHeader {
  std::int32_t size[3];
  std::uint32_t world;
  float lower[3], upper[3];
  float max_value;
};

std::string volume_bytes(const VdbVolume& v) {
  const MediumVolume& volume = *v.volume;
  VdbVolumeHeader header{{volume.size.x, volume.size.y, volume.size.z},
                         v.world ? 1u : 0u,
                         {v.lower.x, v.lower.y, v.lower.z},
                         {v.upper.x, v.upper.y, v.upper.z},
                         volume.max_value};
  std::string bytes(reinterpret_cast<const char*>(&header), sizeof header);
  bytes.append(reinterpret_cast<const char*>(volume.values.data()), volume.values.size() * sizeof(float));
  return bytes;
}

VdbVolume volume_from_bytes(const std::string& bytes, const VdbField& field) {
  VdbVolumeHeader header;
  const auto damaged = [&] {
    return Error(fmt::format("{}: cannot read the VDB file: the OpenVDB reader returned a damaged volume", field.file));
  };
  if (bytes.size() < sizeof header) throw damaged();
  std::memcpy(&header, bytes.data(), sizeof header);
  const glm::ivec3 size(header.size[0], header.size[1], header.size[2]);
  if (size.x < 1 || size.y < 1 || size.z < 1) throw damaged();
  const std::size_t count =
      static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * static_cast<std::size_t>(size.z);
  if ((bytes.size() - sizeof header) / sizeof(float) != count || (bytes.size() - sizeof header) % sizeof(float) != 0)
    throw damaged();
  auto volume = std::make_shared<MediumVolume>();
  volume->vdb = field;
  volume->source = field.file;
  volume->data_file = field.file;
  volume->size = size;
  volume->values.resize(count);
  std::memcpy(volume->values.data(), bytes.data() + sizeof header, count * sizeof(float));
  volume->max_value = header.max_value;
  VdbVolume out;
  out.volume = std::move(volume);
  out.world = header.world != 0;
  out.lower = glm::vec3(header.lower[0], header.lower[1], header.lower[2]);
  out.upper = glm::vec3(header.upper[0], header.upper[1], header.upper[2]);
  return out;
}

}  // namespace

VdbVolume load_medium_vdb(const VdbField& field) {
  check_vdb_header(field.file);
  // Address space for the reader: the largest dense volume (2^27 floats, 512 MiB) twice, OpenVDB's tree of as
  // many voxels and its decompression buffers fit in 4 GiB; each thread OpenVDB's oneTBB starts reserves a
  // malloc arena and a stack on top.
  ImportLimits limits = vdb_read_limits();
  if (limits.memory_bytes == 0)
    limits.memory_bytes =
        (std::uint64_t{4} << 30) + (std::uint64_t{128} << 20) * std::max(1u, std::thread::hardware_concurrency());
  const GuardedReader names{"cannot read the VDB file", "the OpenVDB reader"};
  const std::string bytes =
      read_in_child(field.file, names, [&] { return volume_bytes(read_medium_vdb(field)); }, limits);
  return volume_from_bytes(bytes, field);
}

}  // namespace lucent
