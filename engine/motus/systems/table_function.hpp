#pragma once
// A table function of system dynamics (World2, Limits to Growth): linear
// interpolation between points, held flat beyond the first and last.
#include <algorithm>
#include <vector>

namespace motus {

class TableFunction {
public:
  TableFunction(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {}

  double operator()(double x) const {
    if (x <= x_.front()) return y_.front();
    if (x >= x_.back()) return y_.back();
    const auto upper = std::upper_bound(x_.begin(), x_.end(), x);
    const size_t i = static_cast<size_t>(upper - x_.begin()) - 1;
    const double s = (x - x_[i]) / (x_[i + 1] - x_[i]);
    return y_[i] + s * (y_[i + 1] - y_[i]);
  }

private:
  std::vector<double> x_, y_;
};

}  // namespace motus
