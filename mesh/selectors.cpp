#include "mesh/selectors.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "mesh/text.hpp"

namespace cushion::mesh {
namespace {

struct Parser {
  std::string text, where;
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(where + ": selector '" + text + "': " + what);
  }
  double number(const std::string& token) const {
    const std::string t = trim(token);
    const std::optional<double> value = io::parse_finite_number(t);
    if (!value) fail("bad number '" + t + "'");
    return *value;
  }
  // "name(a, b, ...)" with exactly `count` numbers.
  std::vector<double> arguments(const std::string& body, std::size_t count) const {
    const auto open = body.find('('), close = body.rfind(')');
    if (open == std::string::npos || close == std::string::npos || close < open ||
        !trim(body.substr(close + 1)).empty())
      fail("expected '" + trim(body.substr(0, open)) + "(" + std::to_string(count) + " numbers)'");
    std::vector<double> values;
    std::stringstream list(body.substr(open + 1, close - open - 1));
    for (std::string item; std::getline(list, item, ',');) values.push_back(number(item));
    if (values.size() != count)
      fail("expected " + std::to_string(count) + " numbers, got " + std::to_string(values.size()));
    return values;
  }
};

double resolve(double tol, const Mesh& mesh) {
  if (tol >= 0.0) return tol;
  if (mesh.nodes.empty()) return 0.0;
  Vec3 low = mesh.nodes[0], high = mesh.nodes[0];
  for (const Vec3& x : mesh.nodes) {
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
  }
  return 1e-6 * (high - low).norm();
}

}  // namespace

Selector parse_selector(const std::string& raw, const std::string& where) {
  Parser p{trim(raw), where};
  std::string text = p.text;
  // Optional trailing "tol <number>".
  double tol = kAutoTolerance;
  const auto tol_at = text.find(" tol ");
  if (tol_at != std::string::npos) {
    tol = p.number(text.substr(tol_at + 5));
    if (tol < 0) p.fail("tolerance must be >= 0");
    text = trim(text.substr(0, tol_at));
  }
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == "all") return AllSelector{};
  if (lower.rfind("box", 0) == 0) {
    const auto v = p.arguments(text, 6);
    const Selector s = BoxSelector{Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5]), tol};
    validate(s, where + ": selector '" + p.text + "'");
    return s;
  }
  if (lower.rfind("sphere", 0) == 0) {
    const auto v = p.arguments(text, 4);
    const Selector s = SphereSelector{Vec3(v[0], v[1], v[2]), v[3], tol};
    validate(s, where + ": selector '" + p.text + "'");
    return s;
  }
  if (lower.rfind("cylinder", 0) == 0) {
    const auto v = p.arguments(text, 7);
    const Selector s = CylinderSelector{Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5]), v[6], tol};
    validate(s, where + ": selector '" + p.text + "'");
    return s;
  }
  // "<axis> <op> <value>"
  if (lower.empty()) p.fail("empty selector");
  PlaneSelector plane;
  plane.tol = tol;
  const char axis = lower[0];
  if (axis < 'x' || axis > 'z' || (lower.size() > 1 && std::isalnum(static_cast<unsigned char>(lower[1]))))
    p.fail("unknown axis or selector '" + text.substr(0, text.find_first_of(" =<>(")) +
           "' (expected x, y, z, box, sphere, cylinder or all)");
  plane.axis = axis - 'x';
  std::string rest = trim(text.substr(1));
  static const std::pair<const char*, Comparison> kOps[] = {
      {"==", Comparison::equal},   {"<=", Comparison::less_equal}, {">=", Comparison::greater_equal},
      {"<", Comparison::less},     {">", Comparison::greater},     {"=", Comparison::equal}};
  bool found = false;
  for (const auto& [symbol, op] : kOps) {
    const std::string s(symbol);
    if (rest.rfind(s, 0) == 0) {
      plane.op = op;
      rest = rest.substr(s.size());
      found = true;
      break;
    }
  }
  if (!found) p.fail("bad comparison '" + rest.substr(0, rest.find(' ')) + "' (expected ==, <=, >=, <, >)");
  plane.value = p.number(rest);
  return plane;
}

void validate(const Selector& selector, const std::string& where) {
  const auto fail = [&](const std::string& what) { throw InputError(where + ": " + what); };
  if (const auto* s = std::get_if<PlaneSelector>(&selector)) {
    if (s->axis < 0 || s->axis > 2) fail("axis must be 0, 1 or 2 (x, y, z)");
    if (!std::isfinite(s->value)) fail("value must be finite");
  } else if (const auto* s = std::get_if<BoxSelector>(&selector)) {
    if (!(s->low.array() <= s->high.array()).all()) fail("box low corner must not exceed high corner");
  } else if (const auto* s = std::get_if<SphereSelector>(&selector)) {
    if (!(s->radius >= 0)) fail("sphere radius must be >= 0");
  } else if (const auto* s = std::get_if<CylinderSelector>(&selector)) {
    if (!(s->radius >= 0)) fail("cylinder radius must be >= 0");
    if (!(s->direction.norm() > 0)) fail("cylinder direction must be non-zero");
  }
}

std::vector<int> select_nodes(const Mesh& mesh, const Selector& selector) {
  validate(selector);
  const auto inside = [&](const Vec3& x) -> bool {
    if (const auto* s = std::get_if<PlaneSelector>(&selector)) {
      const double t = resolve(s->tol, mesh), d = x[s->axis] - s->value;
      switch (s->op) {
        case Comparison::equal: return std::abs(d) <= t;
        case Comparison::less_equal: return d <= t;
        case Comparison::greater_equal: return d >= -t;
        case Comparison::less: return d < -t;
        case Comparison::greater: return d > t;
      }
    }
    if (const auto* s = std::get_if<BoxSelector>(&selector)) {
      const double t = resolve(s->tol, mesh);
      return ((x.array() >= s->low.array() - t) && (x.array() <= s->high.array() + t)).all();
    }
    if (const auto* s = std::get_if<SphereSelector>(&selector))
      return (x - s->centre).norm() <= s->radius + resolve(s->tol, mesh);
    if (const auto* s = std::get_if<CylinderSelector>(&selector)) {
      const Vec3 axis = s->direction.normalized(), r = x - s->point;
      return (r - r.dot(axis) * axis).norm() <= s->radius + resolve(s->tol, mesh);
    }
    return true;  // AllSelector
  };
  std::vector<int> nodes;
  for (int i = 0; i < static_cast<int>(mesh.nodes.size()); ++i)
    if (inside(mesh.nodes[i])) nodes.push_back(i);
  return nodes;
}

std::vector<Face> surface_from_node_set(const Mesh& mesh, const std::vector<int>& nodes) {
  std::vector<char> member(mesh.nodes.size(), 0);
  for (int n : nodes) member.at(n) = 1;
  std::vector<Face> surface;
  for (const Face& face : boundary_faces(mesh)) {
    const Element& element = mesh.elements[face.element];
    const int corners = corners_per_face(element.type);
    const std::vector<int> local = face_nodes(element.type, face.face);
    bool all = true;
    for (int k = 0; k < corners && all; ++k) all = member[element.nodes[local[k]]] != 0;
    if (all) surface.push_back(face);
  }
  return surface;
}

}  // namespace cushion::mesh
