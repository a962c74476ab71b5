#include "membrane/system/state.hpp"

#include "core/error.hpp"

namespace lamina::membrane {

namespace {
/// The members of StateForces with their History names.
template <class F, class Fn>
void forEachForce(F& f, Fn&& fn) {
  fn("external", f.external);
  fn("drag", f.drag);
  fn("reaction", f.reaction);
  fn("spring", f.spring);
  fn("damping", f.damping);
  fn("internal", f.internal);
  fn("contact", f.contact.force);
  fn("contact_sum", f.contact.sum);
  fn("contact_depth", f.contact.depth);
}
} // namespace

void saveForces(const std::string& prefix, const StateForces& f, History& h) {
  forEachForce(f, [&](const char* name, const Eigen::VectorXd& v) {
    if (v.size())
      h[prefix + name] = v;
  });
}

void restoreForces(const std::string& prefix, const History& h, StateForces& f) {
  forEachForce(f, [&](const char* name, Eigen::VectorXd& v) {
    const std::string key = prefix + name;
    if (v.size() == 0 && h.count(key))
      throw Error("checkpoint has an entry '" + key + "' this run does not have");
    if (v.size())
      v = historyEntry(h, key, v.size());
  });
}

} // namespace lamina::membrane
