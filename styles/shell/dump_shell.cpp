// Shell surfaces in HDF5 with an XDMF side file: the limit positions of the real
// control nodes (Loop's limit mask, docs/models.md §6.6) on the control triangles, plus
// per-face fields offered by shell and pair styles (U_b, U_s of the Koiter style,
// contact flags of contact/shell), so ParaView shows the limit surface coloured by
// U_b. Layout: /mesh/triangles, /frames/{position,<field>}/{step,time,value}.
#ifdef SLENDER_HAVE_HDF5
#include <cstdio>
#include <fstream>
#include <memory>

#include "h5util.hpp"
#include "registry.hpp"
#include "shell/loop_patch.hpp"
#include "simulation.hpp"

namespace slender {

class ShellDump : public DumpStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("dump", name,
                "shell surface (limit positions on the control triangles) with per-face fields, "
                "HDF5 + XDMF");
    s.string("file", "output file (.h5)").required();
    Cadence::declare(s, "frames");
    s.string("mesh", "surface created by sim:mesh").required();
    s.add("faces", ParamType::StringList,
          "per-face fields as <style id>.<key>, e.g. koiter.Ub, koiter.Us, contact/shell.contact")
        .def(std::vector<std::string>{});
    return s;
  }
  ShellDump(Simulation& sim, const ParamValues& p)
      : file_(p.str("file")), faces_(p.strings("faces")) {
    set_cadence(Cadence::from(p, "dump style 'shell'", true));
    const Surface* s = sim.topology().find_surface(p.str("mesh"));
    if (!s) throw InputError("dump 'shell': no mesh named '" + p.str("mesh") + "'");
    mesh_ = s->mesh;
    base_ = s->first_node;
    for (auto& f : faces_) {
      auto dot = f.rfind('.');
      if (dot == std::string::npos)
        throw InputError("dump 'shell': face field '" + f + "' needs <id>.<key>");
    }
    for (int i = 0; i < mesh_->n_real_nodes; ++i) masks_.push_back(shell::limit_mask(*mesh_, i));
    file_h_ = h5::create_file(file_);
    auto m = h5::create_group(file_h_, "mesh");
    std::vector<int> tri;
    for (int t = 0; t < mesh_->n_real_tris; ++t)
      for (int k : mesh_->mesh.tri[t]) tri.push_back(k);
    h5::write_ints(m, "triangles", tri, {static_cast<std::size_t>(mesh_->n_real_tris), 3});
    frames_g_ = h5::create_group(file_h_, "frames");
    pos_ = std::make_unique<h5::TimeSeries>(frames_g_, "position", 3, false);
    for (auto& f : faces_) {
      std::string n = f;
      for (char& c : n)
        if (c == '/') c = '|';
      names_.push_back(n);
      series_.push_back(std::make_unique<h5::TimeSeries>(frames_g_, n, 1, false));
    }
  }
  void write(Simulation& sim) override {
    const auto& x = sim.nodes().x;
    std::vector<double> buf;
    for (auto& mask : masks_) {
      Vec3 p = Vec3::Zero();
      for (auto& r : mask) p += r.N * x[base_ + r.node];
      buf.insert(buf.end(), {p.x(), p.y(), p.z()});
    }
    pos_->append(sim.step, sim.time, buf.data(), masks_.size());
    for (std::size_t k = 0; k < faces_.size(); ++k) {
      auto dot = faces_[k].rfind('.');
      Style* st = sim.find_style(faces_[k].substr(0, dot));
      const std::vector<double>* v = st ? st->face_values(faces_[k].substr(dot + 1)) : nullptr;
      if (!v || static_cast<int>(v->size()) != mesh_->n_real_tris)
        throw InputError("dump 'shell': no per-face field '" + faces_[k] + "' for this mesh");
      series_[k]->append(sim.step, sim.time, v->data(), v->size());
    }
    times_.push_back(sim.time);
    H5Fflush(file_h_, H5F_SCOPE_GLOBAL);
    write_xdmf();
  }
  void flush() override {
    if (file_h_.valid()) H5Fflush(file_h_, H5F_SCOPE_GLOBAL);
  }

 private:
  std::string base_name() const {
    auto pos = file_.find_last_of('/');
    return pos == std::string::npos ? file_ : file_.substr(pos + 1);
  }
  std::string slab(const std::string& path, long t, std::size_t n, int nc, long T) const {
    return h5::xdmf_slab(base_name(), path, t, n, nc, n, T, "Float");
  }
  void write_xdmf() {
    const std::string path = file_ + ".xdmf", tmp = path + ".tmp";
    std::ofstream out(tmp);
    const long T = static_cast<long>(times_.size());
    const std::size_t nn = masks_.size(), nt = static_cast<std::size_t>(mesh_->n_real_tris);
    const std::vector<double> shown = h5::xdmf_times(times_);
    out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
        << "<Grid Name=\"shell\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (long t = 0; t < T; ++t) {
      out << "<Grid Name=\"frame" << t << "\" GridType=\"Uniform\">\n<Time Value=\""
          << shown[static_cast<std::size_t>(t)] << "\"/>\n"
          << "<Topology TopologyType=\"Triangle\" NumberOfElements=\"" << nt << "\">\n"
          << "<DataItem Dimensions=\"" << nt << " 3\" NumberType=\"Int\" Precision=\"4\" "
          << "Format=\"HDF\">" << base_name() << ":/mesh/triangles</DataItem>\n</Topology>\n"
          << "<Geometry GeometryType=\"XYZ\">\n"
          << slab("/frames/position/value", t, nn, 3, T) << "</Geometry>\n";
      for (std::size_t k = 0; k < faces_.size(); ++k)
        out << "<Attribute Name=\"" << faces_[k] << "\" Center=\"Cell\" AttributeType=\"Scalar\">\n"
            << slab("/frames/" + names_[k] + "/value", t, nt, 1, T) << "</Attribute>\n";
      out << "</Grid>\n";
    }
    out << "</Grid>\n</Domain>\n</Xdmf>\n";
    out.close();
    std::rename(tmp.c_str(), path.c_str());
  }

  std::string file_;
  std::vector<std::string> faces_, names_;
  std::shared_ptr<const shell::GhostedMesh> mesh_;
  int base_ = 0;
  std::vector<shell::Stencil> masks_;
  h5::Handle file_h_, frames_g_;
  std::unique_ptr<h5::TimeSeries> pos_;
  std::vector<std::unique_ptr<h5::TimeSeries>> series_;
  std::vector<double> times_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::DumpStyle, "shell", slender::ShellDump)
#endif
