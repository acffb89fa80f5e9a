// Meshes for the loader's tests, written from analytic solids into a temporary folder: a box, a
// tetrahedron and an icosphere as triangle lists, and writers of binary and ASCII STL, OBJ and
// DAE (COLLADA). Nothing here uses the loader or its libraries.
#ifndef NONSMOOTH_SIM_TEST_SCENE_IO_MESH_FIXTURES_H_
#define NONSMOOTH_SIM_TEST_SCENE_IO_MESH_FIXTURES_H_

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace nonsmooth_sim::scene_io::mesh_test {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

/// The box |x| ≤ h: 8 vertices, 12 triangles.
inline TriangleMesh BoxMesh(const Eigen::Vector3d& h) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 4, 6, 2},
                           {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

/// The surface of revolution about z of `meridian` ((ρ, z) from one end to the other; a point with
/// ρ = 0 is a pole, one vertex), each ring `sectors` vertices, the first at azimuth `phase` [rad].
inline TriangleMesh RevolutionMesh(const std::vector<Eigen::Vector2d>& meridian, int sectors,
                                   double phase = 0.0) {
  TriangleMesh m;
  std::vector<std::vector<int>> rings;
  for (const Eigen::Vector2d& p : meridian) {
    std::vector<int> ring;
    for (int s = 0; s < (p.x() > 0.0 ? sectors : 1); ++s) {
      const double phi = phase + 2.0 * M_PI * s / sectors;
      ring.push_back(static_cast<int>(m.vertices.size()));
      m.vertices.emplace_back(p.x() * std::cos(phi), p.x() * std::sin(phi), p.y());
    }
    rings.push_back(ring);
  }
  const auto at = [&](std::size_t ring, int s) {
    return rings[ring][s % static_cast<int>(rings[ring].size())];
  };
  for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
    for (int s = 0; s < sectors; ++s) {
      if (rings[r].size() > 1) m.triangles.push_back({at(r, s), at(r + 1, s), at(r, s + 1)});
      if (rings[r + 1].size() > 1) {
        m.triangles.push_back({at(r, s + 1), at(r + 1, s), at(r + 1, s + 1)});
      }
    }
  }
  return m;
}

/// The tetrahedron (0,0,0), (a,0,0), (0,b,0), (0,0,c): volume abc/6.
inline TriangleMesh TetrahedronMesh(double a, double b, double c) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {a, 0, 0}, {0, b, 0}, {0, 0, c}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

/// The icosahedron subdivided `levels` times, every vertex on the sphere of `radius`
/// (10·4^levels + 2 vertices: 12, 42, 162, 642).
inline TriangleMesh IcosphereMesh(int levels, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (Eigen::Vector3d& v : m.vertices) v.normalize();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return middle[key] = static_cast<int>(m.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& [a, b, c] : m.triangles) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.push_back({a, ab, ca});
      finer.push_back({b, bc, ab});
      finer.push_back({c, ca, bc});
      finer.push_back({ab, bc, ca});
    }
    m.triangles = std::move(finer);
  }
  for (Eigen::Vector3d& v : m.vertices) v *= radius;
  return m;
}

/// Volume of a closed mesh: Σ over its triangles of the tetrahedra from the origin.
inline double MeshVolume(const TriangleMesh& m) {
  double six = 0.0;
  for (const auto& [a, b, c] : m.triangles) {
    six += m.vertices[a].dot(m.vertices[b].cross(m.vertices[c]));
  }
  return six / 6.0;
}

inline Eigen::Vector3d Normal(const TriangleMesh& m, const std::array<int, 3>& t) {
  return (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized();
}

/// Binary STL: 80-byte header, uint32 count, per triangle 12 float32 and a uint16 (little endian).
inline std::string BinaryStl(const TriangleMesh& m) {
  std::string out(80, ' ');
  const auto put = [&](const void* data, std::size_t n) {
    out.append(static_cast<const char*>(data), n);
  };
  const std::uint32_t count = static_cast<std::uint32_t>(m.triangles.size());
  put(&count, 4);
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = Normal(m, t);
    for (int j = 0; j < 3; ++j) {
      const float x = static_cast<float>(n[j]);
      put(&x, 4);
    }
    for (int i : t) {
      for (int j = 0; j < 3; ++j) {
        const float x = static_cast<float>(m.vertices[i][j]);
        put(&x, 4);
      }
    }
    const std::uint16_t attribute = 0;
    put(&attribute, 2);
  }
  return out;
}

inline std::string Number(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

inline std::string AsciiStl(const TriangleMesh& m) {
  std::string out = "solid test\n";
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = Normal(m, t);
    out += "facet normal " + Number(n.x()) + " " + Number(n.y()) + " " + Number(n.z()) +
           "\n outer loop\n";
    for (int i : t) {
      const Eigen::Vector3d& v = m.vertices[i];
      out += "  vertex " + Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + "\n";
    }
    out += " endloop\nendfacet\n";
  }
  return out + "endsolid test\n";
}

inline std::string Obj(const TriangleMesh& m) {
  std::string out = "# test\n";
  for (const Eigen::Vector3d& v : m.vertices) {
    out += "v " + Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + "\n";
  }
  for (const auto& [a, b, c] : m.triangles) {
    out += "f " + std::to_string(a + 1) + " " + std::to_string(b + 1) + " " +
           std::to_string(c + 1) + "\n";
  }
  return out;
}

/// COLLADA 1.4.1 with one geometry under one node; `meter`: its <unit meter>; z up.
inline std::string Dae(const TriangleMesh& m, double meter = 1.0) {
  std::string positions, indices;
  for (const Eigen::Vector3d& v : m.vertices) {
    positions += Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + " ";
  }
  for (const auto& [a, b, c] : m.triangles) {
    indices += std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + " ";
  }
  const std::string n = std::to_string(m.vertices.size());
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
         "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
         "<asset><unit name=\"u\" meter=\"" + Number(meter) + "\"/><up_axis>Z_UP</up_axis></asset>\n"
         "<library_geometries><geometry id=\"g\" name=\"g\"><mesh>\n"
         "<source id=\"g-pos\"><float_array id=\"g-pos-array\" count=\"" +
         std::to_string(3 * m.vertices.size()) + "\">" + positions + "</float_array>\n"
         "<technique_common><accessor source=\"#g-pos-array\" count=\"" + n + "\" stride=\"3\">"
         "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
         "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
         "<vertices id=\"g-vtx\"><input semantic=\"POSITION\" source=\"#g-pos\"/></vertices>\n"
         "<triangles count=\"" + std::to_string(m.triangles.size()) + "\">"
         "<input semantic=\"VERTEX\" source=\"#g-vtx\" offset=\"0\"/><p>" + indices + "</p>"
         "</triangles>\n</mesh></geometry></library_geometries>\n"
         "<library_visual_scenes><visual_scene id=\"s\" name=\"s\"><node id=\"n\" name=\"n\">"
         "<instance_geometry url=\"#g\"/></node></visual_scene></library_visual_scenes>\n"
         "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
}

/// A fresh temporary folder, removed with its contents on destruction.
class TempFolder {
 public:
  TempFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "nonsmooth_sim_mesh_XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const std::string& path() const { return path_; }
  /// Writes `contents` to <folder>/<relative> (folders created); returns its path.
  std::string Write(const std::string& relative, const std::string& contents) const {
    const std::filesystem::path file = std::filesystem::path(path_) / relative;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << contents;
    return file.string();
  }

 private:
  std::string path_;
};

}  // namespace nonsmooth_sim::scene_io::mesh_test

#endif  // NONSMOOTH_SIM_TEST_SCENE_IO_MESH_FIXTURES_H_
