// navfn-smt: geometry_msgs/Point, for the oracle build (doubles, as the message defines them).
#ifndef NAVFN_SMT_PLUGIN_STUB_POINT_HPP_
#define NAVFN_SMT_PLUGIN_STUB_POINT_HPP_
namespace geometry_msgs
{
namespace msg
{
struct Point
{
  double x = 0.0, y = 0.0, z = 0.0;
};
}  // namespace msg
}  // namespace geometry_msgs
#endif
