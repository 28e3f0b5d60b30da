// navfn-smt: geometry_msgs/Pose, for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_POSE_HPP_
#define NAVFN_SMT_PLUGIN_STUB_POSE_HPP_
#include "geometry_msgs/msg/point.hpp"
#include "geometry_msgs/msg/quaternion.hpp"
namespace geometry_msgs
{
namespace msg
{
struct Pose
{
  Point position;
  Quaternion orientation;
};
}  // namespace msg
}  // namespace geometry_msgs
#endif
