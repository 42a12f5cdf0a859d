// shader_sources.cpp: #include expansion over the embedded shader files.
#include "gpu/shader_sources.h"

#include <regex>
#include <set>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "lucent/error.h"

namespace lucent::gpu {
namespace {

const EmbeddedFile* find_embedded(const std::string& path) {
  for (std::size_t i = 0; i < kEmbeddedFileCount; ++i)
    if (path == kEmbeddedFiles[i].path) return &kEmbeddedFiles[i];
  return nullptr;
}

struct Expander {
  ExpandedSource out;
  std::set<std::string> included;

  void expand(const std::string& path, const std::string& included_from) {
    if (!included.insert(path).second) return;
    const EmbeddedFile* file = find_embedded(path);
    if (!file) throw Error(fmt::format("shader {}: included file '{}' is not embedded", included_from, path));
    std::size_t number = out.files.size();
    out.files.push_back(path);
    out.text += fmt::format("#line 1 {}\n", number);
    std::istringstream lines(std::string(file->text, file->size));
    std::string line;
    int line_number = 0;
    while (std::getline(lines, line)) {
      ++line_number;
      std::string_view view = line;
      auto first = view.find_first_not_of(" \t");
      auto open = view.find('"'), close = view.rfind('"');
      bool local_include = first != std::string_view::npos && view.substr(first, 8) == "#include" &&
                           open != std::string_view::npos && close > open;  // <system> includes are C++ only
      if (local_include) {
        expand(std::string(view.substr(open + 1, close - open - 1)), path);
        out.text += fmt::format("#line {} {}\n", line_number + 1, number);
      } else {
        out.text += line;
        out.text += '\n';
      }
    }
  }
};

}  // namespace

std::string ExpandedSource::annotate_log(const std::string& log) const {
  // Mesa writes "0:12(5): error", NVIDIA "0(12) : error".
  static const std::regex reference(R"((\d+)(?::(\d+)|\((\d+)\)))");
  std::string result;
  auto begin = std::sregex_iterator(log.begin(), log.end(), reference);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    std::size_t index = std::stoul(m[1].str());
    if (index >= files.size() || static_cast<std::size_t>(m.position(0)) < last) continue;
    std::string line = m[2].matched ? m[2].str() : m[3].str();
    result += log.substr(last, static_cast<std::size_t>(m.position(0)) - last);
    result += files[index] + ":" + line;
    last = static_cast<std::size_t>(m.position(0) + m.length(0));
  }
  result += log.substr(last);
  return result;
}

ExpandedSource expand_shader(const std::string& path, const std::string& defines) {
  Expander expander;
  expander.out.text = "#version 450 core\n" + defines;
  expander.expand(path, path);
  return std::move(expander.out);
}

}  // namespace lucent::gpu
