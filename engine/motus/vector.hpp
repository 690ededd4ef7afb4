#pragma once
// One vector type for all state: a contiguous array of doubles (Eigen::VectorXd).
// A mechanical state of N particles in d dimensions stores particle i's
// coordinate k at index i*d + k.
#include <Eigen/Core>

namespace motus {

using Vector = Eigen::VectorXd;

// A writable view of contiguous doubles: a whole Vector, or a segment of one.
using VectorRef = Eigen::Ref<Vector>;

// A read-only view of contiguous doubles. Eigen::Ref<const VectorXd> would do, but it
// carries a hidden VectorXd (for expressions it must copy) whose destructor is a call
// to free() every time one is made — several per force evaluation. This view only
// ever points at memory that exists, so it costs nothing.
class ConstVectorRef : public Eigen::Map<const Vector> {
public:
  template <class Derived>
  ConstVectorRef(const Eigen::DenseBase<Derived>& v)  // NOLINT: implicit, like Eigen::Ref
      : Eigen::Map<const Vector>(v.derived().data(), v.size()) {
    static_assert(Derived::InnerStrideAtCompileTime == 1, "a ConstVectorRef views contiguous doubles only");
  }
};

}  // namespace motus
