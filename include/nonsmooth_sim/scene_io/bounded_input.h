// Bounds on what a file or a client brings to the loader, checked before any large allocation or
// any parsing (docs/ros.md, "Bounds"; docs/urdf.md):
//  - files are regular files (not a directory, device such as /dev/zero, FIFO or socket), opened
//    non-blocking so that a FIFO never hangs, and read with a size bound;
//  - a YAML text is at most kMaxInputBytes, one document, nested at most kMaxYamlDepth levels
//    (a pre-scan: yaml-cpp parses recursively and needs memory and time in the nesting depth);
//  - names (robot, links, joints, collisions, models) are 1 to kMaxNameLength bytes.
// Errors are std::invalid_argument with one line: the reason, the bound and what is allowed (the
// callers put the file or element in front).
#ifndef NONSMOOTH_SIM_SCENE_IO_BOUNDED_INPUT_H_
#define NONSMOOTH_SIM_SCENE_IO_BOUNDED_INPUT_H_

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace nonsmooth_sim::scene_io {

/// [bytes] of a URDF or YAML file or text: 16 MiB (the shipped URDFs have a few kB; 4 096 tops
/// in one URDF would have about 6 MB).
inline constexpr std::size_t kMaxInputBytes = std::size_t{16} << 20;
/// Nesting levels of a YAML document (the initial-state format needs 5).
inline constexpr int kMaxYamlDepth = 64;
/// [bytes] of a name: the robot, a link, a joint, a collision, a model.
inline constexpr std::size_t kMaxNameLength = 256;
/// <collision> elements in one URDF (a bound on the work per step and on the node's topics).
inline constexpr std::size_t kMaxCollisionsPerModel = 4096;

/// The contents of the regular file `path`, at most `max_bytes` long. Throws std::invalid_argument
/// with the reason alone ("no such file", "is a FIFO, not a regular file; allowed: ...",
/// "has 20000000 bytes, more than the bound of 16777216 bytes (16 MiB)", ...); `expected` names
/// what the file should be ("a URDF file"). Never blocks on a FIFO, never reads more than
/// max_bytes + 1 bytes.
std::string ReadBoundedFile(const std::string& path, std::size_t max_bytes, const char* expected);

/// "16777216 bytes (16 MiB)": a byte bound for messages.
std::string DescribeBytes(std::size_t bytes);

/// Throws std::invalid_argument ("<n> bytes, more than the bound ...", "nested deeper than 64
/// levels (line 3) ...") unless `text` is at most `max_bytes` and its nesting is at most
/// kMaxYamlDepth levels. The depth is an upper estimate from the text: flow brackets [ { open
/// a level, and each block level (a deeper indentation, or a "- " / "? " indicator) one more;
/// quoted scalars and comments are skipped.
void CheckYamlText(std::string_view text, std::size_t max_bytes = kMaxInputBytes);

/// A refused YAML text: the reason and where (1-based line and column).
struct YamlTextError : std::invalid_argument {
  YamlTextError(int line, int column, const std::string& reason)
      : std::invalid_argument(reason), line(line), column(column) {}
  int line;
  int column;
};

/// The one document of `text` (a Null node for a text without one), after CheckYamlText. Throws
/// YamlTextError: "not valid YAML: <yaml-cpp's reason>" at the place it names, or "a second YAML
/// document ...; allowed: one" where the second begins. The documents are counted by yaml-cpp's
/// event parser, stopping at the second: YAML::LoadAll (yaml-cpp 0.7) never returns on a token
/// that no document consumes, such as a "," outside brackets, and appends empty documents until
/// the memory is exhausted.
YAML::Node LoadOneYamlDocument(const std::string& text, std::size_t max_bytes = kMaxInputBytes);

/// Throws std::invalid_argument "<what> "<name>...": <n> bytes, more than the bound of 256"
/// unless `name` has at most kMaxNameLength bytes (the name quoted only by its start).
void CheckNameLength(const std::string& what, std::string_view name);

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_BOUNDED_INPUT_H_
