#include "materials/law.hpp"

#include "core/error.hpp"

#include <Eigen/Cholesky>

#include <string_view>
#include <vector>

namespace lamina::materials {

const char* toString(LawKind k) {
  return kLawKindNames.name(k).data(); // the table's names are literals: NUL-terminated
}

std::string lawKindNames() {
  std::vector<std::string_view> names;
  for (const auto& [name, kind] : kLawKindNames)
    // reduced-order: referred to by an entry's name; void: a cell's pore, no keys
    if (kind != LawKind::ReducedOrder && kind != LawKind::Void)
      names.push_back(name);
  return core::choiceList(names);
}

double ConstitutiveLaw::storedEnergy(const Vector6& sigma, const double*, double J) const {
  return 0.5 * sigma.dot(elasticStrain(sigma, J));
}

Vector6 ConstitutiveLaw::elasticStrain(const Vector6& sigma, double J) const {
  return elasticStiffness(J).matrix().ldlt().solve(sigma);
}

bool ConstitutiveLaw::planeStressStep(const PlaneStressStep&, const double*, double*, double,
                                      PlaneStressResult&) const {
  return false;
}

LinearElasticLaw::LinearElasticLaw(LawKind kind, const Stiffness& C) : kind_(kind), C_(C) {
  LAMINA_CHECK(kind != LawKind::Gvbo && kind != LawKind::ReducedOrder && kind != LawKind::Fabric,
               "the ", toString(kind), " law is not linear elasticity");
}

void LinearElasticLaw::update(const PointStep& step, const double*, double*, Vector6& sigma,
                              Matrix6* tangent) const {
  sigma = C_.matrix() * step.eps;
  if (tangent)
    *tangent = C_.matrix();
}

} // namespace lamina::materials
