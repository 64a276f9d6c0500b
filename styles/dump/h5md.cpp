// Trajectory dump in HDF5 following the H5MD 1.1 layout: particles/all/<field>/
// {step,time,value}, particles/all/id (the node index, fill value -1 past a frame's node
// count), observables/nodes (the count per frame), connectivity/edges (fill value -1, its
// particles_group an object reference to particles/all). Outside H5MD, xdmf/polylines holds
// the chains as XDMF mixed-topology polylines for the XDMF side file, so ParaView opens the
// trajectory as one polyline per wire. The file is flushed after every frame.
#include <cstdio>
#include <fstream>
#include <memory>

#include "h5util.hpp"
#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class H5mdDump : public DumpStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("dump", name, "H5MD trajectory (HDF5) with an XDMF side file for ParaView");
    s.string("file", "output file (.h5)").required();
    Cadence::declare(s, "frames");
    s.add("fields", ParamType::StringList,
          "per-node fields: position, velocity, force, mass, or any node property")
        .def(std::vector<std::string>{"position"});
    s.boolean("xdmf", "write <file>.xdmf next to the .h5 file").def(true);
    return s;
  }
  H5mdDump(Simulation& sim, const ParamValues& p)
      : file_(p.str("file")),

        fields_(p.strings("fields")),
        xdmf_(p.boolean("xdmf")),
        dim_(sim.dimension()) {
    set_cadence(Cadence::from(p, "dump style 'h5md'", true));
    bool has_pos = false;
    for (auto& f : fields_) has_pos = has_pos || f == "position";
    if (!has_pos) fields_.insert(fields_.begin(), "position");
    for (auto& f : fields_)
      if (f != "position" && f != "velocity" && f != "force" && f != "mass" && !sim.nodes().has(f))
        throw InputError("dump style 'h5md': unknown field '" + f +
                         "' (position, velocity, force, mass or a node property of this scene)");
    file_h_ = h5::create_file(file_);
    auto meta = h5::create_group(file_h_, "h5md");
    h5::attr_ints(meta, "version", {1, 1});
    auto author = h5::create_group(meta, "author");
    h5::attr_string(author, "name", "slender user");
    auto creator = h5::create_group(meta, "creator");
    h5::attr_string(creator, "name", "slender");
    h5::attr_string(creator, "version", SLENDER_VERSION_STRING);
    auto particles = h5::create_group(file_h_, "particles");
    all_ = h5::create_group(particles, "all");
    auto box = h5::create_group(all_, "box");
    h5::attr_int(box, "dimension", dim_);
    h5::attr_strings(box, "boundary", std::vector<std::string>(static_cast<size_t>(dim_), "none"));
    for (auto& f : fields_) {
      ncomps_.push_back(ncomp(sim, f));
      series_.push_back(std::make_unique<h5::TimeSeries>(all_, f, ncomps_.back(), false));
    }
    ids_ = std::make_unique<h5::TimeSeries>(all_, "id", 1, true);
    auto obs = h5::create_group(file_h_, "observables");
    count_ = std::make_unique<h5::ScalarSeries>(obs, "nodes");
    auto conn = h5::create_group(file_h_, "connectivity");
    edges_ = std::make_unique<h5::TimeSeries>(conn, "edges", 2, true);
    h5::attr_reference(h5::open_group(conn, "edges"), "particles_group", file_h_, "/particles/all");
    // the same chains as XDMF mixed-topology polylines, one per chain in chain order (closed
    // chains end on their first node): ParaView's Extract Surface + Tube draw each wire as a tube
    xdmf_group_ = h5::create_group(file_h_, "xdmf");
    polylines_ = std::make_unique<h5::TimeSeries>(xdmf_group_, "polylines", 1, true);
  }

  void write(Simulation& sim) override {
    auto& n = sim.nodes();
    const size_t N = n.n_owned();
    for (size_t k = 0; k < fields_.size(); ++k) {
      std::vector<double> buf = gather(sim, fields_[k]);
      series_[k]->append(sim.step, sim.time, buf.data(), N);
    }
    std::vector<double> id(N);
    for (size_t i = 0; i < N; ++i) id[i] = double(i);
    ids_->append(sim.step, sim.time, id.data(), N);
    count_->append(sim.step, sim.time, double(N));
    std::vector<double> e;
    for (auto& c : sim.topology().chains)
      for (int j = 0; j < c.n_edges(); ++j)
        e.insert(e.end(), {double(c.edge_tail(j)), double(c.edge_head(j))});
    edges_->append(sim.step, sim.time, e.data(), e.size() / 2);
    std::vector<double> pl;
    std::size_t lines = 0;
    for (auto& c : sim.topology().chains) {
      if (c.n_nodes() < 2) continue;
      pl.insert(pl.end(), {kXdmfPolyline, double(c.n_nodes() + (c.closed ? 1 : 0))});
      for (int i : c.nodes) pl.push_back(double(i));
      if (c.closed) pl.push_back(double(c.nodes.front()));
      ++lines;
    }
    polylines_->append(sim.step, sim.time, pl.data(), pl.size());
    frames_.push_back({sim.time, N, e.size() / 2, lines, pl.size()});
    write_walls(sim);
    H5Fflush(file_h_, H5F_SCOPE_GLOBAL);
    if (xdmf_) write_xdmf(sim);
  }
  void flush() override {
    if (file_h_.valid()) H5Fflush(file_h_, H5F_SCOPE_GLOBAL);
  }

 private:
  struct Frame {
    double time;
    size_t nodes, edges, lines, line_values;
  };
  static constexpr double kXdmfPolyline = 2;  // the polyline's cell type in XDMF's mixed topology
  int ncomp(Simulation& sim, const std::string& f) const {
    if (f == "position" || f == "velocity" || f == "force") return dim_;
    if (f == "mass") return 1;
    return sim.nodes().find_any(f)->ncomp();
  }
  std::vector<double> gather(Simulation& sim, const std::string& f) const {
    auto& n = sim.nodes();
    const size_t N = n.n_owned();
    std::vector<double> buf;
    buf.reserve(N * 3);
    auto vecs = [&](const std::vector<Vec3>& v) {
      for (size_t i = 0; i < N; ++i)
        for (int c = 0; c < dim_; ++c) buf.push_back(v[i][c]);
    };
    if (f == "position")
      vecs(n.x);
    else if (f == "velocity")
      vecs(n.v);
    else if (f == "force")
      vecs(n.f);
    else if (f == "mass")
      buf.assign(n.mass.begin(), n.mass.begin() + static_cast<long>(N));
    else {
      buf = n.find_any(f)->to_flat();
      buf.resize(N * static_cast<size_t>(n.find_any(f)->ncomp()));
    }
    return buf;
  }
  // The walls as their styles draw them now (Style::outline), from the first frame that has
  // one: /xdmf/wall_points and /xdmf/wall_polylines, and <file>.walls.xdmf for ParaView
  // (a second file: the walls carry none of the nodes' fields).
  void write_walls(Simulation& sim) {
    std::vector<std::vector<Vec3>> lines;
    for (const Style* st : sim.styles())
      for (auto& l : st->outline()) lines.push_back(l);
    if (!wall_points_ && lines.empty()) return;
    if (!wall_points_) {
      wall_points_ = std::make_unique<h5::TimeSeries>(xdmf_group_, "wall_points", dim_, false);
      wall_lines_ = std::make_unique<h5::TimeSeries>(xdmf_group_, "wall_polylines", 1, true);
    }
    std::vector<double> pts, pl;
    std::size_t n = 0;
    for (auto& l : lines) {
      pl.insert(pl.end(), {kXdmfPolyline, double(l.size())});
      for (auto& p : l) {
        for (int c = 0; c < dim_; ++c) pts.push_back(p[c]);
        pl.push_back(double(n++));
      }
    }
    wall_points_->append(sim.step, sim.time, pts.data(), n);
    wall_lines_->append(sim.step, sim.time, pl.data(), pl.size());
    wall_frames_.push_back({sim.time, n, 0, lines.size(), pl.size()});
    if (xdmf_) write_walls_xdmf();
  }
  void write_walls_xdmf() {
    const std::string path = file_ + ".walls.xdmf", tmp = path + ".tmp";
    std::ofstream out(tmp);
    out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
        << "<Grid Name=\"walls\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    const long T = static_cast<long>(wall_frames_.size());
    std::vector<double> times;
    for (auto& fr : wall_frames_) times.push_back(fr.time);
    const std::vector<double> shown = h5::xdmf_times(times);
    for (long t = 0; t < T; ++t) {
      auto& fr = wall_frames_[static_cast<size_t>(t)];
      out << "<Grid Name=\"walls" << t << "\" GridType=\"Uniform\">\n<Time Value=\""
          << shown[static_cast<size_t>(t)] << "\"/>\n";
      out << "<Topology TopologyType=\"Mixed\" NumberOfElements=\"" << fr.lines << "\">\n"
          << slab("/xdmf/wall_polylines/value", t, fr.line_values, 1, wall_lines_->capacity(), T,
                  "Int")
          << "</Topology>\n";
      out << "<Geometry GeometryType=\"" << (dim_ == 2 ? "XY" : "XYZ") << "\">\n"
          << slab("/xdmf/wall_points/value", t, fr.nodes, dim_, wall_points_->capacity(), T,
                  "Float")
          << "</Geometry>\n</Grid>\n";
    }
    out << "</Grid>\n</Domain>\n</Xdmf>\n";
    out.close();
    std::rename(tmp.c_str(), path.c_str());
  }
  std::string slab(const std::string& path, long t, size_t n, int nc, size_t cap, long frames,
                   const char* type) const {
    return h5::xdmf_slab(base_name(), path, t, n, nc, cap, frames, type);
  }
  std::string base_name() const {
    auto pos = file_.find_last_of('/');
    return pos == std::string::npos ? file_ : file_.substr(pos + 1);
  }
  // Rewritten after each frame (temp + rename) so it always matches the .h5 file.
  void write_xdmf(Simulation&) {
    const std::string path = file_ + ".xdmf", tmp = path + ".tmp";
    std::ofstream out(tmp);
    out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
        << "<Grid Name=\"trajectory\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    const long T = static_cast<long>(frames_.size());
    std::vector<double> times;
    for (auto& fr : frames_) times.push_back(fr.time);
    const std::vector<double> shown = h5::xdmf_times(times);
    for (long t = 0; t < T; ++t) {
      auto& fr = frames_[static_cast<size_t>(t)];
      out << "<Grid Name=\"frame" << t << "\" GridType=\"Uniform\">\n<Time Value=\""
          << shown[static_cast<size_t>(t)] << "\"/>\n";
      out << "<Topology TopologyType=\"Mixed\" NumberOfElements=\"" << fr.lines << "\">\n"
          << slab("/xdmf/polylines/value", t, fr.line_values, 1, polylines_->capacity(), T, "Int")
          << "</Topology>\n";
      out << "<Geometry GeometryType=\"" << (dim_ == 2 ? "XY" : "XYZ") << "\">\n"
          << slab("/particles/all/position/value", t, fr.nodes, dim_, series_[0]->capacity(), T,
                  "Float")
          << "</Geometry>\n";
      for (size_t k = 1; k < fields_.size(); ++k) {
        const int nc = ncomps_[k];
        out << "<Attribute Name=\"" << fields_[k] << "\" Center=\"Node\" AttributeType=\""
            << (nc == 1 ? "Scalar" : "Vector") << "\">\n"
            << slab("/particles/all/" + fields_[k] + "/value", t, fr.nodes, nc,
                    series_[k]->capacity(), T, "Float")
            << "</Attribute>\n";
      }
      out << "</Grid>\n";
    }
    out << "</Grid>\n</Domain>\n</Xdmf>\n";
    out.close();
    std::rename(tmp.c_str(), path.c_str());
  }

  std::string file_;
  std::vector<std::string> fields_;
  bool xdmf_;
  int dim_;
  h5::Handle file_h_, all_, xdmf_group_;
  std::vector<std::unique_ptr<h5::TimeSeries>> series_;
  std::unique_ptr<h5::TimeSeries> ids_, edges_, polylines_;
  std::unique_ptr<h5::ScalarSeries> count_;
  std::unique_ptr<h5::TimeSeries> wall_points_, wall_lines_;
  std::vector<Frame> wall_frames_;
  std::vector<Frame> frames_;
  std::vector<int> ncomps_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::DumpStyle, "h5md", slender::H5mdDump)
