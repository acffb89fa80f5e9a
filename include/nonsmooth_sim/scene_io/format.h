// A number, and a name, as the loader's and the programs' error lines quote them.
#ifndef NONSMOOTH_SIM_SCENE_IO_FORMAT_H_
#define NONSMOOTH_SIM_SCENE_IO_FORMAT_H_

#include <sstream>
#include <string>

namespace nonsmooth_sim::scene_io {

/// `value` as std::ostream writes it by default (%g with 6 significant digits: "0.0015", "1e+06",
/// "inf", "nan"): the form every error line and warning uses for the values and bounds it names.
inline std::string Format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// `text` in double quotes, as error lines and warnings name links, joints and collisions.
inline std::string Quoted(const std::string& text) { return "\"" + text + "\""; }

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_FORMAT_H_
