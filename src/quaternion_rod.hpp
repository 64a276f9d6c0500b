// Kinematics and energies of the quaternion Cosserat rod (docs/models.md §4): one unit
// quaternion per edge gives the material frame {d1, d2, d3}; the discrete Darboux
// vector at a vertex from the two neighbouring quaternions; bending/torsion energy
// against a rest Darboux vector; the penalty that ties d3 to the edge tangent.
// Quaternions are scalar-first, q = (q0, q1, q2, q3), and need not be unit length
// here: the formulas are the functions of q that docs/models.md §4 defines, and their
// gradients are exact for any q (the style keeps |q| = 1).
#pragma once

#include <Eigen/Geometry>

#include "nodes.hpp"

namespace slender::qrod {

using Quat = Eigen::Vector4d;  // (q0, q1, q2, q3)

// B_j q for the skew matrices B_1..B_3 of docs/models.md §4.2 (scalar-first ordering),
// so that k_j = 2 (B_j q) . q' for a unit quaternion field.
inline Quat B(int j, const Quat& q) {
  switch (j) {
    case 0:  // B_1
      return Quat(-q[1], q[0], q[3], -q[2]);
    case 1:  // B_2
      return Quat(-q[2], -q[3], q[0], q[1]);
    default:  // B_3
      return Quat(-q[3], q[2], -q[1], q[0]);
  }
}

// Directors, the columns of the rotation matrix of q (4.21)-(4.23).
inline Vec3 d1(const Quat& q) {
  return Vec3(q[0] * q[0] + q[1] * q[1] - q[2] * q[2] - q[3] * q[3],
              2 * (q[1] * q[2] + q[0] * q[3]), 2 * (q[1] * q[3] - q[0] * q[2]));
}
inline Vec3 d2(const Quat& q) {
  return Vec3(2 * (q[1] * q[2] - q[0] * q[3]),
              q[0] * q[0] - q[1] * q[1] + q[2] * q[2] - q[3] * q[3],
              2 * (q[2] * q[3] + q[0] * q[1]));
}
inline Vec3 d3(const Quat& q) {
  return Vec3(2 * (q[1] * q[3] + q[0] * q[2]), 2 * (q[2] * q[3] - q[0] * q[1]),
              q[0] * q[0] - q[1] * q[1] - q[2] * q[2] + q[3] * q[3]);
}
// J3 = d d3 / d q (3 x 4), docs/models.md §4.4
inline Eigen::Matrix<double, 3, 4> J3(const Quat& q) {
  Eigen::Matrix<double, 3, 4> J;
  J << q[2], q[3], q[0], q[1], -q[1], -q[0], q[3], q[2], q[0], -q[1], -q[2], q[3];
  return 2.0 * J;
}

// Quaternion product p o q (4.17).
inline Quat mul(const Quat& p, const Quat& q) {
  const Vec3 pv = p.tail<3>(), qv = q.tail<3>();
  Quat r;
  r[0] = p[0] * q[0] - pv.dot(qv);
  r.tail<3>() = p[0] * qv + q[0] * pv + pv.cross(qv);
  return r;
}

// Bending and torsion at the vertex between edges with quaternions qa (before)
// and qb (after), vertex length l = (|e_a rest| + |e_b rest|) / 2 (§4.3):
// kappa_j = (2 / l) (B_j qa) . qb, E = l/2 sum_j K_j (kappa_j - kbar_j)^2 with
// K = (YI, YI, GJ). Adds the generalised forces -dE/dqa, -dE/dqb (§4.4) and
// returns the bending (j = 1, 2) and torsion (j = 3) parts of the energy.
struct HingeEnergy {
  double bend = 0.0, twist = 0.0;
  Vec3 kappa = Vec3::Zero();
};
inline HingeEnergy hinge(const Quat& qa, const Quat& qb, double l, const Vec3& K, const Vec3& kbar,
                         Quat& fa, Quat& fb) {
  HingeEnergy h;
  for (int j = 0; j < 3; ++j) {
    const Quat Ba = B(j, qa), Bb = B(j, qb);
    const double kj = 2.0 / l * Ba.dot(qb);
    h.kappa[j] = kj;
    const double v = kj - kbar[j];
    const double e = 0.5 * l * K[j] * v * v;
    (j < 2 ? h.bend : h.twist) += e;
    // dkappa/dqa = (2/l) B^T qb = -(2/l) B qb; dkappa/dqb = (2/l) B qa
    fa += 2.0 * K[j] * v * Bb;
    fb -= 2.0 * K[j] * v * Ba;
  }
  return h;
}

// Coupling of d3(q) to the unit tangent of the edge from xa to xb (4.42)-(4.45):
// E = C/2 |e_rest| |t - d3|^2. Adds -dE/dq, -dE/dxa, -dE/dxb; returns E.
inline double coupling(const Quat& q, const Vec3& xa, const Vec3& xb, double rest, double C,
                       Quat& fq, Vec3& fxa, Vec3& fxb) {
  const Vec3 e = xb - xa;
  const double len = e.norm();
  const Vec3 t = e / len;
  const Vec3 d = d3(q);
  const Vec3 diff = t - d;
  const double w = C * rest;
  fq += w * (J3(q).transpose() * diff);
  const Vec3 fx = (w / len) * (d - t * t.dot(d));  // (1 - t t^T) d3
  fxb += fx;
  fxa -= fx;
  return 0.5 * w * diff.squaredNorm();
}

// The 4 x 3 map phi -> (0, phi) o q: a small rotation phi (a world-frame vector) applied
// after q changes it by L(q) phi / 2. For |q| = 1 its columns are orthonormal and
// orthogonal to q.
inline Eigen::Matrix<double, 4, 3> rotation_map(const Quat& q) {
  Eigen::Matrix<double, 4, 3> L;
  const Vec3 v = q.tail<3>();
  L.row(0) = -v.transpose();
  L.bottomRows<3>() << q[0], v[2], -v[1],  //
      -v[2], q[0], v[0],                   //
      v[1], -v[0], q[0];                   // q0 I - [v]x
  return L;
}

// The world-frame torque of a generalised force F on a unit quaternion: the work of F
// on the change L(q) phi / 2 is torque . phi.
inline Vec3 torque(const Quat& q, const Quat& F) {
  return 0.5 * rotation_map(q).transpose() * F;
}

// q turned by the smallest rotation that carries d3(q) onto the unit vector t: the
// frame carried along when its tangent moves (docs/models.md §4.6).
inline Quat carried_onto(const Quat& q, const Vec3& t) {
  const Vec3 d = d3(q);
  const double c = d.dot(t);
  if (c < -1.0 + 1e-6) {
    // d3 almost opposite to t: the axis of the smallest rotation is ill-defined
    const Eigen::Quaterniond r = Eigen::Quaterniond::FromTwoVectors(d, t);
    return mul(Quat(r.w(), r.x(), r.y(), r.z()), q).normalized();
  }
  // (1 + cos θ, d × t) = 2 cos(θ/2) (cos(θ/2), sin(θ/2) n): the rotation by θ about n
  // from d onto t, up to a positive factor that the final normalisation removes (one
  // root instead of the four of FromTwoVectors; this runs for every edge and evaluation)
  Quat r;
  r[0] = 1.0 + c;
  r.tail<3>() = d.cross(t);
  return mul(r, q).normalized();
}

// The unit quaternion whose d3 is the unit vector t, turning the z axis onto t by
// the shortest rotation (d1, d2 follow from it).
inline Quat aligned_with(const Vec3& t) {
  const Eigen::Quaterniond r = Eigen::Quaterniond::FromTwoVectors(Vec3(0, 0, 1), t);
  return Quat(r.w(), r.x(), r.y(), r.z());
}

}  // namespace slender::qrod
