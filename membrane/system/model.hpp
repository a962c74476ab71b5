#pragma once
/// @file model.hpp
/// @brief A membrane problem fully resolved against its mesh: the body
/// (mesh, sections per region, point masses; model/body.hpp), constrained
/// DOFs, load patterns with time profiles, drag, springs, rigid sets,
/// rigid surfaces in contact, probes and the time-stepping settings. Built
/// from a case file by case_file.hpp, or directly by tests.
///
/// Units SI. Forces are nodal force vectors of length 3 * nodes (N), the
/// DOF numbering of assembly.hpp. The pieces live by floor: the body and the
/// constraints in model/, the loads in loads/; this aggregate sits above
/// both (system/), where the second-order system of the structure and what
/// acts on it (its forces, reactions and works for the integrators) belongs.

#include "core/enum_names.hpp"
#include "membrane/loads/contact.hpp"
#include "membrane/loads/ground_springs.hpp"
#include "membrane/loads/load.hpp"
#include "membrane/loads/surface_load.hpp"
#include "membrane/model/body.hpp"
#include "membrane/model/constraint.hpp"

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

namespace lamina::membrane {

/// A named probe: the node nearest to a point.
struct Probe {
  std::string name; ///< column prefix in probes.csv
  int node = -1;    ///< node index
};

/// The membrane model of a case (key `model`).
enum class ModelKind {
  Linear,         ///< the membrane paper's small-displacement model (default)
  LargeDeflection ///< total-Lagrangian fabric membrane in 3D
};
/// The case-file names of ModelKind (key `model`, and the summary's "model").
inline constexpr auto kModelKindNames = core::enumNames<ModelKind>(
    {{"linear", ModelKind::Linear}, {"large_deflection", ModelKind::LargeDeflection}});

/// @return the geometry the surface loads (pressures, drag) of a model of
/// kind @p kind act on: the linear model's flat reference membrane, the
/// large-deflection model's current surface.
inline Geometry surfaceGeometry(ModelKind kind) {
  return kind == ModelKind::LargeDeflection ? Geometry::Current : Geometry::Reference;
}

/// The time integrator of a case (key `time.integrator`).
enum class IntegratorKind {
  Newmark, ///< the paper's Newmark / HHT-alpha (linear model only; its default)
  Explicit ///< central differences, lumped mass (the large-deflection model's default)
};
/// The case-file names of IntegratorKind (key `time.integrator`).
inline constexpr auto kIntegratorKindNames = core::enumNames<IntegratorKind>(
    {{"newmark", IntegratorKind::Newmark}, {"explicit", IntegratorKind::Explicit}});

/// The linear solver of a Newmark step (key `solver.type`).
enum class LinearSolverKind {
  Cg,      ///< block-Jacobi preconditioned CG, warm started ("cg", the default)
  Cholesky ///< sparse Cholesky factorization once, then triangular solves ("cholesky")
};

/// The case-file names of LinearSolverKind (key `solver.type`, and the summary's).
inline constexpr auto kLinearSolverKindNames = core::enumNames<LinearSolverKind>(
    {{"cg", LinearSolverKind::Cg}, {"cholesky", LinearSolverKind::Cholesky}});

/// DOFs that move together (a rigid translating frame): one acceleration,
/// total force over total mass (both schemes; Newmark condenses them,
/// integrators/rigid_condensation.hpp).
struct RigidSet {
  std::string name;      ///< for messages
  std::vector<int> dofs; ///< the DOFs tied together (one component each set)
};

/// Time integration and solver settings.
struct TimeSettings {
  IntegratorKind integrator = IntegratorKind::Newmark; ///< the scheme
  double safety = 0.9;  ///< explicit: dt = safety * stable step (when dt = 0)
  double damping = 0;   ///< explicit: mass-proportional damping c (1/s), F = -c M v
  double dt = 0;        ///< tau, s (explicit: 0 = safety * stable step)
  double t_end = 0;     ///< s
  double beta1 = 0.5;   ///< Newmark beta1 (eq. 30; gamma in other texts)
  double beta2 = 0.5;   ///< Newmark beta2 (eq. 30; 2 beta in other texts)
  double hht_alpha = 0; ///< HHT-alpha in [-1/3, 0]; 0 = the paper's scheme
  bool lumped = false;  ///< lumped (row-sum) instead of consistent mass
  LinearSolverKind solver = LinearSolverKind::Cg; ///< Newmark's linear solver
  double tolerance = 1e-10;  ///< relative residual of the CG solve (1e-10: answers equal the
                             ///< factorized solve to ~4e-11, bench/membrane)
  int max_iterations = 2000; ///< CG iteration limit per solve
  int projection = 0;        ///< CG start from the A-projection on this many past solutions
                             ///< (0 = off: linear extrapolation; measured no gain, bench/membrane)
  int drag_iterations = 20;  ///< fixed-point iterations on the drag per step
  double drag_tolerance = 1e-12; ///< relative change of a ending them
};

/// Output settings.
struct OutputSettings {
  int field_every = 10;      ///< write fields every this many steps (0 = first and last only)
  int energy_every = 1;      ///< compute kinetic/strain energy every this many steps
  bool fields = true;        ///< write the XDMF/HDF5 series at all
  long checkpoint_every = 0; ///< write checkpoint.h5 every this many steps (0: only on interrupt)
};

/// Everything a run needs: the body (mesh, sections, point masses) and
/// what acts on it. The structures (model/) see only the Body part.
struct Model : Body {
  std::string name;                    ///< case name (file stem)
  std::vector<Constraint> constraints; ///< fixed and moving DOF sets
  std::vector<Load> loads;             ///< external loads (incl. gravity)
  ModelKind kind = ModelKind::Linear;  ///< which membrane model
  std::vector<std::shared_ptr<const SurfaceLoad>>
      surface_loads; ///< configuration-dependent loads (pressures, drag)
  std::vector<std::shared_ptr<const GroundSprings>> springs; ///< springs to the ground
  std::vector<RigidSet> rigid;                               ///< rigid translating sets
  std::vector<ContactSurface> contact;                       ///< rigid surfaces in contact
  std::vector<Probe> probes;                                 ///< probes
  TimeSettings time;                                         ///< time stepping
  OutputSettings output;                                     ///< outputs
  Eigen::VectorXd u0, v0;            ///< initial displacement and velocity (empty = zero)
  bool compare_without_drag = false; ///< run also without the drag and compare peaks
};

} // namespace lamina::membrane
