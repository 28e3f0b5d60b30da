// navfn-smt: the occupancy grid values of nav_msgs/OccupancyGrid as nav2_util names them.
#ifndef NAVFN_SMT_PLUGIN_STUB_OCC_GRID_VALUES_HPP_
#define NAVFN_SMT_PLUGIN_STUB_OCC_GRID_VALUES_HPP_
namespace nav2_util
{
constexpr signed char OCC_GRID_UNKNOWN = -1;
constexpr signed char OCC_GRID_FREE = 0;
constexpr signed char OCC_GRID_OCCUPIED = 100;
}
#endif
