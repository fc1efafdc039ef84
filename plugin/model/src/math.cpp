#include "tressvk/model/math.hpp"

namespace tressvk::model {

Quat quat_from_matrix(const std::array<std::array<double, 3>, 3>& m) {
  // Shepperd's method: branch on the largest of the trace and the diagonal for a well-conditioned square root.
  double tr = m[0][0] + m[1][1] + m[2][2];
  Quat q;
  if (tr > m[0][0] && tr > m[1][1] && tr > m[2][2]) {
    double s = std::sqrt(1.0 + tr) * 2.0;
    q = {(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s};
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    double s = std::sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2.0;
    q = {0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s};
  } else if (m[1][1] > m[2][2]) {
    double s = std::sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2.0;
    q = {(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s};
  } else {
    double s = std::sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2.0;
    q = {(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s};
  }
  return normalize(q);
}

std::array<std::array<double, 3>, 3> matrix_from_quat(Quat q) {
  std::array<std::array<double, 3>, 3> m{};
  Vec3 cols[3] = {quat_rotate(q, {1, 0, 0}), quat_rotate(q, {0, 1, 0}), quat_rotate(q, {0, 0, 1})};
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) m[static_cast<size_t>(r)][static_cast<size_t>(c)] = cols[c][r];
  }
  return m;
}

}  // namespace tressvk::model
