#pragma once
/// @file law.hpp
/// @brief The seam for constitutive laws: one vocabulary of law names and one
/// interface for a law with internal state at a material point.
///
/// A law maps, over one time step, the state at t_n and the strain at t_n and
/// t_{n+1} to the stress at t_{n+1}, the new state and the consistent
/// (algorithmic) tangent d sigma_{n+1} / d eps_{n+1}. Strains and stresses
/// are in lamina order (engineering shear strain, Pa) and in the law's
/// rotation-free frame: for small strain this is the global frame; for
/// finite deformation the caller rotates with R of F = R U (Green-Naghdi,
/// polyurea chapter eq. 5; see kinematics.hpp). The state is a flat array
/// of stateSize() doubles owned by the caller (one block per voxel in the
/// FFT solver), so a law object is immutable and shared by all its points.
///
/// A linear law (isLinear()) has no state and sigma = C eps: solvers keep
/// their fast paths for it (per-phase C, no per-point update).

#include "core/enum_names.hpp"
#include "materials/stiffness.hpp"

#include <memory>
#include <optional>
#include <string>

namespace lamina::materials {

/// The law names of the catalog, cell files and case files (one spelling).
enum class LawKind {
  Isotropic,             ///< "isotropic": E, nu
  TransverselyIsotropic, ///< "transversely-isotropic": E1, E2, G12, nu12, nu23 (axis x)
  Anisotropic,           ///< "anisotropic": C, 6x6, lamina order, Pa
  Gvbo,                  ///< "gvbo": the polyurea chapter's rate-dependent law
  /// "fabric": warp and fill yarns without compression and an in-plane shear
  /// modulus (fabric_law.hpp): E_warp or warp_curve, E_fill or fill_curve, G12
  Fabric,
  /// "reduced-order": a reduced-order cell (reduced_order_law.hpp). Not a law
  /// with keys: it is a library entry made by `homogenize --reduced-order`
  /// and referred to by its name; readLawSpec refuses it.
  ReducedOrder,
  /// "void": a pore of a cell (zero stiffness and density, no keys). Only a
  /// cell's [[phases]] may give it (readLawSpec with VoidLaw::Allowed), and
  /// only the linear homogenization takes it (docs/homogenize-solver.md,
  /// "Pores").
  Void,
};

/// The file spellings of LawKind (parse, print, list).
inline constexpr auto kLawKindNames =
    core::enumNames<LawKind>({{"isotropic", LawKind::Isotropic},
                              {"transversely-isotropic", LawKind::TransverselyIsotropic},
                              {"anisotropic", LawKind::Anisotropic},
                              {"gvbo", LawKind::Gvbo},
                              {"fabric", LawKind::Fabric},
                              {"reduced-order", LawKind::ReducedOrder},
                              {"void", LawKind::Void}});

/// @return the file spelling of @p k ("isotropic", ...)
const char* toString(LawKind k);
/// @return the laws a file may give with keys, for messages:
/// "'isotropic', 'transversely-isotropic', 'anisotropic', 'gvbo' or 'fabric'" (not
/// "reduced-order", which is referred to by an entry's name, nor "void", a
/// cell's pore without keys)
std::string lawKindNames();

/// Stress or strain vector in lamina order.
using Vector6 = Eigen::Matrix<double, 6, 1>;

/// What one step at a material point is given.
struct PointStep {
  Vector6 eps_n = Vector6::Zero(); ///< total strain at t_n (rotation-free frame)
  Vector6 eps = Vector6::Zero();   ///< total strain at t_{n+1}
  double J_n = 1;                  ///< volume ratio det F at t_n
  double J = 1;                    ///< volume ratio det F at t_{n+1}
  double dt = 0;                   ///< t_{n+1} - t_n (s), >= 0
};

struct PlaneStressStep;
struct PlaneStressResult;

/// A constitutive law with internal state (immutable; state lives outside).
class ConstitutiveLaw {
public:
  virtual ~ConstitutiveLaw() = default;
  /// @return which law this is
  virtual LawKind kind() const = 0;
  /// @return true when sigma = C eps with no state and no rate dependence
  virtual bool isLinear() const = 0;
  /// @return true when the law stores all the work of its stress: the
  /// Kirchhoff stress J sigma is the gradient of a stored energy of the
  /// strain, J storedEnergy() per reference volume, so no strain path
  /// dissipates (the fabric law). Callers then book no inelastic strain and
  /// no dissipation. Default: false.
  virtual bool isHyperelastic() const { return false; }
  /// @return doubles of internal state per point (0 for linear laws)
  virtual int stateSize() const = 0;
  /// Writes the initial (unstressed, virgin) state into @p state.
  virtual void initState(double* state) const = 0;
  /// Instantaneous elastic stiffness at volume ratio @p J (lamina order, Pa);
  /// the infinite-rate tangent. Linear laws ignore J.
  virtual Stiffness elasticStiffness(double J = 1.0) const = 0;
  /// One step: reads @p state_n, writes @p state (may alias state_n),
  /// @p sigma at t_{n+1} and, if not null, the consistent tangent
  /// d sigma / d eps at t_{n+1} (lamina order, engineering shear, Pa).
  virtual void update(const PointStep& step, const double* state_n, double* state, Vector6& sigma,
                      Matrix6* tangent) const = 0;
  /// Energy stored per unit volume of the law's frame at a state whose
  /// stress is @p sigma (J/m^3): the work the law would return on elastic
  /// unloading. Default: sigma . C(J)^-1 sigma / 2 with C =
  /// elasticStiffness(J) (C maps engineering strain to stress, so C^-1 sigma
  /// is an engineering strain and the dot product with the tensor components
  /// of sigma is the full contraction). Used by callers to split the work of
  /// the stress into stored energy and inelastic dissipation. @p state is
  /// the law's state at that stress (stateSize() doubles; may be null for a
  /// law without state), @p J its volume ratio.
  virtual double storedEnergy(const Vector6& sigma, const double* state, double J) const;
  /// @return C(J)^-1 @p sigma, the engineering strain the instantaneous
  /// stiffness gives to the stress @p sigma at volume ratio @p J (the elastic
  /// part of a strain increment: d eps - elasticStrain(d sigma) is inelastic).
  /// Default: an LDL^T solve with elasticStiffness(J); a law with a closed
  /// form (isotropic GVBO) overrides it.
  virtual Vector6 elasticStrain(const Vector6& sigma, double J) const;
  /// The law's own membrane plane-stress step without tangent, where it has
  /// one for @p step (plane_stress.hpp states the step and the tolerance;
  /// the isotropic GVBO law solves its two scalar unknowns at once): fills
  /// @p out, writes @p state (may alias @p state_n) and returns true, or
  /// returns false without writing anything, and planeStressUpdate() runs
  /// its Newton on the law's update. Default: false.
  virtual bool planeStressStep(const PlaneStressStep& step, const double* state_n, double* state,
                               double tolerance, PlaneStressResult& out) const;
};

/// Shared handle to an immutable law.
using LawPtr = std::shared_ptr<const ConstitutiveLaw>;

/// Linear elasticity (isotropic, transversely isotropic or anisotropic):
/// sigma = C eps, no state.
class LinearElasticLaw final : public ConstitutiveLaw {
public:
  /// @param kind which linear law produced @p C (not Gvbo, not ReducedOrder);
  /// @param C stiffness
  LinearElasticLaw(LawKind kind, const Stiffness& C);
  LawKind kind() const override { return kind_; }
  bool isLinear() const override { return true; }
  int stateSize() const override { return 0; }
  void initState(double*) const override {}
  Stiffness elasticStiffness(double = 1.0) const override { return C_; }
  void update(const PointStep& step, const double* state_n, double* state, Vector6& sigma,
              Matrix6* tangent) const override;

private:
  LawKind kind_;
  Stiffness C_;
};

} // namespace lamina::materials
