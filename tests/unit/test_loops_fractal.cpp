// Unit tests of compute loops2d and fractal2d on hand-made wires with a known number
// of loops and a known dimension.
#include <cmath>

#include "helpers.hpp"
#include "raster2d.hpp"

using namespace slender;
using namespace slender::test;

namespace {
// points from a towards b with spacing about 1 (b itself excluded)
void line(std::vector<Vec3>& pts, Vec3 a, Vec3 b) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm())));
  for (int i = 0; i < n; ++i) pts.push_back(a + (b - a) * (static_cast<double>(i) / n));
}
// arc around c of radius R from angle t0 to t1 (either sense), spacing about 1
void arc(std::vector<Vec3>& pts, Vec3 c, double R, double t0, double t1) {
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(t1 - t0) * R)));
  for (int i = 0; i < n; ++i) {
    const double t = t0 + (t1 - t0) * i / n;
    pts.push_back(c + Vec3(R * std::cos(t), R * std::sin(t), 0));
  }
}
// A "racket": two strands `gap` apart (centre to centre) run from x0 - handle to
// x0 at height y, open into a circular bulb of radius R and come back: one loop
// closed by a contact neck when gap is about d.
std::vector<Vec3> racket(double x0, double y, double handle, double R, double gap = 1.0) {
  std::vector<Vec3> pts;
  const double h = 0.5 * gap, c = std::sqrt(R * R - h * h);
  line(pts, Vec3(x0 - handle, y - h, 0), Vec3(x0, y - h, 0));
  const double t0 = std::atan2(-h, -c);  // just below the bulb's leftmost point
  arc(pts, Vec3(x0 + c, y, 0), R, t0, t0 + 2 * M_PI - 2 * std::abs(M_PI + t0));
  line(pts, Vec3(x0, y + h, 0), Vec3(x0 - handle, y + h, 0));
  pts.push_back(Vec3(x0 - handle, y + h, 0));
  return pts;
}

// A serpentine of strands 0.9 d apart for |y| <= ymax, clipped to the disc of radius R.
std::vector<Vec3> serpentine(double ymax, double R) {
  std::vector<Vec3> pts;
  int k = 0;
  for (double y = -ymax; y <= ymax; y += 0.9, ++k) {
    const double x = std::sqrt(std::max(0.0, R * R - y * y));
    if (k % 2 == 0)
      line(pts, Vec3(-x, y, 0), Vec3(x, y, 0));
    else
      line(pts, Vec3(x, y, 0), Vec3(-x, y, 0));
  }
  return pts;
}

double loops(Simulation& sim, double r, const std::string& column = "l.loops",
             double pixel = 0.25) {
  sim.add_compute("l", "loops2d", P({{"radius", r}, {"pixel", pixel}}));
  return sim.column(column);
}
}  // namespace

TEST(Loops2dCompute, StraightWireHasNoLoopsAndNoHoles) {
  Simulation sim(2, 1);
  std::vector<Vec3> pts;
  line(pts, Vec3(-30, 0, 0), Vec3(30, 0, 0));
  sim.add_chain("w", pts, 1.0, false);
  EXPECT_EQ(loops(sim, 20), 0.0);
  EXPECT_EQ(sim.column("l.holes"), 0.0);
}

TEST(Loops2dCompute, RacketIsOneLoopWithItsAreaAndLength) {
  const double R = 6.0;
  for (double pixel : {0.25, 0.1}) {
    Simulation sim(2, 1);
    sim.add_chain("w", racket(-5, 0, 20, R), 1.0, false);
    EXPECT_EQ(loops(sim, 30, "l.loops", pixel), 1.0) << "pixel " << pixel;
    EXPECT_EQ(sim.column("l.holes"), 1.0);
    // the empty disc inside the line of half-width 0.55; the bulb's inner side
    const double inner = R - 0.55;
    EXPECT_NEAR(sim.column("l.loop_area"), M_PI * inner * inner, 0.06 * M_PI * inner * inner);
    EXPECT_NEAR(sim.column("l.mean_loop_length"), 2 * M_PI * R, 0.1 * 2 * M_PI * R);
  }
}

TEST(Loops2dCompute, StrandsThatDoNotTouchCloseNoLoop) {
  // the same racket with its strands 1.5 d apart: no contact neck, the bulb's
  // inside leaks out along the handle to the wall
  Simulation sim(2, 1);
  sim.add_chain("w", racket(-5, 0, 40, 6.0, 1.5), 1.0, false);
  EXPECT_EQ(loops(sim, 30), 0.0);
  EXPECT_EQ(sim.column("l.holes"), 0.0);
}

TEST(Loops2dCompute, CountsLoopsOnSeveralChainsAndAlongOneChain) {
  Simulation sim(2, 1);
  sim.add_chain("a", racket(-5, -12, 15, 4.0), 1.0, false);
  sim.add_chain("b", racket(-5, 0, 15, 3.0), 1.0, false);
  sim.add_chain("c", racket(-5, 12, 15, 5.0), 1.0, false);
  EXPECT_EQ(loops(sim, 35), 3.0);

  // one chain: a racket, a climb, a second racket (a cascade of two)
  Simulation one(2, 1);
  auto p = racket(0, 0, 20, 4.0);
  p.pop_back();
  line(p, Vec3(-20, 0.5, 0), Vec3(-20, 12, 0));
  auto q = racket(0, 12.5, 20, 3.0);
  p.insert(p.end(), q.begin(), q.end());
  one.add_chain("w", p, 1.0, false);
  EXPECT_EQ(loops(one, 35), 2.0);
}

TEST(Loops2dCompute, AreaClosedByTwoWiresOrByTheWallIsNoLoop) {
  // a lens: two chains touching at both ends enclose a hole bounded by two stretches
  Simulation lens(2, 1);
  std::vector<Vec3> a, b;
  arc(a, Vec3(0, -4, 0), 6.0, M_PI - std::acos(4.5 / 6.0), std::acos(4.5 / 6.0));
  arc(b, Vec3(0, 4, 0), 6.0, -M_PI + std::acos(4.5 / 6.0), -std::acos(4.5 / 6.0));
  lens.add_chain("a", a, 1.0, false);
  lens.add_chain("b", b, 1.0, false);
  EXPECT_EQ(loops(lens, 20), 0.0);
  EXPECT_EQ(lens.column("l.holes"), 1.0);

  // an arch whose feet stand on the wall encloses an area that reaches the wall
  Simulation arch(2, 1);
  std::vector<Vec3> c;
  arc(c, Vec3(20, 0, 0), 6.0, 0.5 * M_PI, 1.5 * M_PI);
  c.push_back(Vec3(20, -6, 0));
  arch.add_chain("w", c, 1.0, false);
  EXPECT_EQ(loops(arch, 20), 0.0);
  EXPECT_EQ(arch.column("l.holes"), 0.0);
}

TEST(Loops2dCompute, ClosedRingIsOneLoop) {
  Simulation sim(2, 1);
  std::vector<Vec3> c;
  arc(c, Vec3(0, 0, 0), 5.0, 0, 2 * M_PI);
  sim.add_chain("w", c, 1.0, true);
  EXPECT_EQ(loops(sim, 20), 1.0);
}

TEST(Loops2dCompute, RejectsAPixelTooCoarseForTheWire) {
  Simulation sim(2, 1);
  EXPECT_THROW(sim.add_compute("l", "loops2d", P({{"radius", 10.0}, {"pixel", 0.8}})), InputError);
}

TEST(Fractal2dCompute, LineIsOneDimensional) {
  Simulation sim(2, 1);
  std::vector<Vec3> pts;
  line(pts, Vec3(-60, 0.3, 0), Vec3(60, 0.3, 0));
  sim.add_chain("w", pts, 1.0, false);
  sim.add_compute("D", "fractal2d", P({{"radius", 50.0}}));
  EXPECT_NEAR(sim.column("D.D"), 1.0, 0.05);
  EXPECT_GT(sim.column("D.centres"), 10.0);
  EXPECT_LT(sim.column("D.D_err"), 0.02);
}

TEST(Fractal2dCompute, DenselyPackedWireIsTwoDimensional) {
  // a serpentine of strands 0.9 d apart fills the disc: M grows like rho^2
  Simulation sim(2, 1);
  const std::vector<Vec3> pts = serpentine(49, 50);
  sim.add_chain("w", pts, 1.0, false);
  sim.add_compute("D", "fractal2d", P({{"radius", 50.0}}));
  EXPECT_NEAR(sim.column("D.D"), 2.0, 0.05);
}

TEST(Fractal2dCompute, SparseParallelStrandsLieBetween) {
  // strands 6 d apart: a line below the spacing, a plane above it
  Simulation sim(2, 1);
  int k = 0;
  for (double y = -48; y <= 48; y += 6, ++k) {
    std::vector<Vec3> pts;
    line(pts, Vec3(-60, y, 0), Vec3(60, y, 0));
    std::string name = "s";
    name += std::to_string(k);
    sim.add_chain(name, pts, 1.0, false);
  }
  sim.add_compute("D", "fractal2d", P({{"radius", 50.0}}));
  const double D = sim.column("D.D");
  EXPECT_GT(D, 1.2);
  EXPECT_LT(D, 1.9);
}

TEST(Fractal2dCompute, NoCentreFarEnoughFromTheWall) {
  Simulation sim(2, 1);
  std::vector<Vec3> pts;
  arc(pts, Vec3(0, 0, 0), 45.0, 0, M_PI);
  sim.add_chain("w", pts, 1.0, false);
  sim.add_compute("D", "fractal2d", P({{"radius", 50.0}, {"rho_max", 0.3}}));
  EXPECT_EQ(sim.column("D.centres"), 0.0);
  EXPECT_EQ(sim.column("D.D"), 0.0);
}

// The computes keep one image between evaluations (cleared, not reallocated): a wire that
// moved must leave no trace of where it was.
TEST(Loops2dCompute, ReusedImageForgetsTheLastShape) {
  Simulation sim(2, 1);
  const std::vector<Vec3> bulb = racket(-5, 0, 20, 6.0);
  sim.add_chain("w", bulb, 1.0, false);
  EXPECT_EQ(loops(sim, 30), 1.0);
  const double area = sim.column("l.loop_area");
  // the same nodes on a straight line (spacing 0.5): no loop, no hole
  auto& x = sim.nodes().x;
  for (std::size_t i = 0; i < bulb.size(); ++i)
    x[i] = Vec3(-25.0 + 0.5 * static_cast<double>(i) * 50.0 / bulb.size(), -10, 0);
  ++sim.state_epoch;
  EXPECT_EQ(sim.column("l.loops"), 0.0);
  EXPECT_EQ(sim.column("l.holes"), 0.0);
  for (std::size_t i = 0; i < bulb.size(); ++i) x[i] = bulb[i];
  ++sim.state_epoch;
  EXPECT_EQ(sim.column("l.loops"), 1.0);
  EXPECT_EQ(sim.column("l.loop_area"), area);
}

TEST(Fractal2dCompute, ReusedImageForgetsTheLastShape) {
  // a dense serpentine (D = 2), then the same nodes on one straight line (D = 1)
  Simulation sim(2, 1);
  const std::vector<Vec3> pts = serpentine(20, 25);
  sim.add_chain("w", pts, 1.0, false);
  sim.add_compute("D", "fractal2d", P({{"radius", 50.0}}));
  EXPECT_GT(sim.column("D.D"), 1.8);
  auto& x = sim.nodes().x;
  const double spacing = 90.0 / static_cast<double>(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    x[i] = Vec3(-45.0 + spacing * static_cast<double>(i), 0.3, 0);
  ++sim.state_epoch;
  EXPECT_NEAR(sim.column("D.D"), 1.0, 0.05);
}

// The disc masses come from per-row pixel counts; they must be the plain count of the
// method's definition: every wire pixel whose centre lies within rho of the sandbox centre,
// tested one by one over the whole image. A crumpled random walk, off-centre discs.
TEST(Fractal2dCompute, DiscMassesAreThePlainPixelCounts) {
  Simulation sim(2, 1);
  std::vector<Vec3> pts{Vec3(0.3, -0.2, 0)};
  unsigned state = 12345u;
  auto uniform = [&state] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / 16777216.0;
  };
  double angle = 0.0;
  const double R = 30.0;
  while (pts.size() < 1500) {
    angle += 1.2 * (uniform() - 0.5);
    Vec3 next = pts.back() + Vec3(std::cos(angle), std::sin(angle), 0);
    if (next.head<2>().norm() > R - 2) {  // turn back from the wall
      angle += M_PI;
      continue;
    }
    pts.push_back(next);
  }
  const Chain& chain = sim.add_chain("w", pts, 1.0, false);
  const double rho_min = 1.5, rho_max = 0.45, pixel = 0.25;
  const int radii = 7, centres = 40;
  sim.add_compute("D", "fractal2d",
                  P({{"radius", R},
                     {"rho_min", rho_min},
                     {"rho_max", rho_max},
                     {"radii", static_cast<double>(radii)},
                     {"centres", static_cast<double>(centres)},
                     {"pixel", pixel}}));
  const double D = sim.column("D.D"), D_err = sim.column("D.D_err");

  WireRaster img(Vec3::Zero(), R, pixel);
  std::vector<const Chain*> chains{&chain};
  img.draw_chains(sim, chains, 0.5);
  std::vector<Vec3> eligible;
  for (const Vec3& x : pts)
    if (x.head<2>().norm() + rho_max * R <= R) eligible.push_back(x);
  ASSERT_GE(eligible.size(), static_cast<std::size_t>(centres));
  std::vector<double> logr(radii), mean(radii, 0.0), slopes;
  for (int k = 0; k < radii; ++k)
    logr[k] = std::log(rho_min * std::pow(rho_max * R / rho_min, k / (radii - 1.0)));
  auto fit = [&](const std::vector<double>& y) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < radii; ++k) {
      sx += logr[k], sy += y[k], sxx += logr[k] * logr[k], sxy += logr[k] * y[k];
    }
    return (radii * sxy - sx * sy) / (radii * sxx - sx * sx);
  };
  for (int q = 0; q < centres; ++q) {
    const Vec3& c = eligible[(static_cast<std::size_t>(q) * eligible.size()) / centres];
    std::vector<double> logm(radii);
    for (int k = 0; k < radii; ++k) {
      const double rho = std::exp(logr[k]);
      double m = 0;
      for (int j = 0; j < img.size(); ++j)
        for (int i = 0; i < img.size(); ++i) {
          const double dx = img.px(i) - c.x(), dy = img.py(j) - c.y();
          if (img.state(i, j) == WireRaster::kWire && dx * dx + dy * dy <= rho * rho) m += 1;
        }
      mean[k] += m / centres;
      logm[k] = std::log(std::max(m, 1.0));
    }
    slopes.push_back(fit(logm));
  }
  for (auto& v : mean) v = std::log(v);
  EXPECT_NEAR(D, fit(mean), 1e-9);
  double avg = 0, var = 0;
  for (double s : slopes) avg += s / centres;
  for (double s : slopes) var += (s - avg) * (s - avg);
  EXPECT_NEAR(D_err, std::sqrt(var / (centres - 1) / centres), 1e-9);
  EXPECT_GT(D, 1.2);  // a crumpled walk: between a line and the plane
  EXPECT_LT(D, 1.95);
}
