// navfn-smt: nav2_util::geometry_utils::orientationAroundZAxis, which is not among the sources
// the oracle builds (nav2_util): tf2::Quaternion::setRPY(0, 0, angle), its products as tf2
// writes them, in double.  This is the one piece of arithmetic the project writes itself for
// the plugin build: it is the same formula the model states (quaternion_from_yaw), so the
// final-orientation comparison is as good as that formula, not independent evidence of it.
#ifndef NAVFN_SMT_PLUGIN_STUB_GEOMETRY_UTILS_HPP_
#define NAVFN_SMT_PLUGIN_STUB_GEOMETRY_UTILS_HPP_
#include <cmath>
#include "geometry_msgs/msg/quaternion.hpp"
namespace nav2_util
{
namespace geometry_utils
{
inline geometry_msgs::msg::Quaternion orientationAroundZAxis(double angle)
{
  double half_yaw = angle * 0.5, half_pitch = 0.0 * 0.5, half_roll = 0.0 * 0.5;
  double cy = std::cos(half_yaw), sy = std::sin(half_yaw);
  double cp = std::cos(half_pitch), sp = std::sin(half_pitch);
  double cr = std::cos(half_roll), sr = std::sin(half_roll);
  geometry_msgs::msg::Quaternion q;
  q.x = sr * cp * cy - cr * sp * sy;
  q.y = cr * sp * cy + sr * cp * sy;
  q.z = cr * cp * sy - sr * sp * cy;
  q.w = cr * cp * cy + sr * sp * sy;
  return q;
}
}  // namespace geometry_utils
}  // namespace nav2_util
#endif
