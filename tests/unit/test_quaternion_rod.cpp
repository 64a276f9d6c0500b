// Unit tests of the quaternion Cosserat rod kinematics and energies
// (src/quaternion_rod.hpp, docs/models.md §4): directors, the B_j matrices in the
// scalar-first ordering, the discrete Darboux vector, and finite-difference checks
// of every generalised force against its energy.
#include <random>

#include "helpers.hpp"
#include "quaternion_rod.hpp"

using namespace slender;
using namespace slender::qrod;

namespace {
std::mt19937 gen(17);
Quat random_quat(bool unit = true) {
  std::normal_distribution<double> n(0, 1);
  Quat q(n(gen), n(gen), n(gen), n(gen));
  return unit ? Quat(q.normalized()) : Quat(q);
}
Quat conj(const Quat& q) {
  return Quat(q[0], -q[1], -q[2], -q[3]);
}
}  // namespace

TEST(QuaternionRod, DirectorsAreTheColumnsOfTheRotationMatrix) {
  for (int k = 0; k < 20; ++k) {
    const Quat q = random_quat();
    const Eigen::Matrix3d R = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
    EXPECT_LT((d1(q) - R.col(0)).norm(), 1e-12);
    EXPECT_LT((d2(q) - R.col(1)).norm(), 1e-12);
    EXPECT_LT((d3(q) - R.col(2)).norm(), 1e-12);
    // J3 is the derivative of d3
    const double h = 1e-6;
    for (int c = 0; c < 4; ++c) {
      Quat p = q, m = q;
      p[c] += h;
      m[c] -= h;
      EXPECT_LT(((d3(p) - d3(m)) / (2 * h) - J3(q).col(c)).norm(), 1e-8);
    }
  }
  EXPECT_LT((d3(aligned_with(Vec3(1, 2, -2).normalized())) - Vec3(1, 2, -2) / 3.0).norm(), 1e-12);
}

TEST(QuaternionRod, CarriedOntoIsTheSmallestRotationOfTheFrame) {
  // carried_onto(q, t) turns the frame by the smallest rotation taking d3 onto t (§4.6):
  // the result is Eigen's FromTwoVectors rotation applied to q, for any angle up to and
  // including d3 opposite to t, and a frame already on t is left as it is
  std::normal_distribution<double> n(0, 1);
  for (int k = 0; k < 200; ++k) {
    const Quat q = random_quat();
    Vec3 t(n(gen), n(gen), n(gen));
    if (k % 4 == 1) t = d3(q) + 1e-3 * t;   // small turns, as in a step
    if (k % 4 == 2) t = -d3(q) + 1e-9 * t;  // nearly opposite: the fallback
    t.normalize();
    const Eigen::Quaterniond r = Eigen::Quaterniond::FromTwoVectors(d3(q), t);
    const Quat expected = mul(Quat(r.w(), r.x(), r.y(), r.z()), q).normalized();
    const Quat got = carried_onto(q, t);
    EXPECT_NEAR(got.norm(), 1.0, 1e-14);
    // (Eigen's path for opposite vectors, through an SVD, is good to ~1e-8)
    EXPECT_LT((d3(got) - t).norm(), k % 4 == 2 ? 1e-6 : 1e-12) << k;
    EXPECT_LT((got - expected).norm(), 1e-12) << k;
  }
  const Quat q = random_quat();
  EXPECT_LT((carried_onto(q, d3(q)) - q).norm(), 1e-15);
}

TEST(QuaternionRod, BMatricesGiveTheMaterialDarbouxVector) {
  // (B_j q) . p = vec(conj(q) o p)_j in the scalar-first ordering (docs/models.md §4.2)
  for (int k = 0; k < 20; ++k) {
    const Quat q = random_quat(false), p = random_quat(false);
    const Quat r = mul(conj(q), p);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(B(j, q).dot(p), r[j + 1], 1e-12);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(B(j, q).dot(q), 0.0, 1e-12);  // skew
  }
  // a turn by theta about the material axis n between neighbours:
  // kappa = (2 / l) sin(theta / 2) n (docs/models.md §4.3)
  const Quat qa = random_quat();
  const Vec3 n = Vec3(0.3, -0.5, 0.8).normalized();
  const double theta = 0.7, l = 0.9;
  const Quat turn(std::cos(theta / 2), std::sin(theta / 2) * n.x(), std::sin(theta / 2) * n.y(),
                  std::sin(theta / 2) * n.z());
  const Quat qb = mul(qa, turn);
  Quat fa = Quat::Zero(), fb = Quat::Zero();
  const auto h = hinge(qa, qb, l, Vec3(1, 1, 1), Vec3::Zero(), fa, fb);
  EXPECT_LT((h.kappa - 2.0 / l * std::sin(theta / 2) * n).norm(), 1e-12);
  // the discrete curvature approaches the continuum one: a frame turning about d2
  // at rate k along a circle of radius 1/k
  const double kc = 0.2, ds = 0.01;
  const Quat q0 = aligned_with(Vec3(1, 0, 0));
  const Quat q1 = mul(q0, Quat(std::cos(kc * ds / 2), 0, std::sin(kc * ds / 2), 0));
  fa.setZero();
  fb.setZero();
  EXPECT_NEAR(hinge(q0, q1, ds, Vec3(1, 1, 1), Vec3::Zero(), fa, fb).kappa[1], kc, 1e-6);
}

TEST(QuaternionRod, HingeForcesAreMinusTheEnergyGradient) {
  const Vec3 K(2.0, 2.0, 1.5), kbar(0.1, -0.2, 0.3);
  const double l = 1.1, h = 1e-6;
  for (int k = 0; k < 10; ++k) {
    const Quat qa = random_quat(k % 2 == 0), qb = random_quat(k % 2 == 0);
    Quat fa = Quat::Zero(), fb = Quat::Zero(), tmp1, tmp2;
    hinge(qa, qb, l, K, kbar, fa, fb);
    auto E = [&](const Quat& a, const Quat& b) {
      tmp1.setZero();
      tmp2.setZero();
      const auto e = hinge(a, b, l, K, kbar, tmp1, tmp2);
      return e.bend + e.twist;
    };
    for (int c = 0; c < 4; ++c) {
      Quat p = qa, m = qa;
      p[c] += h;
      m[c] -= h;
      EXPECT_NEAR(fa[c], -(E(p, qb) - E(m, qb)) / (2 * h), 1e-6);
      p = qb;
      m = qb;
      p[c] += h;
      m[c] -= h;
      EXPECT_NEAR(fb[c], -(E(qa, p) - E(qa, m)) / (2 * h), 1e-6);
    }
  }
}

TEST(QuaternionRod, CouplingForcesAreMinusTheEnergyGradient) {
  const double C = 3.0, rest = 0.8, h = 1e-6;
  const Vec3 xa(0.1, 0.2, -0.3), xb(0.9, 0.5, 0.2);
  const Quat q = random_quat();
  Quat fq = Quat::Zero(), tq;
  Vec3 fa = Vec3::Zero(), fb = Vec3::Zero(), t1, t2;
  coupling(q, xa, xb, rest, C, fq, fa, fb);
  auto E = [&](const Quat& qq, const Vec3& a, const Vec3& b) {
    tq.setZero();
    t1.setZero();
    t2.setZero();
    return coupling(qq, a, b, rest, C, tq, t1, t2);
  };
  for (int c = 0; c < 4; ++c) {
    Quat p = q, m = q;
    p[c] += h;
    m[c] -= h;
    EXPECT_NEAR(fq[c], -(E(p, xa, xb) - E(m, xa, xb)) / (2 * h), 1e-6);
  }
  for (int c = 0; c < 3; ++c) {
    Vec3 p = xa, m = xa;
    p[c] += h;
    m[c] -= h;
    EXPECT_NEAR(fa[c], -(E(q, p, xb) - E(q, m, xb)) / (2 * h), 1e-6);
    p = xb;
    m = xb;
    p[c] += h;
    m[c] -= h;
    EXPECT_NEAR(fb[c], -(E(q, xa, p) - E(q, xa, m)) / (2 * h), 1e-6);
  }
  // aligned: no energy, no force
  Quat f0 = Quat::Zero();
  Vec3 g0 = Vec3::Zero(), g1 = Vec3::Zero();
  EXPECT_NEAR(coupling(aligned_with((xb - xa).normalized()), xa, xb, rest, C, f0, g0, g1), 0.0,
              1e-24);
  EXPECT_LT(f0.norm() + g0.norm() + g1.norm(), 1e-12);
}

TEST(QuaternionRod, EnergiesAreInvariantUnderRigidRotation) {
  const Quat qa = random_quat(), qb = random_quat(), p = random_quat();
  const Eigen::Matrix3d R = Eigen::Quaterniond(p[0], p[1], p[2], p[3]).toRotationMatrix();
  const Vec3 K(1, 1, 0.7), kbar(0.05, 0.1, -0.02), xa(0, 0, 0), xb(0.3, 0.8, 0.5);
  Quat f1 = Quat::Zero(), f2 = Quat::Zero();
  Vec3 g1 = Vec3::Zero(), g2 = Vec3::Zero();
  const auto e0 = hinge(qa, qb, 1.0, K, kbar, f1, f2);
  const double c0 = coupling(qa, xa, xb, 1.0, 2.0, f1, g1, g2);
  const auto e1 = hinge(mul(p, qa), mul(p, qb), 1.0, K, kbar, f1, f2);
  const double c1 = coupling(mul(p, qa), R * xa, R * xb, 1.0, 2.0, f1, g1, g2);
  EXPECT_NEAR(e0.bend, e1.bend, 1e-12);
  EXPECT_NEAR(e0.twist, e1.twist, 1e-12);
  EXPECT_NEAR(c0, c1, 1e-12);
  // a twist about d3 costs torsion only, a turn about d1 bending only
  const Quat twist = mul(qa, Quat(std::cos(0.1), 0, 0, std::sin(0.1)));
  const Quat bend = mul(qa, Quat(std::cos(0.1), std::sin(0.1), 0, 0));
  const auto t = hinge(qa, twist, 1.0, K, Vec3::Zero(), f1, f2);
  const auto b = hinge(qa, bend, 1.0, K, Vec3::Zero(), f1, f2);
  EXPECT_NEAR(t.bend, 0.0, 1e-14);
  EXPECT_GT(t.twist, 0.0);
  EXPECT_NEAR(b.twist, 0.0, 1e-14);
  EXPECT_GT(b.bend, 0.0);
}
