/// @file reduced_order_accuracy_test.cpp
/// @brief The reduced-order cell against the full-field nonlinear cell on
/// the same voxels, away from any exact limit: the chapter's two-scale
/// polyurea cell (cases/cells/polyurea-two-scale.toml: 19 % hard elastic
/// ellipsoids at 45 degrees in soft GVBO domains) at 16^3, driven in
/// uniaxial stress and in shear at 1e2 /s (the lowest rate of the study,
/// where the soft domains flow most and the models differ most) to 0.3.
/// The figure is the study's (scripts/plot_rom.py,
/// docs/homogenize-nonlinear.md): the largest |sigma_rom - sigma_ff| /
/// |sigma_ff| of the driven component over the steps where |sigma_ff|
/// exceeds 5 % of its peak. The bound is the two-scale model's target for
/// one partition per phase, 5 %, which the clustering scheme meets here
/// with one and with eight partitions per phase (measured 3.1-3.3 % and
/// 3.1-3.7 %; at 32^3 and 60 steps the study gives 2.8-4.3 % and 2.2-2.8 %:
/// the target of 2 % with eight per phase is not met,
/// docs/homogenize-nonlinear.md). The transformation scheme's figure at one partition per
/// phase is asserted to exceed 20 % (measured 54 %), the stiffness its
/// documentation explains: the two schemes are not the same model.

#include "homogenize/library_entry.hpp"
#include "homogenize/macro_history.hpp"
#include "homogenize/nonlinear_homogenizer.hpp"
#include "homogenize/reduced_order_builder.hpp"
#include "homogenize/reduced_order_run.hpp"
#include "materials/point_driver.hpp"
#include "materials/reduced_order_law.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace lamina {
namespace {

namespace mat = materials;
namespace hom = homogenize;

constexpr int kSteps = 30;
constexpr double kRate = 1e2, kTo = 0.3;

struct Study {
  micro::CellSpec spec;
  micro::UnitCell cell;
  std::map<mat::DrivePath, std::vector<hom::StepResult>> full;
  Study()
      : spec(
            micro::readCell(std::string(LAMINA_SOURCE_DIR) + "/cases/cells/polyurea-two-scale.toml",
                            micro::lazyCatalog())),
        cell(micro::buildCell(spec, {16, 16, 16})) {
    std::vector<mat::LawPtr> laws;
    for (const auto& ph : spec.phases)
      laws.push_back(ph.model);
    hom::NonlinearOptions o;
    o.tol = 1e-8; // the full field to 1e-8 of the applied strain: far below 1 %
    o.threads = 1;
    for (mat::DrivePath path : {mat::DrivePath::UniaxialStress, mat::DrivePath::Shear}) {
      hom::NonlinearHomogenizer h(hom::gridOf(cell), cell.phase.toVector(), laws, o);
      full[path] = h.run(hom::pathHistory(path, kRate, kTo, kSteps, false));
    }
  }
  /// the study's agreement figure of the law of @p scheme, @p k per phase
  double agreement(mat::ReducedOrderScheme scheme, int k, mat::DrivePath path) const {
    hom::ReducedOrderOptions opt;
    opt.threads = 1;
    opt.scheme = scheme;
    if (k > 1) {
      opt.partitions.method = hom::PartitionMethod::KMeans;
      opt.partitions.per_phase = k;
    }
    const mat::ReducedOrderLaw law("two-scale", hom::buildReducedOrder(spec, cell, opt).model);
    mat::DriveOptions d;
    d.path = path;
    d.rate = kRate;
    d.to = kTo;
    d.steps = kSteps;
    d.kinematics = mat::Kinematics::Small;
    const std::vector<mat::DriveRow> rows = mat::drive(law, d);
    const std::vector<hom::StepResult>& ff = full.at(path);
    const Eigen::Index c = path == mat::DrivePath::Shear ? 3 : 0; // lamina order: xx, ..., xy
    double peak = 0, worst = 0;
    for (const auto& s : ff)
      peak = std::max(peak, std::abs(s.Sigma[c]));
    for (std::size_t i = 0; i < ff.size(); ++i)
      if (std::abs(ff[i].Sigma[c]) > 0.05 * peak)
        worst = std::max(worst, std::abs(rows[i + 1].sigma[c] - ff[i].Sigma[c]) /
                                    std::abs(ff[i].Sigma[c]));
    return worst;
  }
};

const Study& study() {
  static const Study s;
  return s;
}

TEST(ReducedOrderAccuracy, ClusteringWithinFivePercentAtOneAndEightPartitionsPerPhase) {
  for (int k : {1, 8})
    for (mat::DrivePath path : {mat::DrivePath::UniaxialStress, mat::DrivePath::Shear}) {
      const double a = study().agreement(mat::ReducedOrderScheme::Clustering, k, path);
      RecordProperty("clustering_k" + std::to_string(k) + "_" + mat::toString(path),
                     std::to_string(a));
      EXPECT_LT(a, 0.05) << mat::toString(path) << ", " << k << " per phase";
    }
}

TEST(ReducedOrderAccuracy, TransformationSchemeIsStifferThanTheFullField) {
  const double a =
      study().agreement(mat::ReducedOrderScheme::Transformation, 1, mat::DrivePath::UniaxialStress);
  RecordProperty("tfa_k1_uniaxial-stress", std::to_string(a));
  EXPECT_GT(a, 0.20);
}

} // namespace
} // namespace lamina
