// navfn-smt: nav_msgs/Path, for the oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_PATH_HPP_
#define NAVFN_SMT_PLUGIN_STUB_PATH_HPP_
#include <vector>
#include "geometry_msgs/msg/pose_stamped.hpp"
namespace nav_msgs
{
namespace msg
{
struct Path
{
  std_msgs::msg::Header header;
  std::vector<geometry_msgs::msg::PoseStamped> poses;
};
}  // namespace msg
}  // namespace nav_msgs
#endif
