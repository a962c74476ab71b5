#include "membrane/loads/contact.hpp"

#include "membrane/model/stable_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lamina::membrane {

namespace {

/// The regularized Coulomb force at a node of lumped mass @p m pressed with
/// @p fn (N) whose velocity relative to the surface is @p vr, normal @p n,
/// in a step @p dt (contact.hpp).
Eigen::Vector3d frictionForce(const ContactSurface& s, double fn, const Eigen::Vector3d& vr,
                              const Eigen::Vector3d& n, double m, double dt) {
  const Eigen::Vector3d vt = vr - vr.dot(n) * n;
  const double slip = vt.norm();
  if (!(slip > 0))
    return Eigen::Vector3d::Zero();
  const double coulomb = s.friction * fn * std::min(slip / s.slip_velocity, 1.0);
  return (-std::min(coulomb, m * slip / dt) / slip) * vt;
}

/// Adds surface @p k's forces to @p out.
void addSurface(const ContactSurface& s, int k, const Mesh& mesh, const ContactInput& in,
                ContactResult& out) {
  const Eigen::Vector3d d = in.su.segment<3>(3 * k), vs = in.sv.segment<3>(3 * k);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double deepest = 0;
  int at = -1;
  for (int i : s.nodes) {
    const Eigen::Vector3d x = mesh.point(i) + in.u.segment<3>(3 * i) - d;
    const Proximity p = s.geometry.proximity(x);
    if (!(p.gap < 0))
      continue;
    const double m = in.mass.size()
                         ? std::min({in.mass[3 * i], in.mass[3 * i + 1], in.mass[3 * i + 2]})
                         : std::numeric_limits<double>::infinity();
    const Eigen::Vector3d vr = in.v.segment<3>(3 * i) - vs;
    double fn = s.penalty * -p.gap;
    if (s.damping > 0 && std::isfinite(m)) // never pulling
      fn = std::max(fn - 2 * s.damping * std::sqrt(s.penalty * m) * vr.dot(p.normal), 0.0);
    Eigen::Vector3d f = fn * p.normal;
    if (s.friction > 0)
      f += frictionForce(s, fn, vr, p.normal, m, in.dt);
    out.force.segment<3>(3 * i) += f;
    sum += f;
    if (-p.gap > deepest) {
      deepest = -p.gap;
      at = i;
    }
  }
  out.sum.segment<3>(3 * k) = sum;
  out.depth[2 * k] = deepest;
  out.depth[2 * k + 1] = at;
}

} // namespace

void contactForces(const std::vector<ContactSurface>& surfaces, const Mesh& mesh,
                   const ContactInput& in, ContactResult& out) {
  const auto ns = static_cast<Eigen::Index>(surfaces.size());
  out.force.setZero(3 * mesh.numNodes());
  out.sum.setZero(3 * ns);
  out.depth.setZero(2 * ns);
  for (Eigen::Index k = 0; k < ns; ++k)
    addSurface(surfaces[static_cast<size_t>(k)], static_cast<int>(k), mesh, in, out);
}

SurfaceMotion initialMotion(const std::vector<ContactSurface>& surfaces) {
  const auto ns = static_cast<Eigen::Index>(surfaces.size());
  SurfaceMotion m;
  m.u = Eigen::VectorXd::Zero(3 * ns);
  m.v = Eigen::VectorXd::Zero(3 * ns);
  m.a = Eigen::VectorXd::Zero(3 * ns);
  for (Eigen::Index k = 0; k < ns; ++k)
    m.v.segment<3>(3 * k) = surfaces[static_cast<size_t>(k)].velocity;
  return m;
}

void setAccelerations(const std::vector<ContactSurface>& surfaces, const Eigen::VectorXd& sum,
                      Eigen::VectorXd& a) {
  a.setZero(3 * static_cast<Eigen::Index>(surfaces.size()));
  for (size_t k = 0; k < surfaces.size(); ++k) {
    const ContactSurface& s = surfaces[k];
    const auto at = static_cast<Eigen::Index>(3 * k);
    if (s.free()) // the membrane pushes the body back: -sum
      a.segment<3>(at) = -sum.segment<3>(at) / s.mass + s.gravity;
  }
}

void predictMotion(const std::vector<ContactSurface>& surfaces, const SurfaceMotion& m, double t1,
                   double dt, Eigen::VectorXd& u1, Eigen::VectorXd& vh) {
  const auto ns = static_cast<Eigen::Index>(surfaces.size());
  u1.resize(3 * ns);
  vh.resize(3 * ns);
  for (Eigen::Index k = 0; k < ns; ++k) {
    const ContactSurface& s = surfaces[static_cast<size_t>(k)];
    if (s.free()) {
      vh.segment<3>(3 * k) = m.v.segment<3>(3 * k) + 0.5 * dt * m.a.segment<3>(3 * k);
      u1.segment<3>(3 * k) = m.u.segment<3>(3 * k) + dt * vh.segment<3>(3 * k);
    } else { // exactly v t: no round-off accumulates over the steps
      vh.segment<3>(3 * k) = s.velocity;
      u1.segment<3>(3 * k) = t1 * s.velocity;
    }
  }
}

double penaltyOmega2(const std::vector<ContactSurface>& surfaces, const Eigen::VectorXd& mass) {
  Eigen::VectorXd node_w2 = Eigen::VectorXd::Zero(mass.size() / 3);
  double body_w2 = 0;
  for (const ContactSurface& s : surfaces) {
    // A free body's spring couples two masses: each row sums two terms.
    const double damped = std::sqrt(1 + s.damping * s.damping) - s.damping;
    const double coupling = (s.free() ? 2.0 : 1.0) / (damped * damped);
    for (int i : s.nodes) {
      const double m = std::min({mass[3 * i], mass[3 * i + 1], mass[3 * i + 2]});
      node_w2[i] += coupling * s.penalty / m;
    }
    if (s.free())
      body_w2 =
          std::max(body_w2, coupling * static_cast<double>(s.nodes.size()) * s.penalty / s.mass);
  }
  return std::max(node_w2.size() ? node_w2.maxCoeff() : 0.0, body_w2);
}

double defaultPenetrationTolerance(const RigidSurface& geometry, const Mesh& mesh) {
  double shortest = std::numeric_limits<double>::infinity();
  for (int e = 0; e < mesh.numElements(); ++e)
    shortest = std::min(shortest, elementLength(mesh, e));
  return std::min(kToleranceOfElement * shortest, kToleranceOfThickness * geometry.thickness());
}

} // namespace lamina::membrane
