// navfn-smt: nav_msgs/OccupancyGrid (resolution a float32, as the message defines it), for the
// oracle build.
#ifndef NAVFN_SMT_PLUGIN_STUB_OCCUPANCY_GRID_HPP_
#define NAVFN_SMT_PLUGIN_STUB_OCCUPANCY_GRID_HPP_
#include <cstdint>
#include <memory>
#include <vector>
#include "geometry_msgs/msg/pose.hpp"
#include "std_msgs/msg/header.hpp"
namespace nav_msgs
{
namespace msg
{
struct MapMetaData
{
  builtin_interfaces::msg::Time map_load_time;
  float resolution = 0.0f;
  uint32_t width = 0, height = 0;
  geometry_msgs::msg::Pose origin;
};
struct OccupancyGrid
{
  using SharedPtr = std::shared_ptr<OccupancyGrid>;
  using ConstSharedPtr = std::shared_ptr<const OccupancyGrid>;
  std_msgs::msg::Header header;
  MapMetaData info;
  std::vector<int8_t> data;
};
}  // namespace msg
}  // namespace nav_msgs
#endif
