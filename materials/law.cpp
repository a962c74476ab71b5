#include "materials/law.hpp"

#include "core/error.hpp"

#include <Eigen/Cholesky>

#include <array>
#include <utility>

namespace lamina::materials {

namespace {
constexpr std::array<std::pair<LawKind, const char*>, 5> kLawNames{{
    {LawKind::Isotropic, "isotropic"},
    {LawKind::TransverselyIsotropic, "transversely-isotropic"},
    {LawKind::Anisotropic, "anisotropic"},
    {LawKind::Gvbo, "gvbo"},
    {LawKind::ReducedOrder, "reduced-order"},
}};
} // namespace

const char* toString(LawKind k) {
  for (const auto& [kind, name] : kLawNames)
    if (kind == k)
      return name;
  return "?";
}

std::optional<LawKind> parseLawKind(const std::string& name) {
  for (const auto& [kind, text] : kLawNames)
    if (name == text)
      return kind;
  return std::nullopt;
}

std::string lawKindNames() {
  std::string out;
  for (const auto& [kind, name] : kLawNames)
    if (kind != LawKind::ReducedOrder) // referred to by an entry's name, not given with keys
      out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

double ConstitutiveLaw::storedEnergy(const Vector6& sigma, const double*, double J) const {
  return 0.5 * sigma.dot(elasticStrain(sigma, J));
}

Vector6 ConstitutiveLaw::elasticStrain(const Vector6& sigma, double J) const {
  return elasticStiffness(J).matrix().ldlt().solve(sigma);
}

LinearElasticLaw::LinearElasticLaw(LawKind kind, const Stiffness& C) : kind_(kind), C_(C) {
  LAMINA_CHECK(kind != LawKind::Gvbo && kind != LawKind::ReducedOrder, "the ", toString(kind),
               " law is not linear elasticity");
}

void LinearElasticLaw::update(const PointStep& step, const double*, double*, Vector6& sigma,
                              Matrix6* tangent) const {
  sigma = C_.matrix() * step.eps;
  if (tangent)
    *tangent = C_.matrix();
}

} // namespace lamina::materials
