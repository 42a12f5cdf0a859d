// output_file.cpp: temporary file + fsync + rename for every file lucent writes, and the checks commands run on
// their output paths before they start (see lucent/output_file.h).
#include "lucent/output_file.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <system_error>
#include <unordered_map>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "io/file_path_check.h"
#include "io/interruption.h"
#include "lucent/error.h"

namespace lucent {
namespace {

namespace fs = std::filesystem;

std::string errno_text(int error) { return std::error_code(error, std::generic_category()).message(); }

fs::path directory_of(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

// Paths under /dev and /proc (/dev/stdout, /proc/self/fd/1) name open streams: written in place, never resolved,
// so `lucent tonemap a.exr -o /dev/stdout > out.png` writes into the shell's file.
bool is_stream_path(const std::string& path) { return path.starts_with("/dev/") || path.starts_with("/proc/"); }

// The file a write to `path` replaces: the end of a chain of symbolic links (also when that end does not exist
// yet), else `path` itself.
fs::path destination(const std::string& path) {
  if (is_stream_path(path)) return path;
  fs::path p = path;
  std::error_code ec;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    if (hops == 40) throw Error(fmt::format("{}: cannot write: {}", path, errno_text(ELOOP)));
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) break;
    p = target.is_absolute() ? target : directory_of(p) / target;
  }
  return p;
}

// A name beside `target` that no other writer (another lucent process, another thread) picks.
fs::path temporary_beside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  // At most 200 bytes of the name, so the temporary stays within NAME_MAX (255) whenever the name itself does.
  const std::string name = target.filename().string().substr(0, 200);
  return directory_of(target) / fmt::format(".{}.lucent-tmp-{}-{}", name, ::getpid(), counter.fetch_add(1));
}

void write_all(int fd, std::string_view bytes, const std::string& path) {
  const char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(fmt::format("{}: cannot write: {}", path, errno_text(n < 0 ? errno : ENOSPC)));
    data += n;
    left -= static_cast<std::size_t>(n);
  }
}

void create_directory_for(const fs::path& file, const std::string& what) {
  std::error_code ec;
  const fs::path dir = directory_of(file);
  fs::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("{}: cannot create directory {}: {}", what, dir.string(), ec.message()));
}

// A file being written: complete on disk under `temporary` (empty for a special file written in place) and not yet
// renamed over `target`.
struct PendingFile {
  fs::path target;
  fs::path temporary;
  std::shared_ptr<RemoveOnSignal> removal;  // the temporary is removed if a signal ends the process first
};

bool is_special_file(const fs::path& target) {
  if (is_stream_path(target.string())) return true;
  std::error_code ec;
  const fs::file_status status = fs::status(target, ec);
  return !ec && fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status);
}

// Writes the bytes to a device, pipe or FIFO that already exists (renaming over it would replace the node).
void write_in_place(const fs::path& target, std::string_view bytes, const std::string& path) {
  const int fd = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw Error(fmt::format("{}: cannot write: {}", path, errno_text(errno)));
  try {
    write_all(fd, bytes, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw Error(fmt::format("{}: cannot write: {}", path, errno_text(errno)));
}

PendingFile write_pending(const std::string& path, std::string_view bytes) {
  PendingFile pending{destination(path), {}, {}};
  std::error_code ec;
  if (fs::is_directory(pending.target, ec)) throw Error(fmt::format("{}: cannot write: is a directory", path));
  if (is_special_file(pending.target)) {
    write_in_place(pending.target, bytes, path);
    return pending;
  }
  pending.temporary = temporary_beside(pending.target);
  pending.removal = std::make_shared<RemoveOnSignal>(pending.temporary.string());
  const int fd = ::open(pending.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw Error(fmt::format("{}: cannot write: {}", path, errno_text(errno)));
  try {
    struct stat old {};
    if (::stat(pending.target.c_str(), &old) == 0) ::fchmod(fd, old.st_mode & 07777);  // keep the old file's mode
    write_all(fd, bytes, path);
    if (::fsync(fd) != 0 && errno != EINVAL) throw Error(fmt::format("{}: cannot write: {}", path, errno_text(errno)));
  } catch (...) {
    ::close(fd);
    ::unlink(pending.temporary.c_str());
    throw;
  }
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(pending.temporary.c_str());
    throw Error(fmt::format("{}: cannot write: {}", path, errno_text(error)));
  }
  return pending;
}

void discard(const PendingFile& pending) {
  if (!pending.temporary.empty()) ::unlink(pending.temporary.c_str());
}

void install(const PendingFile& pending, const std::string& path) {
  if (pending.temporary.empty()) return;
  if (::rename(pending.temporary.c_str(), pending.target.c_str()) != 0) {
    const int error = errno;
    discard(pending);
    throw Error(fmt::format("{}: cannot write: {}", path, errno_text(error)));
  }
  // The rename itself is durable once the directory is flushed; a failure here loses nothing already written.
  const int dir = ::open(directory_of(pending.target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

}  // namespace

std::string lowercase_extension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void write_file(const std::string& path, std::string_view bytes) {
  check_file_path(path);  // a NUL byte would cut the name handed to the system: another file would be written
  const PendingFile pending = write_pending(path, bytes);
  const DeferredInterruption renaming;  // a signal here ends the process after the rename
  install(pending, path);
}

void OutputSet::add(std::string path, std::string bytes) { entries_.push_back({std::move(path), std::move(bytes)}); }

void OutputSet::commit() {
  std::vector<PendingFile> pending;
  try {
    for (const Entry& e : entries_) pending.push_back(write_pending(e.path, e.bytes));
  } catch (...) {
    for (const PendingFile& p : pending) discard(p);
    throw;
  }
  // The renames are not cut by a signal: one that arrives ends the process after the last (the set stays one
  // version).
  const DeferredInterruption renaming;
  for (std::size_t i = 0; i < pending.size(); ++i) {
    try {
      install(pending[i], entries_[i].path);
    } catch (...) {
      for (std::size_t j = i + 1; j < pending.size(); ++j) discard(pending[j]);
      throw;
    }
  }
  entries_.clear();
}

namespace {

// What makes two paths one file (same_file): "i" and the device and inode of a file that exists (links followed),
// else "p" and the absolute path with its existing part resolved; nullopt when neither can be found.
std::optional<std::string> file_identity(const std::string& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) == 0) return fmt::format("i{}:{}", s.st_dev, s.st_ino);
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) return std::nullopt;
  return "p" + canonical.string();
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  const std::optional<std::string> ia = file_identity(a), ib = file_identity(b);
  return ia && ib && *ia == *ib;
}

void check_outputs(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs) {
  // Identities are compared, not pairs of paths: an animation's thousands of frames are checked in linear time.
  std::unordered_map<std::string, std::size_t> input_of, output_of;  // identity -> index
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (std::optional<std::string> id = file_identity(inputs[i])) input_of.emplace(std::move(*id), i);
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const OutputPath& o = outputs[k];
    if (o.path.empty()) continue;
    const std::optional<std::string> id = file_identity(o.path);
    if (!id) continue;
    const std::string what = fmt::format("{} {}", o.option, o.path);
    if (auto input = input_of.find(*id); input != input_of.end())
      throw Error(fmt::format("{}: would overwrite the input {}; choose another output path", what,
                              inputs[input->second]));
    if (auto [other, inserted] = output_of.emplace(*id, k); !inserted)
      throw Error(fmt::format("{}: is also the output {} {}; give each output its own path", what,
                              outputs[other->second].option, outputs[other->second].path));
  }
  // A device or FIFO (/dev/stdout) takes any format; a file's name must say the format written.
  for (const OutputPath& o : outputs)
    if (!o.path.empty() && !o.extensions.empty() && !is_special_file(destination(o.path))) require_extension(o);
  std::set<fs::path> probed;  // directories known to accept a new file
  for (const OutputPath& o : outputs) {
    if (o.path.empty()) continue;
    const std::string what = fmt::format("{} {}", o.option, o.path);
    const fs::path target = destination(o.path);
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw Error(fmt::format("{}: is a directory", what));
    if (is_special_file(target)) {
      if (::access(target.c_str(), W_OK) != 0) throw Error(fmt::format("{}: cannot write: {}", what, errno_text(errno)));
      continue;
    }
    // A file the user may not write is not replaced behind their back (rename would ignore its permissions).
    if (fs::exists(target, ec) && ::access(target.c_str(), W_OK) != 0)
      throw Error(fmt::format("{}: cannot write: {}", what, errno_text(errno)));
    if (!probed.insert(directory_of(target)).second) continue;
    create_directory_for(target, what);
    // The directory must accept a new file (the temporary that is renamed into place).
    const fs::path probe = temporary_beside(target);
    const RemoveOnSignal removal(probe.string());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0)
      throw Error(fmt::format("{}: cannot write in {}: {}", what, directory_of(target).string(), errno_text(errno)));
    ::close(fd);
    ::unlink(probe.c_str());
  }
}

void require_extension(const OutputPath& output) {
  const std::string extension = lowercase_extension(output.path);
  std::string allowed;
  for (std::string_view e : output.extensions) {
    if (extension == e) return;
    allowed += (allowed.empty() ? "" : " or ") + std::string(e);
  }
  if (extension.empty()) throw Error(fmt::format("{} {}: no file extension; use {}", output.option, output.path, allowed));
  throw Error(fmt::format("{} {}: '{}' is not a format this command writes; use {}", output.option, output.path,
                          extension, allowed));
}

}  // namespace lucent

namespace lucent {
namespace {

// `.<name>.lucent-lock` beside the file a write to `target` replaces; a long name is shortened and keeps a hash of
// itself, so that the lock's name stays within NAME_MAX and distinct.
fs::path lock_file_of(const fs::path& target) {
  std::string name = target.filename().string();
  if (name.size() > 200) {
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
    for (unsigned char c : name) hash = (hash ^ c) * 1099511628211ull;
    name = fmt::format("{}-{:016x}", name.substr(0, 180), hash);
  }
  return directory_of(target) / fmt::format(".{}.lucent-lock", name);
}

// The process id a lock file holds ("" when it holds none yet).
std::string holder_of(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, n > 0 ? static_cast<std::size_t>(n) : 0);
  pid.erase(std::remove_if(pid.begin(), pid.end(), [](char c) { return !std::isdigit(static_cast<unsigned char>(c)); }),
            pid.end());
  return pid;
}

}  // namespace

struct OutputLock::Held {
  fs::path file;
  int fd = -1;
  std::unique_ptr<RemoveOnSignal> removal;
  ~Held() {
    removal.reset();  // first: a signal from here on leaves the file (harmless), never removes another's
    ::unlink(file.c_str());
    ::close(fd);  // releases the lock
  }
};

OutputLock::OutputLock(const std::vector<OutputPath>& outputs) {
  for (const OutputPath& o : outputs) {
    if (o.path.empty()) continue;
    const fs::path target = destination(o.path);
    if (is_special_file(target)) continue;
    const fs::path file = lock_file_of(target);
    const std::string what = fmt::format("{} {}", o.option, o.path);
    // The lock file is removed when released: a lock taken on a file that was removed meanwhile (or replaced by a
    // newer one) locks nothing, so it is taken again on the file the name now holds.
    for (;;) {
      const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
      if (fd < 0) throw Error(fmt::format("{}: cannot lock {}: {}", what, file.string(), errno_text(errno)));
      if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        const std::string pid = error == EWOULDBLOCK ? holder_of(fd) : "";
        ::close(fd);
        if (error != EWOULDBLOCK)
          throw Error(fmt::format("{}: cannot lock {}: {}", what, file.string(), errno_text(error)));
        throw Error(fmt::format("{}: is being written by another lucent process{}; wait until it ends", what,
                                pid.empty() ? "" : fmt::format(" (pid {})", pid)));
      }
      struct stat opened {}, named {};
      if (::fstat(fd, &opened) != 0 || ::stat(file.c_str(), &named) != 0 || opened.st_dev != named.st_dev ||
          opened.st_ino != named.st_ino) {
        ::close(fd);
        continue;
      }
      auto held = std::make_unique<Held>();
      held->file = file;
      held->fd = fd;
      held->removal = std::make_unique<RemoveOnSignal>(file.string());
      // The pid only names the holder in another process's message: not writing it is no error.
      const std::string pid = std::to_string(::getpid()) + "\n";
      const bool pid_written = ::ftruncate(fd, 0) == 0 && ::pwrite(fd, pid.data(), pid.size(), 0) > 0;
      static_cast<void>(pid_written);
      held_.push_back(std::move(held));
      break;
    }
  }
}

OutputLock::~OutputLock() {
  while (!held_.empty()) held_.pop_back();  // in reverse order
}

OutputLock::OutputLock(OutputLock&&) noexcept = default;
OutputLock& OutputLock::operator=(OutputLock&&) noexcept = default;

}  // namespace lucent
