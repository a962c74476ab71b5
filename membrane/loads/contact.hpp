#pragma once
/// @file contact.hpp
/// @brief One-sided penalty contact between the membrane's nodes and rigid
/// surfaces (rigid_surface.hpp), with optional regularized Coulomb friction,
/// and the motion of the surfaces (prescribed, or a free rigid body).
///
/// Normal force: a node i of a surface's node set whose current position
/// x_i = X_i + u_i lies inside the solid, gap g < 0 against the surface
/// displaced by its motion d (g = proximity(x_i - d)), receives
///   f_n = k (-g) n
/// along the outward normal n of the nearest face, k the surface's
/// `penalty` (N/m per node, the same at every node). Without friction and
/// on a fixed surface this is the gradient of the penalty energy k g^2 / 2:
/// conservative, the contact work returns what the penetration stored.
///
/// Normal damping (`contact_damping` zeta in [0, 1), default 0): while in
/// contact, f_n = max(k (-g) - c v_r.n, 0) n with c = 2 zeta sqrt(k m_i), a
/// fraction zeta of the critical damping of the node's penalty spring (m_i
/// its lumped mass), never pulling. Explicit penalty contact resolves an
/// impact in few steps when the penalty frequency sqrt(k / m_i) nears the
/// step's limit, and the discrete impacts can then gain energy: a node may
/// bounce on the surface at rest ("chatter"); zeta ~ 0.1 to 0.2 (LS-DYNA's
/// VDC) damps it, or a smaller penalty or step. zeta > 0 dissipates: the
/// contact work is then not returned.
///
/// Friction (`friction` mu > 0): with the node's velocity relative to the
/// surface v_r = v_i - v_s and its tangential part v_t = v_r - (v_r.n) n,
///   f_t = -min(mu |f_n| min(|v_t| / v_e, 1), m_i |v_t| / dt) v_t / |v_t|,
/// Coulomb's law regularized by the slip velocity v_e (`slip_velocity`):
/// viscous below v_e, the Coulomb force mu |f_n| against the slip above it,
/// and never more than the force m_i |v_t| / dt that stops the node's slip
/// within one step dt (m_i its lumped mass): the viscous branch mu f_n / v_e
/// may be far stiffer than an explicit step can take, and a friction force
/// cannot reverse a slip. It holds no state (no stick anchors), so a
/// checkpoint needs none; a node at rest under a tangential load below
/// mu |f_n| creeps at a speed below v_e.
///
/// Motion: a surface with no `mass` moves with its constant `velocity` v
/// (displacement d = v t). A free body (`mass` M > 0, spheres) starts with
/// `velocity` and moves under the reaction of its contact forces on the
/// membrane and the case's gravity: M a = -sum_i f_i + M g, stepped by the
/// integrator with the membrane (central differences).

#include "membrane/loads/rigid_surface.hpp"
#include "membrane/model/mesh.hpp"

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace lamina::membrane {

/// A rigid surface with its contact settings and the nodes it touches.
struct ContactSurface {
  std::string name;      ///< for reactions.csv, the summary and messages
  RigidSurface geometry; ///< shape and initial position
  /// Prescribed velocity; for a free body its initial velocity (m/s)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  double mass = 0; ///< kg; > 0: a free rigid body moved by its contact forces
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero(); ///< acceleration on a free body (m/s^2)
  double penalty = 0;                                ///< normal stiffness k per node (N/m)
  double damping = 0;       ///< normal damping, fraction of critical (contact_damping)
  double friction = 0;      ///< Coulomb coefficient mu (>= 0)
  double slip_velocity = 0; ///< friction's regularization v_e (m/s)
  double tolerance = 0;     ///< the largest penetration the run accepts (m)
  std::vector<int> nodes;   ///< the membrane nodes that take part

  /// @return whether the surface is a free body (else its motion is prescribed)
  bool free() const { return mass > 0; }
};

/// The motion of the rigid surfaces: per surface its displacement from the
/// initial position, velocity and acceleration, 3 each (surface k at 3 k).
struct SurfaceMotion {
  Eigen::VectorXd u; ///< displacements (m)
  Eigen::VectorXd v; ///< velocities (m/s)
  Eigen::VectorXd a; ///< accelerations (m/s^2)
};

/// What one evaluation of the contact forces gives per surface.
struct ContactResult {
  Eigen::VectorXd force; ///< nodal contact forces on the membrane, all surfaces (N, 3 per node)
  /// Per surface: the total force on the membrane (N, 3 at 3 k)
  Eigen::VectorXd sum;
  /// Per surface: the deepest penetration (m, >= 0) and its node (-1: none), at 2 k, 2 k + 1
  Eigen::VectorXd depth;
};

/// The deepest penetration of one surface over a run.
struct PenetrationPeak {
  double depth = 0; ///< m (0: never in contact)
  double time = 0;  ///< s, when first reached
  int node = -1;    ///< node index (-1: none)
};

/// The membrane's state and step a contact evaluation reads.
struct ContactInput {
  const Eigen::VectorXd& u;    ///< membrane displacements (m, 3 per node)
  const Eigen::VectorXd& v;    ///< membrane velocities (m/s)
  const Eigen::VectorXd& su;   ///< surfaces' displacements (m, 3 per surface)
  const Eigen::VectorXd& sv;   ///< surfaces' velocities (m/s)
  const Eigen::VectorXd& mass; ///< lumped nodal mass per DOF (kg; read only with friction)
  double dt;                   ///< the time step (s; read only with friction)
};

/// Evaluates the contact forces of @p surfaces on @p mesh at @p in into
/// @p out (sized here).
void contactForces(const std::vector<ContactSurface>& surfaces, const Mesh& mesh,
                   const ContactInput& in, ContactResult& out);

/// The surfaces' state at t = 0: zero displacement, the (initial) velocity,
/// zero acceleration (setAccelerations() completes it once forces are known).
SurfaceMotion initialMotion(const std::vector<ContactSurface>& surfaces);

/// Sets the free bodies' accelerations in @p a from their contact forces
/// @p sum (ContactResult::sum: the force on the membrane, whose reaction
/// acts on the body) and gravity; prescribed surfaces have a = 0.
void setAccelerations(const std::vector<ContactSurface>& surfaces, const Eigen::VectorXd& sum,
                      Eigen::VectorXd& a);

/// The first half of a central-difference step of the surfaces from @p m
/// at t_n to @p t1 = t_n + @p dt: mid-step velocities @p vh and
/// displacements @p u1 at t1 (prescribed: exactly v t1 and v).
void predictMotion(const std::vector<ContactSurface>& surfaces, const SurfaceMotion& m, double t1,
                   double dt, Eigen::VectorXd& u1, Eigen::VectorXd& vh);

/// @return the largest omega^2 (1/s^2) the penalty springs add to the lumped
/// system of nodal masses @p mass (per DOF, 3 per node), by Gershgorin's
/// bound: k / m_i summed over the surfaces of node i for fixed or prescribed
/// surfaces; 2 k / m_i and, on the body's row, 2 N k / M (N its nodes) for a
/// free body of mass M; 0 without surfaces. A surface with normal damping
/// zeta counts k / (sqrt(1 + zeta^2) - zeta)^2 (the explicit step of a
/// damped oscillator, 2 / omega (sqrt(1 + zeta^2) - zeta)).
double penaltyOmega2(const std::vector<ContactSurface>& surfaces, const Eigen::VectorXd& mass);

/// @return the default `penetration_tolerance` of @p geometry on @p mesh (m):
/// min(kToleranceOfElement x the shortest element length, kToleranceOfThickness
/// x the solid's thickness)
double defaultPenetrationTolerance(const RigidSurface& geometry, const Mesh& mesh);

/// The default tolerance's fraction of the shortest element length (2 A / longest edge).
inline constexpr double kToleranceOfElement = 0.1;
/// The default tolerance's fraction of the solid's thickness (RigidSurface::thickness()).
inline constexpr double kToleranceOfThickness = 0.25;
/// The default slip velocity v_e of the regularized friction (m/s).
inline constexpr double kSlipVelocity = 1e-3;

} // namespace lamina::membrane
