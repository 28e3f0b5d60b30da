// navfn-smt: geometry_msgs/PoseStamped, for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_POSE_STAMPED_HPP_
#define NAVFN_SMT_PLUGIN_STUB_POSE_STAMPED_HPP_
#include "geometry_msgs/msg/pose.hpp"
#include "std_msgs/msg/header.hpp"
namespace geometry_msgs
{
namespace msg
{
struct PoseStamped
{
  std_msgs::msg::Header header;
  Pose pose;
};
}  // namespace msg
}  // namespace geometry_msgs
#endif
