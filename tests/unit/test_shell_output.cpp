// Shell observables and output: compute rim_modes counts the wings of a disc from an
// FFT of its rim height; dump shell (dump_shell.cpp) writes the limit surface and the
// per-face fields that its XDMF file points ParaView to; compute core_radius finds
// where a ring-averaged face density falls below a fraction of its peak.
#ifdef SLENDER_HAVE_SHELL
#include <cmath>
#include <fstream>
#include <sstream>

#include "helpers.hpp"
#include "shell/surface.hpp"
#include "shell/trimesh.hpp"
#ifdef SLENDER_HAVE_HDF5
#include "h5util.hpp"
#endif
#include "registry.hpp"

using namespace slender;
using namespace slender::test;

#ifdef SLENDER_HAVE_FFTW
TEST(RimModes, CountsTheWingsOfARim) {
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  shell::add_surface(*sim, "d", shell::make_disc(1.0, 4), 0.0);
  auto& c = sim->add_compute("rim", "rim_modes", P({{"group", std::string("d.boundary")}}));
  for (auto [a2, a3] : {std::pair{0.1, 0.03}, {0.02, 0.08}}) {
    for (int i : sim->group("d")) {
      Vec3& x = sim->nodes().x[i];
      const double phi = std::atan2(x.y(), x.x()), r2 = x.x() * x.x() + x.y() * x.y();
      x.z() = r2 * (a2 * std::cos(2 * phi) + a3 * std::sin(3 * phi)) + 0.05 * x.x();  // + tilt
    }
    c.evaluate(*sim);
    EXPECT_EQ(c.value("n"), a2 > a3 ? 2 : 3);
    EXPECT_NEAR(c.value("a2"), a2, 2e-3);
    EXPECT_NEAR(c.value("a3"), a3, 2e-3);
    EXPECT_NEAR(c.value("a1"), 0.05, 2e-3);  // the tilt is mode 1, never counted as wings
  }
}
#endif

namespace {
// Test-only face fields with exact core radii: with s = (r - r0) / a, "Us" is the peak
// exp(-s^2) and "Ub" has r sqrt(Ub) = 1 - exp(-s^2), a plateau of 1 outside a core. Both
// cross their cut at r0 + a sqrt(ln(1 / fraction)).
class RadialFaceFields : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name, "test: radial per-face fields with a known core");
    s.string("mesh", "surface").required();
    s.real("a", "width").def(0.1);
    s.real("r0", "peak radius").def(0.0);
    return s;
  }
  RadialFaceFields(Simulation& sim, const ParamValues& p) {
    const auto& g = *sim.topology().find_surface(p.str("mesh"))->mesh;
    for (int t = 0; t < g.n_real_tris; ++t) {
      const auto& tri = g.mesh.tri[t];
      const Vec3 m = (g.mesh.x[tri[0]] + g.mesh.x[tri[1]] + g.mesh.x[tri[2]]) / 3.0;
      const double r = std::hypot(m.x(), m.y()), s = (r - p.real("r0")) / p.real("a");
      us_.push_back(std::exp(-s * s));
      ub_.push_back(std::pow((1 - std::exp(-s * s)) / r, 2));
    }
  }
  void evaluate(Simulation&) override {}
  const std::vector<double>* face_values(const std::string& key) const override {
    return key == "Us" ? &us_ : key == "Ub" ? &ub_ : nullptr;
  }

 private:
  std::vector<double> us_, ub_;
};
}  // namespace
SLENDER_REGISTER_STYLE(slender::ComputeStyle, "test/radial_face_fields", RadialFaceFields)

TEST(CoreRadius, FindsTheCoreOfKnownProfiles) {
  struct Case {
    const char* criterion;
    double a, r0, fraction;
  };
  // energy: E(r) = 2 pi int_0^r (1 - exp(-x^2/a^2))^2 / x dx = 2 pi (ln(r / a) + C) for
  // r >> a, C = -0.0579658 by quadrature, so R_C = a exp(-C) = 1.0596787 a and A = 2 pi
  for (auto k : {Case{"stretching", 0.1, 0.0, 0.1}, Case{"stretching", 0.05, 0.0, 0.1},
                 Case{"stretching", 0.1, 0.3, 0.1}, Case{"stretching", 0.1, 0.0, 0.5},
                 Case{"curvature", 0.1, 0.0, 0.1}, Case{"curvature", 0.05, 0.0, 0.1},
                 Case{"curvature", 0.05, 0.0, 0.3}, Case{"energy", 0.1, 0.0, 0.1},
                 Case{"energy", 0.05, 0.0, 0.1}, Case{"energy", 0.02, 0.0, 0.1}}) {
    const bool energy = std::string(k.criterion) == "energy";
    auto sim = std::make_unique<Simulation>(3, 1);
    sim->verbose = false;
    // edge 1/16 outside, 1/64 within r < 0.2: the profile is sampled on unequal rings
    shell::add_surface(*sim, "d", shell::make_disc(1.0, 4, 0.4, 2), 0.0);
    sim->add_compute("u", "test/radial_face_fields",
                     P({{"mesh", std::string("d")}, {"a", k.a}, {"r0", k.r0}}));
    auto& c = sim->add_compute("core", "core_radius",
                               P({{"mesh", std::string("d")},
                                  {"shell", std::string("u")},
                                  {"criterion", std::string(k.criterion)},
                                  {"fraction", k.fraction}}));
    c.evaluate(*sim);
    const double expect =
        energy ? 1.0596787 * k.a : k.r0 + k.a * std::sqrt(std::log(1.0 / k.fraction));
    // ring criteria: measured 0.6e-3 to 2.0e-3, the linear interpolation between ring
    // means; energy: 1.1 % to 2.7 %, the faceted quadrature of the core
    EXPECT_NEAR(c.value("radius"), expect, energy ? 0.04 * expect : 0.004)
        << k.criterion << " a " << k.a << " r0 " << k.r0;
    // the fitted A = 2 pi, the plateau or the peak 1
    EXPECT_NEAR(c.value("level"), energy ? 2 * M_PI : 1.0, 0.05 * (energy ? 2 * M_PI : 1.0))
        << k.criterion;
    if (!energy) {
      EXPECT_GT(c.value("rings"), 20);
    }
  }
  // a shell without the density is named in the error
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  shell::add_surface(*sim, "d", shell::make_disc(1.0, 2), 0.0);
  auto& c = sim->add_compute("core", "core_radius", P({{"mesh", std::string("d")}}));
  try {
    c.evaluate(*sim);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("koiter.Ub"), std::string::npos) << e.what();
  }
}

#ifdef SLENDER_HAVE_HDF5
TEST(ShellDump, WritesLimitSurfaceAndFaceFields) {
  auto sim = std::make_unique<Simulation>(3, 1);
  sim->verbose = false;
  shell::add_surface(*sim, "d", shell::make_disc(1.0, 2), 0.0);
  sim->add_shell(
      "koiter",
      P({{"mesh", std::string("d")}, {"thickness", 0.02}, {"boundary", std::string("mirror")}}));
  auto& dump = sim->add_dump("out", "shell",
                             P({{"file", std::string("dump_shell_test.h5")},
                                {"every", 1.0},
                                {"mesh", std::string("d")},
                                {"faces", std::vector<std::string>{"koiter.Ub", "koiter.Us"}}}));
  // a bowl z = 0.1 r^2: bending everywhere, larger U_b than the flat start
  sim->compute_forces();
  dump.write(*sim);
  for (int i : sim->group("d")) {
    Vec3& x = sim->nodes().x[i];
    x.z() = 0.1 * (x.x() * x.x() + x.y() * x.y());
  }
  sim->compute_forces();
  sim->step = 1;
  dump.write(*sim);
  dump.flush();
  auto f = h5::open_file("dump_shell_test.h5", false);
  auto tri = h5::read_doubles(f, "mesh/triangles");
  EXPECT_EQ(tri.size(), 3u * 96);
  auto g = h5::open_group(f, "frames");
  auto pos = h5::read_doubles(h5::open_group(g, "position"), "value");
  auto ub = h5::read_doubles(h5::open_group(g, "koiter.Ub"), "value");
  const std::size_t n = sim->group("d").size();
  ASSERT_EQ(pos.size(), 2 * 3 * n);
  ASSERT_EQ(ub.size(), 2u * 96);
  double ub0 = 0, ub1 = 0;
  for (int t = 0; t < 96; ++t) {
    ub0 += ub[t];
    ub1 += ub[96 + t];
  }
  EXPECT_EQ(ub0, 0.0);
  EXPECT_GT(ub1, 0.0);
  // the limit position of the centre node: z = 0 in the flat frame, > 0 in the bowl
  // only through its neighbours (the control node itself is at 0)
  EXPECT_NEAR(pos[2], 0.0, 1e-15);
  EXPECT_GT(pos[3 * n + 2], 0.0);
  std::ifstream x("dump_shell_test.h5.xdmf");
  std::stringstream ss;
  ss << x.rdbuf();
  EXPECT_NE(ss.str().find("TopologyType=\"Triangle\""), std::string::npos);
  EXPECT_NE(ss.str().find("koiter.Ub"), std::string::npos);
  std::remove("dump_shell_test.h5");
  std::remove("dump_shell_test.h5.xdmf");
}
#endif

#endif
