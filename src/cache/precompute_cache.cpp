// precompute_cache.cpp: the on-disk precompute cache (precompute_cache.h).
// The hash is MurmurHash3_x64_128 (Austin Appleby, SMHasher, public domain), written here from the algorithm as a
// stream: 16-byte blocks as they arrive, the tail and the length at the end.
#include "cache/precompute_cache.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "io/input_file.h"
#include "lucent/warning.h"
#include "lucent/error.h"
#include "lucent/output_file.h"

namespace lucent::cache {

static_assert(std::endian::native == std::endian::little, "cache keys and entries are little-endian");

namespace fs = std::filesystem;

// ---- MurmurHash3_x64_128 -----------------------------------------------------------------------------------

namespace {

constexpr std::uint64_t kC1 = 0x87c37b91114253d5ull, kC2 = 0x4cf5ad432745937full;

std::uint64_t fmix64(std::uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdull;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ull;
  k ^= k >> 33;
  return k;
}

std::uint64_t load64(const std::byte* bytes) {
  std::uint64_t value = 0;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

std::uint64_t mix_k1(std::uint64_t k1) { return std::rotl(k1 * kC1, 31) * kC2; }
std::uint64_t mix_k2(std::uint64_t k2) { return std::rotl(k2 * kC2, 33) * kC1; }

}  // namespace

void Hasher::mix_block(const std::byte* block) {
  h1_ ^= mix_k1(load64(block));
  h1_ = std::rotl(h1_, 27) + h2_;
  h1_ = h1_ * 5 + 0x52dce729;
  h2_ ^= mix_k2(load64(block + 8));
  h2_ = std::rotl(h2_, 31) + h1_;
  h2_ = h2_ * 5 + 0x38495ab5;
}

void Hasher::update(std::span<const std::byte> bytes) {
  length_ += bytes.size();
  if (tail_size_ > 0) {  // complete the pending block first
    const std::size_t take = std::min(bytes.size(), tail_.size() - tail_size_);
    std::copy_n(bytes.begin(), take, tail_.begin() + static_cast<std::ptrdiff_t>(tail_size_));
    tail_size_ += take;
    bytes = bytes.subspan(take);
    if (tail_size_ < tail_.size()) return;
    mix_block(tail_.data());
    tail_size_ = 0;
  }
  for (; bytes.size() >= 16; bytes = bytes.subspan(16)) mix_block(bytes.data());
  std::copy(bytes.begin(), bytes.end(), tail_.begin());
  tail_size_ = bytes.size();
}

Digest Hasher::finish() const {
  std::uint64_t h1 = h1_, h2 = h2_, k1 = 0, k2 = 0;
  for (std::size_t i = tail_size_; i-- > 0;) {  // the tail's bytes, little-endian, as in the reference
    const auto byte = std::to_integer<std::uint64_t>(tail_[i]);
    if (i >= 8) k2 ^= byte << (8 * (i - 8));
    else k1 ^= byte << (8 * i);
  }
  if (tail_size_ > 8) h2 ^= mix_k2(k2);
  if (tail_size_ > 0) h1 ^= mix_k1(k1);
  h1 ^= length_;
  h2 ^= length_;
  h1 += h2;
  h2 += h1;
  h1 = fmix64(h1);
  h2 = fmix64(h2);
  h1 += h2;
  h2 += h1;
  return {h1, h2};
}

Digest hash_bytes(std::span<const std::byte> bytes) {
  Hasher hasher;
  hasher.update(bytes);
  return hasher.finish();
}

std::string Digest::hex() const { return fmt::format("{:016x}{:016x}", h1, h2); }

// ---- Key -----------------------------------------------------------------------------------------------------

namespace {

bool valid_kind(std::string_view kind) {
  return !kind.empty() && kind.size() <= 64 && kind.front() != '.' && std::all_of(kind.begin(), kind.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
           c == '.';
  });
}

template <class T>
std::span<const std::byte> as_bytes(const std::vector<T>& values) {
  return std::as_bytes(std::span<const T>(values));
}

}  // namespace

Key::Key(std::string_view kind, std::uint32_t format_version) : kind_(kind), format_version_(format_version) {
  if (!valid_kind(kind)) throw std::invalid_argument("cache kind \"" + kind_ + "\" is not a folder name");
  text(kind);
  integer(format_version);
}

void Key::tag(char type, std::uint64_t size) {
  raw(type);
  raw(size);
}

Key& Key::bytes(std::span<const std::byte> data) {
  tag('b', data.size());
  hasher_.update(data);
  return *this;
}

Key& Key::text(std::string_view value) {
  tag('s', value.size());
  hasher_.update(std::as_bytes(std::span<const char>(value.data(), value.size())));
  return *this;
}

Key& Key::integer(std::int64_t value) {
  tag('i', 8);
  raw(value);
  return *this;
}

Key& Key::number(double value) {
  tag('f', 8);
  raw(value == 0.0 ? 0.0 : value);  // -0 == +0
  return *this;
}

Key& Key::vec3(glm::vec3 value) {
  tag('v', 3);
  for (int i = 0; i < 3; ++i) raw(value[i] == 0.0f ? 0.0f : value[i]);
  return *this;
}

Key& Key::mesh(const TriangleMesh& mesh) {
  tag('m', 4);
  bytes(as_bytes(mesh.positions));
  bytes(as_bytes(mesh.normals));
  bytes(as_bytes(mesh.indices));
  bytes(as_bytes(mesh.uvs));
  return *this;
}

Key& Key::material(const Material& m) {
  tag('M', 0);
  vec3(m.sigma_a).vec3(m.sigma_s).vec3(m.g).number(m.eta).integer(static_cast<int>(m.model));
  if (m.model == BssrdfModel::Multipole) number(m.thickness_mm);  // only there, so that other keys stay as they were
  const MediumField& field = m.field;
  integer(static_cast<int>(field.type)).number(field.scale_mm).number(field.contrast);
  integer(field.has_bounds ? 1 : 0).vec3(field.bounds_lower).vec3(field.bounds_upper);
  if (field.volume) {
    const MediumVolume& volume = *field.volume;
    integer(volume.size.x).integer(volume.size.y).integer(volume.size.z).bytes(as_bytes(volume.values));
  } else {
    integer(-1);
  }
  if (m.maps) {  // textured: the per-texel values, not the files' names
    const MaterialMaps& maps = *m.maps;
    vec3(maps.base_alpha).vec3(maps.base_mfp_mm);
    integer(maps.alpha_size.x).integer(maps.alpha_size.y).bytes(as_bytes(maps.alpha));
    integer(maps.mfp_size.x).integer(maps.mfp_size.y).bytes(as_bytes(maps.mfp_mm));
  } else {
    integer(-2);
  }
  return *this;
}

Key& Key::params(const ParamValues& values) {
  tag('p', values.all().size());
  for (const auto& [name, value] : values.all()) {
    text(name);
    integer(static_cast<std::int64_t>(value.index()));
    if (const auto* d = std::get_if<double>(&value)) number(*d);
    else if (const auto* b = std::get_if<bool>(&value)) integer(*b ? 1 : 0);
    else if (const auto* s = std::get_if<std::string>(&value)) text(*s);
    else if (const auto* v = std::get_if<glm::vec3>(&value)) vec3(*v);
    else if (const auto* list = std::get_if<std::vector<glm::vec3>>(&value)) {
      integer(static_cast<std::int64_t>(list->size()));
      for (glm::vec3 item : *list) vec3(item);
    }
  }
  return *this;
}

// ---- settings ------------------------------------------------------------------------------------------------

namespace {

struct Settings {
  std::mutex mutex;  // held while reading or changing files, so that one process's stores and evictions do not mix
  std::atomic<bool> enabled{true};
  std::atomic<std::uint64_t> max_bytes{kDefaultMaxBytes};
  fs::path warned_unwritable;  // the last directory found unwritable: warned about once
};

Settings& settings() {
  static Settings s;
  return s;
}


}  // namespace

void set_enabled(bool on) { settings().enabled = on; }
bool enabled() { return settings().enabled; }
void set_max_bytes(std::uint64_t bytes) { settings().max_bytes = bytes; }
std::uint64_t max_bytes() { return settings().max_bytes; }

fs::path directory() {
  auto variable = [](const char* name) -> std::string {
    const char* value = std::getenv(name);
    return value ? value : "";
  };
  if (std::string dir = variable("LUCENT_CACHE_DIR"); !dir.empty()) return dir;
  if (fs::path xdg = variable("XDG_CACHE_HOME"); xdg.is_absolute()) return xdg / "lucent";
  if (std::string home = variable("HOME"); !home.empty()) return fs::path(home) / ".cache" / "lucent";
  return {};
}

fs::path entry_path(const Key& key) {
  const fs::path dir = directory();
  return dir.empty() ? dir : dir / key.kind() / (key.digest().hex() + ".bin");
}

// ---- entries -------------------------------------------------------------------------------------------------

namespace {

constexpr std::array<char, 8> kMagic = {'L', 'U', 'C', 'A', 'C', 'H', 'E', '\n'};
constexpr std::uint32_t kEntryFormat = 1;

// The start of every entry file, followed by the payload.
struct EntryHeader {
  std::array<char, 8> magic = kMagic;
  std::uint32_t entry_format = kEntryFormat;
  std::uint32_t format_version = 0;  // the kind's
  std::uint64_t payload_size = 0;    // bytes
  Digest key;                        // the entry's own key: a file under the wrong name is not trusted
  Digest payload_hash;
};
static_assert(sizeof(EntryHeader) == 56);

// The whole file; nullopt when it does not exist or cannot be read.
std::optional<std::string> read_whole(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return std::nullopt;
  return bytes;
}

// Why the entry cannot be trusted, or "" when it can.
std::string check_entry(const std::string& file, const Key& key, EntryHeader& header) {
  if (file.size() < sizeof header) return fmt::format("{} bytes, shorter than the header", file.size());
  std::memcpy(&header, file.data(), sizeof header);
  if (header.magic != kMagic) return "not a lucent cache entry";
  if (header.entry_format != kEntryFormat || header.format_version != key.format_version())
    return fmt::format("format {}.{}, expected {}.{}", header.entry_format, header.format_version, kEntryFormat,
                       key.format_version());
  if (header.payload_size != file.size() - sizeof header)
    return fmt::format("payload of {} bytes, the header says {}", file.size() - sizeof header, header.payload_size);
  if (header.key != key.digest()) return "stored under another key's name";
  const auto payload = std::as_bytes(std::span<const char>(file.data() + sizeof header, file.size() - sizeof header));
  if (hash_bytes(payload) != header.payload_hash) return "payload checksum mismatch";
  return "";
}

// An entry that is not a regular file (a directory, a FIFO, a device: reading one would fail or block, writing
// one would go into it) is derived data gone wrong: one warning line, and it is removed so that the recomputed
// entry takes its place. False when it is still there (not removable).
bool remove_if_not_a_file(const fs::path& path) {
  const std::string kind = non_regular_file_kind(path.string());
  if (kind.empty()) return true;
  std::error_code ec;
  fs::remove_all(path, ec);  // a link is removed itself, never what it points to
  const bool gone = !fs::exists(fs::symlink_status(path, ec));
  warn(fmt::format("{}: precompute cache entry is {}, not a file; {}", path.string(), kind,
                   gone ? "removed and recomputed" : "ignored (it cannot be removed) and not cached"));
  return gone;
}

// Every entry file under the cache directory with its size and last use, oldest first.
struct EntryFile {
  fs::file_time_type used;
  fs::path path;
  std::uint64_t size = 0;
};

std::vector<EntryFile> list_entries(const fs::path& dir) {
  std::vector<EntryFile> entries;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& path = it->path();
    if (path.extension() != ".bin" || path.filename().string().front() == '.') continue;  // skips write temporaries
    std::error_code entry_ec;
    if (!it->is_regular_file(entry_ec)) continue;
    EntryFile entry{it->last_write_time(entry_ec), path, it->file_size(entry_ec)};
    if (!entry_ec) entries.push_back(std::move(entry));
  }
  std::sort(entries.begin(), entries.end(), [](const EntryFile& a, const EntryFile& b) {
    return std::tie(a.used, a.path) < std::tie(b.used, b.path);
  });
  return entries;
}

// Removes the least recently used entries until the total is at most `limit` bytes; `keep` goes last.
void evict(const fs::path& dir, std::uint64_t limit, const fs::path& keep) {
  std::vector<EntryFile> entries = list_entries(dir);
  std::stable_partition(entries.begin(), entries.end(), [&](const EntryFile& e) { return e.path != keep; });
  std::uint64_t total = 0;
  for (const EntryFile& e : entries) total += e.size;
  for (const EntryFile& e : entries) {
    if (total <= limit) break;
    std::error_code ec;
    if (fs::remove(e.path, ec)) total -= e.size;
  }
}

}  // namespace

std::optional<std::vector<std::byte>> load(const Key& key) {
  if (!enabled()) return std::nullopt;
  const fs::path path = entry_path(key);
  if (path.empty()) return std::nullopt;
  std::lock_guard lock(settings().mutex);
  if (!non_regular_file_kind(path.string()).empty()) {
    remove_if_not_a_file(path);
    return std::nullopt;
  }
  const std::optional<std::string> file = read_whole(path);
  if (!file) return std::nullopt;
  EntryHeader header;
  if (std::string problem = check_entry(*file, key, header); !problem.empty()) {
    warn(fmt::format("{}: damaged precompute cache entry ({}); recomputing", path.string(), problem));
    std::error_code ec;
    fs::remove(path, ec);
    return std::nullopt;
  }
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // a hit is a use (least recently used last)
  const auto* payload = reinterpret_cast<const std::byte*>(file->data()) + sizeof header;
  return std::vector<std::byte>(payload, payload + header.payload_size);
}

void store(const Key& key, std::span<const std::byte> payload) {
  if (!enabled()) return;
  const fs::path path = entry_path(key);
  const std::uint64_t limit = max_bytes();
  if (path.empty() || payload.size() + sizeof(EntryHeader) > limit) return;
  EntryHeader header;
  header.format_version = key.format_version();
  header.payload_size = payload.size();
  header.key = key.digest();
  header.payload_hash = hash_bytes(payload);
  std::string file(sizeof header + payload.size(), '\0');
  std::memcpy(file.data(), &header, sizeof header);
  if (!payload.empty()) std::memcpy(file.data() + sizeof header, payload.data(), payload.size());

  Settings& s = settings();
  std::lock_guard lock(s.mutex);
  try {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw Error(path.parent_path().string() + ": cannot create: " + ec.message());
    if (!remove_if_not_a_file(path)) return;
    write_file(path.string(), file);
  } catch (const Error& e) {
    if (std::exchange(s.warned_unwritable, directory()) != directory())
      warn(fmt::format("precompute cache not written ({}); the work is not cached", e.what()));
    return;
  }
  evict(directory(), limit, path);
}

}  // namespace lucent::cache
