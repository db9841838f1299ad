#include "mesh/stl.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "io/input_error.hpp"
#include "io/text_support.hpp"

namespace cushion::mesh {
namespace {

/// Largest accepted coordinate magnitude [mm] (1000 km): beyond it a model is a unit mistake, and the
/// merge tolerance (relative to the extent) would overflow.
constexpr double max_coordinate_mm = 1e9;

bool plausible(const Vec3& x) { return x.allFinite() && x.cwiseAbs().maxCoeff() <= max_coordinate_mm; }

// Merges coincident corners: positions snapped to a grid of spacing `tol` (neighbour cells checked).
TriangleSurface merge(const std::vector<Vec3>& corners) {
  TriangleSurface surface;
  if (corners.empty()) return surface;
  Vec3 low = corners[0], high = corners[0];
  for (const Vec3& x : corners) {
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
  }
  const double tol = std::max(1e-9 * (high - low).norm(), 1e-300);
  std::map<std::array<long long, 3>, int> cells;
  std::vector<int> index(corners.size());
  for (std::size_t c = 0; c < corners.size(); ++c) {
    std::array<long long, 3> key;
    for (int d = 0; d < 3; ++d) key[d] = std::llround((corners[c][d] - low[d]) / tol);
    int found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          const auto it = cells.find({key[0] + dx, key[1] + dy, key[2] + dz});
          if (it != cells.end() && (surface.vertices[it->second] - corners[c]).norm() <= tol)
            found = it->second;
        }
    if (found < 0) {
      found = static_cast<int>(surface.vertices.size());
      surface.vertices.push_back(corners[c]);
      cells[key] = found;
    }
    index[c] = found;
  }
  for (std::size_t t = 0; t + 2 < index.size(); t += 3)
    surface.triangles.push_back({index[t], index[t + 1], index[t + 2]});
  return surface;
}

std::vector<Vec3> read_ascii(std::istream& in, const std::string& path) {
  std::vector<Vec3> corners;
  std::string line;
  int line_no = 0, in_facet = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    for (auto& ch : word) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (word == "vertex") {
      Vec3 x;
      if (!(words >> x[0] >> x[1] >> x[2]) || !plausible(x))
        throw InputError(path + ":" + std::to_string(line_no) +
                         ": bad vertex coordinates (need 3 finite numbers of magnitude <= 1e9 mm)");
      corners.push_back(x);
      ++in_facet;
    } else if (word == "endfacet") {
      if (in_facet != 3)
        throw InputError(path + ":" + std::to_string(line_no) + ": facet with " +
                         std::to_string(in_facet) + " vertices (expected 3)");
      in_facet = 0;
    } else if (word != "solid" && word != "facet" && word != "outer" && word != "endloop" &&
               word != "endsolid") {
      throw InputError(path + ":" + std::to_string(line_no) + ": unexpected '" + word + "'");
    }
  }
  if (corners.empty()) throw InputError(path + ": no facets");
  return corners;
}

}  // namespace

TriangleSurface read_stl(const std::string& path) {
  io::require_readable_file(path, "STL file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open STL file");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<Vec3> corners;
  std::uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, 4);
  if (bytes.size() >= 84 && bytes.size() == 84 + 50ull * count) {
    for (std::uint32_t t = 0; t < count; ++t)
      for (int v = 0; v < 3; ++v) {
        float xyz[3];
        std::memcpy(xyz, bytes.data() + 84 + 50ull * t + 12 + 12 * v, 12);
        corners.emplace_back(xyz[0], xyz[1], xyz[2]);
        if (!plausible(corners.back()))
          throw InputError(path + ": triangle " + std::to_string(t + 1) +
                           ": non-finite vertex or coordinate beyond 1e9 mm");
      }
    if (corners.empty()) throw InputError(path + ": no facets");
  } else if (bytes.compare(0, 5, "solid") == 0) {
    std::istringstream text(bytes);
    corners = read_ascii(text, path);
  } else {
    throw InputError(path + ": neither ASCII STL (starting 'solid') nor binary STL (size 84 + 50 n)");
  }
  return merge(corners);
}

void write_stl(const TriangleSurface& surface, const std::string& path, bool binary) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path + ": cannot write STL file");
  const auto normal = [&](const std::array<int, 3>& t) {
    const Vec3& a = surface.vertices[t[0]];
    Vec3 n = (surface.vertices[t[1]] - a).cross(surface.vertices[t[2]] - a);
    return n.norm() > 0 ? Vec3(n.normalized()) : n;
  };
  if (!binary) {
    out.precision(17);
    out << "solid cushion\n";
    for (const auto& t : surface.triangles) {
      const Vec3 n = normal(t);
      out << "  facet normal " << n[0] << ' ' << n[1] << ' ' << n[2] << "\n    outer loop\n";
      for (int v : t) {
        const Vec3& x = surface.vertices[v];
        out << "      vertex " << x[0] << ' ' << x[1] << ' ' << x[2] << "\n";
      }
      out << "    endloop\n  endfacet\n";
    }
    out << "endsolid cushion\n";
    return;
  }
  char header[80] = {};
  std::strncpy(header, "cushion binary STL", sizeof(header) - 1);
  out.write(header, 80);
  const std::uint32_t count = static_cast<std::uint32_t>(surface.triangles.size());
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (const auto& t : surface.triangles) {
    float record[12];
    const Vec3 n = normal(t);
    for (int d = 0; d < 3; ++d) record[d] = static_cast<float>(n[d]);
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 3; ++d) record[3 + 3 * v + d] = static_cast<float>(surface.vertices[t[v]][d]);
    out.write(reinterpret_cast<const char*>(record), 48);
    const std::uint16_t attribute = 0;
    out.write(reinterpret_cast<const char*>(&attribute), 2);
  }
}

void check_closed(const TriangleSurface& surface, const std::string& where) {
  if (surface.triangles.empty()) throw InputError(where + ": surface has no triangles");
  // Directed edge counts: a closed, consistently oriented 2-manifold uses every edge once in each
  // direction.
  std::map<std::pair<int, int>, int> directed;
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& tri = surface.triangles[t];
    const Vec3& a = surface.vertices[tri[0]];
    if ((surface.vertices[tri[1]] - a).cross(surface.vertices[tri[2]] - a).norm() == 0.0)
      throw InputError(where + ": triangle " + std::to_string(t + 1) + " is degenerate (zero area)");
    for (int k = 0; k < 3; ++k) ++directed[{tri[k], tri[(k + 1) % 3]}];
  }
  int open = 0, flipped = 0;
  std::ostringstream list;
  const auto describe = [&](int a, int b) {
    if (open + flipped > 5) return;
    const Vec3 &x = surface.vertices[a], &y = surface.vertices[b];
    list << " (" << x[0] << "," << x[1] << "," << x[2] << ")-(" << y[0] << "," << y[1] << ","
         << y[2] << ")";
  };
  for (const auto& [edge, count] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    const int reverse = back == directed.end() ? 0 : back->second;
    if (count > 1) {
      ++flipped;  // same direction used twice: inconsistent orientation or non-manifold edge
      describe(edge.first, edge.second);
    } else if (reverse == 0) {
      ++open;
      describe(edge.first, edge.second);
    }
  }
  if (open > 0 || flipped > 0)
    throw InputError(where + ": surface not closed/manifold: " + std::to_string(open) +
                     " open edge(s), " + std::to_string(flipped) +
                     " edge(s) with inconsistent orientation or more than two triangles; first:" +
                     list.str() + " mm");
}

double enclosed_volume(const TriangleSurface& surface) {
  double volume = 0.0;
  for (const auto& t : surface.triangles)
    volume += surface.vertices[t[0]].dot(surface.vertices[t[1]].cross(surface.vertices[t[2]])) / 6.0;
  return volume;
}

}  // namespace cushion::mesh
