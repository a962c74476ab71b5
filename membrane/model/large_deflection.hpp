#pragma once
/// @file large_deflection.hpp
/// @brief The geometrically exact fabric membrane: total-Lagrangian CST
/// triangles anywhere in 3D (fabric_element.hpp), plane-stress stiffness per
/// region, pre-stress, tension-only wrinkling (relaxed_wrinkling.hpp, or the
/// projection of fabric_element.hpp), failure thresholds, lumped
/// mass (rho h A / 3 per node plus point masses). The internal force is
/// computed element by element (no global stiffness), eight elements at a
/// time where they share a section (fabric_lanes.hpp, law_lanes.hpp), in
/// one parallel region with static shares: a thread adds each corner force
/// to its node when its share holds the node's first element, and keeps the
/// others for after the team's barrier (CornerPlan), so that a node's sum is
/// taken in element order from zero, the same at any thread count (no
/// atomics, no buffer per corner).
///
/// A section with a linear law has S = C_ps E + S0 (Saint Venant-Kirchhoff,
/// the fast path), relaxed where it is not taut when the section is
/// tension-only with the relaxed law. A section with a nonlinear law (GVBO, a reduced-order
/// cell) keeps a history block per element (law_point.hpp: the law's state,
/// its strain, the thickness stretch, the stored and dissipated energy),
/// owned here: committed and trial copies, the trial one written by
/// internalForce() and accepted by commitStep() (structure.hpp).

#include "core/parallel.hpp"
#include "membrane/model/body.hpp"
#include "membrane/model/fabric_element.hpp"
#include "membrane/model/fabric_lanes.hpp"
#include "membrane/model/structure.hpp"

#include <vector>

namespace lamina::membrane {

/// Large-deflection membrane of one Body.
class LargeDeflection final : public Structure {
public:
  /// Whether linear sections' elements take the lanes (fabric_lanes.hpp;
  /// default) or the one-element loop, for every LargeDeflection of the
  /// process: tests compare the two (not thread-safe against a running force).
  static void useLanes(bool lanes);
  /// Builds the element frames (material axis per region), C_ps per region
  /// and the lumped mass. Keeps a reference to @p body.
  explicit LargeDeflection(const Body& body);
  int numDofs() const override { return 3 * body_.mesh.numNodes(); }
  const SparseMatrix& mass() const override { return M_; }
  void internalForce(const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  /// @return sum of h A0 (E.C_ps E / 2 + S0.E); in a tension-only region the
  /// stored energy h A0 (S.C_ps^-1 S - S0.C_ps^-1 S0) / 2 of fabricStoredEnergy()
  /// (the relaxed energy, the potential of the relaxed law's force; a state
  /// function but not a potential of the projection's force)
  double strainEnergy(const Eigen::VectorXd& u) const override;
  bool hasPotential() const override { return !any_projection_ && !hasHistory(); }
  /// @return whether a section with a linear law wrinkles by the projection
  bool nonConservativeWrinkling() const override { return any_projection_; }
  /// The stable step at rest: a nonlinear law's instantaneous stiffness at J = 1
  double stableStep() const override;
  /// The stable step at displacements @p u and the committed history, per
  /// reference length and mass. A nonlinear region: its instantaneous
  /// stiffness elasticStiffness(J) taken at 9 values of J across the range of
  /// J of its elements (the largest wave modulus over them), times the
  /// region's largest J / lambda_min^2, plus its largest tension
  /// J s1 / lambda_min^2, with the region's shortest element. The elements
  /// of linear sections each with its own speed (linearStableStep()); never
  /// above the rest step
  double currentStableStep(const Eigen::VectorXd& u) const override;
  /// Stretch stiffens every law: the stable step follows the state.
  bool stateDependentStep() const override { return true; }
  bool hasHistory() const override { return !history_offset_.empty(); }
  void beginStep(double t1, double dt) override {
    step_t1_ = t1;
    step_dt_ = dt;
  }
  void commitStep() override { std::swap(history_, trial_); }
  /// Sum over the elements of h0 A0 times their dissipation per reference volume
  double inelasticDissipation() const override;
  /// Entry "structure/law_history": the committed blocks of every element with a
  /// nonlinear law, in element order
  void saveHistory(History& h) const override;
  void restoreHistory(const History& h) override;
  /// "strain" and "stress" ([E11, E22, 2E12], [S11, S22, S12] in the element's
  /// material frame), "principal_strain", "principal_stress" (Cauchy, Pa; major
  /// first), "wrinkled" (0 taut, 1 wrinkled, 2 slack); with a nonlinear law
  /// also "inelastic_strain" (equivalent, accumulated), "inelastic_strain_rate"
  /// (1/s, over the last step) and "thickness_stretch" (h / h0); 0, 0 and 1
  /// in linear sections
  std::vector<CellField> cellFields(const Eigen::VectorXd& u) const override;
  bool deformedGeometry() const override { return true; }
  bool hasFailureThresholds() const override { return any_threshold_; }
  void checkFailure(double t, const Eigen::VectorXd& u, FailureRecord& record) const override;
  double setupSeconds() const override { return setup_s_; }

  /// @return the stress state of element @p e at displacements @p u (with a
  /// nonlinear law: its committed stress, u the displacements of the commit)
  FabricStress stress(int e, const Eigen::VectorXd& u) const;
  /// @return the committed history block of element @p e (law_point.hpp), or
  /// nullptr in a section with a linear law
  const double* history(int e) const {
    return hasHistory() && history_offset_[e] >= 0 ? history_.data() + history_offset_[e] : nullptr;
  }
  /// @return the reference data of element @p e
  const FabricElement& element(int e) const { return elements_[e]; }
  /// @return C_ps of region @p r (Pa)
  const Eigen::Matrix3d& planeStress(int r) const { return cps_[r]; }

private:
  const Body& body_;
  std::vector<FabricElement> elements_;
  std::vector<Eigen::Matrix3d> cps_;     // per region
  std::vector<Eigen::Matrix3d> cps_inv_; // C_ps^-1 per region (1/Pa)
  std::vector<Eigen::Vector3d> s0_;      // pre-stress per region (Pa)
  /// What the internal-force loop reads per element, packed in one line of
  /// memory (72 bytes instead of the 160 of FabricElement plus the section).
  struct Packed {
    int node[3];   ///< node indices
    int region;    ///< region, or -1 - region for a projection or nonlinear one (general path)
    double dN[6];  ///< dN_a in the element frame: x0, y0, x1, y1, x2, y2 (1/m)
    double hA = 0; ///< thickness x reference area (m^3)
  };
  std::vector<Packed> packed_;
  /// The columns @p F0, @p F1 of F = sum_a x_a dN_a^T of the packed
  /// element @p p at the positions @p x (3 per node, positions()).
  void deformation(const Packed& p, const double* x, double (&F0)[3], double (&F1)[3]) const;
  /// @return the positions x = X + u at displacements @p u (3 per node), in x_
  const double* positions(const Eigen::VectorXd& u) const;
  mutable std::vector<double> x_; // positions of the last positions()
  std::vector<double> x0_;        // reference positions, 3 per node (m)
  SparseMatrix M_;
  bool any_projection_ = false, any_threshold_ = false;
  std::vector<char> relaxed_; // per region: a linear law with the relaxed wrinkling law
  /// Per element: offset of its history block in history_, -1 with a linear
  /// law; empty when no section has a nonlinear law.
  std::vector<long> history_offset_;
  std::vector<double> history_;       // committed blocks
  mutable std::vector<double> trial_; // blocks of the last internalForce()
  double step_t1_ = 0, step_dt_ = 0;  // the step of the next internalForce()
  std::vector<double> wave_modulus_;  // per region: the largest wave modulus of C_ps (Pa)
  std::vector<double> rest_speed_;    // per region: restSpeed() (m/s)
  std::vector<double> length_;        // per element: its length 2 A / longest edge (m)
  std::vector<double> min_length_;    // per region: its elements' least length (m)
  /// How a group of kLawLanes consecutive elements is stepped.
  enum class LaneKind : char {
    Elements, ///< one element at a time (mixed sections, the general path, a short last group)
    Linear,   ///< one linear section: linearFabricForces (fabric_lanes.hpp)
    Gvbo      ///< one GVBO section: stepGvboLawPoints (law_lanes.hpp)
  };
  /// A group's kind and section.
  struct LaneGroup {
    LaneKind kind = LaneKind::Elements;
    int region = -1;
  };
  std::vector<LaneGroup> lane_groups_; // per group of kLawLanes elements
  std::vector<FabricLaneGroup>
      lane_elements_;                    // per group: its elements in lanes (read by Linear ones)
  std::vector<LinearLaneLaw> lane_laws_; // per region: its law in lanes (linear ones)
  /// Groups the elements by kLawLanes consecutive ones and gives each group
  /// its kind (after initHistory()).
  void initLanes();
  /// The force of element @p e at positions @p x (displacements @p u) into
  /// @p out (9: node a's x, y, z at 3 a + c); a law's failure into @p errors.
  void elementForce(int e, const double* x, const Eigen::VectorXd& u, double* out,
                    core::ParallelErrors& errors) const;
  /// Adds the forces of group @p g's elements to @p f (its nodes held by
  /// this thread first) or to the plan's deferred_f (planCorners()).
  void groupForces(int g, const double* x, const Eigen::VectorXd& u, double* f,
                   core::ParallelErrors& errors) const;
  /// Where each corner's force goes when a team of @p threads takes the
  /// groups in contiguous shares (core::threadRange), in plan_.
  void planCorners(int threads) const;
  /// The element forces summed at the nodes without a buffer per corner:
  /// the thread whose share holds a node's first element adds that
  /// element's force and those of its later elements in its share directly
  /// to f; a later thread's corner waits in deferred_f and is added after
  /// the team's barrier. Each node's sum is then taken in element order
  /// from zero, as one thread would: the same bits at any team size.
  struct CornerPlan {
    int threads = 0;                 ///< the team size planned for (0: none)
    std::vector<int> corner;         ///< 3 e + a -> its node i, or -1 - its place in deferred_f
    std::vector<int> deferred_node;  ///< the nodes with deferred corners, ascending
    std::vector<int> deferred_start; ///< their places [start, next start) in deferred_f
    std::vector<double> deferred_f;  ///< the deferred corners' forces, 3 per place (N)
  };
  mutable CornerPlan plan_;
  /// The force of a nonlinear element at F (trial history), into @p out (9).
  void lawElementForce(int e, const Eigen::Matrix<double, 3, 2>& F, double* out) const;
  /// The forces of the @p n (<= kLawLanes) elements from @p e0 of a lane
  /// group of GVBO region @p r at positions @p x, stepped together
  /// (stepGvboLawPoints; the lanes it hands back by lawElementForce).
  void lawLaneForces(int e0, int n, int r, const double* x, double (*out)[9]) const;
  /// @return the fastest wave speed of region @p r at rest, its pre-tension
  /// included (m/s; from wave_modulus_, kept in rest_speed_)
  double restSpeed(size_t r) const;
  /// The stress S = C_ps E + S0 (Pa) of an element of linear region @p r
  /// whose F has columns @p F0, @p F1 (E the Green-Lagrange strain), relaxed
  /// where the region's relaxed wrinkling law finds it not taut (a projection
  /// region's is not projected); @p C receives C = F^T F [C11, C22, C12].
  Eigen::Vector3d linearStress(int r, const double (&F0)[3], const double (&F1)[3],
                               double (&C)[3]) const;
  /// @return the least, over the elements of linear sections, of length /
  /// wave speed at displacements @p u (s; infinite without such elements):
  /// each element's speed from its own lambda_max^2 and principal second
  /// Piola-Kirchhoff stress (the tension-only stress where it wrinkles),
  /// never below its region's rest speed and equal to it until faster by
  /// more than round-off
  double linearStableStep(const Eigen::VectorXd& u) const;
  /// The stable step of element @p e of a linear section at positions @p x
  /// (displacements @p u): its length over its fastest wave's speed.
  double elementStableStep(int e, const double* x, const Eigen::VectorXd& u) const;
  /// @return the principal Cauchy stresses of element @p e in state @p st (its law's with history)
  Eigen::Vector2d cauchyPrincipal(int e, const FabricStress& st) const;
  /// Builds the history blocks of the nonlinear sections.
  void initHistory();
  double setup_s_ = 0;
};

} // namespace lamina::membrane
