// navfn-smt: geometry_msgs/PolygonStamped, for the oracle build.
#ifndef NAVFN_SMT_STUB_POLYGON_STAMPED_HPP_
#define NAVFN_SMT_STUB_POLYGON_STAMPED_HPP_
#include "geometry_msgs/msg/polygon.hpp"
#include "std_msgs/msg/header.hpp"
namespace geometry_msgs
{
namespace msg
{
struct PolygonStamped
{
  std_msgs::msg::Header header;
  Polygon polygon;
};
}  // namespace msg
}  // namespace geometry_msgs
#endif
