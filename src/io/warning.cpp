// warning.cpp: the warning channel (lucent/warning.h).
#include "lucent/warning.h"

#include <cstdint>
#include <cstring>

#include "io/warning_capture.h"

#include <cstdio>
#include <mutex>

namespace lucent {
namespace {

std::mutex& warning_mutex() {
  static std::mutex mutex;
  return mutex;
}

thread_local std::vector<std::string>* t_capture = nullptr;

WarningHandler& installed_handler() {
  static WarningHandler handler;
  return handler;
}

}  // namespace

void warn(const std::string& message) {
  if (t_capture) {
    t_capture->push_back(message);
    return;
  }
  std::lock_guard lock(warning_mutex());
  if (const WarningHandler& handler = installed_handler()) {
    handler(message);
  } else {
    std::fprintf(stderr, "lucent: warning: %s\n", message.c_str());
    std::fflush(stderr);
  }
}

WarningHandler set_warning_handler(WarningHandler handler) {
  std::lock_guard lock(warning_mutex());
  WarningHandler previous = std::move(installed_handler());
  installed_handler() = std::move(handler);
  return previous;
}

WarningCapture::WarningCapture(std::vector<std::string>* into) : previous_(t_capture) { t_capture = into; }
WarningCapture::~WarningCapture() { t_capture = previous_; }

namespace {

void put_size(std::string& out, std::uint64_t n) { out.append(reinterpret_cast<const char*>(&n), sizeof n); }

bool get_size(const std::string& in, std::size_t& at, std::uint64_t& n) {
  if (in.size() - at < sizeof n) return false;
  std::memcpy(&n, in.data() + at, sizeof n);
  at += sizeof n;
  return true;
}

}  // namespace

std::string pack_warnings(const std::vector<std::string>& warnings, std::string payload) {
  std::string out;
  put_size(out, warnings.size());
  for (const std::string& w : warnings) {
    put_size(out, w.size());
    out += w;
  }
  return out + payload;
}

std::string unpack_warnings(std::string packed) {
  std::size_t at = 0;
  std::uint64_t count = 0;
  std::vector<std::string> warnings;
  if (!get_size(packed, at, count)) return packed;
  for (std::uint64_t i = 0; i < count; ++i) {
    std::uint64_t size = 0;
    if (!get_size(packed, at, size) || packed.size() - at < size) return packed;
    warnings.emplace_back(packed, at, size);
    at += size;
  }
  for (const std::string& w : warnings) warn(w);
  return packed.substr(at);
}

}  // namespace lucent
