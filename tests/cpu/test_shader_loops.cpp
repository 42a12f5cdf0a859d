// test_shader_loops.cpp: no shader loop whose count comes from data can pass llvmpipe's loop cap
// (platform::kLlvmpipeLoopIterations: the driver ends every loop of an invocation, silently, once the iterations of
// all its loops together reach it). A scan of every embedded GLSL source (shader stages and the headers shared with
// C++): a loop is bounded by constants when its header names only literals and compile-time constants (k*,
// LUCENT_*), or when it is a `for` with a constant init and a conjunct of its condition bounding the loop variable
// by constants (`i < kMaxSteps && t < length`); where that constant resolves, it must not pass the cap. Any other
// loop carries a comment
//
//   // loop bound: <term> x <term> ...; <what enforces it>
//
// (on its line or in the comment lines directly above it), whose terms are integer literals, constants of the
// embedded sources, or `param.<name>` (the largest value the owning method's parameter accepts). The product is the
// most iterations the loop, with the loops nested in it, can run in one invocation, counting the multiplicity of the
// code that encloses or calls it; it must stay under the cap. Each annotation bounds its own loop: sequential loops
// of one invocation are not summed (a sum over files would count nested annotated loops twice).
// The term `checked` says the host refuses, at run time, an invocation that would pass the cap
// (platform::check_loop_iterations, or a method counting its iterations against kLlvmpipeLoopIterations): the
// owning method's folder, or for a shared file some method, must do so.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/shader_sources.h"
#include "methods/method_info.h"
#include "platform/gl_capabilities.h"
#include "../test_paths.h"
#include "../test_support.h"

namespace {

using lucent::gpu::kEmbeddedFileCount;
using lucent::gpu::kEmbeddedFiles;

struct ShaderLoop {
  std::string file;
  int line = 0;
  std::string header;      // "for (...)" or "while (...)"
  std::string annotation;  // the text after "loop bound:", empty when none
};

std::vector<std::string> lines_of(std::string_view text) {
  std::vector<std::string> lines;
  std::istringstream in{std::string(text)};
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The loop headers of one source, with their annotations (comments are stripped from the header itself).
std::vector<ShaderLoop> loops_in(const std::string& file, std::string_view text) {
  static const std::regex loop_start(R"((^|[^A-Za-z0-9_])(for|while)\s*\()");
  const std::vector<std::string> lines = lines_of(text);
  std::vector<ShaderLoop> loops;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string code = lines[i].substr(0, lines[i].find("//"));
    std::smatch m;
    if (!std::regex_search(code, m, loop_start)) continue;
    // The header up to its matching parenthesis, over following lines if it spans them.
    std::string header = code.substr(static_cast<std::size_t>(m.position(0)) + m[1].length());
    std::size_t end = std::string::npos;
    for (std::size_t j = i;; ++j) {
      int depth = 0;  // the header is scanned again from its start once a line is appended
      for (std::size_t k = 0; k < header.size(); ++k) {
        if (header[k] == '(') ++depth;
        if (header[k] == ')' && --depth == 0) {
          end = k;
          break;
        }
      }
      if (end != std::string::npos || j + 1 >= lines.size()) break;
      header += " " + lines[j + 1].substr(0, lines[j + 1].find("//"));
    }
    ShaderLoop loop{file, static_cast<int>(i + 1), header.substr(0, end == std::string::npos ? header.size() : end + 1),
                    ""};
    // The annotation: on the loop's line, or in the comment lines directly above it.
    for (std::size_t j = i + 1; j-- > 0;) {
      const std::size_t at = lines[j].find("loop bound:");
      if (at != std::string::npos) {
        loop.annotation = lines[j].substr(at + std::string("loop bound:").size());
        break;
      }
      const std::size_t first = lines[j].find_first_not_of(" \t");
      if (j != i && (first == std::string::npos || lines[j].compare(first, 2, "//") != 0)) break;
      if (j + 4 < i) break;
    }
    loops.push_back(loop);
  }
  return loops;
}

// Compile-time integer constants of the embedded sources: `const int kName = 60000;`, `#define LUCENT_NAME 8`.
std::map<std::string, std::int64_t> source_constants() {
  static const std::regex constant(R"(const\s+(?:int|uint)\s+(k[A-Z]\w*)\s*=\s*(\d+)u?\s*;)");
  static const std::regex define(R"(#define\s+(LUCENT_[A-Z0-9_]+)\s+\(?(\d+)u?\)?\s*(//.*)?$)");
  std::map<std::string, std::int64_t> values;
  for (std::size_t f = 0; f < kEmbeddedFileCount; ++f)
    for (const std::string& line : lines_of(std::string_view(kEmbeddedFiles[f].text, kEmbeddedFiles[f].size))) {
      std::smatch m;
      if (std::regex_search(line, m, constant) || std::regex_search(line, m, define))
        values[m[1].str()] = std::stoll(m[2].str());
    }
  return values;
}

bool constant_name(const std::string& name) {
  return (name.size() > 1 && name[0] == 'k' && std::isupper(static_cast<unsigned char>(name[1]))) ||
         name.rfind("LUCENT_", 0) == 0;
}

// Whether every identifier of `text`, besides `variable` and the types, is a compile-time constant.
bool only_constants(const std::string& text, const std::string& variable) {
  static const std::regex identifier(R"([A-Za-z_][A-Za-z0-9_]*)");
  static const std::regex number(R"(\b[0-9][0-9A-Fa-fXx.]*[uUfF]?\b)");
  const std::string names = std::regex_replace(text, number, " ");
  for (auto it = std::sregex_iterator(names.begin(), names.end(), identifier); it != std::sregex_iterator(); ++it) {
    const std::string name = it->str();
    if (name == "for" || name == "while" || name == "int" || name == "uint" || name == variable) continue;
    if (!constant_name(name)) return false;
  }
  return true;
}

// Whether the loop is bounded by compile-time constants: every identifier of its header is one, or it is a `for`
// whose init is constant and one conjunct of whose condition is `<variable> < constant` (or <=). `limit` receives
// the bounding constant's value where it is one literal or one constant of `constants`, else -1.
bool bounded_by_constants(const std::string& header, const std::map<std::string, std::int64_t>& constants = {},
                          std::int64_t* limit = nullptr) {
  static const std::regex declared(R"((?:int|uint)\s+([A-Za-z_]\w*)\s*=)");
  static const std::regex conjunct_bound(R"(^\s*\(?\s*([A-Za-z_]\w*)\s*<=?\s*([A-Za-z_0-9]+?)u?\s*\)?\s*$)");
  if (limit) *limit = -1;
  std::string variable;
  std::smatch d;
  if (std::regex_search(header, d, declared)) variable = d[1].str();
  const std::size_t open = header.find('('), first = header.find(';'), second = header.find(';', first + 1);
  const bool is_for = header.rfind("for", 0) == 0 && first != std::string::npos && second != std::string::npos;
  if (!is_for) return only_constants(header, variable);
  const std::string init = header.substr(open + 1, first - open - 1);
  const std::string condition = header.substr(first + 1, second - first - 1);
  if (!only_constants(init, variable)) return false;
  for (std::size_t at = 0; at <= condition.size();) {
    const std::size_t end = std::min(condition.find("&&", at), condition.size());
    const std::string part = condition.substr(at, end - at);
    std::smatch m;
    if (std::regex_match(part, m, conjunct_bound) && m[1].str() == variable && only_constants(m[2].str(), "")) {
      const std::string term = m[2].str();
      if (limit && std::isdigit(static_cast<unsigned char>(term[0]))) *limit = std::stoll(term);
      if (limit && constants.count(term)) *limit = constants.at(term);
      return true;
    }
    at = end + 2;
  }
  return only_constants(header, variable);
}

// The method whose folder holds `file` ("methods/per_pixel/shaders/x.comp" -> per-pixel), or null.
const lucent::methods::MethodInfo* owning_method(const std::string& file) {
  if (file.rfind("methods/", 0) != 0) return nullptr;
  const std::string folder = file.substr(8, file.find('/', 8) - 8);
  for (const lucent::methods::MethodInfo* method : lucent::methods::method_registry()) {
    std::string name(method->name);
    for (char& c : name)
      if (c == '-') c = '_';
    if (name == folder) return method;
  }
  return nullptr;
}

// The annotation's product, or a message saying what is wrong with it.
std::int64_t annotated_bound(const ShaderLoop& loop, const std::map<std::string, std::int64_t>& constants,
                             std::string& problem) {
  const std::string expression = loop.annotation.substr(0, loop.annotation.find(';'));
  std::istringstream terms(expression);
  std::int64_t product = 1;
  int count = 0;
  for (std::string term; terms >> term;) {
    if (term == "x") continue;
    ++count;
    std::int64_t value = 0;
    if (term == "checked") {
      value = 1;  // the host refuses what would pass the cap (the test checks it calls the check)
    } else if (std::isdigit(static_cast<unsigned char>(term[0]))) {
      value = std::stoll(term);
    } else if (term.rfind("param.", 0) == 0) {
      const lucent::methods::MethodInfo* method = owning_method(loop.file);
      const std::string name = term.substr(6);
      bool found = false;
      if (method)
        for (const lucent::ParamDecl& p : method->params)
          if (p.name == name) value = static_cast<std::int64_t>(p.max), found = true;
      if (!found) {
        problem = "no parameter " + name + " of the method owning the file";
        return 0;
      }
    } else if (constants.count(term)) {
      value = constants.at(term);
    } else {
      problem = "unknown term '" + term + "'";
      return 0;
    }
    product *= value;
  }
  if (count == 0) problem = "no bound before ';'";
  return product;
}

// Whether a C++ source of the method's folder (any method's, for null) calls platform::check_loop_iterations or
// budgets the shader's loops against platform::kLlvmpipeLoopIterations itself (random-walk).
bool method_checks_loops(const lucent::methods::MethodInfo* method) {
  namespace fs = std::filesystem;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(LUCENT_SOURCE_DIR) / "src/methods")) {
    if (entry.path().extension() != ".cpp") continue;
    if (method) {
      std::string folder(method->name);
      for (char& c : folder)
        if (c == '-') c = '_';
      if (entry.path().parent_path().filename() != folder) continue;
    }
    const std::string text = lucent::test::read_text(entry.path());
    if (text.find("check_loop_iterations(") != std::string::npos) return true;
    if (text.find("kLlvmpipeLoopIterations") != std::string::npos) return true;  // budgets its loops itself
  }
  return false;
}

TEST(ShaderLoops, EveryLoopOverDataStatesABoundUnderTheDriverCap) {
  const std::map<std::string, std::int64_t> constants = source_constants();
  const std::int64_t cap = lucent::platform::kLlvmpipeLoopBudget;  // half the cap: see gl_capabilities.h
  int annotated = 0;
  for (std::size_t f = 0; f < kEmbeddedFileCount; ++f) {
    const std::string file = kEmbeddedFiles[f].path;
    for (const ShaderLoop& loop : loops_in(file, std::string_view(kEmbeddedFiles[f].text, kEmbeddedFiles[f].size))) {
      const std::string where = file + ":" + std::to_string(loop.line) + " " + loop.header;
      if (loop.annotation.empty()) {
        std::int64_t limit = -1;
        EXPECT_TRUE(bounded_by_constants(loop.header, constants, &limit))
            << where << ": a loop whose count comes from data needs a '// loop bound: ...' comment";
        EXPECT_LE(limit, cap) << where << ": its constant bound passes the cap; it needs a '// loop bound: ...' comment";
        continue;
      }
      ++annotated;
      std::string problem;
      const std::int64_t bound = annotated_bound(loop, constants, problem);
      EXPECT_TRUE(problem.empty()) << where << ": " << problem;
      EXPECT_LE(bound, cap) << where << ": bound " << loop.annotation;
      const std::string expression = loop.annotation.substr(0, loop.annotation.find(';'));
      if (std::regex_search(expression, std::regex(R"(\bchecked\b)"))) {
        EXPECT_TRUE(method_checks_loops(owning_method(file)))
            << where << ": 'checked', but no method owning it calls platform::check_loop_iterations";
      }
    }
  }
  EXPECT_GT(annotated, 20);
}

TEST(ShaderLoops, TheScanFindsLoopsOverDataAndReadsTheirBounds) {
  const std::string source =
      "void f() {\n"
      "  for (int band = 0; band < 3; ++band) x += 1;\n"
      "  for (int i = 0; i < kMaxSteps; ++i) x += 1;\n"
      "  for (int i = 0; i < method.counts.x; ++i) {\n"
      "  // loop bound: 4096 x 3; the N parameter's range, three bands inside\n"
      "  for (int i = 0;\n"
      "       i < method.counts.x; ++i) {\n"
      "  while (lo < hi) {\n"
      "}\n";
  const std::vector<ShaderLoop> loops = loops_in("methods/x/shaders/t.comp", source);
  ASSERT_EQ(loops.size(), 5u);
  EXPECT_TRUE(bounded_by_constants(loops[0].header));
  EXPECT_TRUE(bounded_by_constants(loops[1].header));
  EXPECT_FALSE(bounded_by_constants(loops[2].header));
  EXPECT_TRUE(loops[2].annotation.empty());
  EXPECT_EQ(loops[3].header, "for (int i = 0;        i < method.counts.x; ++i)");
  std::string problem;
  EXPECT_EQ(annotated_bound(loops[3], {}, problem), 4096 * 3);
  EXPECT_TRUE(problem.empty()) << problem;
  EXPECT_FALSE(bounded_by_constants(loops[4].header));
  // A constant conjunct bounds a loop whose init is constant; a data init does not; a resolvable constant is read.
  std::int64_t limit = 0;
  EXPECT_TRUE(bounded_by_constants("for (int i = 0; i < kMaxSteps && t < length_ab; ++i)", {{"kMaxSteps", 64}}, &limit));
  EXPECT_EQ(limit, 64);
  EXPECT_TRUE(bounded_by_constants("for (int k = 0; k < LUCENT_GRID && total > 0.0f; ++k)"));
  EXPECT_FALSE(bounded_by_constants("for (int level = levels - 2; level >= 0; --level)"));
  EXPECT_FALSE(bounded_by_constants("for (int i = first; i < kMax && i < last; ++i)"));
  EXPECT_TRUE(bounded_by_constants("for (int event = 0; event < 1000000 && n < method.dispatch.y; ++event)", {},
                                   &limit));
  EXPECT_EQ(limit, 1000000);
  // `checked` is a term of value 1, and a method that calls the run-time check exists.
  ShaderLoop checked = loops[3];
  checked.annotation = " checked; the host refuses";
  EXPECT_EQ(annotated_bound(checked, {}, problem), 1);
  EXPECT_TRUE(method_checks_loops(nullptr));
  // A cap of 65,535 holds 4096 x 3 but not 4096 x 32.
  ShaderLoop too_many = loops[3];
  too_many.annotation = " 4096 x 32; too many";
  EXPECT_GT(annotated_bound(too_many, {}, problem), lucent::platform::kLlvmpipeLoopIterations);
}

}  // namespace
