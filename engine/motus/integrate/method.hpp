#pragma once
// The integrator a run uses: one of motus's own (an Integrator), or one given from outside
// as functions (an ExternalIntegrator from a student's plug-in, named "PLUGIN:NAME").
#include <string>

#include "motus/external/external_parts.hpp"
#include "motus/integrate/integrator_catalog.hpp"

namespace motus {

class Method {
public:
  Method(Integrator builtin) : builtin_(builtin) {}  // NOLINT: implicit, so an Integrator is a Method
  Method(const ExternalIntegrator& outside, std::string name) : outside_(&outside), name_(std::move(name)) {}

  bool is_external() const { return outside_ != nullptr; }
  // Only for is_external() == false.
  Integrator builtin() const { return builtin_; }
  // Only for is_external() == true.
  const ExternalIntegrator& outside() const { return *outside_; }

  std::string name() const { return outside_ ? name_ : info(builtin_).name; }
  std::string description() const { return outside_ ? outside_->description : info(builtin_).description; }
  int order() const { return outside_ ? outside_->order : info(builtin_).order; }
  bool adaptive() const { return outside_ ? outside_->kind == kExternalAdaptive : info(builtin_).adaptive; }
  // Works on x and v apart (the symplectic family, and a plug-in's step(x, v), symplectic or not),
  // so only on point masses.
  bool needs_mechanical() const {
    return outside_ ? outside_->kind == kExternalMechanical || outside_->kind == kExternalPositionVerlet
                    : info(builtin_).needs_mechanical;
  }

private:
  Integrator builtin_ = Integrator::Euler;
  const ExternalIntegrator* outside_ = nullptr;
  std::string name_;
};

}  // namespace motus
