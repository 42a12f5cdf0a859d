// import_guard.cpp: file readers in a forked child process (import_guard.h).
//
// Why a child process: assimp is a third-party parser of dozens of formats with a history of crash bugs on hostile
// files (reads past the end of buffers, null dereferences, endless loops, allocations sized by a header field),
// OpenVDB allocates from the sizes a file declares, and a scene file may name any file. The child runs the reader
// under CPU, memory and core-file limits and hands its result back as bytes; if it dies, the parent reports the
// file as unreadable and goes on.
// Why fork (and not a helper executable): the importer stays ordinary in-process code, and fork is safe with
// glibc's malloc, which holds its arena locks across fork (pthread_atfork), so the child can allocate even when
// other threads of the parent were allocating at that moment. A lock of another kind held by another parent
// thread stays held in the child; a child that waits on one is caught by the wall-clock limit.
// Transfer: the child writes its result into a memfd (shared memory) and then a small header into a pipe; the
// parent waits on the pipe with a deadline and copies the result out. (Through the pipe alone, each 64 KiB costs
// a context switch: 20 to 50 ms more for a 70k-triangle mesh on a loaded 2-core machine.)
#include "scene/import_guard.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "io/printable_text.h"
#include "io/warning_capture.h"
#include "lucent/error.h"

#if defined(__SANITIZE_ADDRESS__)
#define LUCENT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LUCENT_ASAN 1
#endif
#endif
#if defined(LUCENT_ASAN)
#include <sanitizer/common_interface_defs.h>
#endif

namespace lucent {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::uint32_t kMagic = 0x4c4d5348;  // "LMSH"
constexpr std::uint32_t kBytesResult = 0, kErrorResult = 1;
constexpr std::uint64_t kMaxMessage = 1 << 16;

// The fixed-size start of the child's reply: the result (its size in the shared memory file) or an error (the
// length of the message that follows in the pipe).
struct ReplyHeader {
  std::uint32_t magic = kMagic;
  std::uint32_t kind = kBytesResult;
  std::uint64_t size = 0;
};

// ---- child ----------------------------------------------------------------------------------------------

bool write_all(int fd, const void* data, std::size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// The result goes to the shared memory file, then the header to the pipe: its arrival says the data is complete.
bool send_result(int fd, int data_fd, const std::string& bytes) {
  const ReplyHeader header{kMagic, kBytesResult, bytes.size()};
  return write_all(data_fd, bytes.data(), bytes.size()) && write_all(fd, &header, sizeof header);
}

bool send_error(int fd, std::string message) {
  message.resize(std::min<std::size_t>(message.size(), kMaxMessage));
  const ReplyHeader header{kMagic, kErrorResult, message.size()};
  return write_all(fd, &header, sizeof header) && write_all(fd, message.data(), message.size());
}

// Crash signals die with their default action, so that the parent sees the signal: the handlers the parent may
// have installed (the fuzzer's, a sanitizer's) would otherwise report the crash as their own.
void restore_crash_signals() {
  for (int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGXCPU, SIGPIPE}) std::signal(sig, SIG_DFL);
#if defined(LUCENT_ASAN)
  __sanitizer_set_death_callback(nullptr);  // a fuzzer's callback would record the child's death as its own crash
#endif
}

void set_limit(int resource, rlim_t soft, rlim_t hard) {
  const rlimit limit{soft, hard};
  setrlimit(resource, &limit);  // best effort: an unlimited child still cannot harm the parent
}

void apply_limits(const ImportLimits& limits, std::uint64_t inherited_address_space) {
  set_limit(RLIMIT_CORE, 0, 0);
  const auto cpu = static_cast<rlim_t>(limits.cpu_seconds);
  set_limit(RLIMIT_CPU, cpu, cpu + 5);  // SIGXCPU at the soft limit, SIGKILL 5 s later
#if !defined(LUCENT_ASAN)
  if (limits.memory_bytes > 0) {
    const auto bytes = static_cast<rlim_t>(inherited_address_space + limits.memory_bytes);
    set_limit(RLIMIT_AS, bytes, bytes);
  }
#else
  (void)inherited_address_space;
#endif
}

[[noreturn]] void run_child(int fd, int data_fd, const std::string& path, const GuardedReader& names,
                            const std::function<std::string()>& read, const ImportLimits& limits,
                            std::uint64_t inherited_address_space) {
  restore_crash_signals();
  apply_limits(limits, inherited_address_space);
  bool sent = false;
  try {
    std::vector<std::string> warnings;
    std::string result;
    {
      const WarningCapture capture(&warnings);  // returned with the result, warned by the parent
      result = read();
    }
    sent = send_result(fd, data_fd, pack_warnings(warnings, std::move(result)));
  } catch (const Error& e) {
    sent = send_error(fd, e.what());
  } catch (const std::bad_alloc&) {
    sent = send_error(fd, fmt::format("{}: {}: {} ran out of memory (limit {} MiB)", path, names.failure,
                                      names.reader, limits.memory_bytes >> 20));
  } catch (const std::exception& e) {
    sent = send_error(fd, fmt::format("{}: {}: {} failed: {}", path, names.failure, names.reader,
                                      printable_text(e.what())));
  } catch (...) {
    sent = send_error(fd, fmt::format("{}: {}: {} failed", path, names.failure, names.reader));
  }
  _exit(sent ? 0 : 3);  // no atexit handlers, no stdio flushing of the parent's buffers
}

// ---- parent ---------------------------------------------------------------------------------------------

// The address space the process has now [bytes] (first field of /proc/self/statm, in pages); the child's limit
// is counted on top of it.
std::uint64_t address_space_bytes() {
  std::FILE* file = std::fopen("/proc/self/statm", "r");
  if (!file) return 0;
  unsigned long long pages = 0;
  if (std::fscanf(file, "%llu", &pages) != 1) pages = 0;
  std::fclose(file);
  return pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

// Reads the child's reply with a deadline.
class PipeReader {
 public:
  PipeReader(int fd, Clock::time_point deadline) : fd_(fd), deadline_(deadline) {}

  // False on end of file, error or timeout (then timed_out()).
  bool read(void* data, std::size_t size) {
    char* bytes = static_cast<char*>(data);
    while (size > 0) {
      if (!wait_readable()) return false;
      const ssize_t n = ::read(fd_, bytes, size);
      if (n < 0 && errno == EINTR) continue;
      if (n == 0) eof_ = true;
      if (n <= 0) return false;
      bytes += n;
      size -= static_cast<std::size_t>(n);
    }
    return true;
  }

  bool timed_out() const { return timed_out_; }
  bool at_end() const { return eof_; }  // the child closed its end: it has exited

 private:
  bool wait_readable() {
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - Clock::now()).count();
      if (left <= 0) {
        timed_out_ = true;
        return false;
      }
      pollfd p{fd_, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1 << 30)));
      if (ready > 0) return true;
      if (ready < 0 && errno != EINTR) return false;
    }
  }

  int fd_;
  Clock::time_point deadline_;
  bool timed_out_ = false;
  bool eof_ = false;
};

// Closes a file descriptor when it goes out of scope.
struct FileDescriptor {
  explicit FileDescriptor(int descriptor) : fd(descriptor) {}
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int release() { return std::exchange(fd, -1); }
  int fd;
};

// The child's reply: its result, or the message of the error it threw; nullopt when the reply is incomplete.
struct Reply {
  std::optional<std::string> result;
  std::string error;
};

// The first `size` bytes of the shared memory file, which must hold them.
std::optional<std::string> read_data(int data_fd, std::uint64_t size) {
  struct stat data_stat {};
  if (::fstat(data_fd, &data_stat) != 0 || static_cast<std::uint64_t>(data_stat.st_size) < size) return std::nullopt;
  std::string bytes(static_cast<std::size_t>(size), '\0');
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::pread(data_fd, bytes.data() + done, bytes.size() - done, static_cast<off_t>(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return std::nullopt;
    done += static_cast<std::size_t>(n);
  }
  return bytes;
}

std::optional<Reply> receive(PipeReader& reader, int data_fd) {
  ReplyHeader header;
  if (!reader.read(&header, sizeof header) || header.magic != kMagic) return std::nullopt;
  Reply reply;
  if (header.kind == kErrorResult) {
    if (header.size > kMaxMessage) return std::nullopt;
    reply.error.resize(header.size);
    if (!reader.read(reply.error.data(), reply.error.size())) return std::nullopt;
    return reply;
  }
  if (header.kind != kBytesResult) return std::nullopt;
  reply.result = read_data(data_fd, header.size);
  if (!reply.result) return std::nullopt;
  return reply;
}

// Waits for the child; its wait status, or -1 when it was reaped elsewhere (SIGCHLD ignored).
int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return status;
}

// Why the child gave no complete reply.
std::string child_failure(int status, bool timed_out, const ImportLimits& limits, const std::string& reader) {
  if (timed_out) return fmt::format("{} did not finish within {} s", reader, limits.wall_seconds);
  if (status == -1) return reader + " stopped without a result";
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    if (sig == SIGXCPU) return fmt::format("{} used more than {} s of CPU time", reader, limits.cpu_seconds);
    return fmt::format("{} crashed (signal {}, {})", reader, sig, strsignal(sig));
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
    return fmt::format("{} crashed (exit status {})", reader, WEXITSTATUS(status));
  return reader + " stopped without a result";
}

// ---- the mesh as bytes: three counts (vertices, indices, texture coordinates), then the arrays ------------

template <class T>
void append_array(std::string& bytes, const std::vector<T>& values) {
  if (!values.empty()) bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

std::string mesh_bytes(const TriangleMesh& mesh, const std::string& path) {
  if (mesh.normals.size() != mesh.positions.size() || (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()))
    throw Error(fmt::format("{}: cannot read mesh: the importer returned {} normals and {} texture coordinates for "
                            "{} vertices",
                            path, mesh.normals.size(), mesh.uvs.size(), mesh.positions.size()));
  const std::uint64_t counts[3] = {mesh.positions.size(), mesh.indices.size(), mesh.uvs.size()};
  std::string bytes(reinterpret_cast<const char*>(counts), sizeof counts);
  bytes.reserve(sizeof counts + mesh.positions.size() * 2 * sizeof(glm::vec3) +
                mesh.indices.size() * sizeof(std::uint32_t) + mesh.uvs.size() * sizeof(glm::vec2));
  append_array(bytes, mesh.positions);
  append_array(bytes, mesh.normals);
  append_array(bytes, mesh.indices);
  append_array(bytes, mesh.uvs);
  return bytes;
}

// Copies `count` elements at `offset` of `bytes`, which must hold them.
template <class T>
bool take_array(std::string_view bytes, std::size_t& offset, std::uint64_t count, std::vector<T>& values) {
  if (count > (bytes.size() - offset) / sizeof(T)) return false;
  values.resize(static_cast<std::size_t>(count));
  if (!values.empty()) std::memcpy(values.data(), bytes.data() + offset, values.size() * sizeof(T));
  offset += values.size() * sizeof(T);
  return true;
}

std::optional<TriangleMesh> mesh_from_bytes(std::string_view bytes) {
  std::uint64_t counts[3];
  if (bytes.size() < sizeof counts) return std::nullopt;
  std::memcpy(counts, bytes.data(), sizeof counts);
  std::size_t offset = sizeof counts;
  TriangleMesh mesh;
  if ((counts[2] != 0 && counts[2] != counts[0]) || !take_array(bytes, offset, counts[0], mesh.positions) ||
      !take_array(bytes, offset, counts[0], mesh.normals) || !take_array(bytes, offset, counts[1], mesh.indices) ||
      !take_array(bytes, offset, counts[2], mesh.uvs) || offset != bytes.size())
    return std::nullopt;
  return mesh;
}

}  // namespace

ImportLimits& mesh_import_limits() {
  static ImportLimits limits;
  return limits;
}

ImportLimits& vdb_read_limits() {
  static ImportLimits limits = [] {
    ImportLimits l;
    l.in_process_when_threaded_under_asan = true;  // OpenVDB's tests run TBB threads before a read
    return l;
  }();
  return limits;
}

#if defined(LUCENT_ASAN)
// The threads of this process (the Threads: line of /proc/self/status); 0 when unknown.
int thread_count() {
  std::FILE* file = std::fopen("/proc/self/status", "r");
  if (!file) return 0;
  char line[256];
  int threads = 0;
  while (std::fgets(line, sizeof line, file))
    if (std::sscanf(line, "Threads: %d", &threads) == 1) break;
  std::fclose(file);
  return threads;
}
#endif

std::string read_in_child(const std::string& path, const GuardedReader& names,
                          const std::function<std::string()>& read, const ImportLimits& limits) {
#if defined(LUCENT_ASAN)
  // AddressSanitizer's allocator (clang 14) is not fork-safe: a child forked while another thread held its lock
  // (a TBB worker freeing memory) waits on it forever, where glibc's malloc would not. With other threads
  // running, a sanitizer build reads VDB files (whose tests run TBB threads first) in this process instead, where
  // AddressSanitizer sees the reader's code; single-threaded processes (the fuzz targets, the CLI loading a
  // scene) and the mesh importer, whose crash tests need the child, still fork.
  if (limits.in_process_when_threaded_under_asan && thread_count() != 1) {
    try {
      return read();
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(fmt::format("{}: {}: {} failed: {}", path, names.failure, names.reader, printable_text(e.what())));
    }
  }
#endif
  const std::uint64_t inherited_address_space = address_space_bytes();
  const auto fail = [&](const char* what) {
    throw Error(fmt::format("{}: {}: {}: {}", path, names.failure, what, std::strerror(errno)));
  };
  const FileDescriptor data(::memfd_create("lucent-guarded-read", MFD_CLOEXEC));
  if (data.fd < 0) fail("cannot create the reader's shared memory");
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) fail("cannot create a pipe");
  FileDescriptor read_end(fds[0]), write_end(fds[1]);
  const pid_t pid = ::fork();
  if (pid < 0) fail("cannot start the reader");
  if (pid == 0) run_child(write_end.fd, data.fd, path, names, read, limits, inherited_address_space);
  ::close(write_end.release());
  PipeReader reader(read_end.fd, Clock::now() + std::chrono::seconds(limits.wall_seconds));
  std::optional<Reply> reply = receive(reader, data.fd);
  if (!reply && !reader.at_end()) ::kill(pid, SIGKILL);  // timed out, or a reply that makes no sense
  const int status = wait_for(pid);
  if (!reply)
    throw Error(fmt::format("{}: {}: {}", path, names.failure,
                            child_failure(status, reader.timed_out(), limits, names.reader)));
  if (!reply->result) throw Error(reply->error);
  return unpack_warnings(std::move(*reply->result));
}

TriangleMesh import_in_child(const std::string& path, const std::function<TriangleMesh()>& import,
                             const ImportLimits& limits) {
  const GuardedReader names;
  std::optional<TriangleMesh> mesh =
      mesh_from_bytes(read_in_child(path, names, [&] { return mesh_bytes(import(), path); }, limits));
  if (!mesh) throw Error(fmt::format("{}: {}: {} returned a damaged mesh", path, names.failure, names.reader));
  return std::move(*mesh);
}

}  // namespace lucent
