// output_file.h: how lucent writes files, so that no output ever destroys an input or leaves a damaged file.
//
// The rules (docs/design.md, "Errors and output safety"):
// - Every file is written to a temporary file in its own directory, flushed to disk, and renamed over the
//   destination only when complete: an interrupt, a crash or a full disk leaves the old file or the new one,
//   never a truncated one. A destination that exists and is not a regular file (/dev/null, /dev/full, a FIFO)
//   is written in place, since renaming over it would replace the device node.
// - Write errors are errors (lucent::Error naming the path), never a 0-byte file and exit 0.
// - Files that belong together (a reference's mean, standard error and metadata) are written as one set:
//   every temporary is complete before the first rename.
// - Before any work starts, commands check their outputs: no output is one of the inputs or another output,
//   the extension names a format the command writes, and the directory exists (or is created) and accepts a new
//   file. A reference that takes hours fails in its first millisecond, not after its last sample.
//
//   lucent::check_outputs({{png, "--output"}, {exr, "--exr"}}, scene.input_files);   // before rendering
//   lucent::write_file(png, encode_png(image));                                       // after
#pragma once
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace lucent {

// Replaces `path` by `bytes` (temporary file, flush, fsync, rename). The directory must exist (check_outputs creates
// it). A symbolic link is followed: the file it names is replaced. Throws lucent::Error("<path>: cannot write: <why>").
void write_file(const std::string& path, std::string_view bytes);

// Several files replaced together: commit() writes every temporary file completely, then renames them all. When a
// write fails nothing is renamed and the temporaries are removed.
class OutputSet {
 public:
  void add(std::string path, std::string bytes);
  void commit();

 private:
  struct Entry {
    std::string path;
    std::string bytes;
  };
  std::vector<Entry> entries_;
};

// One output of a command, for the checks: its path, the option or argument that named it ("--exr"), and the
// extensions of the formats written there (with the dot; empty: any name).
struct OutputPath {
  std::string path;
  std::string option;
  std::vector<std::string_view> extensions;
};

// One lucent process writes an output at a time: an OutputLock holds an advisory lock (flock) on
// `.<name>.lucent-lock` beside each output, which holds the process id, from before the command reads what it will
// replace (a reference's --resume) until after its last rename. A second process that wants one of the outputs fails
// at once with "<option> <path>: is being written by another lucent process (pid N)". Lock files are removed on
// release (and by the CLI's signal handlers); one left by a process killed with SIGKILL is harmless: the next writer
// takes it over and removes it. Devices, FIFOs and /dev, /proc paths are not locked.
//
//   lucent::check_outputs(outputs, scene_input_files(scene));
//   const lucent::OutputLock lock(outputs);   // until the outputs are written
class OutputLock {
 public:
  OutputLock() = default;
  explicit OutputLock(const std::vector<OutputPath>& outputs);
  ~OutputLock();
  OutputLock(OutputLock&&) noexcept;
  OutputLock& operator=(OutputLock&&) noexcept;

 private:
  struct Held;  // one lock file, its descriptor and its removal on signals
  std::vector<std::unique_ptr<Held>> held_;
};

// Throws lucent::Error("<option> <path>: <problem>") unless each output with a non-empty path: (a) is not the same
// file as any input (compared as files: through links, "./" and "..") nor as another output; (b) has one of its
// extensions (a device such as /dev/stdout takes any format); (c) is not a directory; (d) can be created: its directory exists or is created here, and a file can
// be created in it. Inputs that do not exist are ignored.
void check_outputs(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs);

// Throws lucent::Error("<option> <path>: '.jpg' is not a format this command writes; use .png") unless `path`
// ends in one of `output.extensions` (compared without case).
void require_extension(const OutputPath& output);

// The extension of `path` in lower case, with its dot ("out/A.EXR" -> ".exr"); empty when there is none.
std::string lowercase_extension(const std::string& path);

// True when `a` and `b` name the same file (both exist and are equivalent, or both resolve to the same path).
bool same_file(const std::string& a, const std::string& b);

}  // namespace lucent
