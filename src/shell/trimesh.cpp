#include "shell/trimesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

#include "params.hpp"

namespace slender::shell {

namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

void refine(TriMesh& m) {
  std::map<std::uint64_t, int> mid;
  auto midpoint = [&](int a, int b) {
    auto [it, fresh] = mid.try_emplace(edge_key(a, b), m.n_nodes());
    if (fresh) m.x.push_back(0.5 * (m.x[a] + m.x[b]));
    return it->second;
  };
  std::vector<Tri> out;
  out.reserve(4 * m.tri.size());
  for (const Tri& t : m.tri) {
    const int a = t[0], b = t[1], c = t[2];
    const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    out.push_back({a, ab, ca});
    out.push_back({ab, b, bc});
    out.push_back({ca, bc, c});
    out.push_back({ab, bc, ca});
  }
  m.tri = std::move(out);
}

void refine_where(TriMesh& m, const std::function<bool(const Vec3&)>& inside) {
  const int nt = m.n_tris();
  std::vector<char> red(nt, 0);
  std::map<std::uint64_t, int> split;  // edge -> midpoint node (-1 until created)
  auto mark = [&](int t) {
    red[t] = 1;
    for (int k = 0; k < 3; ++k) split.try_emplace(edge_key(m.tri[t][k], m.tri[t][(k + 1) % 3]), -1);
  };
  for (int t = 0; t < nt; ++t)
    if (inside((m.x[m.tri[t][0]] + m.x[m.tri[t][1]] + m.x[m.tri[t][2]]) / 3.0)) mark(t);
  // closure: a triangle with two or three split edges is split into four as well
  for (bool grew = true; grew;) {
    grew = false;
    for (int t = 0; t < nt; ++t) {
      if (red[t]) continue;
      int n = 0;
      for (int k = 0; k < 3; ++k)
        n += split.count(edge_key(m.tri[t][k], m.tri[t][(k + 1) % 3])) ? 1 : 0;
      if (n >= 2) {
        mark(t);
        grew = true;
      }
    }
  }
  auto midpoint = [&](int a, int b) {
    int& id = split.at(edge_key(a, b));
    if (id < 0) {
      id = m.n_nodes();
      m.x.push_back(0.5 * (m.x[a] + m.x[b]));
    }
    return id;
  };
  std::vector<Tri> out;
  for (int t = 0; t < nt; ++t) {
    const Tri tr = m.tri[t];
    if (red[t]) {
      const int a = tr[0], b = tr[1], c = tr[2];
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      out.insert(out.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
      continue;
    }
    bool done = false;
    for (int k = 0; k < 3 && !done; ++k) {
      const int a = tr[k], b = tr[(k + 1) % 3], c = tr[(k + 2) % 3];
      if (split.count(edge_key(a, b))) {  // green: halve towards the opposite vertex
        const int ab = midpoint(a, b);
        out.insert(out.end(), {{a, ab, c}, {ab, b, c}});
        done = true;
      }
    }
    if (!done) out.push_back(tr);
  }
  m.tri = std::move(out);
}

TriMesh make_disc(double radius, int refinements, double core_radius, int core_levels) {
  if (radius <= 0) throw InputError("disc mesh: radius must be positive");
  if (refinements < 0 || refinements > 9)
    throw InputError("disc mesh: refinements must be in [0, 9]");
  if (core_levels < 0 || core_levels > 6)
    throw InputError("disc mesh: core refinement levels must be in [0, 6]");
  if (core_levels > 0 && (core_radius <= 0 || core_radius >= radius))
    throw InputError("disc mesh: the refined core needs 0 < core radius < radius");
  if (core_levels > 0 && refinements < 2)
    throw InputError("disc mesh: a refined core needs an edge of at most radius/4");
  TriMesh m;
  m.x.push_back(Vec3::Zero());
  for (int k = 0; k < 6; ++k)
    m.x.push_back(Vec3(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0.0));
  for (int k = 0; k < 6; ++k) m.tri.push_back({0, 1 + k, 1 + (k + 1) % 6});
  // the hexagonal norm: 1 on the hexagon's boundary, mapped to the disc's radius below
  const double apothem = std::cos(M_PI / 6);
  auto hexnorm = [&](const Vec3& p) {
    double n = 0.0;
    for (int k = 0; k < 6; ++k) {
      const double a = M_PI / 6 + k * M_PI / 3;
      n = std::max(n, (p.x() * std::cos(a) + p.y() * std::sin(a)) / apothem);
    }
    return n;
  };
  if (core_levels == 0) {
    for (int r = 0; r < refinements; ++r) refine(m);
  } else {
    // red-green refinement of the core, level k within core_radius / 2^(k-1), on the
    // mesh one level coarser; the final global refinement leaves every irregular node
    // of the green transitions alone in its triangles (docs/models.md §6.6)
    for (int r = 0; r + 1 < refinements; ++r) refine(m);
    for (int k = 0; k < core_levels; ++k) {
      const double rk = core_radius / radius / std::pow(2.0, k);
      refine_where(m, [&](const Vec3& c) { return hexnorm(c) < rk; });
    }
    refine(m);
  }
  // hexagon -> disc: keep the direction, map the hexagonal norm to the radius
  for (Vec3& p : m.x) {
    const double len = p.norm();
    if (len < 1e-14) continue;
    p *= radius * hexnorm(p) / len;
  }
  return m;
}

namespace {
TriMesh structured(int nu, int nv, bool periodic_v, const std::function<Vec3(int, int)>& place) {
  TriMesh m;
  const int cols = periodic_v ? nv : nv + 1;
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i <= nu; ++i) m.x.push_back(place(i, j));
  auto id = [&](int i, int j) { return (periodic_v ? j % nv : j) * (nu + 1) + i; };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      m.tri.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.tri.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}
}  // namespace

TriMesh make_ring(double r_in, double r_out, int n_r, int n_phi) {
  if (!(r_in > 0 && r_out > r_in)) {
    std::ostringstream os;
    os << "ring mesh: inner_radius (" << r_in << ") must be positive and smaller than radius ("
       << r_out << "), the outer radius";
    throw InputError(os.str());
  }
  if (n_r < 1 || n_phi < 6) throw InputError("ring mesh: need n_r >= 1 and n_phi >= 6");
  return structured(n_r, n_phi, true, [&](int i, int j) {
    const double r = r_in + (r_out - r_in) * i / n_r, a = 2 * M_PI * j / n_phi;
    return Vec3(r * std::cos(a), r * std::sin(a), 0.0);
  });
}

TriMesh make_rectangle(double lx, double ly, int nx, int ny) {
  if (!(lx > 0 && ly > 0)) throw InputError("rectangle mesh: sides must be positive");
  if (nx < 2 || ny < 2) throw InputError("rectangle mesh: need at least 2 x 2 cells");
  return structured(nx, ny, false,
                    [&](int i, int j) { return Vec3(lx * i / nx, ly * j / ny, 0.0); });
}

TriMesh make_sphere(double radius, int refinements) {
  if (radius <= 0) throw InputError("sphere mesh: radius must be positive");
  if (refinements < 1 || refinements > 8)
    throw InputError(
        "sphere mesh: refinements must be in [1, 8] (one refinement keeps the "
        "12 valence-5 nodes apart)");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriMesh m;
  m.x = {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
         Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
         Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)};
  m.tri = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
           {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
           {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int r = 0; r < refinements; ++r) {
    refine(m);
    for (Vec3& p : m.x) p.normalize();
  }
  for (Tri& tr : m.tri) {  // outward normals
    const Vec3 n = (m.x[tr[1]] - m.x[tr[0]]).cross(m.x[tr[2]] - m.x[tr[0]]);
    if (n.dot(m.x[tr[0]] + m.x[tr[1]] + m.x[tr[2]]) < 0) std::swap(tr[1], tr[2]);
  }
  for (Vec3& p : m.x) p *= radius;
  return m;
}

// ------------------------------------------------------------------ files

namespace {
std::string lower_ext(const std::string& path) {
  auto dot = path.find_last_of('.');
  std::string e = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}
[[noreturn]] void bad(const std::string& path, int line, const std::string& what) {
  throw InputError(path + ":" + std::to_string(line) + ": " + what);
}
}  // namespace

TriMesh read_mesh(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open mesh file '" + path + "'");
  return parse_mesh(in, lower_ext(path), path);
}

// Three coordinates as whole tokens: `>> double` stops at "nan" or "inf" and would report
// a missing coordinate; strtod reads them, and the caller refuses them by name.
static bool read_xyz(std::istringstream& s, Vec3& p) {
  for (int a = 0; a < 3; ++a) {
    std::string tok;
    if (!(s >> tok)) return false;
    char* end = nullptr;
    p[a] = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0') return false;
  }
  return true;
}

// Every message names the file and the line: vertex numbers would be ambiguous (OBJ counts
// from 1, OFF from 0, slender's node numbers from 1).
TriMesh parse_mesh(std::istream& in, const std::string& format, const std::string& name) {
  TriMesh m;
  std::vector<int> vertex_line, face_line;
  std::string line;
  int ln = 0;
  auto add_vertex = [&](const Vec3& p) {
    // squared lengths of larger coordinates overflow (areas, normals, distances)
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(p[a]) || std::abs(p[a]) > 1e150)
        bad(name, ln, "vertex coordinates must be finite and at most 1e150 in magnitude");
    m.x.push_back(p);
    vertex_line.push_back(ln);
  };
  // `first`: the number of the first vertex in this format (OBJ 1, OFF 0)
  auto add_face = [&](const std::vector<long>& ids, int first) {
    Tri t{};
    for (int k = 0; k < 3; ++k) {
      if (ids[k] < 0 || ids[k] >= m.n_nodes())
        bad(name, ln,
            "face index " + std::to_string(ids[k] + first) + " out of range " +
                std::to_string(first) + ".." + std::to_string(m.n_nodes() - 1 + first) +
                " (the vertices defined before this line)");
      t[k] = static_cast<int>(ids[k]);
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      bad(name, ln, "a triangle names the same vertex twice");
    m.tri.push_back(t);
    face_line.push_back(ln);
  };
  if (format == "obj") {
    while (std::getline(in, line)) {
      ++ln;
      std::istringstream s(line);
      std::string tag;
      if (!(s >> tag) || tag[0] == '#') continue;
      if (tag == "v") {
        Vec3 p;
        if (!read_xyz(s, p)) bad(name, ln, "a vertex needs three numbers x y z");
        add_vertex(p);
      } else if (tag == "f") {
        std::vector<long> ids;
        std::string tok;
        while (s >> tok) {
          long k = 0;
          try {
            std::size_t used = 0;
            const std::string num = tok.substr(0, tok.find('/'));
            k = std::stol(num, &used);
            if (used != num.size() || k == 0) throw std::invalid_argument(tok);
          } catch (...) {
            bad(name, ln, "bad face index '" + tok + "' (OBJ numbers vertices from 1)");
          }
          // negative indices count back from the last vertex defined so far
          ids.push_back(k < 0 ? m.n_nodes() + k : k - 1);
        }
        if (ids.size() != 3) bad(name, ln, "only triangles are supported");
        add_face(ids, 1);
      }
    }
  } else if (format == "off") {
    auto next = [&](std::istringstream& s) {
      while (std::getline(in, line)) {
        ++ln;
        auto h = line.find('#');
        if (h != std::string::npos) line.resize(h);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        s = std::istringstream(line);
        return true;
      }
      return false;
    };
    std::istringstream s;
    if (!next(s)) bad(name, ln, "empty file");
    std::string tag;
    s >> tag;
    if (tag != "OFF") bad(name, ln, "expected the OFF header");
    long nv = 0, nf = 0;
    if (!(s >> nv >> nf)) {
      if (!next(s) || !(s >> nv >> nf)) bad(name, ln, "expected the vertex and face counts");
    }
    if (nv < 0 || nf < 0) bad(name, ln, "negative vertex or face count");
    for (long i = 0; i < nv; ++i) {
      Vec3 p;
      if (!next(s))
        bad(name, ln,
            "the file ends after " + std::to_string(i) + " of the " + std::to_string(nv) +
                " vertices the header announces");
      if (!read_xyz(s, p))
        bad(name, ln,
            "a vertex needs three numbers x y z (the header announces " + std::to_string(nv) +
                " vertices)");
      add_vertex(p);
    }
    for (long i = 0; i < nf; ++i) {
      long k = 0;
      std::vector<long> ids(3);
      if (!next(s))
        bad(name, ln,
            "the file ends after " + std::to_string(i) + " of the " + std::to_string(nf) +
                " faces the header announces");
      if (!(s >> k) || k != 3 || !(s >> ids[0] >> ids[1] >> ids[2]))
        bad(name, ln,
            "only triangles ('3 a b c') are supported (the header announces " + std::to_string(nf) +
                " faces)");
      add_face(ids, 0);
    }
    if (next(s))
      bad(name, ln,
          "more lines than the " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
              " faces the header announces");
  } else {
    throw InputError("mesh file '" + name + "': unknown extension (use .obj or .off)");
  }
  if (m.tri.empty()) throw InputError("mesh file '" + name + "' has no triangles");
  // a vertex no triangle uses has no stiffness: the first step would send it anywhere
  std::vector<char> used(m.x.size(), 0);
  for (const Tri& t : m.tri)
    for (int k : t) used[static_cast<std::size_t>(k)] = 1;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (!used[i]) bad(name, vertex_line[i], "this vertex belongs to no triangle: remove it");
  // two vertices at one position leave a slit between the triangles on either side
  std::vector<int> order(m.x.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  auto less = [&](int a, int b) {
    return std::lexicographical_compare(m.x[a].data(), m.x[a].data() + 3, m.x[b].data(),
                                        m.x[b].data() + 3);
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t k = 1; k < order.size(); ++k)
    if (m.x[order[k - 1]] == m.x[order[k]]) {
      const int a = std::min(order[k - 1], order[k]), b = std::max(order[k - 1], order[k]);
      bad(name, vertex_line[b],
          "this vertex sits where the vertex of line " + std::to_string(vertex_line[a]) +
              " does: merge them (two vertices at one place leave a slit in the surface)");
    }
  // the same triangle twice (in either orientation) is not a surface
  std::map<Tri, int> seen;
  for (std::size_t t = 0; t < m.tri.size(); ++t) {
    Tri key = m.tri[t];
    std::sort(key.begin(), key.end());
    auto [it, fresh] = seen.emplace(key, face_line[t]);
    if (!fresh)
      bad(name, face_line[t],
          "this triangle repeats the one of line " + std::to_string(it->second));
  }
  return m;
}

void write_mesh(const std::string& path, const TriMesh& m) {
  const std::string ext = lower_ext(path);
  std::ofstream out(path);
  if (!out) throw InputError("cannot write mesh file '" + path + "'");
  out.precision(17);
  if (ext == "obj") {
    for (auto& p : m.x) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (auto& t : m.tri) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  } else if (ext == "off") {
    out << "OFF\n" << m.n_nodes() << ' ' << m.n_tris() << " 0\n";
    for (auto& p : m.x) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (auto& t : m.tri) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  } else {
    throw InputError("mesh file '" + path + "': unknown extension (use .obj or .off)");
  }
}

// ------------------------------------------------------------------ rings

Rings build_rings(int n_nodes, const std::vector<Tri>& tri) {
  Rings r;
  r.ring.assign(n_nodes, {});
  r.closed.assign(n_nodes, 0);
  r.tris.assign(n_nodes, {});
  std::vector<std::vector<std::pair<int, int>>> next(n_nodes);
  for (int t = 0; t < static_cast<int>(tri.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int v = tri[t][k], a = tri[t][(k + 1) % 3], b = tri[t][(k + 2) % 3];
      next[v].push_back({a, b});
      r.tris[v].push_back(t);
    }
  for (int v = 0; v < n_nodes; ++v) {
    auto& nx = next[v];
    if (nx.empty()) continue;
    auto succ = [&](int a) {
      for (auto& [p, q] : nx)
        if (p == a) return q;
      return -1;
    };
    // an open ring starts at a neighbour that is nobody's successor
    int start = nx[0].first;
    for (auto& [p, q] : nx) {
      bool is_target = false;
      for (auto& [p2, q2] : nx) is_target |= (q2 == p);
      if (!is_target) {
        start = p;
        break;
      }
    }
    std::vector<int>& ring = r.ring[v];
    int a = start;
    for (std::size_t guard = 0; guard <= nx.size() + 1; ++guard) {
      ring.push_back(a);
      a = succ(a);
      if (a < 0) break;
      if (a == start) {
        r.closed[v] = 1;
        break;
      }
    }
    if (ring.size() != nx.size() + (r.closed[v] ? 0 : 1))
      throw InputError("mesh is not a manifold with consistently oriented triangles (node " +
                       std::to_string(v) + ")");
  }
  return r;
}

std::vector<int> ring_from(const Rings& r, int v, int first) {
  const auto& ring = r.ring[v];
  auto it = std::find(ring.begin(), ring.end(), first);
  if (it == ring.end()) throw std::logic_error("ring_from: not a neighbour");
  std::vector<int> out(it, ring.end());
  out.insert(out.end(), ring.begin(), it);
  return out;
}

GhostedMesh add_ghosts(const TriMesh& m) {
  GhostedMesh g;
  g.mesh = m;
  g.n_real_nodes = m.n_nodes();
  g.n_real_tris = m.n_tris();
  // directed edges without a reverse are on the boundary
  std::map<std::pair<int, int>, int> owner;
  for (int t = 0; t < m.n_tris(); ++t)
    for (int k = 0; k < 3; ++k) owner[{m.tri[t][k], m.tri[t][(k + 1) % 3]}] = t;
  std::map<int, int> ghost_after, ghost_before;  // node -> ghost of its outgoing/incoming edge
  std::vector<char> is_bnd(m.n_nodes(), 0), is_row(m.n_nodes(), 0);
  for (auto& [e, t] : owner) {
    if (owner.count({e.second, e.first})) continue;
    const int p = e.first, q = e.second;
    int s = -1;
    for (int k : m.tri[t])
      if (k != p && k != q) s = k;
    const int gid = g.mesh.n_nodes();
    g.mesh.x.push_back(m.x[p] + m.x[q] - m.x[s]);
    g.mesh.tri.push_back({q, p, gid});
    g.ghosts.push_back({gid, p, q, s});
    ghost_after[p] = gid;
    ghost_before[q] = gid;
    is_bnd[p] = is_bnd[q] = 1;
    is_row[s] = 1;
  }
  for (auto& [b, ga] : ghost_after) {
    auto it = ghost_before.find(b);
    if (it == ghost_before.end())
      throw InputError("mesh boundary is not a set of closed loops (node " + std::to_string(b) +
                       ")");
    g.mesh.tri.push_back({b, it->second, ga});
  }
  for (int i = 0; i < m.n_nodes(); ++i) {
    if (is_bnd[i]) g.boundary.push_back(i);
    if (is_row[i] && !is_bnd[i]) g.first_row.push_back(i);
  }
  g.rings = build_rings(g.mesh.n_nodes(), g.mesh.tri);
  g.valence.resize(g.mesh.n_nodes());
  for (int i = 0; i < g.mesh.n_nodes(); ++i)
    g.valence[i] = static_cast<int>(g.rings.ring[i].size());
  return g;
}

void check_patches(const GhostedMesh& g) {
  for (int t = 0; t < g.n_real_tris; ++t) {
    int irregular = 0;
    for (int k : g.mesh.tri[t]) {
      if (!g.rings.closed[k])
        throw InputError("shell mesh: node " + std::to_string(k) + " of triangle " +
                         std::to_string(t) + " has an incomplete 1-ring");
      if (g.valence[k] != 6) ++irregular;
      if (g.valence[k] < 3)
        throw InputError("shell mesh: node " + std::to_string(k) + " has valence " +
                         std::to_string(g.valence[k]));
    }
    if (irregular > 1)
      throw InputError("shell mesh: triangle " + std::to_string(t) + " has " +
                       std::to_string(irregular) +
                       " irregular nodes (valence != 6); Loop elements allow one. Refine the "
                       "mesh once more (refine = n + 1)");
  }
}

}  // namespace slender::shell
