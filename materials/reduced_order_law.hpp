#pragma once
/// @file reduced_order_law.hpp
/// @brief A reduced-order unit cell as a constitutive law (polyurea chapter,
/// section 4.2, eqs. 22-34; micro-inertia eq. 40): the coarse stress of a
/// material point whose microstructure is the cell of a ReducedOrderModel
/// (reduced_order.hpp), each partition following its phase's law.
///
/// **Method.** The cell is split into n partitions alpha, each inside one
/// phase with reference stiffness L0 (its law's elasticStiffness(1.0), the
/// stiffness the influence functions were computed with). Every partition
/// carries a uniform strain eps^(alpha) and an eigenstrain mu^(alpha); the
/// reduced system (eq. 32 averaged over partition beta) is
///
///     d eps^(beta) = A^(beta) d eps^c + sum_alpha P^(beta alpha) d mu^(alpha),
///
/// and the eigenstrain increment of eq. 23 carries both the inelastic strain
/// and the change of moduli of the partition's law:
///
///     d mu^(alpha) = d eps^(alpha) - L0^-1 (sigma^(alpha) - sigma^(alpha)_n).
///
/// Summed from the virgin state (eps = sigma = mu = 0) this is mu^(alpha) =
/// eps^(alpha) - L0^-1 sigma^(alpha), and the step is solved in that summed
/// form at t_{n+1} (the same equations; it needs no stress of t_n and does
/// not accumulate the Newton residuals of earlier steps):
///
///     r^(beta) = eps^(beta) - A^(beta) eps^c - sum_{alpha nonlinear} P^(beta alpha) mu^(alpha) =
///     0,
///
/// with one unknown eps^(beta) (6) per *nonlinear* partition beta. A
/// partition with a linear law has sigma = L0 eps, so mu = 0 exactly: it
/// carries no unknowns, and its strain follows once the nonlinear ones are
/// known. This is what makes a point cheap: a GVBO + elastic cell with 8
/// partitions per phase solves a 48 x 48 system, not 96 x 96. Each partition
/// is stepped by its own law from its eps^(alpha)_n with J^(alpha) = 1 +
/// tr eps^(alpha) in small kinematics (J = 1 + tr eps^c, the FFT cell's
/// definition) and J^(alpha) = J exp(tr eps^(alpha) - tr eps^c) in finite
/// kinematics (eps the integrated rate of deformation, tr eps = ln J).
/// Newton on the unknowns, Jacobian
///
///     K_(beta alpha) = delta_(beta alpha) I - P^(beta alpha) L0_alpha^-1 (L0_alpha - T_alpha),
///
/// T_alpha the consistent tangent of partition alpha's law, from eps^(beta)_n
/// + A^(beta) d eps^c; converged when max |r| <= tolerance * max(|eps^c|,
/// |eps^(beta)|, |mu^(beta)|) (max norms: the size of the terms r sums, so
/// that a point unloaded to zero strain but holding inelastic strain still
/// converges to the round-off of its eigenstrains). The coarse stress is the average (eq. 33),
/// sigma^c = sum c_alpha sigma^(alpha), and the consistent coarse tangent is
///
///     d eps_N / d eps^c = K^-1 A_N,   d mu_N / d eps^c = L0^-1 (L0 - T) d eps_N / d eps^c,
///     C_T = sum_{nonlinear b} c_b T_b d eps^(b)/d eps^c
///         + sum_{linear e} c_e L_e (A^(e) + sum_a P^(e a) d mu^(a)/d eps^c)
///
/// (N: the nonlinear partitions stacked). The GVBO tangent holds each
/// partition's J fixed, so the Newton and the coarse tangent leave out the
/// derivative of the moduli through J (gvbo_law.hpp).
///
/// **Micro-inertia.** d mu / d eps^c of the last step gives the nonlinear
/// dispersion of eq. 40, D_nonlin = M^T R M + Q M + (Q M)^T with M = d mu_N /
/// d eps^c (6m x 6) and R, Q restricted to the nonlinear partitions (the
/// linear ones have d mu = 0), in kg/m like Material::dispersion.
///
/// **State** per point: for every partition alpha in order, its total strain
/// eps^(alpha) (6, lamina order, engineering shear) followed by its law's
/// state; stateSize() = sum_alpha (6 + stateSize of its law). A GVBO (20) +
/// elastic (0) cell: 32 doubles with one partition per phase, 256 with 8.
///
/// **Cost** of one step with m nonlinear of n partitions (flops: a 6x6
/// matrix-vector product is 72, a matrix-matrix product 432). Per Newton
/// iteration: m law updates with tangent, the eigenstrains (72 m), the
/// residual (72 m (m + 1)), K (432 m (m + 1)), its LU (144 m^3) and solve
/// (72 m^2). Once per step: K and its LU again at the converged strains for
/// the tangent (plus 432 m^2 for its six right-hand sides and 1300 m for d mu
/// and C_T), the stress (72 (m + 1); the linear partitions enter through two
/// precomputed sums, C_lin = sum c_e L_e A^(e) and B_a = sum c_e L_e
/// P^(e a)), and the linear partitions' strains for the state (72 (n - m)
/// (m + 1)). Newton iterations per step, measured on the chapter's
/// laminate (GVBO soft 0.81, elastic hard 0.19) driven to 0.3 and back in
/// 200 steps per leg: 1-2 in uniaxial strain, 3-4 in confined compression
/// (the J held fixed in the tangent makes the convergence linear where the
/// moduli grow with compression, eqs. 13-16: up to 20 iterations with steps
/// of 0.1 strain), none in in-plane shear. Memory per point:
/// stateSize() doubles; the law object holds the model (36 n^2 + 72 n^2 for
/// P and R).
///
/// **Clustering** (model().scheme == ReducedOrderScheme::Clustering; the
/// clustering analysis of Liu, Bessa and Liu 2016, with its own choice of
/// reference medium). The partitions are coupled through an isotropic
/// reference medium C0 (Lame lambda0, mu0) instead of the phases' own
/// stiffnesses: the Lippmann-Schwinger equation eps = eps^c - Gamma0 (sigma
/// - C0 eps), averaged over partition beta with every field uniform per
/// partition, is
///
///     r^(beta) = eps^(beta) - eps^c + sum_alpha G^(beta alpha) (sigma^(alpha) - C0 eps^(alpha)) =
///     0,
///
/// G^(beta alpha) = (Ga - beta0 Gb) / mu0 with beta0 = (lambda0 + mu0) /
/// (lambda0 + 2 mu0) (homogenize/cluster_interaction.hpp), one unknown
/// eps^(beta) per partition, linear ones too. Newton with K_(beta alpha) =
/// delta I + G^(beta alpha) (T_alpha - C0); sigma^c = sum c_alpha
/// sigma^(alpha); d eps / d eps^c = K^-1 [I; ...; I] and C_T = sum c_alpha
/// T_alpha d eps^(alpha) / d eps^c (at fixed C0).
///
/// The reference medium. Exact answers (a laminate, one partition per
/// voxel) do not depend on it; with a few partitions per phase it is what
/// decides how stiffly the partitions hold each other. Its shear modulus
/// mu0 is the smallest secant shear modulus of the phases, mu_p = (dev
/// sigma_p : dev eps_p) / (2 dev eps_p : dev eps_p) of each phase's mean
/// stress and strain at the end of the step (a phase without deviatoric
/// strain has none; never below 1e-3 of the value at rest). This is the
/// Hashin-Shtrikman lower-bound choice of a matrix-inclusion cell, whose
/// continuous soft phase sets the interactions, followed as that phase
/// flows: once the soft domains flow, their secant falls far below their
/// instantaneous modulus, and the partitions interact through that softer
/// medium instead of the elastic one (the transformation scheme's frozen
/// influence functions, or a reference fitted to the consistent tangent,
/// which stays near the instantaneous stiffness in the short steps of a
/// viscous law: both 3-13 times further from the full-field cell than this
/// choice where the soft domains flow, docs/homogenize-nonlinear.md; in
/// shear at 1e5 /s, where they barely flow, the transformation scheme is
/// the closer, 2.5 % against 3.6 %). Its bulk modulus kappa0 is
/// fixed: the bulk modulus of the isotropic part (C_iijj / 9) of the cell's
/// tangent at rest in that medium, iterated to a fixed point once (taking it
/// from the current tangent instead changed the study's figures by less
/// than 0.01 %). A step runs in the medium fitted at the end of the step
/// before (the state keeps it), and its own fit is the next step's: within
/// a step the stress is then a smooth function of the strain and C_T its
/// exact derivative, which the membrane's plane-stress iteration needs (a
/// medium refitted within the step, iterated to a tolerance, made the
/// stress jitter at that tolerance, and the iteration stalled). The lag
/// costs accuracy only in coarse steps: the study's 60 steps to 0.3 give
/// up to 0.7 points more than the refitted medium did.
/// At rest (initState(), elasticStiffness(J)) mu0 is the smallest
/// isotropic shear modulus of the phases at J. With elastic phases and a
/// few partitions the stiffness is therefore this estimate, not the FFT C
/// (which the transformation scheme reproduces exactly).
/// The eigenstrains of eq. 40's micro-inertia are mu^(alpha) = eps^(alpha)
/// - L0^-1 sigma^(alpha) as in the other scheme, through the same R and Q.
/// State: as above for every partition, then mu0 (1).
///
/// **Linear cells.** When every partition's law is linear the cell is linear
/// elasticity: isLinear() is true, stateSize() is 0 (the partition strains
/// A^(alpha) eps are not stored) and sigma = C eps exactly, so solvers keep
/// their fast path: C = sum c L A in the transformation scheme, the
/// clustering estimate at rest in the other (referenceTangent).

#include "materials/law.hpp"
#include "materials/reduced_order.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace lamina::materials {

/// The Newton iteration of the partition strains.
struct ReducedOrderOptions {
  /// converged when max |r| <= tolerance * max(|eps^c|, |eps^(beta)|,
  /// |mu^(beta)|) (max norms, strain): 1e-10 puts the stress about 1e-10 of
  /// its scale from the exact answer, far below any modelling error, and
  /// within reach of round-off
  double tolerance = 1e-10;
  /// iterations before a step is refused (lamina::Error naming the entry):
  /// 50 leaves room for the linear convergence of coarse compressive steps
  int max_iterations = 50;
};

/// What one step of the reduced-order law computes besides the stress.
struct ReducedOrderStepInfo {
  int iterations = 0;  ///< Newton iterations taken (0: the first guess held)
  double residual = 0; ///< final max |r| (strain)
  /// d(d mu)/d(d eps^c) of the nonlinear partitions, stacked in the order of
  /// ReducedOrderLaw::nonlinearPartitions() (6m x 6, engineering strain)
  Eigen::MatrixXd dmu_deps;
};

/// A reduced-order cell at a material point (see the file comment).
class ReducedOrderLaw final : public ConstitutiveLaw {
public:
  /// @param entry the library entry's name (named in every error)
  /// @param model the cell (validated here); partition alpha follows
  ///        model.phases[model.partition_phase[alpha]].law.make()
  /// @param options the Newton tolerance and cap
  ReducedOrderLaw(std::string entry, ReducedOrderModel model, ReducedOrderOptions options = {});

  LawKind kind() const override { return LawKind::ReducedOrder; }
  /// @return true only when every partition's law is linear (then sigma = C eps)
  bool isLinear() const override { return nonlinear_.empty(); }
  int stateSize() const override { return state_size_; }
  void initState(double* state) const override;
  /// The instantaneous coarse tangent at J: every partition at J with its
  /// law's elasticStiffness(J) as T, through the reduced system; at J = 1
  /// (T = L0, d mu = 0) exactly sum c L0 A in the transformation scheme (in
  /// clustering, its estimate in the reference medium at rest).
  Stiffness elasticStiffness(double J = 1.0) const override;
  /// One step (file comment); throws lamina::Error naming the entry, the
  /// Newton residual and the iterations when the Newton does not converge.
  void update(const PointStep& step, const double* state_n, double* state, Vector6& sigma,
              Matrix6* tangent) const override;
  /// The energy stored in the partitions: sum_alpha c_alpha W_alpha, W_alpha
  /// its law's storedEnergy of its own stress, state and volume ratio
  /// J^(alpha) (as update() forms it from the coarse @p J, with tr eps^c =
  /// sum c_alpha tr eps^(alpha), exact as sum c A = I and sum c P = 0). A
  /// GVBO partition's stress is the one its state holds (GvboState::kSigma),
  /// another nonlinear law's that of a zero step (eps = eps_n, dt = 0) from
  /// its state; a linear partition's W is eps^(alpha) . L eps^(alpha) / 2 of
  /// the strain in the state. The coarse @p sigma is not used then. A linear
  /// cell (no state): sigma . C^-1 sigma / 2 with C its stiffness, the energy
  /// its stress returns on unloading (for the exact laminate the partition
  /// sum too, by Hill's lemma).
  double storedEnergy(const Vector6& sigma, const double* state, double J) const override;
  /// As update(), also reporting the iterations, the residual and d mu / d
  /// eps^c in @p info (if not null).
  void updateWithInfo(const PointStep& step, const double* state_n, double* state, Vector6& sigma,
                      Matrix6* tangent, ReducedOrderStepInfo* info) const;

  /// D_nonlin of eq. 40 (kg/m, 6x6, symmetric) from the d mu / d eps^c of
  /// @p info: M^T R M + Q M + (Q M)^T over the nonlinear partitions; exactly
  /// zero for a linear cell.
  Matrix6 nonlinearDispersion(const ReducedOrderStepInfo& info) const;

  /// @return the entry name
  const std::string& entry() const { return entry_; }
  /// @return the cell
  const ReducedOrderModel& model() const { return model_; }
  /// @return the partitions whose law is not linear, ascending (the Newton
  /// unknowns of the transformation scheme; clustering solves for every
  /// partition)
  const std::vector<int>& nonlinearPartitions() const { return nonlinear_; }
  /// @return the partitions whose strains the Newton solves for
  const std::vector<int>& unknownPartitions() const { return unknown_; }
  /// @return clustering: the reference medium (lambda0, mu0) initState()
  /// starts from, the one at rest (J = 1)
  std::array<double, 2> initialReference() const { return lameOf(mu_rest_); }
  /// @return the offset of partition @p alpha's block in the state (its
  /// strain; its law's state follows at offset + 6). Linear cells: none.
  int stateOffset(int alpha) const { return offset_[static_cast<std::size_t>(alpha)]; }
  /// @return the options
  const ReducedOrderOptions& options() const { return options_; }

private:
  struct Trial;
  struct Reference;
  /// Steps every unknown partition to the strains of @p trial.
  void evaluate(const PointStep& step, const double* state_n, Trial& trial) const;
  /// Newton on the unknown partitions' strains from @p trial's start
  /// until the residual is below the tolerance (relative to the terms it
  /// sums); @p iterations and @p norm report the last one. Throws (fail())
  /// at the iteration cap or a non-finite residual. @p ref: the reference
  /// medium of clustering (else null).
  void solveStrains(const PointStep& step, const double* state_n, const Reference* ref,
                    Trial& trial, int& iterations, double& norm) const;
  /// The residual r of the file comment into @p r; @return the size of the terms it sums.
  double residual(const Vector6& eps_c, const Reference* ref, const Trial& t,
                  Eigen::VectorXd& r) const;
  /// Writes the accepted partition strains and law states of @p trial into @p state.
  void accept(const PointStep& step, const Trial& trial, double* state) const;
  /// d eps_U / d eps^c (the unknowns) and d mu_N / d eps^c (the nonlinear
  /// partitions) from the partition tangents @p T.
  void sensitivities(const std::vector<Matrix6>& T, const Reference* ref, Eigen::MatrixXd& deps,
                     Eigen::MatrixXd& dmu) const;
  /// The coarse tangent from the tangents @p T and sensitivities.
  Matrix6 coarseTangent(const std::vector<Matrix6>& T, const Eigen::MatrixXd& deps,
                        const Eigen::MatrixXd& dmu) const;
  /// K of the file comment from the partition tangents @p T.
  Eigen::MatrixXd jacobian(const std::vector<Matrix6>& T, const Reference* ref) const;
  /// Clustering: the reference medium of shear modulus @p mu0 and the bulk
  /// modulus kappa0 (file comment), as Lame constants.
  std::array<double, 2> lameOf(double mu0) const;
  /// @return the smallest isotropic shear modulus of the tangents @p T
  double softestShear(const std::vector<Matrix6>& T) const;
  /// Clustering: the tangent of the cell whose partitions have the tangents
  /// @p T (all partitions) in the reference medium of shear modulus @p mu0.
  Matrix6 referenceTangent(const std::vector<Matrix6>& T, double mu0) const;
  /// Clustering: the reference shear modulus fitted to the solved
  /// partitions of @p t (file comment); @p last where no phase has one.
  double stepReference(const Trial& t, const Vector6& eps_c, double last) const;
  /// The constructor's last part: the scheme's precomputed sums (tfa:
  /// C_linear_, B_; clustering: its reference medium at rest) and R, Q of
  /// the nonlinear partitions.
  void prepareCoupling();
  /// Throws unless sym(sum c L0 A) of the phases' laws equals the model's C
  /// (1e-9 of max|C|): the phases in the library text belong to the arrays.
  void checkPhasesMatchArrays() const;
  /// The stress of nonlinear partition @p alpha from its state block @p block.
  Vector6 partitionStress(int alpha, const double* block, double J) const;
  [[noreturn]] void fail(const std::string& message) const;

  std::string entry_;
  ReducedOrderModel model_;
  ReducedOrderOptions options_;
  std::vector<LawPtr> laws_;            ///< per partition (shared per phase)
  std::vector<Matrix6> L0_, L0inv_;     ///< per partition
  std::vector<int> nonlinear_, linear_; ///< partition indices
  bool clustering_ = false;             ///< the scheme is clustering
  std::vector<int> unknown_;            ///< the Newton's partitions (see unknownPartitions())
  std::vector<int> nl_slot_;            ///< per nonlinear partition k: its index in unknown_
  double kappa0_ = 0;                   ///< clustering: the reference bulk modulus (file comment)
  double mu_rest_ = 0;                  ///< clustering: the reference shear modulus at rest
  int reference_offset_ = -1;           ///< clustering: mu0 in the state
  std::vector<int> offset_;             ///< per partition: start of its state block
  std::vector<int> trial_offset_;       ///< per unknown partition: its law state in a Trial
  int state_size_ = 0, trial_state_size_ = 0;
  /// transformation: sum over linear e of c_e L_e A^(e); clustering: zero,
  /// or for a linear cell its stiffness (referenceTangent at rest)
  Matrix6 C_linear_;
  std::vector<Matrix6> B_;      ///< per nonlinear a: sum over linear e of c_e L_e P^(e a)
  Eigen::MatrixXd R_nl_, Q_nl_; ///< R, Q restricted to the nonlinear partitions
};

} // namespace lamina::materials
