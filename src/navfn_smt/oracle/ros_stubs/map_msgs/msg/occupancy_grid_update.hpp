// navfn-smt: map_msgs/OccupancyGridUpdate, for the oracle build (the oracle sends no updates).
#ifndef NAVFN_SMT_STUB_OCCUPANCY_GRID_UPDATE_HPP_
#define NAVFN_SMT_STUB_OCCUPANCY_GRID_UPDATE_HPP_
#include <cstdint>
#include <memory>
#include <vector>
#include "std_msgs/msg/header.hpp"
namespace map_msgs
{
namespace msg
{
struct OccupancyGridUpdate
{
  using ConstSharedPtr = std::shared_ptr<const OccupancyGridUpdate>;
  using SharedPtr = std::shared_ptr<OccupancyGridUpdate>;
  std_msgs::msg::Header header;
  int32_t x = 0, y = 0;
  uint32_t width = 0, height = 0;
  std::vector<int8_t> data;
};
}  // namespace msg
}  // namespace map_msgs
#endif
