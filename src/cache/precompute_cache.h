// precompute_cache.h: an on-disk cache of precomputed data (a method's preprocessing, texture atlases), keyed by a
// 128-bit hash of everything the data was computed from.
//
// Where: $LUCENT_CACHE_DIR, else $XDG_CACHE_HOME/lucent (an absolute XDG_CACHE_HOME only, as the XDG base
// directory specification says), else $HOME/.cache/lucent; one folder per kind, one file per key
// (<dir>/<kind>/<32 hex digits>.bin).
// Entries: a header (magic, entry format, the kind's format version, payload size, the key, the payload's hash)
// and the payload. A damaged or truncated entry is never trusted: load() prints one warning line, removes it and
// reports a miss, so the caller recomputes. Written through write_file (temporary file + rename): readers never
// see half an entry.
// Size: at most max_bytes() in all; store() evicts the least recently used entries (by modification time, which a
// hit renews) until the new one fits.
// Failures: a directory that cannot be created or written is one warning line (once while it stays the cache
// directory), and the work is simply not cached. set_enabled(false) (the CLI's --no-cache) turns loads into misses and stores into nothing.
//
//   cache::Key key("texture atlas", 3);   // kind, format version
//   key.mesh(object.mesh).material(*object.material).params(method_params);
//   if (auto bytes = cache::load(key)) return decode(*bytes);
//   std::vector<std::byte> bytes = encode(compute());
//   cache::store(key, bytes);
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/material.h"
#include "lucent/mesh.h"
#include "lucent/params.h"

namespace lucent::cache {

// A 128-bit digest: MurmurHash3_x64_128 (Austin Appleby, public domain; seed 0) of a byte stream.
struct Digest {
  std::uint64_t h1 = 0, h2 = 0;
  std::string hex() const;  // 32 lowercase hex digits, h1 then h2
  friend bool operator==(const Digest&, const Digest&) = default;
};

// MurmurHash3_x64_128 over bytes given in pieces; the same digest as the whole stream at once.
class Hasher {
 public:
  void update(std::span<const std::byte> bytes);
  Digest finish() const;  // the digest so far; update() may go on

 private:
  void mix_block(const std::byte* block);
  std::uint64_t h1_ = 0, h2_ = 0;
  std::array<std::byte, 16> tail_{};
  std::size_t tail_size_ = 0;
  std::uint64_t length_ = 0;
};

Digest hash_bytes(std::span<const std::byte> bytes);

// The inputs of a precomputation. Every value is written with a type tag (and strings, arrays with their length),
// so that different sequences of values never give the same stream; floats by their bits (-0 as +0), in the
// machine's byte order (little-endian: checked at compile time).
class Key {
 public:
  // kind: what is cached, which names its folder: letters, digits, '-', '_' and '.' (else std::invalid_argument,
  // a bug of the caller). format_version: bump it whenever the payload's encoding or its computation changes.
  Key(std::string_view kind, std::uint32_t format_version);

  Key& bytes(std::span<const std::byte> data);
  Key& text(std::string_view value);
  Key& integer(std::int64_t value);
  Key& number(double value);
  Key& vec3(glm::vec3 value);
  Key& mesh(const TriangleMesh& mesh);  // positions, normals, indices, texture coordinates
  // The physics of a material: coefficients, eta, model and the heterogeneous field (a volume by its voxels, not
  // its file name); not its name.
  Key& material(const Material& material);
  Key& params(const ParamValues& values);  // every name and value, in name order

  const std::string& kind() const { return kind_; }
  std::uint32_t format_version() const { return format_version_; }
  Digest digest() const { return hasher_.finish(); }

 private:
  void tag(char type, std::uint64_t size);
  template <class T>
  void raw(const T& value) {
    hasher_.update(std::as_bytes(std::span<const T, 1>(&value, 1)));
  }
  std::string kind_;
  std::uint32_t format_version_;
  Hasher hasher_;
};

// The cached payload of `key`; nullopt on a miss, a damaged entry (one warning line; the entry is removed) or
// when the cache is disabled.
std::optional<std::vector<std::byte>> load(const Key& key);

// Stores `payload` for `key`, then evicts least recently used entries beyond max_bytes(). Never throws for the
// file system: an unwritable cache is a warning. A payload larger than max_bytes() is not stored.
void store(const Key& key, std::span<const std::byte> payload);

// Process-wide settings.
void set_enabled(bool enabled);  // false: load() misses, store() writes nothing (--no-cache)
bool enabled();
void set_max_bytes(std::uint64_t bytes);  // default kDefaultMaxBytes
std::uint64_t max_bytes();
inline constexpr std::uint64_t kDefaultMaxBytes = std::uint64_t{1} << 30;  // 1 GiB

// The cache folder as the environment names it now (see the top of this file); empty when none is named (no
// LUCENT_CACHE_DIR, XDG_CACHE_HOME or HOME): then nothing is cached.
std::filesystem::path directory();

// The file of `key` in directory().
std::filesystem::path entry_path(const Key& key);

}  // namespace lucent::cache
