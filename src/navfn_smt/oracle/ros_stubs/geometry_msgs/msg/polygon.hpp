// navfn-smt: geometry_msgs/Polygon, for the oracle build.
#ifndef NAVFN_SMT_STUB_POLYGON_HPP_
#define NAVFN_SMT_STUB_POLYGON_HPP_
#include <memory>
#include <vector>
#include "geometry_msgs/msg/point32.hpp"
namespace geometry_msgs
{
namespace msg
{
struct Polygon
{
  using SharedPtr = std::shared_ptr<Polygon>;
  std::vector<Point32> points;
};
}  // namespace msg
}  // namespace geometry_msgs
#endif
