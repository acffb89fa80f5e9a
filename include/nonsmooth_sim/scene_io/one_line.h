// The loader's error lines and warnings quote what the user wrote (names, attribute values, YAML
// keys, the parsers' own messages about a character): control characters in them are written as
// escapes, so that every message stays the one line urdf_scene.h and initial_state.h promise
// (a newline inside an attribute value used to split it).
#ifndef NONSMOOTH_SIM_SCENE_IO_ONE_LINE_H_
#define NONSMOOTH_SIM_SCENE_IO_ONE_LINE_H_

#include <string>
#include <string_view>

namespace nonsmooth_sim::scene_io {

/// `text` with \n, \r, \t written as those two characters and every other control character
/// (bytes 0x00-0x1f and 0x7f) as \xHH; everything else (UTF-8 included) unchanged.
inline std::string OneLine(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7f) {
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    }
  }
  return out;
}

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_ONE_LINE_H_
