// The include rules of the ROS-free libraries, read from the sources: every #include of the files
// under some folders, held against what the folder may include (core_is_ros_free_test,
// scene_io's ros_free_test: the core, the loader and the world build without ROS).
#ifndef NONSMOOTH_SIM_TEST_INCLUDE_RULES_H_
#define NONSMOOTH_SIM_TEST_INCLUDE_RULES_H_

#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <string>
#include <vector>

namespace nonsmooth_sim::test {

/// What a scan of the includes found.
struct IncludeScan {
  std::size_t files = 0;               // source files read
  int includes = 0;                    // #include lines in them
  std::vector<std::string> forbidden;  // "<file> includes <header>" for each one not allowed
};

/// The #includes of every .h/.cpp file under `folders` (relative to the source tree), each held
/// against `allowed`.
inline IncludeScan ScanIncludes(const std::vector<std::string>& folders,
                                const std::function<bool(const std::string&)>& allowed) {
  namespace fs = std::filesystem;
  const std::regex include_line(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  IncludeScan scan;
  for (const std::string& folder : folders) {
    const fs::path dir = fs::path(NONSMOOTH_SIM_SOURCE_DIR) / folder;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      const auto ext = entry.path().extension();
      if (ext != ".h" && ext != ".cpp") continue;
      ++scan.files;
      std::ifstream in(entry.path());
      std::string line;
      while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_search(line, m, include_line)) continue;
        ++scan.includes;
        if (!allowed(m[1])) {
          scan.forbidden.push_back(entry.path().string() + " includes <" + m[1].str() + ">");
        }
      }
    }
  }
  return scan;
}

/// A standard header: no directory and no extension (<vector>, <cmath>, ...).
inline bool IsStandardHeader(const std::string& header) {
  return header.find('/') == std::string::npos && header.find('.') == std::string::npos;
}

/// Whether `header` starts with one of `prefixes`.
inline bool StartsWithOneOf(const std::string& header, const std::vector<std::string>& prefixes) {
  for (const std::string& prefix : prefixes) {
    if (header.rfind(prefix, 0) == 0) return true;
  }
  return false;
}

}  // namespace nonsmooth_sim::test

#endif  // NONSMOOTH_SIM_TEST_INCLUDE_RULES_H_
