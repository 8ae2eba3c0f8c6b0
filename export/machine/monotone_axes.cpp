#include "export/machine/monotone_axes.h"

#include <algorithm>
#include <cmath>

namespace windplan {

void isotonic_fit(std::vector<double>* v, int begin, int end, bool increasing) {
  if (end - begin < 2) return;
  const double sgn = increasing ? 1.0 : -1.0;
  // Pool adjacent violators on sgn * v: blocks of (mean, count).
  std::vector<double> mean;
  std::vector<int> count;
  for (int i = begin; i < end; ++i) {
    mean.push_back(sgn * (*v)[i]);
    count.push_back(1);
    while (mean.size() > 1 && mean[mean.size() - 2] > mean.back()) {
      const int n = count.back() + count[count.size() - 2];
      const double m =
          (mean.back() * count.back() + mean[mean.size() - 2] * count[count.size() - 2]) / n;
      mean.pop_back();
      count.pop_back();
      mean.back() = m;
      count.back() = n;
    }
  }
  int i = begin;
  for (std::size_t b = 0; b < mean.size(); ++b) {
    for (int k = 0; k < count[b]; ++k) (*v)[i++] = sgn * mean[b];
  }
}

namespace {

double max_change(const std::vector<double>& a, const std::vector<double>& b, int begin, int end) {
  double m = 0.0;
  for (int i = begin; i < end; ++i) m = std::max(m, std::fabs(a[i] - b[i]));
  return m;
}

}  // namespace

double monotone_overall(std::vector<double>* v, int begin, int end) {
  if (end - begin < 2) return 0.0;
  const std::vector<double> before = *v;
  isotonic_fit(v, begin, end, (*v)[end - 1] >= (*v)[begin]);
  return max_change(before, *v, begin, end);
}

double monotone_between_extremes(std::vector<double>* v, int begin, int end) {
  if (end - begin < 2) return 0.0;
  const std::vector<double> before = *v;
  const auto first = v->begin() + begin, last = v->begin() + end;
  const int i_max = static_cast<int>(std::max_element(first, last) - v->begin());
  const int i_min = static_cast<int>(std::min_element(first, last) - v->begin());
  const int e1 = std::min(i_max, i_min), e2 = std::max(i_max, i_min);
  const bool up_first = e1 == i_max;  // rises to the maximum first
  isotonic_fit(v, begin, e1 + 1, up_first);
  isotonic_fit(v, e1, e2 + 1, !up_first);
  isotonic_fit(v, e2, end, up_first);
  return max_change(before, *v, begin, end);
}

}  // namespace windplan
