// navfn-smt: geometry_msgs/TransformStamped, for the oracle build (never filled: see tf2 stubs).
#ifndef NAVFN_SMT_STUB_TRANSFORM_STAMPED_HPP_
#define NAVFN_SMT_STUB_TRANSFORM_STAMPED_HPP_
#include "geometry_msgs/msg/quaternion.hpp"
#include "std_msgs/msg/header.hpp"
namespace geometry_msgs
{
namespace msg
{
struct Vector3
{
  double x = 0.0, y = 0.0, z = 0.0;
};
struct Transform
{
  Vector3 translation;
  Quaternion rotation;
};
struct TransformStamped
{
  std_msgs::msg::Header header;
  std::string child_frame_id;
  Transform transform;
};
}  // namespace msg
}  // namespace geometry_msgs
#endif
