// Shell observables and output: compute rim_modes counts the wings of a disc from an
// FFT of its rim height; dump shell (dump_shell.cpp) writes the limit surface and the
// per-face fields that its XDMF file points ParaView to.
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
