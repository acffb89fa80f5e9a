// A URDF <mesh>: its file (package://, file://, paths) and its cached convex hull. See
// mesh_source.h.
#include "nonsmooth_sim/scene_io/mesh_source.h"

#include <tinyxml2.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "nonsmooth_sim/mesh/mesh_hull.h"
#include "nonsmooth_sim/mesh/mesh_revolution.h"
#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/scene_io/format.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_io {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void Refuse(const std::string& reason) { throw std::invalid_argument(reason); }

constexpr const char* kAllowedMesh =
    "a regular file of a mesh assimp reads (STL, OBJ, DAE, ...) whose vertices enclose a volume";

bool StartsWith(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

// The <name> of the package.xml in `folder` ("" if none or unreadable).
std::string PackageName(const fs::path& folder) {
  std::string text;
  try {
    text = ReadBoundedFile((folder / "package.xml").string(), std::size_t{1} << 20,
                           "a package.xml");
  } catch (const std::invalid_argument&) {
    return "";
  }
  tinyxml2::XMLDocument document;
  if (document.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) return "";
  const tinyxml2::XMLElement* package = document.FirstChildElement("package");
  const tinyxml2::XMLElement* name = package ? package->FirstChildElement("name") : nullptr;
  return name != nullptr && name->GetText() != nullptr ? std::string(name->GetText()) : "";
}

// Depth-first as rospack: the folder holding package.xml named `package`, or "".
std::string FindPackage(const fs::path& folder, const std::string& package, int depth,
                        int* visited) {
  std::error_code error;
  if (++*visited > kMaxPackageSearchFolders || !fs::is_directory(folder, error)) return "";
  if (fs::exists(folder / "CATKIN_IGNORE", error)) return "";
  if (fs::exists(folder / "package.xml", error)) {
    return PackageName(folder) == package ? folder.string() : "";
  }
  if (depth >= kMaxPackageSearchDepth) return "";
  std::vector<fs::path> children;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (!name.empty() && name[0] != '.' && it->is_directory(error)) children.push_back(it->path());
  }
  std::sort(children.begin(), children.end());
  for (const fs::path& child : children) {
    const std::string found = FindPackage(child, package, depth + 1, visited);
    if (!found.empty()) return found;
  }
  return "";
}

// The cache of hulls: (contents hash, size, format, scale, cap) → hull.
using HullKey = std::tuple<std::size_t, std::size_t, std::string, double, double, double, int>;

std::mutex& CacheMutex() {
  static std::mutex mutex;
  return mutex;
}

std::map<HullKey, std::shared_ptr<const ConvexHull>>& Cache() {
  static std::map<HullKey, std::shared_ptr<const ConvexHull>> cache;
  return cache;
}

// The hull of a mesh file, cached (LoadMeshHull without the "allowed" of its refusals).
std::shared_ptr<const ConvexHull> HullOfFile(const std::string& path,
                                             const Eigen::Vector3d& scale, int max_vertices,
                                             std::size_t max_bytes) {
  const std::string bytes = ReadBoundedFile(path, max_bytes, "a mesh file (STL, OBJ, DAE)");
  if (bytes.empty()) Refuse("is empty; allowed: a mesh file (STL, OBJ, DAE) enclosing a volume");
  const std::string extension = fs::path(path).extension().string();
  const std::string format = extension.empty() ? "" : extension.substr(1);
  const HullKey key{std::hash<std::string>{}(bytes), bytes.size(), format, scale.x(),
                    scale.y(), scale.z(), max_vertices};
  {
    const std::lock_guard<std::mutex> lock(CacheMutex());
    const auto it = Cache().find(key);
    if (it != Cache().end()) return it->second;
  }
  std::vector<Eigen::Vector3d> points = mesh::ReadMeshVertices(bytes, format);
  for (Eigen::Vector3d& p : points) p = p.cwiseProduct(scale);
  const std::shared_ptr<const ConvexHull> hull = mesh::HullOfPoints(points, max_vertices);
  const double width = mesh::HullWidth(*hull);
  if (!(width >= kMinLength)) {
    Refuse("its convex hull is " + Format(width) + " m thin (flat): allowed: a solid at least " +
           Format(kMinLength) + " m thick");
  }
  if (!(hull->bounding_radius <= kMaxLength)) {
    Refuse("its convex hull reaches " + Format(hull->bounding_radius) +
           " m from the link frame: allowed: at most " + Format(kMaxLength) + " m");
  }
  const std::lock_guard<std::mutex> lock(CacheMutex());
  if (Cache().size() >= kMaxCachedMeshHulls) Cache().clear();
  Cache().emplace(key, hull);
  return hull;
}

}  // namespace

std::string ResolveMeshFilename(const std::string& filename, const std::string& base_directory,
                                const std::string& ros_package_path) {
  if (filename.empty()) Refuse("empty filename; allowed: package://, file:// or a path");
  const std::string package_scheme = "package://";
  const std::string file_scheme = "file://";
  if (StartsWith(filename, package_scheme)) {
    const std::string rest = filename.substr(package_scheme.size());
    const std::size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 == rest.size()) {
      Refuse("not package://<package>/<path>; allowed: package://<package>/<path in the "
             "package>, file:///<absolute path>, or a path");
    }
    const std::string package = rest.substr(0, slash);
    const fs::path relative = fs::path(rest.substr(slash + 1)).lexically_normal();
    if (relative.empty() || relative.is_absolute() || *relative.begin() == "..") {
      Refuse("escapes its package by \"..\"; allowed: a path inside the package");
    }
    if (ros_package_path.empty()) {
      Refuse("package \"" + package + "\" cannot be found: ROS_PACKAGE_PATH is empty (allowed: "
             "a package on ROS_PACKAGE_PATH, file://, or a path)");
    }
    int visited = 0;
    std::size_t begin = 0;
    while (begin <= ros_package_path.size()) {
      std::size_t end = ros_package_path.find(':', begin);
      if (end == std::string::npos) end = ros_package_path.size();
      const std::string root = ros_package_path.substr(begin, end - begin);
      if (!root.empty()) {
        const std::string found = FindPackage(root, package, 0, &visited);
        if (!found.empty()) return (fs::path(found) / relative).string();
      }
      begin = end + 1;
    }
    Refuse("package \"" + package + "\" is not on ROS_PACKAGE_PATH (" + ros_package_path +
           "): no folder there holds a package.xml named \"" + package +
           "\"; allowed: a package on ROS_PACKAGE_PATH, file://, or a path");
  }
  if (StartsWith(filename, file_scheme)) {
    const std::string path = filename.substr(file_scheme.size());
    if (path.empty() || path[0] != '/') {
      Refuse("not file:///<absolute path>; allowed: file:///<absolute path>");
    }
    return path;
  }
  if (filename.find("://") != std::string::npos) {
    Refuse("unknown scheme; allowed: package://, file://, or a path (relative to the URDF "
           "file's folder)");
  }
  const fs::path path(filename);
  if (path.is_absolute() || base_directory.empty()) return path.string();
  return (fs::path(base_directory) / path).string();
}

namespace {

void CheckScale(const Eigen::Vector3d& scale) {
  for (int i = 0; i < 3; ++i) {
    if (!(scale[i] >= kMinMeshScale && scale[i] <= kMaxMeshScale)) {
      Refuse("scale " + Format(scale[i]) + ": allowed: each component in [" +
             Format(kMinMeshScale) + ", " + Format(kMaxMeshScale) + "]");
    }
  }
}

// `load()`, its refusals each saying what is allowed
template <typename Load>
auto WithAllowed(Load load) {
  try {
    return load();
  } catch (const std::invalid_argument& e) {
    const std::string reason = e.what();
    if (reason.find("allowed") != std::string::npos) throw;
    Refuse(reason + "; allowed: " + kAllowedMesh);
  }
}

}  // namespace

std::shared_ptr<const ConvexHull> LoadMeshHull(const std::string& path,
                                               const Eigen::Vector3d& scale, int max_vertices,
                                               std::size_t max_bytes) {
  CheckScale(scale);
  return WithAllowed([&] { return HullOfFile(path, scale, max_vertices, max_bytes); });
}

MeshRevolution LoadMeshRevolution(const std::string& path, const Eigen::Vector3d& scale,
                                  const Eigen::Vector3d& axis, std::optional<double> tolerance,
                                  std::size_t max_bytes) {
  CheckScale(scale);
  return WithAllowed([&] {
    // the hull's checks (a solid of the loader's sizes) first
    HullOfFile(path, scale, kMaxHullVerticesBound, max_bytes);
    const std::string bytes = ReadBoundedFile(path, max_bytes, "a mesh file (STL, OBJ, DAE)");
    const std::string extension = fs::path(path).extension().string();
    std::vector<Eigen::Vector3d> points =
        mesh::ReadMeshVertices(bytes, extension.empty() ? "" : extension.substr(1));
    for (Eigen::Vector3d& p : points) p = p.cwiseProduct(scale);
    const mesh::BodyOfRevolution fit = mesh::FitBodyOfRevolution(points, axis, tolerance);
    return MeshRevolution{fit.shape, fit.frame, fit.deviation, fit.tolerance};
  });
}

}  // namespace nonsmooth_sim::scene_io
