// navfn-smt: nav2::validateMsg, which is not among the sources the oracle builds (nav2_ros_common):
// the oracle sends only well-formed grids (size matching width x height, a positive resolution),
// which it accepts; any other message stops the oracle rather than guess.
#ifndef NAVFN_SMT_STUB_VALIDATE_MESSAGES_HPP_
#define NAVFN_SMT_STUB_VALIDATE_MESSAGES_HPP_
#include <cstdlib>
#include "nav_msgs/msg/occupancy_grid.hpp"
#include "map_msgs/msg/occupancy_grid_update.hpp"
namespace navfn_smt
{
inline bool well_formed(const nav_msgs::msg::OccupancyGrid & m)
{
  if (m.info.resolution > 0.0f && m.data.size() == static_cast<size_t>(m.info.width) * m.info.height) {
    return true;
  }
  std::abort();
}
inline bool well_formed(const map_msgs::msg::OccupancyGridUpdate &) {std::abort();}
}  // namespace navfn_smt
namespace nav2
{
template<typename MsgT>
bool validateMsg(const MsgT & msg) {return navfn_smt::well_formed(msg);}
}  // namespace nav2
#endif
